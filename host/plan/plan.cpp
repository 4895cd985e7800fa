#include "plan/plan.h"

#include <algorithm>
#include <sstream>

#include "plan/pass_descriptor.h"
#include "util/error.h"

namespace seasim {

void PassPlan::missingFeatures() const {
  throw RuntimeError("plan: the " + name + " entry (kernels/" + kernel_file + ") carries " +
                     (features ? "the features of another pass" : "no features") +
                     "; plan it with makePlan or give it its pass's features struct");
}

bool Plan::hasPass(const std::string& name) const { return find(name) != nullptr; }

const PassPlan* Plan::find(const std::string& name) const {
  for (const auto& p : passes)
    if (p.name == name) return &p;
  return nullptr;
}

bool Plan::produces(const std::string& resource) const {
  for (const auto& p : passes)
    if (std::find(p.writes.begin(), p.writes.end(), resource) != p.writes.end()) return true;
  return false;
}

const PassPlan* Plan::writerOf(const std::string& resource) const {
  for (const auto& p : passes)
    if (std::find(p.writes.begin(), p.writes.end(), resource) != p.writes.end()) return &p;
  return nullptr;
}

std::vector<std::string> Plan::kernelFiles() const {
  std::vector<std::string> files;
  for (const auto& p : passes)
    if (!p.kernel_file.empty() && std::find(files.begin(), files.end(), p.kernel_file) == files.end())
      files.push_back(p.kernel_file);
  return files;
}

std::string Plan::toText() const {
  std::ostringstream s;
  int i = 1;
  for (const auto& p : passes) {
    s << i++ << ". " << p.name << "  " << (p.kernel_file.empty() ? "(host only)" : "kernels/" + p.kernel_file) << " ";
    if (p.defines.empty()) s << " (no defines)";
    for (const auto& d : p.defines) s << " -D" << d;
    // The typed features the defines were generated from (plan/features.h).
    if (p.features) s << "  | features: " << featuresText(p.features.get());
    s << "  | reads:";
    for (const auto& r : p.reads) s << " " << r;
    s << "  writes:";
    for (const auto& w : p.writes) s << " " << w;
    s << "  | " << p.why;
    if (!p.implemented) s << "  [not implemented yet: " << p.missing << "]";
    s << "\n";
  }
  return s.str();
}

bool fastMathFor(const Scene& scene) {
  const auto fast = scene.quality.find("fast_math");
  if (fast == scene.quality.end()) return false;
  if (!fast->second.automatic) return fast->second.value != 0;
  const bool sea_view = scene.water.present && scene.camera.position.y >= 0.0;
  const bool waves = scene.surface.type == SurfaceDesc::Type::Fft && scene.water.present;
  return !(sea_view && waves);
}

// Each model's rule decides whether the scene needs it (plan/pass_descriptor.h); the order of the
// list is the order the passes run in. quality.fast_math marks the passes whose descriptors allow
// relaxed maths (the define tells Device::program and the kernels).
Plan makePlan(const Scene& scene) {
  Plan plan;
  const bool fast_math = fastMathFor(scene);
  for (const PassDescriptor& descriptor : passDescriptors()) {
    std::optional<PassPlan> entry = descriptor.rule(scene, plan);
    if (!entry) continue;
    entry->name = descriptor.name;
    entry->kernel_file = descriptor.kernel_file;
    entry->defines = kernelDefines(entry->features.get(), fast_math && descriptor.fast_math);
    plan.passes.push_back(std::move(*entry));
  }
  return plan;
}

}  // namespace seasim
