#include "passes/whitecaps_threshold.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "util/error.h"

namespace seasim {

WhitecapsFoamLevels whitecapsFoamLevels(std::vector<float> jacobian, double coverage) {
  if (jacobian.empty()) throw RuntimeError("whitecaps pass: the ocean's Jacobian map is empty");
  if (!(coverage >= 0 && coverage <= 1))
    throw RuntimeError("whitecaps pass: the whitecap coverage must be in [0, 1], got " + std::to_string(coverage));
  for (float j : jacobian)
    if (!std::isfinite(j)) throw RuntimeError("whitecaps pass: the ocean's Jacobian map holds a non-finite value");
  const size_t n = jacobian.size();
  const size_t k = std::min(n, static_cast<size_t>(std::llround(coverage * static_cast<double>(n))));
  WhitecapsFoamLevels out;
  out.foam_texels = k;
  if (k == 0) {
    out.threshold = std::numeric_limits<float>::lowest();
    out.rank_j.fill(out.threshold);
    return out;
  }
  // The k smallest values in order; the threshold is the next one (the k smaller, when distinct from
  // it, are the foam).
  const auto foam_end = jacobian.begin() + static_cast<std::ptrdiff_t>(k);
  std::partial_sort(jacobian.begin(), foam_end, jacobian.end());
  out.threshold = k < n ? *std::min_element(foam_end, jacobian.end()) : std::numeric_limits<float>::max();
  for (int i = 0; i < WHITECAPS_RANK_NODES; ++i) {
    const double q = static_cast<double>(i) / (WHITECAPS_RANK_NODES - 1);
    const double pos = std::clamp(q * static_cast<double>(k) - 0.5, 0.0, static_cast<double>(k - 1));
    const size_t lo = static_cast<size_t>(pos), hi = std::min(lo + 1, k - 1);
    const double t = pos - static_cast<double>(lo);
    out.rank_j[i] = static_cast<float>(jacobian[lo] + t * (static_cast<double>(jacobian[hi]) - jacobian[lo]));
  }
  return out;
}

}  // namespace seasim
