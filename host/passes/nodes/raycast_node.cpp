// raycast_node.cpp — "raycast" of raycast.cl: the underwater frame's G-buffer (002 §4.3.2: hit
// distance, normal, material, sun visibility). raycast.cl and kd_multiple.cl share one
// UnderwaterPass (passes/underwater_pass.h), published as "gbuffer". A change of sun, water, time or
// knobs rewrites its parameter blocks in place (UnderwaterPass::update) and runs the kernels again;
// only the camera, the objects or the band count set it up again.
#include <memory>

#include "passes/nodes/underwater_frame.h"
#include "passes/underwater_features.h"
#include "plan/pass_descriptor.h"
#include "plan/scene_facts.h"
#include "render/pass.h"
#include "util/error.h"

namespace seasim {

namespace {

// Sizes (image, bands, objects) and the kernels' defines come from the first list. sky.model and
// sky.image: kd_multiple's SEASIM_SKY_MODEL and the size of its sky buffer.
const PassKeys kRaycastKeys = {{"camera.*", "spectral.*", "objects.*", "sky.model", "sky.image"},
                               kUnderwaterSetupKeys};

class RaycastNode : public Pass {
 public:
  RaycastNode(const PassPlan& entry, const PassPlan& kd) : entry_(entry), kd_(kd) {}
  PassKeys keys() const override { return kRaycastKeys; }
  void prepare(FrameContext& ctx, PassResources& res) override {
    auto gbuffer = std::make_shared<UnderwaterGBuffer>();
    gbuffer->pass = std::make_unique<UnderwaterPass>(ctx.device(), ctx.underwaterSetup(), entry_, kd_,
                                                     ctx.scene().spectral.spectral_exr);
    gbuffer->setup_version = ctx.setupVersion();
    res.publish("gbuffer", gbuffer);
  }
  void execute(FrameContext& ctx, PassResources& res) override {
    UnderwaterGBuffer& gbuffer = res.read<UnderwaterGBuffer>("gbuffer");
    gbuffer.sync(ctx);
    ctx.timings.push_back({"raycast", gbuffer.pass->runRaycast(underwaterCausticMaps(res))});
  }

 private:
  const PassPlan& entry_;
  const PassPlan& kd_;
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
    std::vector<std::string> reads = {"scene"};
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
  d.factory = [](const PassPlan& e, const Plan& plan, const Scene&, const AutoQuality&) -> std::unique_ptr<Pass> {
    const PassPlan* kd = plan.find("kd_multiple");
    if (!kd) throw RuntimeError("plan: the underwater raycast pass needs a kd_multiple pass in the same plan");
    return std::make_unique<RaycastNode>(e, *kd);
  };
  return d;
}

}  // namespace seasim
