// auto_quality.h — how a pass gets the settings of its "auto" quality knobs without depending on
// the brute-force references. The searches (host/quality/shafts_auto.h, sea_auto.h) compare the
// fast path with a reference; they live outside host/passes and come in through this hook, which
// host/quality/auto_quality.h fills. An empty hook gives each "auto" knob its placeholder
// (ShaftsPass::configFromScene: n = 30, m = 6; SeaSecondPass::configFromScene: n_z = 8, n_d = 512).
#pragma once
#include <functional>
#include <optional>

#include "device/device.h"
#include "passes/sea_second_pass.h"
#include "passes/shafts_pass.h"
#include "plan/plan.h"
#include "scene/scene.h"

namespace seasim {

struct AutoQuality {
  // The shafts settings for `scene` with its "auto" (n, m) chosen; `plan` is the "shafts" entry.
  std::function<ShaftsPass::Config(Device&, const Scene&, const PassPlan&)> shafts;
  // The sea second-order settings for `scene` with its "auto" knobs chosen.
  std::function<SeaSecondPass::Config(Device&, const Scene&)> sea_second;
  // The scene with the choices its plan leaves to measurement made (PassRegistry::PlanChoices).
  std::function<std::optional<Scene>(Device&, const Scene&)> plan_choices;

  ShaftsPass::Config shaftsConfig(Device& device, const Scene& scene, const PassPlan& plan) const {
    return shafts ? shafts(device, scene, plan) : ShaftsPass::configFromScene(scene);
  }
  SeaSecondPass::Config seaSecondConfig(Device& device, const Scene& scene) const {
    return sea_second ? sea_second(device, scene) : SeaSecondPass::configFromScene(scene);
  }
};

}  // namespace seasim
