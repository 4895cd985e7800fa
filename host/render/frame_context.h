// frame_context.h — what every pass of a frame shares besides the named resources: the device, the
// scene as it stands after the last update, the keys changed since the last frame, and the
// scene-wide products every model uses (wavelength grid, sensor weights from the camera CSVs). Each
// product is made on first use and kept until an update changes a key it depends on. A model's own
// set-up is a resource its pass publishes (the underwater one: nodes/underwater_setup_node.cpp), not
// a member here. Its scene always has data files (Scene::files): the scene's own, or one made here
// and kept across updates.
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

namespace seasim {

class FrameContext {
 public:
  FrameContext(Device& device, const Scene& scene);

  Device& device() { return device_; }
  const Scene& scene() const { return scene_; }

  // spectral.* changes remake the grid and the sensor. The changed keys add to changedKeys().
  void setScene(const Scene& scene, const std::vector<std::string>& changed_keys);
  // The keys changed since the last frame (every update's, in order; empty on the first frame): a
  // pass that can take some changes more cheaply than by a new set-up reads them here.
  const std::vector<std::string>& changedKeys() const { return changed_keys_; }
  // The renderer calls this when a frame is done: changedKeys() starts empty again.
  void frameDone() { changed_keys_.clear(); }

  const WavelengthGrid& grid();
  const Sensor& sensor();

  // Kernel times of the passes that ran in this frame, in order.
  std::vector<PassTiming> timings;
  long long nonfinite = 0;

 private:
  Device& device_;
  Scene scene_;
  std::optional<WavelengthGrid> grid_;
  std::optional<Sensor> sensor_;
  std::vector<std::string> changed_keys_;
};

}  // namespace seasim
