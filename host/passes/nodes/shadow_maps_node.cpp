// shadow_maps_node.cpp — "shadow_maps" of shafts.cl: one shadow map per spotlight for the planes
// method when objects cast shadows (the intervals method casts exact shadow volumes, the march exact
// shadow rays instead); run by
// the shafts node (shafts_frame.h).
#include <memory>

#include "passes/nodes/shafts_frame.h"
#include "plan/scene_facts.h"

namespace seasim {

PassDescriptor shadowMapsDescriptor() {
  PassDescriptor d;
  d.name = "shadow_maps";
  d.kernel_file = "shafts.cl";
  d.role = PassRole::ShadowMaps;
  d.rule = [](const Scene& scene, const Plan&) -> std::optional<PassPlan> {
    if (!spotlightsInAir(scene) || scene.objects.empty()) return std::nullopt;
    const auto features = shaftsFeatures(scene);
    if (!features->planes()) return std::nullopt;  // exact shadow volumes or rays
    return planEntry({"scene"}, {"shadow_maps"}, "spotlights and objects that cast shadows", features);
  };
  d.keys = kShaftsKeys;
  d.knobs = {{"shadow_map_size", 512}};
  d.buffers = [d](const Scene& s, const PassPlan& p) -> std::vector<BufferEstimate> {
    const double S = d.knob(s, "shadow_map_size"), lights = static_cast<double>(s.spotlights.size());
    return {{p.name, "shadow maps (one per spotlight)", 4 * lights * S * S,
             {"spotlights (count)", "quality.shadow_map_size", "quality.shadow_map_size"}, {lights, S, S}}};
  };
  d.cost = [](const Scene&, const PassPlan&) { return 1.0; };
  d.factory = [](const PassPlan&, const Plan&, const Scene&, const AutoQuality&) -> std::unique_ptr<Pass> {
    return std::make_unique<InsideShaftsNode>();
  };
  return d;
}

}  // namespace seasim
