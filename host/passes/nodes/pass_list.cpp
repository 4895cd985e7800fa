// pass_list.cpp — every shipped model's descriptor, in the order its passes run. A new model adds
// its node file (host/passes/nodes/<model>_node.cpp) and one line here.
#include "plan/pass_descriptor.h"

namespace seasim {

PassDescriptor shaftsRaycastDescriptor();
PassDescriptor oceanDescriptor();
PassDescriptor shadowMapsDescriptor();
PassDescriptor causticsDescriptor();
PassDescriptor raycastDescriptor();
PassDescriptor froxelDescriptor();
PassDescriptor fourFlowDescriptor();
PassDescriptor seaSingleDescriptor();
PassDescriptor seaSecondDescriptor();
PassDescriptor shaftsDescriptor();
PassDescriptor kdMultipleDescriptor();
PassDescriptor waterSpreadDescriptor();
PassDescriptor underwaterLampsDescriptor();
PassDescriptor geometryLayersDescriptor();
PassDescriptor effectiveCoefficientsDescriptor();
PassDescriptor nonfiniteCheckDescriptor();

const std::vector<PassDescriptor>& passDescriptors() {
  // Order matters where one pass reads what another writes: the ocean before its caustics, the
  // caustics before the G-buffer that reads them, the shading before what adds into its "rgb".
  static const std::vector<PassDescriptor> list = {
      shaftsRaycastDescriptor(), oceanDescriptor(),      shadowMapsDescriptor(),   causticsDescriptor(),
      raycastDescriptor(),       froxelDescriptor(),     fourFlowDescriptor(),     seaSingleDescriptor(),
      seaSecondDescriptor(),     shaftsDescriptor(),     kdMultipleDescriptor(),   waterSpreadDescriptor(),
      underwaterLampsDescriptor(), geometryLayersDescriptor(), effectiveCoefficientsDescriptor(),
      nonfiniteCheckDescriptor()};
  return list;
}

}  // namespace seasim
