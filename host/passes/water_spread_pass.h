// water_spread_pass.h — host side of kernels/water_spread.cl (the water's point-spread for
// underwater.model = "discrete_ordinates"; kernels/common/water_spread.h derives it): its parameter
// blocks (sensor RGB and, with spectral output, the bands), the layers' taps, the grid's buffers, the four
// kernels and their times.
//
// Reads: the G-buffer and the moments of the forward light kd_multiple.cl kept apart
// (the "gbuffer" geometry and the "forward_light" moments, nodes/underwater_frame.h). Writes: adds the light, blurred,
// into the frame's rgb (and spectral) buffers.
#pragma once
#include <CL/opencl.hpp>

#include <string>
#include <vector>

#include "device/device.h"
#include "plan/plan.h"
#include "underwater/water_spread_setup.h"

namespace seasim {

class WaterSpreadPass {
 public:
  // spread: the blur (makeWaterSpread); band_count > 0 also sets up the spectral blur.
  WaterSpreadPass(Device& device, const PassPlan& plan, const WaterSpread& spread, int band_count);
  // Adds the blurred forward light into rgb (and, when set up with bands and given, into spectral).
  // geom: float4 per pixel, S first; depth: [pixel][2]; forward_rgb: [pixel][2][3]; forward_spectral:
  // [pixel][2][band_count] (common/water_spread_params.h). Returns the summed kernel ms.
  double run(const cl::Buffer& geom, const cl::Buffer& depth, const cl::Buffer& forward_rgb, cl::Buffer& rgb,
             const cl::Buffer* forward_spectral = nullptr, cl::Buffer* spectral = nullptr);
  // Adds the RGB blur of the last run() into another 3-channel frame as well (the "forward"
  // ground-truth layer): the expansion again, nothing blurred twice. Returns its ms.
  double addRgbInto(cl::Buffer& frame);
  // The same for the per-band blur, into a [pixel][band_count] frame (the forward layer per band).
  double addBandsInto(cl::Buffer& frame);
  const WaterSpread& spread() const { return spread_; }

 private:
  // One blur's buffers: a parameter block with its channel count and the grid's per-channel buffers.
  struct Channels {
    cl::Buffer params, layers, rows, blurred;
  };
  Channels makeChannels(int channels);
  double expandInto(Channels& ch, cl::Buffer& frame);
  double blur(Channels& ch, const cl::Buffer& geom, const cl::Buffer& depth, const cl::Buffer& forward,
              cl::Buffer& frame);
  Device& device_;
  WaterSpread spread_;
  int band_count_;
  cl::Kernel reduce_, rows_, columns_, expand_;
  cl::Buffer taps_, cell_s_, cell_d_;
  Channels rgb_, spectral_;
};

}  // namespace seasim
