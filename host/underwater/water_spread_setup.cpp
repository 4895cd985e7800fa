#include "underwater/water_spread_setup.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "util/error.h"

namespace seasim {

static_assert(sizeof(UwsParams) == 16 * 4, "UwsParams layout changed: update water_spread_params.h users");
static_assert(offsetof(UwsParams, factor) == 4 * 4 && offsetof(UwsParams, channels) == 5 * 4);
static_assert(offsetof(UwsParams, radius) == 8 * 4 && offsetof(UwsParams, tap_offset) == 12 * 4);

namespace {

// The peak's cumulative distribution over theta (water_spread_setup.h), on `steps` + 1 evenly spaced
// angles from 0 to pi, clamped to [0, 1] (the peak is negative at some angles for a truncated HG, so
// its raw cumulative rises a few % above 1 before it ends at 1). Empty without a peak.
std::vector<double> peakCdf(double g, int order, int steps) {
  if (g <= 0 || order < 1) return {};
  const double f = std::pow(g, order);
  if (f < 1e-6) return {};
  const double pi = std::acos(-1.0);
  // Density over theta of the peak's probability: peak(mu) sin(theta) / 2 (the peak integrates to 1 over
  // dOmega / (4 pi)).
  auto density = [&](double theta) {
    const double mu = std::cos(theta);
    const double hg = (1 - g * g) / std::pow(1 + g * g - 2 * g * mu, 1.5);
    double p_prev = 1, p = mu, truncated = 1 - f;  // l = 0: (g^0 - f) P_0
    for (int l = 1; l < order; ++l) {
      truncated += (2 * l + 1) * (std::pow(g, l) - f) * p;
      const double next = ((2 * l + 1) * mu * p - l * p_prev) / (l + 1);
      p_prev = p;
      p = next;
    }
    return (hg - truncated) / f * std::sin(theta) / 2;
  };
  const double h = pi / steps;
  std::vector<double> cdf(steps + 1, 0.0);
  double sum = 0, prev = density(0.0);
  for (int i = 1; i <= steps; ++i) {
    const double d = density(i * h);
    sum += 0.5 * (prev + d) * h;
    prev = d;
    cdf[i] = std::clamp(sum, 0.0, 1.0);
  }
  return cdf;
}

// The table's value at theta (linear; 1 beyond pi).
double cdfAt(const std::vector<double>& cdf, double theta) {
  const int steps = static_cast<int>(cdf.size()) - 1;
  const double x = theta / std::acos(-1.0) * steps;
  if (x >= steps) return 1.0;
  const int i = static_cast<int>(x);
  return cdf[i] + (x - i) * (cdf[i + 1] - cdf[i]);
}

constexpr int kCdfSteps = 20000;

}  // namespace

double deltaMPeakMedianAngle(double g, int order) {
  const std::vector<double> cdf = peakCdf(g, order, kCdfSteps);
  if (cdf.empty()) return 0.0;
  const double h = std::acos(-1.0) / kCdfSteps;
  for (int i = 1; i <= kCdfSteps; ++i)
    if (cdf[i] >= 0.5) return (i - 1 + (0.5 - cdf[i - 1]) / (cdf[i] - cdf[i - 1])) * h;
  return std::acos(-1.0);
}

double deltaMPeakDisplacementMedian(double g, int order) {
  const std::vector<double> cdf = peakCdf(g, order, kCdfSteps);
  if (cdf.empty()) return 0.0;
  // P(theta v < rho) = integral_0^1 C(rho / v) dv, v = 1 - x/S uniform (water_spread.h (2)); midpoint rule
  // in v, bisection in rho (P rises with rho from 0 to 1).
  auto below = [&](double rho) {
    const int n = 4000;
    double sum = 0;
    for (int j = 0; j < n; ++j) sum += cdfAt(cdf, rho / ((j + 0.5) / n));
    return sum / n;
  };
  double lo = 0, hi = std::acos(-1.0);
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    (below(mid) < 0.5 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double singleScatterSpread(double g, int order) {
  return deltaMPeakDisplacementMedian(g, order) / std::sqrt(2 * std::log(2.0));
}

std::vector<float> gaussianTaps(double sigma, int max_radius) {
  if (!(sigma > 0)) return {1.0f};
  const int radius = std::min(max_radius, static_cast<int>(std::ceil(3 * sigma)));
  std::vector<double> w(radius + 1);
  double sum = 0;
  for (int j = 0; j <= radius; ++j) {
    w[j] = std::exp(-0.5 * (j / sigma) * (j / sigma));
    sum += j == 0 ? w[j] : 2 * w[j];
  }
  std::vector<float> taps(radius + 1);
  for (int j = 0; j <= radius; ++j) taps[j] = static_cast<float>(w[j] / sum);
  return taps;
}

WaterSpread waterSpreadGrid(int width, int height, int factor) {
  WaterSpread s;
  s.params.width = width;
  s.params.height = height;
  s.params.factor = factor;
  s.params.low_width = (width + factor - 1) / factor;
  s.params.low_height = (height + factor - 1) / factor;
  s.params.channels = 3;
  return s;
}

void addLayerTaps(WaterSpread& s, int k, double sigma_cells) {
  // A layer wider than the grid adds nothing but time: its taps stop at the grid's larger side.
  const std::vector<float> taps = gaussianTaps(sigma_cells, std::max(s.params.low_width, s.params.low_height));
  s.params.radius[k] = static_cast<int>(taps.size()) - 1;
  s.params.tap_offset[k] = static_cast<int>(s.taps.size());
  s.taps.insert(s.taps.end(), taps.begin(), taps.end());
}

WaterSpread makeWaterSpread(double g, int order, double tan_half_fov_y, int width, int height) {
  if (width <= 0 || height <= 0 || !(tan_half_fov_y > 0))
    throw RuntimeError("water spread: the image needs a size and a field of view");
  const double sigma1_px = singleScatterSpread(g, order) / (2 * tan_half_fov_y / height);
  const int factor = std::max(1, static_cast<int>(std::floor(sigma1_px / 2)));
  WaterSpread s = waterSpreadGrid(width, height, factor);
  s.sigma1_px = sigma1_px;
  const double added = (double(factor) * factor - 1) / 12 + double(factor) * factor / 6;  // pixels^2
  for (int k = 0; k < UWS_LAYERS; ++k) {
    const double sigma_px2 = sigma1_px * sigma1_px * double(1 << k);
    addLayerTaps(s, k, factor == 1 ? std::sqrt(sigma_px2) : std::sqrt(std::max(sigma_px2 - added, 0.0)) / factor);
  }
  return s;
}

}  // namespace seasim
