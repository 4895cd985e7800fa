#include "underwater/forward_peak.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "math/kernel_math.h"

namespace seasim {

namespace {

constexpr double kPi = std::numbers::pi;

double hg(double mu, double g) { return (1 - g * g) / (4 * kPi * std::pow(1 + g * g - 2 * g * mu, 1.5)); }

// ∫ p_HG dΩ over the cone cos θ >= mu_c: (1 - g²)/(2g) [1/(1 - g) - (1 + g² - 2 g mu_c)^{-1/2}] (g >= 1e-3,
// where the difference loses no more than 1e-13).
double hgCone(double mu_c, double g) {
  return (1 - g * g) / (2 * g) * (1 / (1 - g) - 1 / std::sqrt(1 + g * g - 2 * g * mu_c));
}

// What p_HG holds above its value at mu_c: the cone's light less the cylinder p(mu_c) 2π (1 - mu_c); it
// falls from the whole phase but its floor (mu_c = -1) to 0 (mu_c = 1), since d/dmu_c = -2π (1 - mu_c) p'.
double excessAbove(double mu_c, double g) { return hgCone(mu_c, g) - hg(mu_c, g) * 2 * kPi * (1 - mu_c); }

// The Langevin function coth κ - 1/κ, the von Mises-Fisher mean cosine (its series below κ = 1e-3).
double langevin(double kappa) {
  if (kappa < 1e-3) return kappa / 3 - kappa * kappa * kappa / 45;
  return 1 / std::tanh(kappa) - 1 / kappa;
}

}  // namespace

double hgPeakCeiling(double g, double f) {
  if (!(g >= 1e-3) || !(f >= 1e-9)) return 0.0;
  const double gc = std::min(g, 0.999999);
  if (excessAbove(-1.0, gc) <= f) return hg(-1.0, gc);
  double lo = -1, hi = 1;  // excessAbove(lo) > f >= excessAbove(hi)
  for (int i = 0; i < 200 && hi - lo > 1e-15; ++i) {
    const double mid = 0.5 * (lo + hi);
    (excessAbove(mid, gc) > f ? lo : hi) = mid;
  }
  return hg(0.5 * (lo + hi), gc);
}

double hgPeakMeanCosine(double g, double p_clip) {
  if (!(p_clip > 0) || !(g > 0)) return 1.0;
  const double gc = std::min(g, 0.999999);
  // The peak's edge: p_HG(mu_c) = p_clip, mu_c = (1 + g² - ((1 - g²)/(4π p_clip))^{2/3}) / (2g).
  const double mu_c = std::clamp((1 + gc * gc - std::pow((1 - gc * gc) / (4 * kPi * p_clip), 2.0 / 3.0)) / (2 * gc),
                                 -1.0, 1.0);
  const double theta_c = std::acos(mu_c);
  // θ = θ_c s²: steps crowd where the peak is sharpest.
  constexpr int kSteps = 4000;
  double light = 0, moment = 0;
  for (int i = 0; i < kSteps; ++i) {
    const double s = (i + 0.5) / kSteps, theta = theta_c * s * s;
    const double mu = std::cos(theta);
    const double w = std::max(hg(mu, gc) - p_clip, 0.0) * std::sin(theta) * 2 * theta_c * s;
    light += w;
    moment += w * mu;
  }
  return light > 0 ? std::clamp(moment / light, 0.0, 1.0) : 1.0;
}

double vonMisesFisherKappa(double mean_cosine) {
  if (!(mean_cosine > 0)) return 0.0;
  if (mean_cosine < 1e-9) return 3 * mean_cosine;
  const double target = std::min(mean_cosine, 1 - 1e-12);
  double lo = std::log(1e-10), hi = std::log(1e13);
  for (int i = 0; i < 200 && hi - lo > 1e-14; ++i) {
    const double mid = 0.5 * (lo + hi);
    (langevin(std::exp(mid)) < target ? lo : hi) = mid;
  }
  return std::exp(0.5 * (lo + hi));
}

double vonMisesFisher(double cos_theta, double kappa) {
  if (!(kappa > 1e-10)) return 1 / (4 * kPi);
  return kappa * std::exp(kappa * (std::clamp(cos_theta, -1.0, 1.0) - 1)) / (2 * kPi * -std::expm1(-2 * kappa));
}

namespace {

// The Poisson sum's end for mean n: its tail beyond holds < 1e-12 of the light.
int poissonEnd(double n) { return std::min(static_cast<int>(std::ceil(n + 12 * std::sqrt(n) + 30)), 5000); }

double poisson(int k, double n) { return std::exp(-n + k * std::log(n) - std::lgamma(k + 1.0)); }

}  // namespace

void setForwardPeak(UwiBand& o, const UwBand& band, double g, double f, double mu_w, double y_c) {
  o.p_clip = 0;
  o.aureole_single = 0;
  std::fill(std::begin(o.aureole), std::end(o.aureole), 0.0f);
  // The order-3 in-scatter in src until a high-order fit says otherwise (ordinates_high_order.h).
  std::fill(std::begin(o.aureole_modes), std::end(o.aureole_modes), 0.0f);
  const double p_clip = hgPeakCeiling(g, f);
  if (!(p_clip > 0)) return;
  o.p_clip = static_cast<float>(p_clip);
  // The kernel's own numbers: its beam e_beam0 e^{-m y_c} and the peak's scatterings per metre of depth
  // (c - c') / μ_w, in the floats it reads (uwi_aureole).
  const double q = std::max(double(band.c) - double(o.c_dm), 0.0) / std::max(mu_w, 1e-4);
  const double n = q * std::max(y_c, 0.0);
  const double beam = double(band.e_beam0) * std::exp(-double(o.m) * std::max(y_c, 0.0));
  if (!(n > 0) || !(beam > 0)) return;
  // k = 1: the peak itself, (p_HG - p_clip)+ / f, in Poisson(1; n) of the beam.
  o.aureole_single = static_cast<float>(beam * n * std::exp(-n) / f);
  // k >= 2: von Mises-Fisher with mean cosine ḡ^k, up to where Poisson's tail holds < 1e-12 of the light.
  const double mean = hgPeakMeanCosine(g, p_clip);
  const int k_end = poissonEnd(n);
  std::vector<double> weight, kappa;
  for (int k = 2; k <= k_end; ++k) {
    weight.push_back(poisson(k, n));
    kappa.push_back(vonMisesFisherKappa(std::pow(mean, k)));
  }
  for (int j = 0; j < UWI_AUREOLE_NODES; ++j) {
    const double cos_theta = std::cos(kmath_d::uwi_aureole_node_angle(j));
    double sum = 0;
    for (size_t k = 0; k < weight.size(); ++k) sum += weight[k] * vonMisesFisher(cos_theta, kappa[k]);
    o.aureole[j] = static_cast<float>(beam * sum);
  }
}

void setAureoleModesHeld(UwiBand& o, double g, double mu_w, const std::vector<float>& fit_weight) {
  std::fill(std::begin(o.aureole_modes), std::end(o.aureole_modes), 0.0f);
  if (!(o.p_clip > 0)) return;
  constexpr int kAzimuths = 256;
  const double sin_w = std::sqrt(std::max(1 - mu_w * mu_w, 0.0));
  const int nodes = std::min(static_cast<int>(fit_weight.size()), UWI_SOURCE_NODES);
  for (int j = 0; j < nodes; ++j) {
    const double w = fit_weight[j], nu = kmath_d::uwi_source_node_cosine(j);
    if (!(w > 0) || !(nu > 0)) continue;  // the order-3 table's node, or looking down (no aureole)
    const double sin_nu = std::sqrt(std::max(1 - nu * nu, 0.0));
    double m[3] = {0, 0, 0};
    for (int i = 0; i < kAzimuths; ++i) {
      const double dphi = kPi * (i + 0.5) / kAzimuths;
      const double cos_s = std::clamp(nu * mu_w + sin_nu * sin_w * std::cos(dphi), -1.0, 1.0);
      const double a = kmath_d::uwi_aureole_at_camera(&o, kmath_d::hg_phase(cos_s, g), cos_s, nu);
      for (int mode = 0; mode < 3; ++mode) m[mode] += (mode == 0 ? 1.0 : 2.0) * std::cos(mode * dphi) * a / kAzimuths;
    }
    for (int mode = 0; mode < 3; ++mode) o.aureole_modes[3 * j + mode] = static_cast<float>(w * m[mode]);
  }
}

}  // namespace seasim
