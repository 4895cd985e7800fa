// whitecaps_pass.h — host side of kernels/whitecaps.cl: sea-surface foam composited over the sea seen
// from above (the model: kernels/common/whitecaps.h). Builds WhitecapsParams and the foam's radiance
// from the scene, holds the foam mask's mip chain, enqueues the three kernels, reports their time.
//
// Reads: the ocean's Jacobian map (OceanPass::jacobian(), N x N floats) and the threshold and rank
// table taken from it (passes/whitecaps_threshold.h). Writes: the frame's rgb (3 floats per pixel) and, when set
// up for spectral output, its bands (band_count floats per pixel), in place.
#pragma once
#include <CL/opencl.hpp>

#include <vector>

#include "device/device.h"
#include "passes/whitecaps_threshold.h"
#include "plan/plan.h"
#include "scene/scene.h"
#include "spectral/sensor.h"
#include "spectral/wavelength_grid.h"

extern "C" {
#include "common/whitecaps_params.h"
}

namespace seasim {

// Fresh foam's radiance per band, L_f(λ) = R_0(λ) E_d(λ) / π, W m^-2 sr^-1 nm^-1: R_0 from
// common/whitecaps.h, E_d the sun's irradiance on the horizontal (when it is up) plus the sky's
// (SkyLight::horizontalIrradiance).
std::vector<double> foamRadianceBands(const Scene& scene, const WavelengthGrid& grid);

class WhitecapsPass {
 public:
  // ocean_n, ocean_patch: the ocean's N and L (m), whose Jacobian map run() reads.
  WhitecapsPass(Device& device, const Scene& scene, const PassPlan& plan, const WavelengthGrid& grid,
                const Sensor& sensor, int ocean_n, double ocean_patch);
  // The foam's opacity from `jacobian` and `levels` (made from it), its mips, and the foam over rgb
  // (and spectral, when the plan has spectral output and it is given). Returns the summed kernel ms.
  double run(const cl::Buffer& jacobian, const WhitecapsFoamLevels& levels, cl::Buffer& rgb,
             cl::Buffer* spectral = nullptr);
  // run()'s two halves: the foam's opacity and its mips from the ocean (unchanged while only the
  // camera moves), and the foam over the sea's radiance as seen by the camera. Each returns kernel ms.
  double updateFoam(const cl::Buffer& jacobian, const WhitecapsFoamLevels& levels);
  double composite(cl::Buffer& rgb, cl::Buffer* spectral = nullptr);
  // A camera moved or turned, or its field of view changed, at the same image size: only the
  // parameter block's camera changes. RuntimeError for another image size (a new pass).
  void moveCamera(const CameraDesc& cam);

  const WhitecapsParams& params() const { return params_; }
  const std::vector<float>& foamBands() const { return foam_bands_; }
  // The mask's mip chain as the last run() left it (whitecaps_level_offset's layout; blocking).
  std::vector<float> readMips();

 private:
  Device& device_;
  WhitecapsParams params_{};
  std::vector<float> foam_bands_;
  bool spectral_output_ = false;
  int levels_ = 1;
  cl::Kernel mask_, downsample_, over_sea_;
  cl::Buffer params_buffer_, mips_, foam_buffer_, rank_buffer_;
};

}  // namespace seasim
