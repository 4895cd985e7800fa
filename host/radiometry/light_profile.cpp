#include "radiometry/light_profile.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "math/kernel_math.h"
#include "underwater/discrete_ordinates.h"

namespace seasim {
namespace {

constexpr double kPi = 3.14159265358979323846;

}  // namespace

double uniformSkyTransmittance(double ior) {
  // Midpoint rule: r is smooth from air, and the grazing end has weight μ -> 0.
  const int n = 4000;
  double r = 0;
  for (int i = 0; i < n; ++i) {
    const double mu = (i + 0.5) / n;
    r += kmath_d::fresnel_reflectance(mu, 1.0, ior) * mu;
  }
  return 1 - 2 * r / n;
}

LightProfile solveLightProfile(const PlaneParallelWater& water, const PhaseFunction& phase,
                               const std::vector<double>& depths, int streams) {
  if (!(water.sun_zenith >= 0 && water.sun_zenith < 0.5 * kPi))
    throw std::invalid_argument("light profile: the sun's zenith angle must be in [0, 90) deg");
  if (!(water.sun_irradiance >= 0 && water.sky_irradiance >= 0))
    throw std::invalid_argument("light profile: irradiances must be >= 0");
  for (double z : depths)
    if (!(z >= 0 && std::isfinite(z))) throw std::invalid_argument("light profile: depths must be finite and >= 0");

  // The sun refracted by the flat surface; its horizontal irradiance is conserved but for Fresnel.
  const double mu_air = std::cos(water.sun_zenith);
  const double sin_w = std::sin(water.sun_zenith) / water.ior;
  const double mu_w = std::sqrt(1 - sin_w * sin_w);
  DiscreteOrdinatesLayer layer;
  layer.a = water.a;
  layer.b = water.b;
  layer.ior = water.ior;
  layer.bottom_depth = water.bottom_depth;
  layer.bottom_albedo = water.bottom_albedo;
  layer.mu_sun = mu_w;
  layer.e_sun0 = water.sun_irradiance * mu_air * (1 - kmath_d::fresnel_reflectance(mu_air, 1.0, water.ior));
  layer.e_sky0 = water.sky_transmitted >= 0 ? water.sky_transmitted : water.sky_irradiance * uniformSkyTransmittance(water.ior);
  layer.moments = phase.legendreMoments(2 * streams + 1);
  const DiscreteOrdinates solver(layer, streams);

  LightProfile out;
  out.e_d_air = water.sun_irradiance * mu_air + water.sky_irradiance;
  for (double z : depths) {
    const DiscreteOrdinatesIrradiance e = solver.at(z);
    LightAtDepth row;
    row.depth = z;
    row.e_d = e.down + e.beam_down;
    row.e_u = e.up;
    row.e_0d = e.scalar_down + e.beam_scalar;
    row.e_0u = e.scalar_up;
    out.rows.push_back(row);
  }

  // L_u by the source function along the vertical (see the header), integrated from z_end up.
  const double c_hat = solver.extinction();
  const bool bottom = water.bottom_depth > 0;
  double deepest = 0;
  for (double z : depths) deepest = std::max(deepest, z);
  const double z_end = bottom ? water.bottom_depth : deepest + 40 / c_hat;
  const int samples = std::clamp(static_cast<int>(std::ceil(z_end * c_hat / (0.05 * mu_w))) + 1, 2, 200000);
  const double h = z_end / (samples - 1);
  const std::vector<double> diffuse = solver.inscatterProfile({-1.0}, z_end, samples);
  const double beam_phase = phase.evaluate(kPi - std::acos(mu_w));
  const double f0 = layer.e_sun0 / mu_w;  // the beam's irradiance normal to itself
  std::vector<double> j(samples);
  for (int s = 0; s < samples; ++s)
    j[s] = diffuse[s] + water.b * beam_phase * f0 * std::exp(-solver.beamK() * s * h);
  std::vector<double> l_up(samples, 0.0);
  if (bottom) {
    const DiscreteOrdinatesIrradiance e = solver.at(z_end);
    l_up[samples - 1] = water.bottom_albedo / kPi * (e.down + e.beam_down);
  }
  // Between samples J is linear: L(top) = L(bottom) e^{-ĉh} + J_top I0 + (J_bot - J_top) I1 / h, with
  // I0 = ∫_0^h e^{-ĉs} ds and I1 = ∫_0^h s e^{-ĉs} ds (expm1 forms: no cancellation at small ĉh).
  const double x = c_hat * h, e = std::exp(-x);
  const double i0 = -std::expm1(-x) / c_hat;
  const double i1 = (-std::expm1(-x) - x * e) / (c_hat * c_hat);
  for (int s = samples - 2; s >= 0; --s)
    l_up[s] = l_up[s + 1] * e + j[s] * i0 + (j[s + 1] - j[s]) * i1 / h;
  for (LightAtDepth& row : out.rows) {
    const double pos = std::min(row.depth, z_end) / h;
    const int k = std::min(static_cast<int>(pos), samples - 2);
    const double t = pos - k;
    // Geometric between samples (the field decays exponentially); linear where a value is 0.
    const double lo = l_up[k], hi = l_up[k + 1];
    row.l_u = lo > 0 && hi > 0 ? lo * std::pow(hi / lo, t) : lo + t * (hi - lo);
  }
  const double l_u0 = l_up[0];
  out.l_w = l_u0 * (1 - kmath_d::fresnel_reflectance(1.0, water.ior, 1.0)) / (water.ior * water.ior);
  out.r_rs = out.e_d_air > 0 ? out.l_w / out.e_d_air : 0.0;
  return out;
}

}  // namespace seasim
