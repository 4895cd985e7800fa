// shafts_raycast_node.cpp — "raycast" of shafts.cl: the analytic objects cast per pixel inside the
// shafts kernel (shafts_frame.h), planned so that `seasim plan` shows the work.
#include <memory>

#include "passes/nodes/shafts_frame.h"
#include "plan/scene_facts.h"

namespace seasim {

PassDescriptor shaftsRaycastDescriptor() {
  PassDescriptor d;
  d.name = "raycast";
  d.kernel_file = "shafts.cl";
  d.rule = [](const Scene& scene, const Plan&) -> std::optional<PassPlan> {
    if (scene.objects.empty() || !spotlightsInAir(scene)) return std::nullopt;
    return planEntry({"scene"}, {"gbuffer"}, "scene has objects");
  };
  d.keys = kShaftsKeys;
  d.buffers = [](const Scene&, const PassPlan&) { return std::vector<BufferEstimate>{}; };
  d.cost = [](const Scene&, const PassPlan&) { return 0.7; };
  d.factory = [](const PassPlan&, const Plan&, const Scene&, const AutoQuality&) -> std::unique_ptr<Pass> {
    return std::make_unique<InsideShaftsNode>();
  };
  return d;
}

}  // namespace seasim
