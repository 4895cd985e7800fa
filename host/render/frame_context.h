// frame_context.h — what every pass of a frame shares besides the named resources: the device, the
// scene as it stands after the last update, and the scene-wide products that are costly to make
// (wavelength grid, sensor weights from the camera CSVs, the underwater parameter blocks). Each
// product is made on first use and kept until an update changes a key it depends on. Its scene
// always has data files (Scene::files): the scene's own, or one made here and kept across updates.
#pragma once
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "device/device.h"
#include "render/frame_result.h"
#include "scene/scene.h"
#include "spectral/sensor.h"
#include "spectral/wavelength_grid.h"
#include "underwater/underwater_setup.h"

namespace seasim {

class FrameContext {
 public:
  FrameContext(Device& device, const Scene& scene);

  Device& device() { return device_; }
  const Scene& scene() const { return scene_; }

  // spectral.* changes remake the grid and the sensor; any change remakes the underwater setup
  // (it folds camera, sun, water, objects and knobs into one parameter block), except a change of
  // surface.time alone: the waves' phase is one number of the block (the caustics' time), while the
  // rest, the improved model's per-band tables above all, costs about half a second per frame to
  // remake. setupVersion() still grows, so the passes take the new block.
  void setScene(const Scene& scene, const std::vector<std::string>& changed_keys);

  const WavelengthGrid& grid();
  const Sensor& sensor();
  // makeUnderwaterSetup(scene, grid, sensor); setupVersion() grows each time it is remade.
  const UnderwaterSetup& underwaterSetup();
  uint64_t setupVersion() const { return setup_version_; }

  // Kernel times of the passes that ran in this frame, in order.
  std::vector<PassTiming> timings;
  long long nonfinite = 0;

 private:
  Device& device_;
  Scene scene_;
  std::optional<WavelengthGrid> grid_;
  std::optional<Sensor> sensor_;
  std::optional<UnderwaterSetup> setup_;
  uint64_t setup_version_ = 0;
};

}  // namespace seasim
