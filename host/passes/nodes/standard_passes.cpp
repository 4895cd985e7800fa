#include "passes/nodes/standard_passes.h"

namespace seasim {

PassRegistry standardPasses(const AutoQuality& auto_quality) {
  PassRegistry registry;
  registerOceanPass(registry);
  registerCausticsPass(registry);
  registerSeaPasses(registry, auto_quality);
  registerShaftsPasses(registry, auto_quality);
  registerUnderwaterPasses(registry);
  registerFourFlowPass(registry);
  registerCheckPass(registry);
  return registry;
}

}  // namespace seasim
