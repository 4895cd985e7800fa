// raycast_node.cpp — "raycast" of raycast.cl: the underwater frame's G-buffer (002 §4.3.2: hit
// distance, normal, material, sun visibility), published as "gbuffer" (passes/nodes/underwater_frame.h)
// from the parameter blocks of "underwater_setup". A change of sun, water, time or knobs rewrites those
// blocks in place and runs the kernel again; only the camera or the objects make new buffers.
#include <memory>

#include "device/enqueue.h"
#include "passes/caustic_stack.h"
#include "passes/nodes/underwater_frame.h"
#include "passes/underwater_features.h"
#include "passes/underwater_setup_buffers.h"
#include "plan/pass_descriptor.h"
#include "plan/scene_facts.h"
#include "render/pass.h"
#include "util/error.h"

extern "C" {
#include "common/underwater_params.h"
}

namespace seasim {

namespace {

// Sizes (image, objects) and the kernel's defines come from the first list.
const PassKeys kRaycastKeys = {{"camera.*", "objects.*"}, {}};

class RaycastNode : public Pass {
 public:
  explicit RaycastNode(const PassPlan& entry) : entry_(entry) {}
  PassKeys keys() const override { return kRaycastKeys; }
  void prepare(FrameContext& ctx, PassResources& res) override {
    const UnderwaterSetupBuffers& setup = res.read<UnderwaterSetupBuffers>("underwater_setup");
    const size_t pixels = size_t(ctx.scene().camera.width) * size_t(ctx.scene().camera.height);
    gbuffer_ = std::make_shared<UnderwaterGBuffer>();
    onDevice("raycast pass set-up", [&] {
      kernel_ = cl::Kernel(ctx.device().program(entry_.kernel_file, entry_.defines).program, "raycast");
      gbuffer_->geometry = cl::Buffer(ctx.device().context(), CL_MEM_READ_WRITE, sizeof(cl_float4) * pixels);
      gbuffer_->material = cl::Buffer(ctx.device().context(), CL_MEM_READ_WRITE, sizeof(cl_int) * pixels);
      gbuffer_->visibility = cl::Buffer(ctx.device().context(), CL_MEM_READ_WRITE, sizeof(float) * pixels);
      no_caustics_ = noCausticMap(ctx.device());
      kernel_.setArg(0, setup.params);
      kernel_.setArg(1, setup.objects);
      kernel_.setArg(3, gbuffer_->geometry);
      kernel_.setArg(4, gbuffer_->material);
      kernel_.setArg(5, gbuffer_->visibility);
    });
    res.publish("gbuffer", gbuffer_);
  }
  void execute(FrameContext& ctx, PassResources& res) override {
    const cl::Buffer* caustic_maps = underwaterCausticMaps(res);
    onDevice("raycast arguments", [&] { kernel_.setArg(2, caustic_maps ? *caustic_maps : no_caustics_); });
    // A work-item casts UW_RAYCAST_PIXELS pixels of its row.
    const size_t across = (size_t(ctx.scene().camera.width) + UW_RAYCAST_PIXELS - 1) / UW_RAYCAST_PIXELS;
    ctx.timings.push_back({"raycast", runKernel2d(ctx.device(), "raycast", kernel_, across, ctx.scene().camera.height)});
  }

 private:
  const PassPlan& entry_;
  cl::Kernel kernel_;
  cl::Buffer no_caustics_;
  std::shared_ptr<UnderwaterGBuffer> gbuffer_;
};

}  // namespace

PassDescriptor raycastDescriptor() {
  PassDescriptor d;
  d.name = "raycast";
  d.kernel_file = "raycast.cl";
  d.role = PassRole::UnderwaterGBuffer;
  d.rule = [](const Scene& scene, const Plan& so_far) -> std::optional<PassPlan> {
    if (!cameraUnderwater(scene)) return std::nullopt;
    // With caustic maps, after the caustics pass: the sun visibility reads them.
    std::vector<std::string> reads = {"underwater_setup"};
    if (so_far.produces("caustic_map")) reads.push_back("caustic_map");
    auto features = std::make_shared<UnderwaterRaycastFeatures>();
    features->objects = !scene.objects.empty();
    features->sun = sunUp(scene);
    features->caustics = underwaterCausticsMode(scene);
    return planEntry(reads, {"gbuffer"}, "camera below the surface: per-pixel hit, normal, material", features);
  };
  d.keys = kRaycastKeys;
  d.buffers = [](const Scene& s, const PassPlan& p) -> std::vector<BufferEstimate> {
    const double w = s.camera.width, h = s.camera.height;
    const std::vector<std::string> wh = {"camera.width", "camera.height"};
    // float4 hit and normal; int material and float sun visibility.
    return {{p.name, "G-buffer hits", 16 * w * h, wh, {w, h}},
            {p.name, "G-buffer materials", 4 * w * h, wh, {w, h}},
            {p.name, "G-buffer sun visibility", 4 * w * h, wh, {w, h}}};
  };
  d.cost = [](const Scene&, const PassPlan&) { return 0.7; };
  d.factory = [](const PassPlan& e, const Plan&, const Scene&, const AutoQuality&) -> std::unique_ptr<Pass> {
    return std::make_unique<RaycastNode>(e);
  };
  return d;
}

}  // namespace seasim
