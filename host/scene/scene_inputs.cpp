#include "scene/scene_inputs.h"

#include "io/data_files.h"
#include "io/image_io.h"
#include "util/error.h"

namespace seasim {

void checkSceneInputs(const Scene& scene, std::set<std::string>* already_checked) {
  for (const ImageInputRef& image : scene.images) {
    if (already_checked && already_checked->count(image.path)) continue;
    try {
      // The whole image, not only its header: a truncated body must fail here, not mid-job. Through
      // the scene's data files when it has them, so the render reuses this read.
      (void)readImageVia(scene.files.get(), image.path);
    } catch (const RuntimeError& e) {
      throw InputError(image.loc.file, image.loc.line, image.key, e.what());
    }
    if (already_checked) already_checked->insert(image.path);
  }
}

}  // namespace seasim
