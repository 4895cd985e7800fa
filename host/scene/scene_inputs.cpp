#include "scene/scene_inputs.h"

#include <algorithm>
#include <cmath>

#include "io/data_files.h"
#include "io/image_io.h"
#include "plan/plan.h"
#include "util/error.h"

namespace seasim {

void checkSceneInputs(const Scene& scene, std::set<std::string>* already_checked) {
  for (const ImageInputRef& image : scene.images) {
    if (already_checked && already_checked->count(image.path)) continue;
    try {
      // The whole image, not only its header: a truncated body must fail here, not mid-job. Through
      // the scene's data files when it has them, so the render reuses this read.
      const Image img = readImageVia(scene.files.get(), image.path);
      // A NaN or Inf texel reaches the kernels as a NaN frame that names no file (an EXR light map
      // with NaNs gave "the kernels produced 156 NaN/Inf values"): name the image instead.
      size_t bad = 0, first = 0;
      for (size_t i = 0; i < img.pixels.size(); ++i)
        if (!std::isfinite(img.pixels[i]) && bad++ == 0) first = i;
      if (bad > 0) {
        const size_t channels = static_cast<size_t>(std::max(img.channels, 1));
        const size_t px = first / channels, w = static_cast<size_t>(std::max(img.width, 1));
        throw InputError(image.loc.file, image.loc.line, image.key,
                         "the image '" + image.path + "' holds " + std::to_string(bad) +
                             " NaN/Inf values (the first at pixel x = " + std::to_string(px % w) + ", y = " +
                             std::to_string(px / w) + ", channel " + std::to_string(first % channels) +
                             "); an input image must hold finite values");
      }
    } catch (const RuntimeError& e) {
      throw InputError(image.loc.file, image.loc.line, image.key, e.what());
    }
    if (already_checked) already_checked->insert(image.path);
  }
  // After the images (their errors are the more specific). An empty file parses (every key has a
  // default) but no model draws anything: `validate` said ok and the render failed with "no pass of
  // its plan writes 'rgb'".
  const Plan plan = makePlan(scene);
  const bool draws = std::any_of(plan.passes.begin(), plan.passes.end(), [](const PassPlan& p) {
    return std::find(p.writes.begin(), p.writes.end(), "rgb") != p.writes.end();
  });
  if (!draws)
    throw InputError(scene.file, 1, "",
                     "the scene renders nothing: no pass of its plan draws the image (`seasim plan` shows the "
                     "plan; scenes/README.md says what each model needs)");
}

}  // namespace seasim
