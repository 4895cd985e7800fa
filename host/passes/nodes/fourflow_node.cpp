// fourflow_node.cpp — shallow water with a visible bottom (paper 003): "fourflow"
// (passes/fourflow_pass.h), which owns the frame's "rgb" target. The (l, h) tables are built in
// prepare (the paper's preprocessing stage) and timed there; execute runs the frame kernel.
#include <memory>

#include "passes/fourflow_pass.h"
#include "passes/nodes/standard_passes.h"
#include "render/radiance_target.h"

namespace seasim {

namespace {

class FourFlowNode : public Pass {
 public:
  explicit FourFlowNode(const PassPlan& entry) : entry_(entry) {}
  PassKeys keys() const override {
    // surface.*: with waves, R and T are averaged over the FFT patch (003 eq. 10) when the pass is set up.
    return {{"camera.*", "sun.*", "sky.*", "water.*", "surface.*", "bottom.*", "shallow.*", "spectral.*",
             "quality.fourflow_table_size"},
            {}};
  }
  void prepare(FrameContext& ctx, PassResources& res) override {
    pass_ = std::make_unique<FourFlowPass>(ctx.device(), ctx.scene(), entry_, ctx.grid(), ctx.sensor());
    if (pass_->tableMs() > 0) ctx.timings.push_back({"fourflow_tables", pass_->tableMs()});
    auto target = std::make_shared<RadianceTarget>();
    target->rgb = pass_->rgb();
    target->pixels = static_cast<size_t>(ctx.scene().camera.width) * static_cast<size_t>(ctx.scene().camera.height);
    target->spectral = pass_->spectral();  // null unless spectral.spectral_exr
    target->bands = ctx.grid().size();
    res.publish("rgb", target);
  }
  void execute(FrameContext& ctx, PassResources&) override { ctx.timings.push_back({"fourflow", pass_->run()}); }

 private:
  const PassPlan& entry_;
  std::unique_ptr<FourFlowPass> pass_;
};

}  // namespace

void registerFourFlowPass(PassRegistry& registry) {
  registry.add("fourflow",
               [](const PassPlan& e, const Plan&, const Scene&) { return std::make_unique<FourFlowNode>(e); });
}

}  // namespace seasim
