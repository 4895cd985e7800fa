// sea_single_pass.h — host side of kernels/sea_single.cl: builds SeaParams/SeaBand from the scene,
// enqueues the kernel, reports its time.
#pragma once
#include <CL/opencl.hpp>

#include <vector>

#include "device/device.h"
#include "plan/plan.h"
#include "scene/scene.h"
#include "spectral/sensor.h"
#include "spectral/wavelength_grid.h"

namespace seasim {

class SeaSinglePass {
 public:
  // Output buffers are allocated here: rgb (3 floats per pixel) and, with spectral output,
  // band_count floats per pixel.
  SeaSinglePass(Device& device, const Scene& scene, const PassPlan& plan, const WavelengthGrid& grid,
                const Sensor& sensor);
  // Enqueues the kernel; returns its profiled time in ms (waits for it).
  double run();
  cl::Buffer& rgb() { return rgb_; }
  cl::Buffer& spectral() { return spectral_; }

 private:
  Device& device_;
  cl::Kernel kernel_;
  cl::Buffer params_, bands_, lut_, rgb_, spectral_;
  int width_, height_;
};

}  // namespace seasim
