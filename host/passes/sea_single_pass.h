// sea_single_pass.h — host side of kernels/sea_single.cl: builds SeaParams/SeaBand from the scene,
// enqueues the kernel, reports its time. With FFT waves (SEASIM_HAS_WAVES=1 in the plan) it reads the
// normal map of an OceanPass that has already run (render_frame runs it first); with an analytic or
// image sky it uploads the sky of host/passes/sea_sky.h.
#pragma once
#include <CL/opencl.hpp>

#include <vector>

#include "device/device.h"
#include "passes/caustic_stack.h"
#include "passes/ocean_pass.h"
#include "plan/plan.h"
#include "scene/scene.h"
#include "spectral/sensor.h"
#include "spectral/wavelength_grid.h"

extern "C" {
#include "common/sea_params.h"
}

namespace seasim {

class SeaSinglePass {
 public:
  // Output buffers are allocated here: rgb (3 floats per pixel) and, with spectral output,
  // band_count floats per pixel. ocean: the maps of a run ocean, whose normal map the kernel reads; required
  // when the plan defines SEASIM_HAS_WAVES=1 (RuntimeError otherwise), ignored without waves. The
  // kernel reads the buffer when run() is called, so the ocean must outlive run(). bottom_caustics:
  // required when the plan defines SEASIM_BOTTOM_CAUSTICS=1 (the ocean's caustics on the bottom).
  SeaSinglePass(Device& device, const Scene& scene, const PassPlan& plan, const WavelengthGrid& grid,
                const Sensor& sensor, const OceanMaps* ocean = nullptr, const SeaBottomCaustics* bottom_caustics = nullptr);
  // A camera moved or turned, or its field of view changed, at the same image size: only the
  // parameter block's camera changes (the sky, the bands and the LUT do not depend on it).
  // RuntimeError for another image size, which needs a new pass (its output buffers).
  void moveCamera(const CameraDesc& cam);
  // Enqueues the kernel; returns its profiled time in ms (waits for it).
  double run();
  cl::Buffer& rgb() { return rgb_; }
  cl::Buffer& spectral() { return spectral_; }

 private:
  Device& device_;
  cl::Kernel kernel_;
  cl::Kernel moments_, cells_, downsample_;  // the wave filter's slope-moment mips (SEASIM_WAVE_FILTER)
  int ocean_n_ = 0;                  // > 0 when the filter runs: the normal map's side
  SeaParams host_params_{};  // what params_ holds
  cl::Buffer params_, table_, normals_, mips_, sky_, caustics_, rgb_, spectral_;
  cl::Buffer hf_params_, hf_depth_;  // height-field bottom (000 §5.4), SEASIM_BOTTOM_HEIGHTFIELD
  int width_, height_;
};

}  // namespace seasim
