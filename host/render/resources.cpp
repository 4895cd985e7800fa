#include "render/resources.h"

#include <algorithm>

namespace seasim {

void Resources::touch(const std::string& name) {
  const auto it = entries_.find(name);
  if (it != entries_.end()) it->second.version = ++counter_;
}

uint64_t Resources::generation(const std::string& name) const {
  const auto it = entries_.find(name);
  return it == entries_.end() ? 0 : it->second.generation;
}

uint64_t Resources::version(const std::string& name) const {
  const auto it = entries_.find(name);
  return it == entries_.end() ? 0 : it->second.version;
}

bool PassResources::declaresRead(const std::string& name) const {
  return std::find(reads_.begin(), reads_.end(), name) != reads_.end();
}

void PassResources::check(const std::string& name, bool reading) const {
  const bool written = std::find(writes_.begin(), writes_.end(), name) != writes_.end();
  if (written || (reading && declaresRead(name))) return;
  throw RuntimeError("renderer: pass '" + pass_ + "' " + (reading ? "reads" : "writes") + " resource '" + name +
                     "' that its plan entry does not declare (plan/plan.cpp)");
}

}  // namespace seasim
