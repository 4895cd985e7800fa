// pass_list.cpp — every shipped model's descriptor, in the order its passes run. A new model adds
// its node file (host/passes/nodes/<model>_node.cpp, which defines <model>Descriptor()) and one line
// here, X(<model>Descriptor), at its place in the order.
#include "plan/pass_descriptor.h"

// Order matters where one pass reads what another writes: the ocean before its caustics, the
// underwater set-up before every underwater pass, the caustics before the G-buffer that reads them,
// the shading before what adds into its "rgb".
#define SEASIM_SHIPPED_PASSES(X)        \
  X(shaftsRaycastDescriptor)            \
  X(oceanDescriptor)                    \
  X(underwaterSetupDescriptor)          \
  X(shadowMapsDescriptor)               \
  X(causticsDescriptor)                 \
  X(raycastDescriptor)                  \
  X(froxelDescriptor)                   \
  X(sandShareDescriptor)                \
  X(fourFlowDescriptor)                 \
  X(seaSingleDescriptor)                \
  X(seaSecondDescriptor)                \
  X(whitecapsDescriptor)                \
  X(shaftsDescriptor)                   \
  X(kdMultipleDescriptor)               \
  X(froxelBandsDescriptor)              \
  X(waterSpreadDescriptor)              \
  X(underwaterLampsDescriptor)          \
  X(geometryLayersDescriptor)           \
  X(effectiveCoefficientsDescriptor)    \
  X(lightProfileDescriptor)             \
  X(nonfiniteCheckDescriptor)

namespace seasim {

#define SEASIM_DECLARE_DESCRIPTOR(make) PassDescriptor make();
SEASIM_SHIPPED_PASSES(SEASIM_DECLARE_DESCRIPTOR)
#undef SEASIM_DECLARE_DESCRIPTOR

const std::vector<PassDescriptor>& passDescriptors() {
#define SEASIM_LIST_DESCRIPTOR(make) make(),
  static const std::vector<PassDescriptor> list = {SEASIM_SHIPPED_PASSES(SEASIM_LIST_DESCRIPTOR)};
#undef SEASIM_LIST_DESCRIPTOR
  return list;
}

}  // namespace seasim
