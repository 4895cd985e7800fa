#include "radiometry/light_profile_mc.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "math/kernel_math.h"

namespace seasim {
namespace {

namespace kd = kmath_d;
constexpr double kPi = 3.14159265358979323846;

// One batch's sums per depth (W m^-2 per photon weight), in the order of LightAtDepth's fields.
struct Tally {
  std::vector<double> e_d, e_u, e_0d, e_0u, l_u;
  explicit Tally(size_t n) : e_d(n, 0.0), e_u(n, 0.0), e_0d(n, 0.0), e_0u(n, 0.0), l_u(n, 0.0) {}
};

struct Walk {
  const std::vector<double>& depths;
  double bottom;                // m; 0: none
  double layer;                 // Δ, m
  double cap_cos, cap_solid;    // L_u's cap: cos of its half-angle, its solid angle
  Tally& t;

  // The segment from z0 to z1 travelled with direction cosine mu (> 0 down) by weight w: plane crossings
  // and track lengths.
  void segment(double z0, double z1, double mu, double w) const {
    const double lo = std::min(z0, z1), hi = std::max(z0, z1);
    for (size_t k = 0; k < depths.size(); ++k) {
      const double z = depths[k];
      // A crossing counts when the plane lies between the start (excluded: leaving a boundary is counted
      // by leaves()) and the end (included: arriving on the surface or the bottom is a crossing).
      if (mu > 0 ? (z > z0 && z <= z1) : (z >= z1 && z < z0)) {
        if (mu > 0) t.e_d[k] += w;
        else {
          t.e_u[k] += w;
          if (-mu >= cap_cos) t.l_u[k] += w / (-mu * cap_solid);
        }
      }
      const double a = std::max(z - layer, 0.0), b = bottom > 0 ? std::min(z + layer, bottom) : z + layer;
      const double overlap = std::min(hi, b) - std::max(lo, a);
      if (overlap > 0) (mu > 0 ? t.e_0d[k] : t.e_0u[k]) += w * overlap / (std::abs(mu) * (b - a));
    }
  }
  // A photon leaving a boundary plane z_b (0 or the bottom) with direction cosine mu: the planes at z_b.
  void leaves(double z_b, double mu, double w) const {
    for (size_t k = 0; k < depths.size(); ++k)
      if (depths[k] == z_b) {
        if (mu > 0) t.e_d[k] += w;
        else {
          t.e_u[k] += w;
          if (-mu >= cap_cos) t.l_u[k] += w / (-mu * cap_solid);
        }
      }
  }
};

}  // namespace

LightProfileMc solveLightProfileMonteCarlo(const PlaneParallelWater& water, const PhaseFunction& phase,
                                           const std::vector<double>& depths, const MonteCarloSettings& s) {
  if (s.photons < s.batches || s.batches < 2) throw std::invalid_argument("monte carlo: need photons >= batches >= 2");
  if (!(water.a >= 0 && water.b >= 0 && water.a + water.b > 0))
    throw std::invalid_argument("monte carlo: a, b must be >= 0 with c > 0");
  for (double z : depths)
    if (!(z >= 0) || (water.bottom_depth > 0 && z > water.bottom_depth))
      throw std::invalid_argument("monte carlo: depths must lie in the water");
  const auto t0 = std::chrono::steady_clock::now();
  const double c = water.a + water.b, omega = water.b / c, n = water.ior;
  const double bottom = water.bottom_depth > 0 ? water.bottom_depth : 0.0;
  double deepest = 0;
  for (double z : depths) deepest = std::max(deepest, z);
  const double z_kill = bottom > 0 ? 2 * bottom + 1 : deepest + 40 / c;  // below it no light returns (e^-40)

  // The sources just below the surface (as light_profile.cpp's).
  const double mu_air = std::cos(water.sun_zenith);
  const double sin_w = std::sin(water.sun_zenith) / n, mu_w = std::sqrt(1 - sin_w * sin_w);
  const double e_sun0 = water.sun_irradiance * mu_air * (1 - kd::fresnel_reflectance(mu_air, 1.0, n));
  const double t_sky = uniformSkyTransmittance(n);
  const double e_sky0 = water.sky_transmitted >= 0 ? water.sky_transmitted : water.sky_irradiance * t_sky;
  const double flux = e_sun0 + e_sky0;
  const double w0 = flux / static_cast<double>(s.photons) * s.batches;  // one batch's estimate per photon

  const bool hg = phase.kind() == PhaseFunction::Kind::HenyeyGreenstein;
  const double g = hg ? phase.asymmetry() : 0.0;
  const int table_size = 8192;
  const std::vector<double> table = hg ? std::vector<double>{} : phase.samplingTable(table_size);

  std::vector<Tally> batches(s.batches, Tally(depths.size()));
  const double cap_cos = std::cos(s.cap_deg * kPi / 180);
  for (long long i = 0; i < s.photons; ++i) {
    Tally& tally = batches[i % s.batches];
    const Walk walk{depths, bottom, 0.005 / c, cap_cos, 2 * kPi * (1 - cap_cos), tally};
    const unsigned key = kd::pt_path_key(s.seed, static_cast<unsigned>(i >> 32), static_cast<unsigned>(i));
    unsigned dim = 0;
    auto u = [&] { return kd::pt_uniform(key, dim++); };
    double w = w0, mu;
    if (u() * flux < e_sun0) {
      mu = mu_w;
    } else {
      // A uniform sky: cosine-distributed in air, weighted by its transmittance relative to the mean, refracted.
      const double mu_a = std::sqrt(std::max(u(), 1e-300));
      w *= (1 - kd::fresnel_reflectance(mu_a, 1.0, n)) / t_sky;
      mu = std::sqrt(1 - (1 - mu_a * mu_a) / (n * n));
    }
    double z = 0;
    walk.leaves(0, mu, w);
    for (int step = 0; step < 100000; ++step) {
      const double dist = kd::pt_sample_distance(c, u());
      double z1 = z + mu * dist;
      if (z1 <= 0) {  // the surface from below: Fresnel reflection or escape
        walk.segment(z, 0, mu, w);
        if (u() >= kd::fresnel_reflectance(-mu, n, 1.0)) break;
        mu = -mu;
        z = 0;
        walk.leaves(0, mu, w);
        continue;
      }
      if (bottom > 0 && z1 >= bottom) {  // the Lambertian bottom
        walk.segment(z, bottom, mu, w);
        w *= water.bottom_albedo;
        mu = -std::sqrt(std::max(u(), 1e-300));  // cosine-distributed up
        z = bottom;
        walk.leaves(bottom, mu, w);
      } else {
        walk.segment(z, z1, mu, w);
        z = z1;
        if (z > z_kill) break;
        w *= omega;
        // The new direction: 1 - cos ψ from the phase, azimuth uniform; μ' = μ cos ψ + sin θ sin ψ cos φ.
        const double omc = hg ? kd::pt_hg_one_minus_cos(std::abs(g), u())
                              : kd::phase_table_sample_omc(table.data(), table_size, u());
        const double cos_psi = hg && g < 0 ? omc - 1 : 1 - omc;
        const double sin_psi = std::sqrt(std::max(omc * (2 - omc), 0.0));
        const double sin_mu = std::sqrt(std::max(1 - mu * mu, 0.0));
        mu = std::clamp(mu * cos_psi + sin_mu * sin_psi * std::cos(2 * kPi * u()), -1.0, 1.0);
      }
      if (w < 1e-3 * w0) {  // Russian roulette: unbiased, weight restored on survival
        if (u() >= 0.1) break;
        w *= 10;
      }
      if (mu == 0) mu = 1e-12;  // a horizontal photon would never cross a plane
    }
  }

  // Batch means and standard errors.
  LightProfileMc out;
  const int nb = s.batches;
  auto stats = [&](auto field, size_t k, double& mean, double& se) {
    double sum = 0, sum2 = 0;
    for (const Tally& t : batches) {
      const double v = (t.*field)[k];
      sum += v;
      sum2 += v * v;
    }
    mean = sum / nb;
    se = std::sqrt(std::max(sum2 / nb - mean * mean, 0.0) / (nb - 1));
  };
  out.mean.e_d_air = water.sun_irradiance * mu_air + water.sky_irradiance;
  for (size_t k = 0; k < depths.size(); ++k) {
    LightAtDepth m, e;
    m.depth = e.depth = depths[k];
    stats(&Tally::e_d, k, m.e_d, e.e_d);
    stats(&Tally::e_u, k, m.e_u, e.e_u);
    stats(&Tally::e_0d, k, m.e_0d, e.e_0d);
    stats(&Tally::e_0u, k, m.e_0u, e.e_0u);
    stats(&Tally::l_u, k, m.l_u, e.l_u);
    out.mean.rows.push_back(m);
    out.standard_error.push_back(e);
  }
  // L_w and R_rs from L_u just below the surface, when depth 0 is among those asked.
  const double t0_up = (1 - kd::fresnel_reflectance(1.0, n, 1.0)) / (n * n);
  for (size_t k = 0; k < depths.size(); ++k)
    if (depths[k] == 0) {
      out.mean.l_w = out.mean.rows[k].l_u * t0_up;
      out.l_w_se = out.standard_error[k].l_u * t0_up;
    }
  out.mean.r_rs = out.mean.e_d_air > 0 ? out.mean.l_w / out.mean.e_d_air : 0.0;
  out.r_rs_se = out.mean.e_d_air > 0 ? out.l_w_se / out.mean.e_d_air : 0.0;
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace seasim
