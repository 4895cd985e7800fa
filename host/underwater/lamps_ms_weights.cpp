#include "underwater/lamps_ms_weights.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "math/kernel_math.h"

namespace seasim {

namespace {

// The bottom halo's F(z, μ_e) per band (uw_ms_halo_plane_from's sums, arranged so that the orders' weights
// at each height and μ are computed once per band and the azimuthal phase integrals once per direction).
void addHaloPlane(const std::vector<UwBand>& bands, double g, int orders, double s0, double u_max, float* out) {
  constexpr int kMu = UW_MS_HALO_QUAD_MU, kDirs = UW_MS_HALO_DIRS, kZ = UW_MS_HALO_Z;
  static_assert(kMu % 4 == 0, "the sums below run four chains over μ");
  const int per_mu = orders + 1;
  const size_t stride = static_cast<size_t>(kmath_d::uw_ms_band_stride(static_cast<int>(bands.size())));
  std::vector<double> az(static_cast<size_t>(kDirs) * kMu * per_mu);
  for (int m = 0; m < kDirs; ++m) kmath_d::uw_ms_halo_azimuths(-1.0 + 2.0 * m / (kDirs - 1), g, orders, az.data() + m * kMu * per_mu);
  // Bands on threads (each ~3 M multiply-adds: 33 directions x 256 heights x 64 μ x the orders).
  tbb::parallel_for(tbb::blocked_range<size_t>(0, bands.size()), [&](const tbb::blocked_range<size_t>& range) {
    std::vector<double> w(static_cast<size_t>(kZ) * kMu * per_mu);
    for (size_t i = range.begin(); i != range.end(); ++i) {
      const double sa = bands[i].a, ss = bands[i].b;
      if (!(ss > 0.0)) continue;  // F = 0 (the table starts zeroed)
      for (int j = 0; j < kZ; ++j) {
        const double z = s0 * std::expm1(j * u_max / (kZ - 1));
        for (int k = 0; k < kMu; ++k)
          kmath_d::uw_ms_glow_weights(sa, ss, z / ((k + 0.5) / kMu), orders, w.data() + (j * kMu + k) * per_mu);
      }
      for (int m = 0; m < kDirs; ++m)
        for (int j = 0; j < kZ; ++j) {
          const double* wj = w.data() + static_cast<size_t>(j) * kMu * per_mu;
          const double* am = az.data() + static_cast<size_t>(m) * kMu * per_mu;
          double sum[4] = {0.0, 0.0, 0.0, 0.0};  // four chains, so that the adds overlap
          for (int e = 0; e < kMu * per_mu; e += 4)
            for (int c = 0; c < 4; ++c) sum[c] += wj[e + c] * am[e + c];
          out[(static_cast<size_t>(m) * kZ + j) * stride + i] =
              static_cast<float>(ss * ((sum[0] + sum[1]) + (sum[2] + sum[3])) / kMu);
        }
    }
  });
}

}  // namespace

std::size_t lampMsWeightsSize(std::size_t bands, int orders) {
  // The lamp's orders 1..orders and the glow's 0..orders, then the bottom halo's F, each entry a padded
  // run of bands (uw_ms_band_stride).
  const std::size_t stride = static_cast<std::size_t>(kmath_d::uw_ms_band_stride(static_cast<int>(bands)));
  return UW_MS_WEIGHT_HEADER + stride * (2 * orders + 1) * static_cast<std::size_t>(UW_MS_WEIGHT_STEPS) +
         stride * static_cast<std::size_t>(UW_MS_HALO_DIRS) * UW_MS_HALO_Z;
}

std::vector<float> lampMsWeights(const std::vector<UwBand>& bands, double g, double kappa, int orders) {
  // s0 = 1/σ_t of the most extinguishing band: the grid's steps are finest where any band's weights turn
  // fastest (σ_t at least 1e-3 /m, so a water without extinction still gets a grid).
  double c_max = 1e-3;
  for (const UwBand& b : bands) c_max = std::max(c_max, static_cast<double>(b.a) + b.b);
  const double s0 = 1.0 / c_max, u_max = std::log1p(UW_MS_WEIGHT_S_MAX / s0);
  const int steps = UW_MS_WEIGHT_STEPS;
  std::vector<float> table(lampMsWeightsSize(bands.size(), orders), 0.0f);
  table[0] = static_cast<float>(1.0 / s0);
  table[1] = static_cast<float>((steps - 1) / u_max);
  const auto at = [&](int j) { return s0 * std::expm1(j * u_max / (steps - 1)); };
  // Entry (order, step) holds its bands side by side, `stride` apart (the header's layout).
  const size_t stride = static_cast<size_t>(kmath_d::uw_ms_band_stride(static_cast<int>(bands.size())));
  float* lamp = table.data() + UW_MS_WEIGHT_HEADER;
  for (size_t i = 0; i < bands.size(); ++i)
    for (int n = 1; n <= orders; ++n) {
      const double stretch = kmath_d::uw_ms_stretch(g, n, kappa);
      for (int j = 0; j < steps; ++j)
        lamp[(static_cast<size_t>(n - 1) * steps + j) * stride + i] =
            static_cast<float>(kmath_d::uw_ms_weight(bands[i].a, bands[i].b, at(j), stretch, n, orders));
    }
  float* glow = lamp + static_cast<size_t>(orders) * steps * stride;
  std::vector<double> w(orders + 1);
  for (size_t i = 0; i < bands.size(); ++i)
    for (int j = 0; j < steps; ++j) {
      kmath_d::uw_ms_glow_weights(bands[i].a, bands[i].b, at(j), orders, w.data());
      for (int n = 0; n <= orders; ++n) glow[(static_cast<size_t>(n) * steps + j) * stride + i] = static_cast<float>(w[n]);
    }
  addHaloPlane(bands, g, orders, s0, u_max, glow + static_cast<size_t>(orders + 1) * steps * stride);
  return table;
}

}  // namespace seasim
