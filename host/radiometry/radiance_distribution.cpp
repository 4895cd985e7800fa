#include "radiometry/radiance_distribution.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "math/kernel_math.h"
#include "reference/batch_error.h"

namespace seasim {
namespace {

namespace kd = kmath_d;
constexpr double kPi = 3.14159265358979323846;

struct Dir {
  double x, y, m;  // m = μ = cos θ, > 0 travelling down
};

// d turned by the scattering angle (cos ψ, sin ψ) at azimuth φ about itself.
Dir scatter(const Dir& d, double cos_psi, double sin_psi, double phi) {
  // A unit vector perpendicular to d, then the third of the frame.
  double tx, ty, tm;
  if (std::abs(d.m) < 0.9) {  // d × (0, 0, 1)
    const double l = std::hypot(d.x, d.y);
    tx = d.y / l, ty = -d.x / l, tm = 0;
  } else {  // d × (1, 0, 0)
    const double l = std::hypot(d.m, d.y);
    tx = 0, ty = d.m / l, tm = -d.y / l;
  }
  const double bx = d.y * tm - d.m * ty, by = d.m * tx - d.x * tm, bm = d.x * ty - d.y * tx;
  const double c = std::cos(phi) * sin_psi, s = std::sin(phi) * sin_psi;
  Dir o{d.x * cos_psi + tx * c + bx * s, d.y * cos_psi + ty * c + by * s, d.m * cos_psi + tm * c + bm * s};
  const double n = std::sqrt(o.x * o.x + o.y * o.y + o.m * o.m);
  return Dir{o.x / n, o.y / n, std::clamp(o.m / n, -1.0, 1.0)};
}

}  // namespace

double RadianceDistribution::cellProjectedSolidAngle(int row) const {
  const double t0 = row * kPi / n_theta, t1 = (row + 1) * kPi / n_theta;
  const double s0 = std::sin(t0), s1 = std::sin(t1);
  return std::abs(s1 * s1 - s0 * s0) / 2 * (2 * kPi / n_phi);
}

double RadianceDistribution::hemisphereIrradiance(size_t k, bool down) const {
  double sum = 0;
  for (int i = down ? 0 : n_theta / 2; i < (down ? n_theta / 2 : n_theta); ++i) {
    const double a = cellProjectedSolidAngle(i);
    for (int j = 0; j < n_phi; ++j) sum += radiance[k][static_cast<size_t>(i) * n_phi + j] * a;
  }
  return sum;
}

namespace {

void checkSettings(const PlaneParallelWater& water, const std::vector<double>& depths,
                   const RadianceDistributionSettings& s) {
  if (s.n_theta < 2 || s.n_theta % 2 != 0 || s.n_theta > 1800 || s.n_phi < 1 || s.n_phi > 3600)
    throw std::invalid_argument("radiance distribution: n_theta must be even in [2, 1800], n_phi in [1, 3600]");
  if (s.photons < s.batches || s.batches < 2)
    throw std::invalid_argument("radiance distribution: need photons >= batches >= 2");
  if (!(water.a >= 0 && water.b >= 0 && water.a + water.b > 0))
    throw std::invalid_argument("radiance distribution: a, b must be >= 0 with c > 0");
  for (double z : depths)
    if (!(z >= 0) || (water.bottom_depth > 0 && z > water.bottom_depth))
      throw std::invalid_argument("radiance distribution: depths must lie in the water");
}

// The radiance per cell (the crossing weight over the cell's projected solid angle) and E_d, E_u per depth,
// each with its standard error from the batches (values: the cells of every depth, then E_d, E_u per depth).
RadianceDistribution fromBatches(const BatchMeans& batches, const std::vector<double>& depths,
                                 const RadianceDistributionSettings& s) {
  RadianceDistribution out;
  out.n_theta = s.n_theta;
  out.n_phi = s.n_phi;
  out.depths = depths;
  const size_t nd = depths.size(), cells = static_cast<size_t>(s.n_theta) * s.n_phi, ne = nd * cells;
  for (size_t k = 0; k < nd; ++k) {
    std::vector<double> l(cells), e(cells);
    for (int i = 0; i < s.n_theta; ++i) {
      const double a = out.cellProjectedSolidAngle(i);
      for (int j = 0; j < s.n_phi; ++j) {
        const size_t q = static_cast<size_t>(i) * s.n_phi + j;
        const BatchEstimate b = batches.estimate(k * cells + q);
        l[q] = b.mean / a;
        e[q] = b.std_error / a;
      }
    }
    out.radiance.push_back(std::move(l));
    out.standard_error.push_back(std::move(e));
    const BatchEstimate ed = batches.estimate(ne + 2 * k), eu = batches.estimate(ne + 2 * k + 1);
    out.e_d.push_back(ed.mean);
    out.e_u.push_back(eu.mean);
    out.e_d_se.push_back(ed.std_error);
    out.e_u_se.push_back(eu.std_error);
  }
  return out;
}

}  // namespace

RadianceDistribution solveRadianceDistribution(const PlaneParallelWater& water, const PhaseFunction& phase,
                                               const std::vector<double>& depths,
                                               const RadianceDistributionSettings& s) {
  checkSettings(water, depths, s);
  const auto t0 = std::chrono::steady_clock::now();
  const double c = water.a + water.b, omega = water.b / c, n = water.ior;
  const double bottom = water.bottom_depth > 0 ? water.bottom_depth : 0.0;
  double deepest = 0;
  for (double z : depths) deepest = std::max(deepest, z);
  const double z_kill = bottom > 0 ? 2 * bottom + 1 : deepest + 40 / c;

  const double mu_air = std::cos(water.sun_zenith);
  const double sin_w = std::sin(water.sun_zenith) / n, mu_w = std::sqrt(1 - sin_w * sin_w);
  const double e_sun0 = water.sun_irradiance * mu_air * (1 - kd::fresnel_reflectance(mu_air, 1.0, n));
  const double t_sky = uniformSkyTransmittance(n);
  const double e_sky0 = water.sky_transmitted >= 0 ? water.sky_transmitted : water.sky_irradiance * t_sky;
  const double flux = e_sun0 + e_sky0, w0 = flux;

  const bool hg = phase.kind() == PhaseFunction::Kind::HenyeyGreenstein;
  const double g = hg ? phase.asymmetry() : 0.0;
  const int table_size = 8192;
  const std::vector<double> table = hg ? std::vector<double>{} : phase.samplingTable(table_size);

  const size_t nd = depths.size(), cells = static_cast<size_t>(s.n_theta) * s.n_phi;
  const size_t ne = nd * cells;  // then E_d and E_u per depth
  const size_t nv = ne + 2 * nd;
  std::vector<double> block(nv, 0.0);
  BatchMeans batches(nv);
  long long block_n = 0;
  int block_index = 0;

  auto cross = [&](size_t k, const Dir& d, double w) {
    const double theta = std::acos(std::clamp(d.m, -1.0, 1.0));
    double phi = std::atan2(d.y, d.x);
    if (phi < 0) phi += 2 * kPi;
    const int i = std::min(static_cast<int>(theta / kPi * s.n_theta), s.n_theta - 1);
    const int j = std::min(static_cast<int>(phi / (2 * kPi) * s.n_phi), s.n_phi - 1);
    block[k * cells + static_cast<size_t>(i) * s.n_phi + j] += w;
    block[ne + 2 * k + (d.m > 0 ? 0 : 1)] += w;
  };
  // The planes crossed by a segment z0 -> z1 (start excluded, end included) and those a photon leaves.
  auto segment = [&](double z0, double z1, const Dir& d, double w) {
    for (size_t k = 0; k < nd; ++k)
      if (d.m > 0 ? (depths[k] > z0 && depths[k] <= z1) : (depths[k] >= z1 && depths[k] < z0)) cross(k, d, w);
  };
  auto leaves = [&](double z_b, const Dir& d, double w) {
    for (size_t k = 0; k < nd; ++k)
      if (depths[k] == z_b) cross(k, d, w);
  };

  for (long long p = 0; p < s.photons; ++p) {
    const unsigned key = kd::pt_path_key(s.seed, static_cast<unsigned>(p >> 32), static_cast<unsigned>(p));
    unsigned dim = 0;
    auto u = [&] { return kd::pt_uniform(key, dim++); };
    double w = w0;
    Dir d;
    if (u() * flux < e_sun0) {
      d = Dir{sin_w, 0, mu_w};
    } else {
      const double mu_a = std::sqrt(std::max(u(), 1e-300));
      w *= (1 - kd::fresnel_reflectance(mu_a, 1.0, n)) / t_sky;
      const double m = std::sqrt(1 - (1 - mu_a * mu_a) / (n * n)), a = 2 * kPi * u(), sn = std::sqrt(1 - m * m);
      d = Dir{sn * std::cos(a), sn * std::sin(a), m};
    }
    double z = 0;
    leaves(0, d, w);
    for (int step = 0; step < 100000; ++step) {
      const double z1 = z + d.m * kd::pt_sample_distance(c, u());
      if (z1 <= 0) {  // the surface: the reflected share goes on as a weight
        segment(z, 0, d, w);
        w *= kd::fresnel_reflectance(-d.m, n, 1.0);
        d.m = -d.m;
        z = 0;
        leaves(0, d, w);
      } else if (bottom > 0 && z1 >= bottom) {  // the Lambertian bottom
        segment(z, bottom, d, w);
        w *= water.bottom_albedo;
        const double m = -std::sqrt(std::max(u(), 1e-300)), a = 2 * kPi * u(), sn = std::sqrt(1 - m * m);
        d = Dir{sn * std::cos(a), sn * std::sin(a), m};
        z = bottom;
        leaves(bottom, d, w);
      } else {
        segment(z, z1, d, w);
        z = z1;
        if (z > z_kill) break;
        w *= omega;
        double omc = hg ? kd::pt_hg_one_minus_cos(std::abs(g), u()) : kd::phase_table_sample_omc(table.data(), table_size, u());
        if (hg && g < 0) omc = 2 - omc;
        d = scatter(d, 1 - omc, std::sqrt(std::max(omc * (2 - omc), 0.0)), 2 * kPi * u());
      }
      if (w < 1e-3 * w0) {  // Russian roulette: unbiased, weight restored on survival
        if (w == 0 || u() >= 0.1) break;
        w *= 10;
      }
      if (d.m == 0) d.m = 1e-12;
    }
    ++block_n;
    const long long block_end =
        (s.photons / s.batches) * (block_index + 1) + std::min<long long>(block_index + 1, s.photons % s.batches);
    if (p + 1 == block_end) {
      for (double& v : block) v /= static_cast<double>(block_n);
      batches.addBlock(block.data(), nullptr, block_n);
      std::fill(block.begin(), block.end(), 0.0);
      block_n = 0;
      ++block_index;
    }
  }

  RadianceDistribution out = fromBatches(batches, depths, s);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace seasim
