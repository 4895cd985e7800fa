// pass_registry.h — passes by plan name. The renderer asks the registry for the pass of each plan
// entry; the shipped registry is built from the models' descriptors (plan/pass_descriptor.h,
// passes/nodes/standard_passes.h), so a new model never touches the renderer.
#pragma once
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "device/device.h"
#include "render/pass.h"
#include "scene/scene.h"

namespace seasim {

class PassRegistry {
 public:
  // Makes the pass for one plan entry; may look at the entry (kernel file, defines), the whole plan
  // (passes that share one kernel object) and the scene.
  using Factory = std::function<std::unique_ptr<Pass>(const PassPlan&, const Plan&, const Scene&)>;

  void add(const std::string& name, Factory factory);
  // For a plan name that two models share ("raycast" of raycast.cl and of shafts.cl): this factory
  // for entries of that kernel file, the plain one for the others.
  void add(const std::string& name, const std::string& kernel_file, Factory factory);
  // RuntimeError naming the pass and the registered names when there is none.
  std::unique_ptr<Pass> make(const PassPlan& entry, const Plan& plan, const Scene& scene) const;
  std::vector<std::string> names() const;

  // The scene with the choices its plan leaves to a measurement on the device made (the shafts'
  // quality.shafts_method = "auto", host/quality/shafts_method_auto.h); nullopt: nothing to choose.
  // The Renderer plans the scene this returns.
  using PlanChoices = std::function<std::optional<Scene>(Device&, const Scene&)>;
  void setPlanChoices(PlanChoices choices) { plan_choices_ = std::move(choices); }
  std::optional<Scene> planChoices(Device& device, const Scene& scene) const {
    return plan_choices_ ? plan_choices_(device, scene) : std::nullopt;
  }

 private:
  std::map<std::string, Factory> factories_;  // by "name" or "name@kernel_file"
  PlanChoices plan_choices_;
};

}  // namespace seasim
