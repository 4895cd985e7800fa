#include "passes/nodes/standard_passes.h"

namespace seasim {

PassRegistry standardPasses() {
  PassRegistry registry;
  registerOceanPass(registry);
  registerCausticsPass(registry);
  registerSeaPasses(registry);
  registerShaftsPasses(registry);
  registerUnderwaterPasses(registry);
  registerFourFlowPass(registry);
  registerCheckPass(registry);
  return registry;
}

}  // namespace seasim
