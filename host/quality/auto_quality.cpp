#include "quality/auto_quality.h"

#include "passes/nodes/standard_passes.h"
#include "quality/sea_auto.h"
#include "quality/shafts_auto.h"
#include "quality/shafts_method_auto.h"

namespace seasim {

AutoQuality searchedAutoQuality() {
  AutoQuality q;
  q.shafts = shaftsConfigWithAuto;
  q.sea_second = seaSecondConfigWithAuto;
  q.plan_choices = sceneWithMeasuredShaftsMethod;
  return q;
}

PassRegistry shippedPasses() { return standardPasses(searchedAutoQuality()); }

}  // namespace seasim
