// check_node.cpp — "nonfinite_check": counts NaN/Inf in the frame's radiance target (check.cl), so a
// run fails loudly instead of writing a broken image.
#include <memory>

#include "passes/nodes/standard_passes.h"
#include "passes/nonfinite_check.h"
#include "plan/pass_descriptor.h"
#include "render/radiance_target.h"

namespace seasim {

namespace {

class CheckNode : public Pass {
 public:
  PassKeys keys() const override { return {}; }  // runs whenever the image it reads is written
  void prepare(FrameContext& ctx, PassResources&) override { check_ = std::make_unique<NonfiniteCheck>(ctx.device()); }
  void execute(FrameContext& ctx, PassResources& res) override {
    RadianceTarget& target = res.read<RadianceTarget>("rgb");
    double ms = 0;
    long long count = check_->count(target.rgb, 3 * target.pixels, &ms);
    if (ctx.scene().spectral.spectral_exr && target.hasSpectral()) {
      double spectral_ms = 0;
      count += check_->count(target.spectral, target.pixels * target.bands, &spectral_ms);
      ms += spectral_ms;
    }
    ctx.nonfinite = count;
    ctx.timings.push_back({"nonfinite_check", ms});
  }

 private:
  std::unique_ptr<NonfiniteCheck> check_;
};

}  // namespace

PassDescriptor nonfiniteCheckDescriptor() {
  PassDescriptor d;
  d.name = "nonfinite_check";
  d.kernel_file = "check.cl";
  d.role = PassRole::Check;
  d.rule = [](const Scene&, const Plan&) -> std::optional<PassPlan> {
    return planEntry({"rgb"}, {"status"}, "always: kernels must never emit NaN/Inf");
  };
  // Finite-only maths may assume away the very values it counts.
  d.fast_math = false;
  d.buffers = [](const Scene&, const PassPlan& p) {
    return std::vector<BufferEstimate>{{p.name, "NaN/Inf counter", double(sizeof(cl_uint)), {}, {}}};
  };
  d.cost = [](const Scene&, const PassPlan&) { return 0.01; };
  d.factory = [](const PassPlan&, const Plan&, const Scene&, const AutoQuality&) -> std::unique_ptr<Pass> {
    return std::make_unique<CheckNode>();
  };
  return d;
}

}  // namespace seasim
