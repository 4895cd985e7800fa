// shafts_method.h — which integrator the spotlight shafts use, read by the scene parser,
// the planner and the shafts pass:
//   "intervals"  per pixel and lamp, the exact lit stretches of the view ray (analytic shadow volumes,
//                no shadow maps) integrated in the lamp's angle (kernels/common/shafts_intervals.h);
//   "planes"     paper 001's sampling planes with shadow-map sub-samples, which suit GPU texture units;
//   "march"      per pixel and lamp, quality.shafts_march_steps midpoint steps in the lamp's angle with an
//                exact shadow ray at each (the CPU reference's method, host/reference/shafts_reference.h,
//                in the kernel's float; kernels/common/shafts_render.h shafts_lamp_march).
// quality.shafts_method absent: the rule — intervals while the scene's objects fit the kernel's per-pixel
// list of lit stretches, else planes. Measured on PoCL (results/BENCHMARKS.md "Spotlight shafts in air":
// spot_sphere, stage and tests/perf/shafts_many_objects.toml), that rule gives the methods' shared error
// floor within 18 % of the cheapest setting for errors up to about 0.3 levels; it does not read
// quality.shafts_error_budget, and for a budget near 1 level the march at a few steps is 2.2-2.5x
// cheaper on two of the three scenes. "auto": the method is measured on the device at that budget
// (host/quality/shafts_method_auto.h) and written into the scene before it is planned; a scene planned
// before that (`seasim plan` with nothing cached) gets the rule.
#pragma once
#include "scene/scene.h"

namespace seasim {

// SHAFTS_MAX_PIECES - 1 (kernels/common/shafts_intervals.h): each object's shadow splits at most one stretch.
constexpr int kShaftsIntervalsMaxObjects = 15;
// Intervals method defaults: the widest quadrature panel in degrees of the lamp's angle, and in
// light-map texels (chosen from the error-time sweep in results/BENCHMARKS.md).
constexpr double kShaftsPanelDegDefault = 4.0;
constexpr double kShaftsPanelTexelsDefault = 2.0;
// March method: steps per ray and lamp (results/BENCHMARKS.md "Spotlight shafts in air").
constexpr int kShaftsMarchStepsDefault = 20;

// The integrator, as quality.shafts_method stores it (Knob.value).
enum class ShaftsMethod { Planes = 0, Intervals = 1, March = 2 };

inline ShaftsMethod shaftsMethod(const Scene& scene) {
  const auto it = scene.quality.find("shafts_method");
  if (it == scene.quality.end() || it->second.automatic)
    return static_cast<int>(scene.objects.size()) <= kShaftsIntervalsMaxObjects ? ShaftsMethod::Intervals
                                                                                  : ShaftsMethod::Planes;
  return static_cast<ShaftsMethod>(static_cast<int>(it->second.value));
}


}  // namespace seasim
