#include "render/frame_context.h"

#include <algorithm>

#include "io/data_files.h"
#include "render/pass.h"

namespace seasim {

FrameContext::FrameContext(Device& device, const Scene& scene) : device_(device), scene_(scene) {
  if (!scene_.files) scene_.files = std::make_shared<DataFiles>();
}

void FrameContext::setScene(const Scene& scene, const std::vector<std::string>& changed_keys) {
  std::shared_ptr<DataFiles> files = scene_.files;
  scene_ = scene;
  if (!scene_.files) scene_.files = std::move(files);  // the data read so far stays read
  const bool spectral_changed = std::any_of(changed_keys.begin(), changed_keys.end(),
                                            [](const std::string& k) { return keyMatches("spectral.*", k); });
  if (spectral_changed) {
    grid_.reset();
    sensor_.reset();
  }
  changed_keys_.insert(changed_keys_.end(), changed_keys.begin(), changed_keys.end());
}

const WavelengthGrid& FrameContext::grid() {
  if (!grid_) grid_ = makeGrid(scene_.spectral.count, scene_.spectral.min_nm, scene_.spectral.max_nm);
  return *grid_;
}

const Sensor& FrameContext::sensor() {
  if (!sensor_) {
    sensor_ = makeSensor(scene_.spectral.sensor, grid(), scene_.spectral.white_balance, scene_.spectral.camera_dir,
                         scene_.files.get());
  }
  return *sensor_;
}

}  // namespace seasim
