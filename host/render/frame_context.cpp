#include "render/frame_context.h"

namespace seasim {

FrameContext::FrameContext(Device& device, const Scene& scene) : device_(device), scene_(scene) {}

void FrameContext::setScene(const Scene& scene, bool spectral_changed) {
  scene_ = scene;
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
    sensor_ = makeSensor(scene_.spectral.sensor, grid(), scene_.spectral.white_balance, scene_.spectral.camera_dir);
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
