// sand_share_node.cpp — "sand_share" of sand_share.cl: the discrete-ordinates model's shares the objects
// leave a view ray, of the sunlit and of the diffusely lit sand's light (common/underwater_ordinates.h,
// uwi_view_sand_shares) and of the light from above in its in-scatter (uwi_view_above_share), on a lattice
// of every quality.sand_share_step-th pixel, published as "sand_share" (UnderwaterSandShare) for
// kd_multiple to interpolate between lattice pixels on the same surface. Planned only where the shares
// are not 1 everywhere: the discrete-ordinates model with multiple scattering and objects, and a step
// above 1 (1: kd_multiple evaluates every pixel itself).
#include <memory>

#include "device/enqueue.h"
#include "passes/nodes/underwater_frame.h"
#include "passes/pixel_lattice.h"
#include "passes/underwater_setup_buffers.h"
#include "plan/pass_descriptor.h"
#include "plan/scene_facts.h"
#include "render/pass.h"
#include "scene/model_keys.h"

namespace seasim {

namespace {

// The lattice's size follows the image and the step; its values the camera, objects, sun and water.
const PassKeys kSandShareKeys = {{"camera.*", "objects.*", "quality.sand_share_step"}, kUnderwaterSetupKeys};


class SandShareNode : public Pass {
 public:
  explicit SandShareNode(const PassPlan& entry) : entry_(entry) {}
  PassKeys keys() const override { return kSandShareKeys; }
  void prepare(FrameContext& ctx, PassResources& res) override {
    const Scene& scene = ctx.scene();
    share_ = std::make_shared<UnderwaterSandShare>();
    share_->step = static_cast<int>(modelKey(scene, "quality.sand_share_step"));
    share_->width = pixelLatticeSize(scene.camera.width, share_->step);
    share_->height = pixelLatticeSize(scene.camera.height, share_->step);
    onDevice("sand_share pass set-up", [&] {
      kernel_ = cl::Kernel(ctx.device().program(entry_.kernel_file, entry_.defines).program, "sand_share");
      share_->map = cl::Buffer(ctx.device().context(), CL_MEM_READ_WRITE,
                               3 * sizeof(float) * static_cast<size_t>(share_->width) * static_cast<size_t>(share_->height));
    });
    res.publish("sand_share", share_);
  }
  void execute(FrameContext& ctx, PassResources& res) override {
    const UnderwaterSetupBuffers& setup = res.read<UnderwaterSetupBuffers>("underwater_setup");
    const UnderwaterGBuffer& g = res.read<UnderwaterGBuffer>("gbuffer");
    onDevice("sand_share pass", [&] {
      int arg = 0;
      kernel_.setArg(arg++, setup.params);
      kernel_.setArg(arg++, setup.band_table);
      kernel_.setArg(arg++, setup.objects);
      kernel_.setArg(arg++, g.geometry);
      kernel_.setArg(arg++, static_cast<cl_int>(share_->step));
      kernel_.setArg(arg++, static_cast<cl_int>(share_->width));
      kernel_.setArg(arg++, static_cast<cl_int>(share_->height));
      kernel_.setArg(arg++, share_->map);
    });
    // A work-item evaluates UW_SAND_SHARE_PIXELS lattice pixels of its row.
    const size_t across = (static_cast<size_t>(share_->width) + UW_SAND_SHARE_PIXELS - 1) / UW_SAND_SHARE_PIXELS;
    ctx.timings.push_back({"sand_share", runKernel2d(ctx.device(), "sand_share", kernel_, across, share_->height)});
  }

 private:
  const PassPlan& entry_;
  cl::Kernel kernel_;
  std::shared_ptr<UnderwaterSandShare> share_;
};

}  // namespace

PassDescriptor sandShareDescriptor() {
  PassDescriptor d;
  d.name = "sand_share";
  d.kernel_file = "sand_share.cl";
  // Every step-th pixel in x and y: 2 pays about a quarter of the share's rays, and kd_multiple evaluates
  // the pixels at silhouettes itself; 1 evaluates every pixel in kd_multiple (no lattice).
  d.scene_keys = {{"quality", "sand_share_step", ModelKey::Type::Integer, 2.0, 1.0, 8.0, ""}};
  d.rule = [](const Scene& scene, const Plan& so_far) -> std::optional<PassPlan> {
    const bool ordinates = scene.underwater.model == UnderwaterDesc::Model::DiscreteOrdinates;
    if (!cameraUnderwater(scene) || !ordinates || !scene.underwater.multiple_scattering || scene.objects.empty() ||
        modelKey(scene, "quality.sand_share_step") <= 1 || !so_far.produces("gbuffer"))
      return std::nullopt;
    return planEntry({"underwater_setup", "gbuffer"}, {"sand_share"},
                     "discrete ordinates with objects: their shares of the sand's light and of the light from above on a lattice every " +
                         std::to_string(static_cast<int>(modelKey(scene, "quality.sand_share_step"))) +
                         " pixels (quality.sand_share_step), interpolated by kd_multiple");
  };
  d.keys = kSandShareKeys;
  d.buffers = [](const Scene& s, const PassPlan& p) -> std::vector<BufferEstimate> {
    const double step = modelKey(s, "quality.sand_share_step");
    const double w = pixelLatticeSize(s.camera.width, static_cast<int>(step));
    const double h = pixelLatticeSize(s.camera.height, static_cast<int>(step));
    return {{p.name, "the objects' three shares on the lattice", 3 * 4 * w * h,
             {"camera.width", "camera.height", "quality.sand_share_step"}, {w, h}}};
  };
  d.cost = [](const Scene& s, const PassPlan&) {
    const double step = modelKey(s, "quality.sand_share_step");
    return 1.0 / (step * step);
  };
  d.factory = [](const PassPlan& e, const Plan&, const Scene&, const AutoQuality&) -> std::unique_ptr<Pass> {
    return std::make_unique<SandShareNode>(e);
  };
  return d;
}

}  // namespace seasim
