// sea_second_pass.h — host side of kernels/sea_second.cl: second-order scattering under a flat sea
// by scattering maps (000 eq. 6–8), over a flat or height-field floor (with the depth tables of §5.4,
// computed on the first run() and cached on disk, host/passes/sea_heightfield.h). Builds SeaSecondParams
// from the scene and its quality knobs, owns the VSF, radiance, direction, plane-weight and
// scattering-map buffers, and ADDS L^(2) into the rgb (and spectral) buffers that sea_single wrote.
// Reads: scene. Writes: rgb (+=).
#pragma once
#include <CL/opencl.hpp>

#include <cstdint>

#include "device/device.h"
#include "plan/plan.h"
#include "scene/scene.h"
#include "spectral/sensor.h"
#include "spectral/wavelength_grid.h"

namespace seasim {

class SeaSecondPass {
 public:
  // The quality knobs as the scene gives them; "auto" knobs get a placeholder here (n_z = 8, n_d = 512,
  // map 32); the per-scene 000 §6.1 search (quality/sea_auto.h) comes in through passes/auto_quality.h.
  struct Config {
    int n_z = 12;        // sampling planes (quality.sea_nz)
    int n_theta = 8;     // n_d = n_theta * n_phi sampling directions (quality.sea_nd)
    int n_phi = 16;
    int map_size = 32;   // sampling points per side of each plane's map (quality.sea_map_size)
    int vsf_size = 1024; // entries of the volume-scattering-function map
  };
  static Config configFromScene(const Scene& scene);
  // n_d -> (n_theta, n_phi): n_theta = round(sqrt(n_d / 2)) (at least 1), n_phi = n_d / n_theta, so
  // dtheta ~ dphi as on the paper's (theta, phi) grid; 128 -> 8 x 16. The count used is n_theta * n_phi.
  static void splitDirections(int n_d, int* n_theta, int* n_phi);

  // rgb: 3 floats per pixel to add into; spectral: band_count floats per pixel (only read with
  // scene.spectral.spectral_exr). Both are the buffers of the pass that ran before (sea_single).
  SeaSecondPass(Device& device, const Scene& scene, const PassPlan& plan, const Config& config,
                const WavelengthGrid& grid, const Sensor& sensor, cl::Buffer& rgb, cl::Buffer* spectral);
  // Enqueues the four kernels; returns their total profiled time in ms (waits for them).
  double run();
  // Of the last run(): ms for the maps (VSF, radiance, scattering maps) and for the accumulation.
  double mapsMs() const { return maps_ms_; }
  // ms of the height-field depth tables (000 §5.4), 0 when there are none or they came from the
  // on-disk cache; computed by the first run() only and not included in its return value.
  double depthTableMs() const { return depth_table_ms_; }
  double accumulateMs() const { return accumulate_ms_; }
  const Config& config() const { return config_; }

 private:
  Device& device_;
  Config config_;
  cl::Kernel vsf_kernel_, radiance_kernel_, maps_kernel_, accumulate_kernel_;
  cl::Buffer params_, bands_, vsf_, dirs_, radiance_, plane_w_, plane_bands_, maps_;
  // Height-field floor (SEASIM_BOTTOM_HEIGHTFIELD): the floor and the depth tables of 000 §5.4.
  cl::Kernel table_kernel_;
  cl::Buffer hf_params_, hf_depth_, table_;
  uint64_t table_key_ = 0;
  bool table_ready_ = false;
  int width_, height_;
  double maps_ms_ = 0, accumulate_ms_ = 0, depth_table_ms_ = 0;
};

}  // namespace seasim
