// auto_quality.h — the passes seasim ships with their "auto" quality knobs searched per scene
// (shafts_auto.h, sea_auto.h). The searches measure the fast path against the brute-force
// references, so they live here and reach the passes through passes/auto_quality.h: host/passes
// and host/render include nothing from host/reference.
#pragma once
#include "passes/auto_quality.h"
#include "render/pass_registry.h"

namespace seasim {

// shaftsConfigWithAuto and seaSecondConfigWithAuto, as the passes' hook; sceneWithMeasuredShaftsMethod
// as the Renderer's plan choice.
AutoQuality searchedAutoQuality();

// standardPasses(searchedAutoQuality()): what every command renders with.
PassRegistry shippedPasses();

}  // namespace seasim
