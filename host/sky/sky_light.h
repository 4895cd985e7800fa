// sky_light.h — the one sky interface of every model: from a scene's [sky] and [sun], per wavelength band,
// the sky's radiance towards a direction, the irradiance it gives a horizontal surface (above and just
// below a flat water surface: E_D0's sky part), the sun's irradiance and the radiance of its disk.
// Every model that lights a scene with the sky reads it here: the sea seen from above (its SeaSky,
// passes/sea_sky.h, is this module's shape), the underwater model (Snell's window through the kernel's
// common/sky_view.h, e_sky0 from transmittedIrradiance) and the shallow-water model (its e_sky and the
// sky its surface reflects).
#pragma once
#include <array>
#include <cstddef>
#include <vector>

#include "passes/sea_sky.h"
#include "scene/scene.h"
#include "spectral/wavelength_grid.h"

extern "C" {
#include "common/sky_params.h"
}

namespace seasim {

struct SkyLight {
  SeaSky shape;                        // model, scale, image texels or Preetham's reals, band weights
  SkyParams params{};                  // the same for the kernels (common/sky_view.h)
  std::vector<double> level;           // per band L_sky(λ): [sky] radiance × D65 shape, W m^-2 sr^-1 nm^-1
  std::vector<double> sun_irradiance;  // per band, normal to the beam, W m^-2 nm^-1 (0: no sun)
  double sun_solid_angle = 0.0;        // sr, 2π (1 − cos r): 6.8e-5 for the default radius 0.2667°
  std::array<double, 3> sun_dir{0, 1, 0};  // unit, towards the sun in air

  // The sky's radiance in a band towards unit d in air (d.y >= 0), without the sun's disk.
  double radiance(std::size_t band, const std::array<double, 3>& d) const;
  // E_sun / Ω: the disk's radiance in a band (0 for a point sun).
  double sunDiskRadiance(std::size_t band) const;
  // ∫_{d.y > 0} L cos θ dω per band: exactly π L_sky for the uniform sky; the other models by the
  // midpoint rule in (cos²θ, φ) over n_s × n_phi directions (256 × 512: within 1e-4 of a brute-force
  // quadrature, tests/unit/sky_light_test.cpp's sweep).
  std::vector<double> horizontalIrradiance(int n_s = 256, int n_phi = 512) const;
  // ∫_{d.y > 0} L (1 − F(θ)) cos θ dω per band: the sky's irradiance on a horizontal plane just below
  // a flat surface of relative index ior (the sky's part of E_D0). Uniform sky: π L_sky (1 − r̄),
  // r̄ = skyFresnelMean(ior), as the underwater model always had.
  std::vector<double> transmittedIrradiance(double ior, int n_s = 256, int n_phi = 512) const;
  // The shape's reals as the kernels read them (image texels or Preetham's 18; one 0 otherwise).
  std::vector<float> kernelBuffer() const;
  // The 3 × 4 matrix of sky_view_rgb (common/sky_view.h) for a sensor's per-band RGB weights.
  std::array<float, 12> rgbMatrix(const std::vector<double>& to_r, const std::vector<double>& to_g,
                                  const std::vector<double>& to_b) const;
};

// The mean Fresnel reflectance of a uniform sky seen through a flat surface of relative index ior,
// weighted by cos θ: r̄ = 2 ∫_0^{π/2} F(θ) cos θ sin θ dθ (about 0.066 for water).
double skyFresnelMean(double ior);

// The scene's sky and sun over the grid. RuntimeError as makeSeaSky (an unusable sky image).
SkyLight makeSkyLight(const Scene& scene, const WavelengthGrid& grid);

}  // namespace seasim
