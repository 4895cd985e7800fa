// shafts_nodes.cpp — spotlight shafts in air (paper 001, passes/shafts_pass.h). The plan lists three
// entries on shafts.cl: "raycast" and "shadow_maps" name work that ShaftsPass::run does inside the
// shafts kernel's launch sequence (the per-pixel ray cast is in the shafts kernel itself; the shadow
// maps are enqueued just before it), so their nodes hold nothing; "shafts" sets up the pass (and its
// "auto" (n, m) search), runs it, and reports the shadow-map and shafts kernel times.
#include <memory>
#include <utility>

#include "passes/nodes/standard_passes.h"
#include "passes/shafts_pass.h"
#include "render/radiance_target.h"

namespace seasim {

namespace {

const std::vector<std::string> kShaftsKeys = {
    "camera.*",         "spotlights.*",           "objects.*",           "air.*", "spectral.*",
    "quality.shafts_exact", "quality.shafts_planes", "quality.shafts_subplanes", "quality.shafts_error_budget",
    "quality.shafts_table_size", "quality.shadow_map_size", "quality.shafts_method", "quality.shafts_panel_deg",
    "quality.shafts_panel_texels"};

// An entry whose work the shafts node does (see the file comment).
class InsideShaftsNode : public Pass {
 public:
  PassKeys keys() const override { return {kShaftsKeys, {}}; }
  void prepare(FrameContext&, PassResources&) override {}
  void execute(FrameContext&, PassResources&) override {}
};

class ShaftsNode : public Pass {
 public:
  ShaftsNode(const PassPlan& entry, bool shadow_maps, AutoQuality auto_quality)
      : entry_(entry), shadow_maps_(shadow_maps), auto_quality_(std::move(auto_quality)) {}
  PassKeys keys() const override { return {kShaftsKeys, {}}; }
  void prepare(FrameContext& ctx, PassResources& res) override {
    const ShaftsPass::Config config = auto_quality_.shaftsConfig(ctx.device(), ctx.scene(), entry_);
    pass_ = std::make_unique<ShaftsPass>(ctx.device(), ctx.scene(), entry_, config);
    auto target = std::make_shared<RadianceTarget>();
    target->rgb = pass_->rgb();
    target->pixels = static_cast<size_t>(ctx.scene().camera.width) * static_cast<size_t>(ctx.scene().camera.height);
    res.publish("rgb", target);
  }
  void execute(FrameContext& ctx, PassResources&) override {
    pass_->run();
    if (shadow_maps_) ctx.timings.push_back({"shadow_maps", pass_->shadowMapMs()});
    ctx.timings.push_back({"shafts", pass_->shaftsMs()});
  }

 private:
  const PassPlan& entry_;
  bool shadow_maps_;
  AutoQuality auto_quality_;
  std::unique_ptr<ShaftsPass> pass_;
};

}  // namespace

void registerShaftsPasses(PassRegistry& registry, const AutoQuality& auto_quality) {
  registry.add("raycast", "shafts.cl",
               [](const PassPlan&, const Plan&, const Scene&) { return std::make_unique<InsideShaftsNode>(); });
  registry.add("shadow_maps",
               [](const PassPlan&, const Plan&, const Scene&) { return std::make_unique<InsideShaftsNode>(); });
  registry.add("shafts", [auto_quality](const PassPlan& e, const Plan& plan, const Scene&) {
    return std::make_unique<ShaftsNode>(e, plan.hasPass("shadow_maps"), auto_quality);
  });
}

}  // namespace seasim
