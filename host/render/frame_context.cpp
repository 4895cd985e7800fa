#include "render/frame_context.h"

#include "io/data_files.h"

namespace seasim {

FrameContext::FrameContext(Device& device, const Scene& scene) : device_(device), scene_(scene) {
  if (!scene_.files) scene_.files = std::make_shared<DataFiles>();
}

void FrameContext::setScene(const Scene& scene, bool spectral_changed) {
  std::shared_ptr<DataFiles> files = scene_.files;
  scene_ = scene;
  if (!scene_.files) scene_.files = std::move(files);  // the data read so far stays read
  if (spectral_changed) {
    grid_.reset();
    sensor_.reset();
  }
  setup_.reset();
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

const UnderwaterSetup& FrameContext::underwaterSetup() {
  if (!setup_) {
    setup_ = makeUnderwaterSetup(scene_, grid(), sensor());
    ++setup_version_;
  }
  return *setup_;
}

}  // namespace seasim
