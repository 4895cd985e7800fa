#include "scene/model_keys.h"

#include "util/error.h"

namespace seasim {

double modelKey(const Scene& scene, std::string_view dotted) {
  const auto it = scene.model_keys.find(std::string(dotted));
  if (it != scene.model_keys.end()) return it->second;
  for (const ModelKey& k : modelSceneKeys())
    if (k.dotted() == dotted) return k.default_value;
  throw RuntimeError("no model declares the scene key " + std::string(dotted) +
                     " (PassDescriptor::scene_keys, host/plan/pass_descriptor.h)");
}

}  // namespace seasim
