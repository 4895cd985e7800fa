// plan.h — the planner: scene -> ordered passes with their kernel file and feature defines
// (DESIGN.md "Leave out what a scene does not need"). `seasim plan SCENE` prints toText().
#pragma once
#include <string>
#include <vector>

#include "scene/scene.h"

namespace seasim {

struct PassPlan {
  std::string name;                  // "sea_single"
  std::string kernel_file;           // relative to kernels/, e.g. "sea_single.cl"
  std::vector<std::string> defines;  // "SEASIM_HAS_BOTTOM=1"
  std::vector<std::string> reads;    // resources the pass reads ("scene", "gbuffer", ...)
  std::vector<std::string> writes;   // resources it writes ("rgb", ...)
  std::string why;                   // the scene content that made the planner add it
  bool implemented = true;           // false: planned but the model is not built yet
  std::string missing;               // for !implemented: which issue brings it
};

struct Plan {
  std::vector<PassPlan> passes;
  bool hasPass(const std::string& name) const;
  const PassPlan* find(const std::string& name) const;
  std::vector<std::string> kernelFiles() const;  // distinct, in pass order
  std::string toText() const;                    // one pass per line
};

Plan makePlan(const Scene& scene);

}  // namespace seasim
