#include "render/pass_registry.h"

#include "util/error.h"

namespace seasim {

bool keyMatches(const std::string& pattern, const std::string& key) {
  // "objects[2].center" -> section "objects"; a key without a dot is its own section.
  const size_t dot = key.find('.');
  std::string section = key.substr(0, dot);
  const size_t bracket = section.find('[');
  if (bracket != std::string::npos) section = section.substr(0, bracket);
  if (pattern.size() > 2 && pattern.compare(pattern.size() - 2, 2, ".*") == 0) {
    return section == pattern.substr(0, pattern.size() - 2);
  }
  std::string normal = section + (dot == std::string::npos ? "" : key.substr(dot));
  return pattern == key || pattern == normal;
}

bool anyKeyMatches(const std::string& pattern, const std::vector<std::string>& keys) {
  for (const std::string& key : keys)
    if (keyMatches(pattern, key)) return true;
  return false;
}

void PassRegistry::add(const std::string& name, Factory factory) { factories_[name] = std::move(factory); }

void PassRegistry::add(const std::string& name, const std::string& kernel_file, Factory factory) {
  factories_[name + "@" + kernel_file] = std::move(factory);
}

std::unique_ptr<Pass> PassRegistry::make(const PassPlan& entry, const Plan& plan, const Scene& scene) const {
  auto it = factories_.find(entry.name + "@" + entry.kernel_file);
  if (it == factories_.end()) it = factories_.find(entry.name);
  if (it == factories_.end()) {
    std::string known;
    for (const auto& [name, f] : factories_) known += (known.empty() ? "" : ", ") + name;
    throw RuntimeError("renderer: no pass is registered for plan entry '" + entry.name + "' (registered: " + known +
                       ")");
  }
  return it->second(entry, plan, scene);
}

std::vector<std::string> PassRegistry::names() const {
  std::vector<std::string> out;
  for (const auto& [name, f] : factories_) out.push_back(name);
  return out;
}

}  // namespace seasim
