#include "plan/pass_descriptor.h"

#include <algorithm>

#include "util/error.h"

namespace seasim {

namespace {

const KnobDefault& knobDefault(const PassDescriptor& d, const char* name) {
  for (const KnobDefault& k : d.knobs)
    if (std::string(k.name) == name) return k;
  throw RuntimeError("the " + d.name + " pass's descriptor does not list the knob quality." + name);
}

}  // namespace

double PassDescriptor::knob(const Scene& scene, const char* name) const {
  const KnobDefault& k = knobDefault(*this, name);
  const auto it = scene.quality.find(name);
  return it == scene.quality.end() ? k.value : it->second.value;
}

double PassDescriptor::settledKnob(const Scene& scene, const char* name) const {
  const KnobDefault& k = knobDefault(*this, name);
  const auto it = scene.quality.find(name);
  if (it == scene.quality.end() || it->second.automatic || it->second.value <= 0) return k.value;
  return it->second.value;
}

PassPlan planEntry(std::vector<std::string> reads, std::vector<std::string> writes, std::string why,
                   std::shared_ptr<const PassFeatures> features) {
  PassPlan p;
  p.reads = std::move(reads);
  p.writes = std::move(writes);
  p.why = std::move(why);
  p.features = std::move(features);
  return p;
}

const std::vector<ModelKey>& modelSceneKeys() {
  static const std::vector<ModelKey> keys = [] {
    std::vector<ModelKey> out;
    for (const PassDescriptor& d : passDescriptors())
      for (const ModelKey& k : d.scene_keys) {
        for (const ModelKey& seen : out)
          if (seen.dotted() == k.dotted())
            throw RuntimeError("two descriptors declare the scene key " + k.dotted() + " (" + d.name + " is one)");
        out.push_back(k);
      }
    return out;
  }();
  return keys;
}

const std::vector<KnobDefault>& qualityCountKnobs() {
  static const std::vector<KnobDefault> knobs = [] {
    std::vector<KnobDefault> out;
    for (const PassDescriptor& d : passDescriptors())
      for (const KnobDefault& k : d.knobs) {
        if (k.is_switch) continue;
        const auto seen = std::find_if(out.begin(), out.end(),
                                       [&](const KnobDefault& o) { return std::string(o.name) == k.name; });
        if (seen == out.end()) {
          out.push_back(k);
        } else if (seen->value != k.value || seen->automatic != k.automatic) {
          throw RuntimeError(std::string("two descriptors give the knob quality.") + k.name +
                             " different defaults (" + d.name + " is one)");
        }
      }
    return out;
  }();
  return knobs;
}

const PassDescriptor* descriptorOf(const PassPlan& entry) {
  for (const PassDescriptor& d : passDescriptors())
    if (d.name == entry.name && d.kernel_file == entry.kernel_file) return &d;
  return nullptr;
}

const PassDescriptor& descriptorFor(PassRole role) {
  for (const PassDescriptor& d : passDescriptors())
    if (d.role == role) return d;
  throw RuntimeError("no pass descriptor has role " + std::to_string(static_cast<int>(role)));
}

}  // namespace seasim
