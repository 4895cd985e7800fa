#include "underwater/forward_peak.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "math/kernel_math.h"
#include "underwater/discrete_ordinates.h"

namespace seasim {

namespace {

constexpr double kPi = std::numbers::pi;

// The kernel's own HG (optics.h): its denominator keeps its digits as g -> 1 and μ -> 1.
double hg(double mu, double g) { return kmath_d::hg_phase(mu, g); }

// ∫ p_HG dΩ over the cone cos θ >= mu_c: (1 - g²)/(2g) [1/(1 - g) - (1 + g² - 2 g mu_c)^{-1/2}] (g >= 1e-3,
// where the difference loses no more than 1e-13).
double hgCone(double mu_c, double g) {
  return (1 - g * g) / (2 * g) * (1 / (1 - g) - 1 / std::sqrt(1 + g * g - 2 * g * mu_c));
}

// What p_HG holds above its value at mu_c: the cone's light less the cylinder p(mu_c) 2π (1 - mu_c); it
// falls from the whole phase but its floor (mu_c = -1) to 0 (mu_c = 1), since d/dmu_c = -2π (1 - mu_c) p'.
double excessAbove(double mu_c, double g) { return hgCone(mu_c, g) - hg(mu_c, g) * 2 * kPi * (1 - mu_c); }

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

ForwardPeak forwardPeak(double g, double f) {
  ForwardPeak peak;
  peak.g = g;
  peak.f = f;
  peak.p_clip = hgPeakCeiling(g, f);
  if (!(peak.p_clip > 0)) return peak;
  const double gc = std::min(g, 0.999999);
  // The peak's edge: p_HG(mu_c) = p_clip, mu_c = (1 + g² - ((1 - g²)/(4π p_clip))^{2/3}) / (2g).
  const double mu_c = std::clamp(
      (1 + gc * gc - std::pow((1 - gc * gc) / (4 * kPi * peak.p_clip), 2.0 / 3.0)) / (2 * gc), -1.0, 1.0);
  const double theta_c = std::acos(mu_c);
  // θ = θ_c s²: steps crowd where the peak is sharpest (its core is 1 - g wide); at the edge they are
  // 2 θ_c / 6000 apart, a tenth of P_4000's period.
  constexpr int kSteps = 6000, kMaxOrder = 4000, kQuietRun = 32;
  std::vector<double> mu(kSteps), w(kSteps), p_prev(kSteps, 1.0), p(kSteps);
  double light = 0;
  for (int i = 0; i < kSteps; ++i) {
    const double s = (i + 0.5) / kSteps, theta = theta_c * s * s;
    mu[i] = std::cos(theta);
    w[i] = std::max(hg(mu[i], gc) - peak.p_clip, 0.0) * 2 * kPi * std::sin(theta) * 2 * theta_c * s / kSteps;
    light += w[i];
    p[i] = mu[i];
  }
  if (!(light > 0)) return peak;
  peak.moments.push_back(1.0);
  int quiet = 0;
  for (int l = 1; l <= kMaxOrder && quiet < kQuietRun; ++l) {
    double chi = 0;
    for (int i = 0; i < kSteps; ++i) chi += w[i] * p[i];
    chi /= light;
    peak.moments.push_back(chi);
    quiet = std::abs(chi) < 1e-7 ? quiet + 1 : 0;
    for (int i = 0; i < kSteps; ++i) {  // P_{l+1} = ((2l + 1) μ P_l - l P_{l-1}) / (l + 1)
      const double next = ((2 * l + 1) * mu[i] * p[i] - l * p_prev[i]) / (l + 1);
      p_prev[i] = p[i];
      p[i] = next;
    }
  }
  return peak;
}

double setForwardPeak(UwiBand& o, const UwBand& band, const ForwardPeak& peak, double mu_w, double y_c) {
  o.p_clip = 0;
  o.aureole_single = 0;
  std::fill(std::begin(o.aureole), std::end(o.aureole), 0.0f);
  // The order-3 in-scatter in src until a high-order fit says otherwise (ordinates_high_order.h).
  std::fill(std::begin(o.aureole_modes), std::end(o.aureole_modes), 0.0f);
  if (!(peak.p_clip > 0) || peak.moments.empty()) return 1.0;
  o.p_clip = static_cast<float>(peak.p_clip);
  // The kernel's own numbers: its beam e_beam0 e^{-m y_c} and the peak's scatterings per metre of depth
  // (c - c') / μ_w, in the floats it reads (uwi_aureole).
  const double q = std::max(double(band.c) - double(o.c_dm), 0.0) / std::max(mu_w, 1e-4);
  const double n = q * std::max(y_c, 0.0);
  const double beam = double(band.e_beam0) * std::exp(-double(o.m) * std::max(y_c, 0.0));
  if (!(n > 0) || !(beam > 0)) return 1.0;
  // Once: the peak itself, (p_HG - p_clip)+ / f, in Poisson(1; n) of the beam.
  o.aureole_single = static_cast<float>(beam * n * std::exp(-n) / peak.f);
  // Twice or more: Σ_{k>=2} Poisson(k; n) χ_l^k = e^{-n} (e^{n χ_l} - 1 - n χ_l), written without e^{n}
  // (which overflows for a deep camera) and by its series where n χ_l is small.
  const size_t orders = peak.moments.size();
  std::vector<double> coefficient(orders);
  const double e_n = std::exp(-n);
  for (size_t l = 0; l < orders; ++l) {
    const double chi = peak.moments[l], x = n * chi;
    const double more = std::abs(x) < 1e-3 ? e_n * x * x * (0.5 + x / 6 + x * x / 24)
                                           : std::exp(n * (chi - 1)) - e_n * (1 + x);
    coefficient[l] = (2.0 * l + 1) / (4 * kPi) * more;
  }
  std::vector<double> table(UWI_AUREOLE_NODES);
  for (int j = 0; j < UWI_AUREOLE_NODES; ++j) {
    const double mu = std::cos(kmath_d::uwi_aureole_node_angle(j));
    double p_prev = 1, p = mu, sum = coefficient[0] + (orders > 1 ? coefficient[1] * mu : 0.0);
    for (size_t l = 1; l + 1 < orders; ++l) {
      const double next = ((2.0 * l + 1) * mu * p - double(l) * p_prev) / double(l + 1);
      p_prev = p;
      p = next;
      sum += coefficient[l + 1] * p;
    }
    // The truncated series rings a little where the light is nothing: not below 0.
    table[j] = std::max(sum, 0.0);
  }
  // The table as the kernel reads it (linear in uwi_aureole_node's t = √(θ/π)) holds what it should over the
  // sphere, 1 - e^{-n} (1 + n) of the beam: scaled to it. Measured (forward_peak_test): a factor of 0.995-1.000
  // at g <= 0.95, 0.981 at 0.99, 0.836 at 0.999, whose core (0.06°) falls between the first two nodes.
  double held = 0;
  constexpr int kSub = 32;
  for (int j = 0; j + 1 < UWI_AUREOLE_NODES; ++j)
    for (int i = 0; i < kSub; ++i) {
      const double frac = (i + 0.5) / kSub, t = (j + frac) / (UWI_AUREOLE_NODES - 1);
      const double theta = kPi * t * t, d_theta = 2 * kPi * t / (UWI_AUREOLE_NODES - 1) / kSub;
      held += (table[j] + frac * (table[j + 1] - table[j])) * 2 * kPi * std::sin(theta) * d_theta;
    }
  const double want = std::abs(n) < 1e-3 ? e_n * n * n * (0.5 + n / 3) : 1 - e_n * (1 + n);
  const double scale = held > 0 ? want / held : 1.0;
  for (int j = 0; j < UWI_AUREOLE_NODES; ++j) o.aureole[j] = static_cast<float>(beam * scale * table[j]);
  return scale;
}

void setAureoleModesHeld(UwiBand& o, double g, double mu_w, const std::vector<float>& fit_weight) {
  std::fill(std::begin(o.aureole_modes), std::end(o.aureole_modes), 0.0f);
  if (!(o.p_clip > 0)) return;
  const int nodes = std::min(static_cast<int>(fit_weight.size()), UWI_SOURCE_NODES);
  for (int j = 0; j < nodes; ++j) {
    const double w = fit_weight[j], nu = kmath_d::uwi_source_node_cosine(j);
    if (!(w > 0) || !(nu > 0)) continue;  // the order-3 table's node, or looking down (no aureole)
    const std::array<double, 3> m = azimuthModes(nu, mu_w, 256, [&](double cos_s) {
      return kmath_d::uwi_aureole_at_camera(&o, kmath_d::hg_phase(cos_s, g), cos_s, nu);
    });
    for (int mode = 0; mode < 3; ++mode) o.aureole_modes[3 * j + mode] = static_cast<float>(w * m[mode]);
  }
}

}  // namespace seasim
