// fourflow_setup.h — the four-flow model's per-band kernel block (kernels/common/fourflow_params.h)
// from a band's water optics, light, bottom materials and sensor weights (paper 003 eq. 4 text, eq. 6–7
// for a flat surface). The constants and the surface coefficients are computed in double by the same
// header the kernels run (kmath_d) and stored as float.
#pragma once

#include <array>

#include "common/fourflow_params.h"
#include "underwater/fourflow_waves.h"

namespace seasim {

struct FourFlowBandInput {
  double absorption = 0;      // χ, m⁻¹
  double scattering = 0;      // σ, m⁻¹
  double mean_cosine = 0.9;   // X1 (the phase function's mean cosine, [-1, 1])
  double e_sun = 0, e_sky = 0;  // irradiance on a horizontal plane above the surface
  double rho_a = 0, rho_b = 0;  // bottom materials' albedo
  double rho_mean = 0;          // the bottom texture's mean albedo (003 eq. 12)
  std::array<double, 3> rgb{};  // band -> linear RGB weights
};

// mu_sun: cos of the sun's zenith angle in air; n_water: water's refractive index (a flat surface).
FfBand makeFourFlowBand(const FourFlowBandInput& in, double mu_sun, double n_water);
// With given air–water coefficients (a flat surface, or averaged over waves: underwater/fourflow_waves.h).
FfBand makeFourFlowBand(const FourFlowBandInput& in, const FourFlowSurface& surface);

}  // namespace seasim
