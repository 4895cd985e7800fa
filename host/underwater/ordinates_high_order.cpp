#include "underwater/ordinates_high_order.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "math/kernel_math.h"
#include "math/linear_solve.h"

namespace seasim {
namespace {

constexpr double kPi = 3.14159265358979323846;
// The weak source rows' weight against the segment rows (both relative): 0.005-0.02 gave the same regions,
// 0.1 let the bracket's thin layers pull the far bottom down (0.962 -> 0.937;
// docs/journal/underwater_regions_4_*.md).
constexpr double kSourceRowWeight = 0.01;
// The mirror rays' rows against the camera's (the surface's reflection, seen at its Fresnel share).
constexpr double kMirrorRowWeight = 0.5;
// The taper towards the beam, from and to this angle from its direction (regions unchanged from 5-10° to
// 20-30°: no frame of the study looks towards the sun).
constexpr double kTaperFrom = 10 * kPi / 180, kTaperTo = 20 * kPi / 180;

// ∫_0^Δs S(s) e^{-c (Δs - s)} ds for S linear from s_start to s_end over the step, τ = c Δs > 0:
// (1/c) [S_end (1 - e^{-τ}) - (S_end - S_start) (1 - e^{-τ} (1 + τ)) / τ], the last ratio by its series
// below τ = 1e-3 (it loses digits there).
double linearSourceStep(double s_start, double s_end, double c, double tau, double e_tau) {
  const double ramp = tau < 1e-3 ? tau * (0.5 - tau * (1.0 / 3.0 - tau / 8.0)) : (1 - e_tau * (1 + tau)) / tau;
  return (s_end * -std::expm1(-tau) - (s_end - s_start) * ramp) / c;
}

// 2π ∫_0^1 (1 - R(μ)) μ dμ: the irradiance a unit sky radiance brings through the surface (midpoints
// inside the window), which the solver's sky is scaled by (e_sky0 over it).
double skyUnit(double ior) {
  const double mu_c = ior > 1 ? std::sqrt(1 - 1 / (ior * ior)) : 0.0;
  const int n = 4000;
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    const double mu = mu_c + (1 - mu_c) * (i + 0.5) / n;
    sum += (1 - kmath_d::fresnel_reflectance(mu, ior, 1.0)) * mu;
  }
  return 2 * kPi * sum * (1 - mu_c) / n;
}

}  // namespace

double HighOrderField::lerp(const std::vector<double>& v, int u, double y) const {
  const double t = std::clamp(y / step, 0.0, double(depths - 1));
  const int i = std::min(static_cast<int>(t), depths - 2);
  const double w = t - i;
  return v[size_t(i) * cosines + u] * (1 - w) + v[size_t(i + 1) * cosines + u] * w;
}

