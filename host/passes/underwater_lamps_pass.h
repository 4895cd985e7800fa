// underwater_lamps_pass.h — host side of kernels/underwater_lamps.cl: spotlights in the water's
// spectral medium (paper 001's sampling planes with the water's per-band σ_s, σ_t and HG phase,
// common/underwater_lamps.h), added into the underwater frame's rgb (and spectral) after kd_multiple.
//
// Reads: the underwater set-up (camera, bands with IOPs and sensor weights, objects, albedo), the
// G-buffer (hit distance, normal, material), the lamps with their spectra (spectral/lamp_spectrum.h).
// Writes: += rgb, += spectral. Quality: quality.shafts_planes (n), quality.shafts_subplanes (m), the
// knobs of the shafts in air; "auto" takes the paper's n = 30, m = 6 (the auto search is for air).
// quality.lamps_delta_m (default true): the lamps see the water delta-M scaled, so the light forward
// scattering keeps in the beam is not lost (measured against the path tracer: results/BENCHMARKS.md).
#pragma once
#include <CL/opencl.hpp>

#include <vector>

#include "device/device.h"
#include "plan/plan.h"
#include "scene/scene.h"
#include "spectral/wavelength_grid.h"
#include "underwater/underwater_setup.h"

namespace seasim {

class UnderwaterLampsPass {
 public:
  struct Config {
    int planes = 30;    // n sampling planes per lamp (001 eq. 5)
    int subplanes = 6;  // m sub-samples per interval (001 eq. 7–9)
    bool delta_m = true;  // quality.lamps_delta_m: the water delta-M scaled (underwater/lamps_setup.h)
  };
  static Config configFromScene(const Scene& scene);

  // `plan`: the "underwater_lamps" entry (its defines). RuntimeError for n or m < 1.
  UnderwaterLampsPass(Device& device, const Scene& scene, const UnderwaterSetup& setup, const WavelengthGrid& grid,
                      const PassPlan& plan, const Config& config);
  // Adds the lamps into rgb (and spectral when given) for the G-buffer (geom, material); returns ms.
  // lamps_layer: the "lamps" ground-truth layer (3 floats per pixel) when planned with SEASIM_LAYER_LAMPS.
  double run(cl::Buffer& geom, cl::Buffer& material, cl::Buffer& rgb, cl::Buffer* spectral,
             cl::Buffer* lamps_layer = nullptr);
  // Rewrites the underwater parameter blocks (sun, water or time changed; same sizes).
  void update(const UnderwaterSetup& setup);

 private:
  Device& device_;
  bool delta_m_;
  int width_, height_;
  size_t band_count_, object_count_, albedo_count_;
  cl::Kernel kernel_;
  cl::Buffer params_, bands_, albedo_, objects_, lamp_params_, lamps_, spectra_;
};

}  // namespace seasim
