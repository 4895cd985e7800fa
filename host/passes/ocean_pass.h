// ocean_pass.h — host side of kernels/ocean.cl: Tessendorf's FFT ocean (004 §3) on the device, with
// VkFFT doing the inverse FFTs. Builds h̃0 once (eq. 23–25); run(t) evolves the spectra (eq. 26), runs
// four batched N x N FFTs and writes the maps below as device buffers, which other passes sample
// (caustics, the sea scene's normals) and which read*() copy to the host.
//
// Maps, N x N texels over the periodic L x L patch, texel (i, j) at x = i L/N, z = j L/N, row j
// = z index, x fastest. Sample with wrap-around (i mod N): the patch tiles seamlessly.
//   height        float    h, m
//   slope         float2   (∂h/∂x, ∂h/∂z)                     exact, by FFT of i k h̃ (eq. 20)
//   displacement  float4   (λDx, h, λDz, 0), m: displaced point minus (x, 0, z) (eq. 29)
//   normal        float4   (nx, ny, nz, 0), unit, world frame, y up, of the displaced surface
//   jacobian      float    J = Jxx Jzz - Jxz² (eq. 30); < 0 where the surface folds
//   folding       float4   (J-, J+, e-x, e-z): eigenvalues J- <= J+ and J-'s unit eigenvector (eq. 31–34)
#pragma once
#include <CL/opencl.hpp>

#include <complex>
#include <memory>
#include <vector>

#include "device/device.h"
#include "ocean/vkfft_plan.h"
#include "scene/scene.h"

namespace seasim {

// Parameters of one ocean (a plain struct so tests need no scene file).
struct OceanConfig {
  int grid = 256;                     // N, power of two 16..2048
  double patch_size = 100.0;          // L, m
  double wind_speed = 10.0;           // V, m/s (0: flat water)
  double wind_direction = 0.0;        // radians, from +x towards +z
  double phillips_a = 1.29e-3;        // A, dimensionless (ocean_spectrum.h: RMS height = √(Aπ) V²/g for p = 2)
  double directional_exponent = 2.0;  // p in |k̂·ŵ|^p (004 eq. 23; 6 in Figure 8)
  double small_wave = 0.0;            // ℓ, m (004 eq. 24)
  double depth = 0.0;                 // D, m, finite-depth dispersion (004 eq. 15); 0 = deep
  double loop_period = 0.0;           // T, s (004 eq. 18); 0 = no loop
  double choppiness = 0.0;            // λ (004 eq. 29); > 0 sharpens crests
  double gravity = 9.81;              // g, m/s²
  unsigned seed = 1;
};

// The surface keys of a scene ([surface] in scenes/README.md) as an OceanConfig.
OceanConfig oceanConfigFromSurface(const SurfaceDesc& surface);

// Throws RuntimeError naming the field when a value is out of range (N not a power of two in
// 16..2048, L <= 0, V < 0, g <= 0, ...).
void validateOceanConfig(const OceanConfig& config);

// "ocean_maps": the maps of an ocean that has run, as the passes that read the ocean take them
// (caustics, sea_single's normals, whitecaps' Jacobian): buffers and the config they were made with.
struct OceanMaps {
  OceanConfig config;
  cl::Buffer height, slope, displacement, normal, jacobian, folding, fields;
  int n() const { return config.grid; }
  double patchSize() const { return config.patch_size; }
};

// The Jacobian map's N² floats read back (blocking).
std::vector<float> readJacobian(Device& device, const OceanMaps& maps);

class OceanPass {
 public:
  // Compiles ocean.cl, plans the FFT and computes h̃0 on the device.
  OceanPass(Device& device, const OceanConfig& config);
  ~OceanPass();

  // Evolves to time t (s), runs the FFTs and writes all maps; waits; returns wall milliseconds.
  double run(double time_s);

  const OceanConfig& config() const { return config_; }
  // Its buffers and config, for the passes that read the ocean.
  OceanMaps maps() const {
    return {config_, height_, slope_, displacement_, normal_, jacobian_, folding_, fields_};
  }
  int n() const { return config_.grid; }
  double patchSize() const { return config_.patch_size; }

  // Device buffers (layouts in the header comment). fields(): the four FFT'd slots of ocean.cl
  // (4 N² float2) that caustics.cl reads.
  cl::Buffer& height() { return height_; }
  cl::Buffer& slope() { return slope_; }
  cl::Buffer& displacement() { return displacement_; }
  cl::Buffer& normal() { return normal_; }
  cl::Buffer& jacobian() { return jacobian_; }
  cl::Buffer& folding() { return folding_; }
  cl::Buffer& fields() { return fields_; }
  cl::Buffer& h0() { return h0_; }

  // Host copies (blocking), in the layouts above: 1, 2, 4, 4, 1, 4 floats per texel; fields: 8
  // floats per texel slot-major (slot s, texel t: [s * 2N² + 2t], [.. + 1]).
  std::vector<float> readHeight();
  std::vector<float> readSlope();
  std::vector<float> readDisplacement();
  std::vector<float> readNormal();
  std::vector<float> readJacobian();
  std::vector<float> readFolding();
  std::vector<float> readFields();
  std::vector<std::complex<float>> readH0();

  // h̃(k, t) alone (FFT order) and its inverse FFT h(x, t) as complex numbers, whose imaginary part
  // is rounding only (tests: Hermitian symmetry, dispersion). Does not touch the maps.
  std::vector<std::complex<float>> heightSpectrum(double time_s);
  std::vector<std::complex<float>> heightComplex(double time_s);

 private:
  void setTime(double time_s);
  std::vector<float> read(const cl::Buffer& buffer, size_t floats);

  Device& device_;
  OceanConfig config_;
  cl::Kernel init_, evolve_, spectrum_, maps_;
  cl::Buffer params_, h0_, fields_, height_, slope_, displacement_, normal_, jacobian_, folding_;
  cl::Buffer scratch_;  // N² float2 for heightComplex
  std::unique_ptr<VkfftPlan> fft_, scratch_fft_;
};

}  // namespace seasim
