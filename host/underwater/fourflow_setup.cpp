// fourflow_setup.cpp — FfBand from a band's optics (see the header).
#include "underwater/fourflow_setup.h"

#include <cstddef>
#include <stdexcept>

#include "math/kernel_math.h"

namespace seasim {

static_assert(sizeof(FfBand) == 20 * 4, "FfBand layout changed: update fourflow_params.h users");
static_assert(offsetof(FfBand, rgb) == 16 * 4);
static_assert(sizeof(FfParams) == 16 * 4, "FfParams layout changed: update fourflow_params.h users");
static_assert(offsetof(FfParams, rgb_a) == 8 * 4);
static_assert(sizeof(FfView) == 28 * 4, "FfView layout changed: update fourflow_params.h users");
static_assert(offsetof(FfView, tan_half_fov_y) == 20 * 4);
static_assert(offsetof(FfView, width) == 22 * 4);
static_assert(offsetof(FfView, dark_fraction) == 27 * 4);

FfBand makeFourFlowBand(const FourFlowBandInput& in, double mu_sun, double n_water) {
  return makeFourFlowBand(in, flatFourFlowSurface(mu_sun, n_water));
}

FfBand makeFourFlowBand(const FourFlowBandInput& in, const FourFlowSurface& s) {
  if (!(in.absorption + in.scattering > 0)) throw std::invalid_argument("four-flow band: water must attenuate (a + b > 0)");
  namespace kd = kmath_d;
  const kd::FfMedium m = kd::ff_medium(in.absorption, in.scattering, in.mean_cosine);
  FfBand b{};
  b.eps = float(in.absorption + in.scattering);
  b.k = float(m.k), b.S = float(m.S), b.S1 = float(m.S1), b.S2 = float(m.S2);
  b.T_dd = float(s.T_dd), b.T_df = float(s.T_df), b.T_ff = float(s.T_ff);
  b.Rw_dd = float(s.Rw_dd), b.Rw_df = float(s.Rw_df), b.Rw_ff = float(s.Rw_ff);
  b.e_sun = float(in.e_sun), b.e_sky = float(in.e_sky);
  b.rho_a = float(in.rho_a), b.rho_b = float(in.rho_b), b.rho_mean = float(in.rho_mean);
  for (int c = 0; c < 3; ++c) b.rgb[c] = float(in.rgb[c]);
  return b;
}

}  // namespace seasim
