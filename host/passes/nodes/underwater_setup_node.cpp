// underwater_setup_node.cpp — "underwater_setup": the underwater frame's shared set-up, made once per
// change of the scene and published as "underwater_setup" (passes/underwater_setup_buffers.h): the
// camera, sun, water, bands, objects and sky of makeUnderwaterSetup on the host, and their parameter
// blocks on the device. The passes of the frame read it; none of them builds it. No kernel.
#include <algorithm>
#include <memory>

#include "passes/nodes/underwater_frame.h"
#include "passes/underwater_setup_buffers.h"
#include "plan/pass_descriptor.h"
#include "plan/scene_facts.h"
#include "render/pass.h"

namespace seasim {

namespace {

// The sizes of its buffers (image, bands, objects, sky) follow the first list; every other key it
// folds in rewrites the same buffers (the camera's frame and field of view among them).
const std::vector<std::string> kSetupRerunKeys = [] {
  std::vector<std::string> keys = kUnderwaterSetupKeys;
  keys.push_back("camera.*");
  return keys;
}();
const PassKeys kSetupKeys = {{"camera.width", "camera.height", "spectral.*", "objects.*", "sky.model", "sky.image"},
                             kSetupRerunKeys};

class UnderwaterSetupNode : public Pass {
 public:
  PassKeys keys() const override { return kSetupKeys; }
  void prepare(FrameContext& ctx, PassResources& res) override {
    publish(res, ctx.device(), makeUnderwaterSetup(ctx.scene(), ctx.grid(), ctx.sensor()));
    fresh_ = true;
  }
  void execute(FrameContext& ctx, PassResources& res) override {
    if (fresh_) {
      fresh_ = false;
      return;
    }
    // A change of surface.time alone moves the waves' phase, one number of the block (the caustics'
    // time); remaking the rest, the discrete-ordinates model's per-band tables above all, would cost about
    // half a second per frame.
    // A camera moved at the same depth (the preview's orbit) keeps the tables too (moveUnderwaterCamera).
    const std::vector<std::string>& changed = ctx.changedKeys();
    auto only = [&](auto&& pred) { return !changed.empty() && std::all_of(changed.begin(), changed.end(), pred); };
    const bool time_only = only([](const std::string& k) { return k == "surface.time"; });
    const bool camera_only = only([](const std::string& k) { return k.rfind("camera.", 0) == 0; });
    UnderwaterSetup next = buffers_->setup;
    if (time_only) {
      next.params.time = static_cast<float>(ctx.scene().surface.time);  // as makeUnderwaterSetup sets it
    } else if (!camera_only || !moveUnderwaterCamera(next, ctx.scene())) {
      next = makeUnderwaterSetup(ctx.scene(), ctx.grid(), ctx.sensor());
    }
    if (buffers_->update(ctx.device(), std::move(next))) return;
    publish(res, ctx.device(), std::move(next));  // other sizes: new buffers, and the readers set up again
  }

 private:
  void publish(PassResources& res, Device& device, UnderwaterSetup setup) {
    buffers_ = std::make_shared<UnderwaterSetupBuffers>(device, std::move(setup));
    res.publish("underwater_setup", buffers_);
  }
  std::shared_ptr<UnderwaterSetupBuffers> buffers_;
  bool fresh_ = false;
};

}  // namespace

PassDescriptor underwaterSetupDescriptor() {
  PassDescriptor d;
  d.name = "underwater_setup";
  d.kernel_file = "";  // host only: tables and their upload
  d.rule = [](const Scene& scene, const Plan&) -> std::optional<PassPlan> {
    if (!cameraUnderwater(scene)) return std::nullopt;
    return planEntry({"scene"}, {"underwater_setup"},
                     "camera below the surface: camera, sun, water, bands, objects and sky as the underwater "
                     "passes' parameter blocks");
  };
  d.keys = kSetupKeys;
  d.fast_math = false;  // no kernel
  // Parameter blocks of a few kB per band: below the estimate's resolution.
  d.buffers = [](const Scene&, const PassPlan&) { return std::vector<BufferEstimate>{}; };
  d.cost = [](const Scene&, const PassPlan&) { return 0.0; };  // per frame, not per pixel
  d.factory = [](const PassPlan&, const Plan&, const Scene&, const AutoQuality&) -> std::unique_ptr<Pass> {
    return std::make_unique<UnderwaterSetupNode>();
  };
  return d;
}

}  // namespace seasim