double beamTaper(double nu, double mu_sun, double delta0, double delta1) {
  const double delta = std::abs(std::acos(std::clamp(nu, -1.0, 1.0)) - std::acos(std::clamp(mu_sun, -1.0, 1.0)));
  const double t = std::clamp((delta - delta0) / std::max(delta1 - delta0, 1e-12), 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

HighOrderField solveHighOrderField(const DiscreteOrdinatesLayer& layer, int streams, int modes,
                                   const std::vector<double>& nus, double y_end) {
  if (modes < 1 || modes > 3 || !(y_end > 0)) throw std::invalid_argument("high-order field: 1-3 modes, y_end > 0");
  const int n_nu = static_cast<int>(nus.size());
  for (int u = 0; u < n_nu; ++u)
    if (std::abs(nus[u] + nus[n_nu - 1 - u]) > 1e-12)
      throw std::invalid_argument("high-order field: the cosines must be symmetric about 0");
  const bool bottom = layer.bottom_depth > 0;
  const DiscreteOrdinates field0(layer, streams, 0, streams);
  HighOrderField out;
  out.c = field0.extinction();
  out.modes = modes;
  out.cosines = n_nu;
  const double c_f = out.c, m_f = field0.beamK(), e_beam = layer.e_sun0 / layer.mu_sun;
  const double y_grid = bottom ? layer.bottom_depth : y_end + 30.0 / c_f;
  const int intervals =
      std::clamp(static_cast<int>(std::ceil(std::max(y_grid * c_f / 0.5, 100 * y_grid / y_end))), 2, 6000);
  const double h = y_grid / intervals;
  const int n_y = intervals + 1;
  out.step = h;
  out.depths = n_y;

  double bottom_radiance = 0;  // Lambertian (mode 0): (ρ/π) (E_d + s e_sun0 e^{-m H}), the solver's condition
  if (bottom) {
    const DiscreteOrdinatesIrradiance e = field0.at(layer.bottom_depth);
    bottom_radiance = layer.bottom_albedo / kPi *
                      (e.down + layer.bottom_sunlit * layer.e_sun0 * std::exp(-m_f * layer.bottom_depth));
  }
  const double sky_radiance = layer.e_sky0 > 0 ? layer.e_sky0 / skyUnit(layer.ior) : 0.0;
  for (int mode = 0; mode < modes; ++mode) {
    const DiscreteOrdinates field = mode == 0 ? field0 : DiscreteOrdinates(layer, streams, mode, streams);
    std::vector<double>& src = out.source[mode];
    src = field.inscatterProfile(nus, y_grid, n_y);
    std::vector<double>& phase = out.beam_phase[mode];
    phase.resize(n_nu);
    for (int u = 0; u < n_nu; ++u) phase[u] = layer.b * hgAzimuthMode(layer.g, mode, nus[u], layer.mu_sun) * e_beam;
    for (int i = 0; i < n_y; ++i) {
      const double beam = std::exp(-m_f * i * h);
      for (int u = 0; u < n_nu; ++u) src[size_t(i) * n_nu + u] += phase[u] * beam;
    }
    // Upward directions from the bottom (or the grid's end, where the light is the local source over c_f),
    // then downward ones from the surface (Fresnel's reflection of the upward light, and in mode 0 the sky
    // through the window), each step exact for a source linear in depth. Horizontal: S / c_f.
    std::vector<double>& radiance = out.radiance[mode];
    radiance.assign(src.size(), 0.0);
    auto at = [n_nu](std::vector<double>& v, int i, int u) -> double& { return v[size_t(i) * n_nu + u]; };
    for (int u = 0; u < n_nu; ++u) {
      const double nu = nus[u];
      if (std::abs(nu) < 1e-12) {
        for (int i = 0; i < n_y; ++i) at(radiance, i, u) = at(src, i, u) / c_f;
      } else if (nu < 0) {
        const double tau = c_f * h / -nu, e_tau = std::exp(-tau);
        double l = bottom ? (mode == 0 ? bottom_radiance : 0.0) : at(src, n_y - 1, u) / c_f;
        at(radiance, n_y - 1, u) = l;
        for (int i = n_y - 2; i >= 0; --i) {
          l = l * e_tau + linearSourceStep(at(src, i + 1, u), at(src, i, u), c_f, tau, e_tau);
          at(radiance, i, u) = l;
        }
      }
    }
    for (int u = 0; u < n_nu; ++u) {
      const double nu = nus[u];
      if (!(nu > 1e-12)) continue;
      const double r = kmath_d::fresnel_reflectance(nu, layer.ior, 1.0);
      double l = r * at(radiance, 0, n_nu - 1 - u) + (mode == 0 ? (1 - r) * sky_radiance : 0.0);
      at(radiance, 0, u) = l;
      const double tau = c_f * h / nu, e_tau = std::exp(-tau);
      for (int i = 1; i < n_y; ++i) {
        l = l * e_tau + linearSourceStep(at(src, i - 1, u), at(src, i, u), c_f, tau, e_tau);
        at(radiance, i, u) = l;
      }
    }
  }
  return out;
}

void fitSourceTableToField(const HighOrderField& field, const std::vector<double>& nus, const SourceTableBasis& basis,
                           double mu_sun, bool beam, float* table, int terms_per_cosine, float* fit_weight) {
  const double k = basis.k, m = basis.m, c = basis.c_kernel;
  const bool bottom = basis.bottom_depth > 0;
  const double H = basis.bottom_depth;
  const double y_cam = std::clamp(basis.view_depth, 0.0, bottom ? H : basis.depth_end);
  const double step = basis.depth_end / (basis.samples - 1);
  // As the order-3 fit: e^{-m y} left out where k comes within 2 % of m.
  std::vector<int> columns = bottom ? std::vector<int>{0, 1} : std::vector<int>{0};
  if (std::abs(k - m) >= 0.02 * m) columns.push_back(2);
  const int n = static_cast<int>(columns.size());
  // The source rows' exponentials at the depth samples: the same for every cosine.
  std::vector<std::array<double, 3>> values(basis.samples);
  for (int s = 0; s < basis.samples; ++s) {
    const double y = s * step;
    values[s] = {std::exp(-k * y), bottom ? std::exp(-k * (H - y)) : 0.0, std::exp(-m * y)};
  }
  const int modes = field.modes;
  auto tms = [&](int mode, int j) {
    return basis.tms[mode].empty() ? field.beam_phase[mode][j] : basis.tms[mode][j];
  };
  std::vector<double> normal, rhs;
  for (int j = 0; j < field.cosines; ++j) {
    const double w = beam ? beamTaper(nus[j], mu_sun, kTaperFrom, kTaperTo) : 1.0;
    if (w <= 0) continue;
    const double nu = nus[j];
    // One normal matrix for the cosine (the rows' weights are the azimuth average's), a right-hand side per
    // mode.
    normal.assign(size_t(n) * n, 0.0);
    rhs.assign(size_t(n) * modes, 0.0);
    auto addRow = [&](const std::array<double, 3>& b, const double* targets, double weight) {
      const double w2 = weight * weight;
      for (int r = 0; r < n; ++r) {
        for (int mode = 0; mode < modes; ++mode) rhs[size_t(r) * modes + mode] += w2 * b[columns[r]] * targets[mode];
        for (int q = 0; q < n; ++q) normal[r * n + q] += w2 * b[columns[r]] * b[columns[q]];
      }
    };
    double targets[3] = {0, 0, 0};
    // Segments from the camera, and for light travelling up the surface's mirror rays (from 0, down).
    for (int start = 0; start < (nu < 0 ? 2 : 1); ++start) {
      const double y0 = start == 0 ? y_cam : 0.0;
      const double to_boundary = nu > 1e-12 ? y0 / nu : nu < -1e-12 && bottom ? (H - y0) / -nu : 1e30;
      const double scale = std::max(std::abs(field.radianceAt(0, j, y0)), 1e-300);
      const double weight = (start == 0 ? 1.0 : kMirrorRowWeight) / scale;
      std::vector<double> lengths;
      for (double tau : {0.25, 0.5, 1.0, 2.0, 4.0, 8.0, 16.0, 32.0})
        if (tau / c < to_boundary) lengths.push_back(tau / c);
      lengths.push_back(to_boundary);
      for (double len : lengths) {
        const std::array<double, 3> integrals = {
            kmath_d::kd_exp_integral(k, c, nu, y0, len),
            bottom ? kmath_d::kd_exp_integral(k, c, -nu, std::max(H - y0, 0.0), len) : 0.0,
            kmath_d::kd_exp_integral(m, c, nu, y0, len)};
        const double attenuation = len >= 1e29 ? 0.0 : std::exp(-c * len);
        for (int mode = 0; mode < modes; ++mode)
          targets[mode] = field.radianceAt(mode, j, y0) - attenuation * field.radianceAt(mode, j, y0 - nu * len) -
                          tms(mode, j) * integrals[2];
        addRow(integrals, targets, weight);
      }
    }
    // The bracket itself, weakly, at the depth samples.
    for (int s = 0; s < basis.samples; ++s) {
      const double y = s * step;
      for (int mode = 0; mode < modes; ++mode)
        targets[mode] = field.sourceAt(mode, j, y) - (field.c - c) * field.radianceAt(mode, j, y) -
                        tms(mode, j) * values[s][2];
      addRow(values[s], targets, kSourceRowWeight / std::max(std::abs(field.sourceAt(0, j, y)), 1e-300));
    }
    if (!solveLinear(normal, rhs, n, modes)) continue;  // keeps the order-3 fit
    for (int mode = 0; mode < modes; ++mode) {
      std::array<double, 3> coefficients{};
      for (int r = 0; r < n; ++r) coefficients[columns[r]] = rhs[size_t(r) * modes + mode];
      float* row = table + j * terms_per_cosine + 3 * mode;
      for (int q = 0; q < 3; ++q) row[q] = static_cast<float>(w * coefficients[q] + (1 - w) * row[q]);
    }
    if (fit_weight) fit_weight[j] = static_cast<float>(w);
  }
}

}  // namespace seasim
