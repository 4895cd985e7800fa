#include "jobs/job_inputs.h"

#include <set>

#include "io/image_io.h"
#include "jobs/render_item.h"
#include "plan/plan.h"
#include "scene/scene_inputs.h"
#include "util/error.h"

namespace seasim {

std::map<std::string, std::string> checkJobInputs(const std::vector<RenderItem>& items) {
  std::map<std::string, std::string> failed;
  std::set<std::string> good_images;  // frames and sweeps share textures: read each once
  for (const RenderItem& item : items) {
    try {
      const Scene scene = loadScene(item.scene_file, item.overrides);
      checkSceneInputs(scene, &good_images);
      try {
        checkOutputsPossible(scene, makePlan(scene), item.outputs);  // spectral_exr from an RGB-only plan
      } catch (const RuntimeError& e) {
        throw InputError(item.loc.file, item.loc.line, "outputs", e.what());
      }
      if (!item.reference.empty()) {
        ImageHeader ref;
        try {
          ref = readImageHeader(item.reference);
          if (!good_images.count(item.reference)) (void)readImage(item.reference);
          good_images.insert(item.reference);
        } catch (const RuntimeError& e) {
          throw InputError(item.reference_loc.file, item.reference_loc.line, item.reference_key, e.what());
        }
        if (ref.width != scene.camera.width || ref.height != scene.camera.height)
          throw InputError(item.reference_loc.file, item.reference_loc.line, item.reference_key,
                           "the reference '" + item.reference + "' is " + std::to_string(ref.width) + "x" +
                               std::to_string(ref.height) + " but item '" + item.name + "' renders " +
                               std::to_string(scene.camera.width) + "x" + std::to_string(scene.camera.height) +
                               "; render the reference at the same size");
      }
    } catch (const InputError& e) {
      failed[item.name] = e.what();
    }
  }
  return failed;
}

}  // namespace seasim
