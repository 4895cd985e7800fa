// pass_registry.h — passes by plan name. The renderer asks the registry for the pass of each plan
// entry; the shipped registry is built from the models' descriptors (plan/pass_descriptor.h,
// passes/nodes/standard_passes.h), so a new model never touches the renderer.
#pragma once
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "render/pass.h"

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

 private:
  std::map<std::string, Factory> factories_;  // by "name" or "name@kernel_file"
};

}  // namespace seasim
