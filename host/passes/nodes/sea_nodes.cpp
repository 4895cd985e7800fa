// sea_nodes.cpp — the sea seen from above (paper 000): "sea_single" (reflection, single scattering,
// bottom; passes/sea_single_pass.h), which owns the frame's "rgb" target, and "sea_second" (the
// scattering maps of 000 eq. 6–8; passes/sea_second_pass.h), which adds into it.
#include <memory>
#include <utility>

#include "passes/nodes/standard_passes.h"
#include "passes/sea_second_pass.h"
#include "passes/sea_single_pass.h"
#include "render/radiance_target.h"

namespace seasim {

namespace {

class SeaSingleNode : public Pass {
 public:
  explicit SeaSingleNode(const PassPlan& entry) : entry_(entry) {}
  // The ocean and the caustic map come in as resources: a new one sets this pass up again.
  PassKeys keys() const override {
    return {{"camera.*", "sun.*", "sky.*", "water.*", "bottom.*", "sea.*", "spectral.*", "quality.sea_lut_size",
             "quality.sea_supersample", "quality.wave_filter"},
            {}};
  }
  void prepare(FrameContext& ctx, PassResources& res) override {
    OceanPass* ocean = res.declaresRead("ocean_maps") ? &res.read<OceanPass>("ocean_maps") : nullptr;
    const SeaBottomCaustics* caustics =
        res.declaresRead("caustic_map") ? &res.read<SeaBottomCaustics>("caustic_map") : nullptr;
    pass_ = std::make_unique<SeaSinglePass>(ctx.device(), ctx.scene(), entry_, ctx.grid(), ctx.sensor(), ocean, caustics);
    auto target = std::make_shared<RadianceTarget>();
    target->rgb = pass_->rgb();
    target->spectral = pass_->spectral();
    target->pixels = static_cast<size_t>(ctx.scene().camera.width) * static_cast<size_t>(ctx.scene().camera.height);
    target->bands = ctx.grid().size();
    res.publish("rgb", target);
  }
  void execute(FrameContext& ctx, PassResources&) override { ctx.timings.push_back({"sea_single", pass_->run()}); }

 private:
  const PassPlan& entry_;
  std::unique_ptr<SeaSinglePass> pass_;
};

class SeaSecondNode : public Pass {
 public:
  SeaSecondNode(const PassPlan& entry, AutoQuality auto_quality) : entry_(entry), auto_quality_(std::move(auto_quality)) {}
  PassKeys keys() const override {
    return {{"camera.*", "sun.*", "sky.*", "water.*", "bottom.*", "sea.*", "spectral.*", "quality.sea_nz",
             "quality.sea_nd", "quality.sea_map_size"},
            {}};
  }
  void prepare(FrameContext& ctx, PassResources& res) override {
    RadianceTarget& target = res.read<RadianceTarget>("rgb");
    const SeaSecondPass::Config config = auto_quality_.seaSecondConfig(ctx.device(), ctx.scene());
    pass_ = std::make_unique<SeaSecondPass>(ctx.device(), ctx.scene(), entry_, config, ctx.grid(), ctx.sensor(),
                                            target.rgb, ctx.scene().spectral.spectral_exr ? &target.spectral : nullptr);
  }
  void execute(FrameContext& ctx, PassResources&) override { ctx.timings.push_back({"sea_second", pass_->run()}); }

 private:
  const PassPlan& entry_;
  AutoQuality auto_quality_;
  std::unique_ptr<SeaSecondPass> pass_;
};

}  // namespace

void registerSeaPasses(PassRegistry& registry, const AutoQuality& auto_quality) {
  registry.add("sea_single",
               [](const PassPlan& e, const Plan&, const Scene&) { return std::make_unique<SeaSingleNode>(e); });
  registry.add("sea_second", [auto_quality](const PassPlan& e, const Plan&, const Scene&) {
    return std::make_unique<SeaSecondNode>(e, auto_quality);
  });
}

}  // namespace seasim
