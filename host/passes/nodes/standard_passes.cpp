#include "passes/nodes/standard_passes.h"

#include "plan/pass_descriptor.h"

namespace seasim {

PassRegistry standardPasses(const AutoQuality& auto_quality) {
  PassRegistry registry;
  for (const PassDescriptor& d : passDescriptors()) {
    registry.add(d.name, d.kernel_file,
                 [factory = d.factory, auto_quality](const PassPlan& entry, const Plan& plan, const Scene& scene) {
                   return factory(entry, plan, scene, auto_quality);
                 });
  }
  if (auto_quality.plan_choices) registry.setPlanChoices(auto_quality.plan_choices);
  return registry;
}

}  // namespace seasim
