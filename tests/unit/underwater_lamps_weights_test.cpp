// underwater_lamps_weights_test.cpp — the "orders" model's weights as the kernel reads them
// (host/underwater/lamps_ms_weights.h, kernels/common/underwater_lamps_ms.h's UW_MS_WEIGHT_*): the
// table, interpolated in float and in double, against uw_ms_weight and uw_ms_glow_weights evaluated
// directly, in waters from clear to turbid with bands of very different extinction, 4 and 12 orders;
// its ends (s = 0, beyond S_MAX), a band that does not scatter, and the glow's last order where it is tiny.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "math/kernel_math.h"
#include "underwater/lamps_ms_weights.h"

namespace {

namespace kd = seasim::kmath_d;
namespace kf = seasim::kmath_f;

UwBand band(double a, double b) {
  UwBand w{};
  w.a = static_cast<float>(a);
  w.b = static_cast<float>(b);
  w.c = static_cast<float>(a + b);
  return w;
}

// Distances from 1 mm to 2 km, 40 per decade, and 0.
std::vector<double> distances() {
  std::vector<double> s = {0.0};
  for (int i = 0; i <= 40 * 6; ++i) s.push_back(1e-3 * std::pow(10.0, i / 40.0));
  return s;
}

struct Water {
  const char* name;
  std::vector<UwBand> bands;
  double g;
};

std::vector<Water> waters() {
  return {{"clear ocean, blue to red (sigma_t 0.03 to 0.6)", {band(0.02, 0.01), band(0.06, 0.008), band(0.6, 0.004)}, 0.9},
          {"b/a = 10, g 0.95", {band(0.05, 0.5)}, 0.95},
          {"turbid 9C-like", {band(1.2, 2.5), band(0.8, 3.0)}, 0.85},
          {"isotropic", {band(0.1, 0.3)}, 0.0}};
}

TEST(UnderwaterLampsWeights, TableMatchesTheWeightsEvaluatedDirectly) {
  for (const Water& w : waters())
    for (int orders : {4, 12}) {
      const double kappa = 0.75;
      const std::vector<float> t = seasim::lampMsWeights(w.bands, w.g, kappa, orders);
      ASSERT_EQ(t.size(), seasim::lampMsWeightsSize(w.bands.size(), orders));
      const int nb = static_cast<int>(w.bands.size());
      double worst = 0, worst_glow = 0;
      for (int i = 0; i < nb; ++i) {
        const double a = w.bands[i].a, b = w.bands[i].b;
        // Each order's peak over the distances, the scale its error is judged against (the kernel adds
        // orders and bands: an error relative to a weight far below its own peak carries no light).
        std::vector<double> peak(orders + 1, 0.0), peak_glow(orders + 1, 0.0);
        const std::vector<double> ss = distances();
        std::vector<double> exact(orders), glow(orders + 1);
        for (double s : ss) {
          for (int n = 1; n <= orders; ++n)
            peak[n] = std::max(peak[n], kd::uw_ms_weight(a, b, s, kd::uw_ms_stretch(w.g, n, kappa), n, orders));
          kd::uw_ms_glow_weights(a, b, s, orders, glow.data());
          for (int n = 0; n <= orders; ++n) peak_glow[n] = std::max(peak_glow[n], glow[n]);
        }
        for (double s : ss) {
          int j;
          double f;
          kd::uw_ms_weight_index(t.data(), s, &j, &f);
          double got[UW_MS_MAX_ORDERS + 1];
          kd::uw_ms_weights_at(t.data() + UW_MS_WEIGHT_HEADER, nb, i, orders, j, f, got);
          int jf;
          float ff, got_f[UW_MS_MAX_ORDERS + 1];
          kf::uw_ms_weight_index(t.data(), static_cast<float>(s), &jf, &ff);
          kf::uw_ms_weights_at(t.data() + UW_MS_WEIGHT_HEADER, nb, i, orders, jf, ff, got_f);
          for (int n = 1; n <= orders; ++n) {
            const double e = kd::uw_ms_weight(a, b, s, kd::uw_ms_stretch(w.g, n, kappa), n, orders);
            worst = std::max(worst, std::fabs(got[n - 1] - e) / peak[n]);
            worst = std::max(worst, std::fabs(got_f[n - 1] - e) / peak[n]);
          }
          kd::uw_ms_glow_weights(a, b, s, orders, glow.data());
          kd::uw_ms_weights_at(kd::uw_ms_glow_weight_rows(t.data(), nb, orders), nb, i, orders + 1, j, f, got);
          for (int n = 0; n <= orders; ++n) worst_glow = std::max(worst_glow, std::fabs(got[n] - glow[n]) / peak_glow[n]);
        }
      }
      std::printf("%s, %d orders: table vs direct, max |difference| / order's peak: lamp %.2e, glow %.2e\n", w.name,
                  orders, worst, worst_glow);
      EXPECT_LT(worst, 1e-3) << w.name << " orders " << orders;
      EXPECT_LT(worst_glow, 1e-3) << w.name << " orders " << orders;
    }
}

TEST(UnderwaterLampsWeights, BandsRunFastestPaddedToTheWidestLanes) {
  // 19 bands: a second run of lanes with 3 bands in it. The lanes' accessors (one band per lane on the
  // host) read what the per-band ones read, and every padding entry is 0, which a kernel's lanes past
  // the last band read.
  std::vector<UwBand> bands;
  for (int i = 0; i < 19; ++i) bands.push_back(band(0.02 + 0.03 * i, 0.3 - 0.01 * i));
  const int nb = static_cast<int>(bands.size()), orders = 4;
  ASSERT_EQ(kd::uw_ms_band_stride(nb), 32);
  EXPECT_EQ(kd::uw_ms_band_stride(16), 16);
  EXPECT_EQ(kd::uw_ms_band_stride(1), UW_MS_BAND_PAD);
  const std::vector<float> t = seasim::lampMsWeights(bands, 0.9, 0.75, orders);
  ASSERT_EQ(t.size(), seasim::lampMsWeightsSize(bands.size(), orders));
  const float* lamp = t.data() + UW_MS_WEIGHT_HEADER;
  const float* glow = kd::uw_ms_glow_weight_rows(t.data(), nb, orders);
  const float* halo = kd::uw_ms_halo_rows(t.data(), nb, orders);
  EXPECT_EQ(halo + 32 * UW_MS_HALO_DIRS * UW_MS_HALO_Z, t.data() + t.size());
  for (double s : {0.3, 2.0, 11.0}) {
    int j;
    double f;
    kd::uw_ms_weight_index(t.data(), s, &j, &f);
    for (int i = 0; i < nb; ++i) {
      double one[UW_MS_MAX_ORDERS + 1], lanes[UW_MS_MAX_ORDERS + 1];
      kd::uw_ms_weights_at(lamp, nb, i, orders, j, f, one);
      kd::uw_ms_weights_at_b(lamp, nb, i, orders, j, f, lanes);
      for (int n = 0; n < orders; ++n) EXPECT_EQ(one[n], lanes[n]) << "band " << i << " order " << n + 1;
      EXPECT_GT(one[0], 0.0) << "band " << i;
      kd::uw_ms_weights_at(glow, nb, i, orders + 1, j, f, one);
      kd::uw_ms_weights_at_b(glow, nb, i, orders + 1, j, f, lanes);
      for (int n = 0; n <= orders; ++n) EXPECT_EQ(one[n], lanes[n]) << "band " << i << " glow order " << n;
      // The halo's lanes read row 7 and 8, heights j/4 and the next, band i, 32 floats from one entry to the next.
      const float* h0 = halo + (7 * UW_MS_HALO_Z + j / 4) * 32 + i;
      const float* h1 = h0 + UW_MS_HALO_Z * 32;
      const double want = 0.7 * ((1 - f) * h0[0] + f * h0[32]) + 0.3 * ((1 - f) * h1[0] + f * h1[32]);
      EXPECT_NEAR(kd::uw_ms_halo_at_b(halo, nb, i, 7, 0.3, j / 4, f), want, 1e-12 * std::fabs(want) + 1e-30);
      // The orders' sum in lanes is the per-band weights against the factors, the factors <= 0 left out.
      const double geo[4] = {0.7, 0.0, -1.0, 0.2};
      double w4[UW_MS_MAX_ORDERS];
      kd::uw_ms_weights_at(lamp, nb, i, orders, j, f, w4);
      EXPECT_NEAR(kd::uw_ms_orders_sum_b(lamp, nb, i, orders, j, f, geo), 0.7 * w4[0] + 0.2 * w4[3],
                  1e-12 * (0.7 * w4[0] + 0.2 * w4[3]));
    }
  }
  // The padding: bands 19..31 of every entry.
  double padding = 0.0;
  for (const float* e = lamp; e < t.data() + t.size(); e += 32)
    for (int i = nb; i < 32; ++i) padding = std::max(padding, std::fabs(static_cast<double>(e[i])));
  EXPECT_EQ(padding, 0.0);
}

TEST(UnderwaterLampsWeights, EndsOfTheTableAndABandThatDoesNotScatter) {
  const std::vector<UwBand> bands = {band(0.1, 0.3), band(0.2, 0.0)};
  const std::vector<float> t = seasim::lampMsWeights(bands, 0.9, 0.75, 4);
  int j;
  double f;
  kd::uw_ms_weight_index(t.data(), 0.0, &j, &f);
  EXPECT_EQ(j, 0);
  EXPECT_DOUBLE_EQ(f, 0.0);
  kd::uw_ms_weight_index(t.data(), -1.0, &j, &f);  // never from a length, but clamped all the same
  EXPECT_EQ(j, 0);
  EXPECT_DOUBLE_EQ(f, 0.0);
  for (double s : {UW_MS_WEIGHT_S_MAX, 10.0 * UW_MS_WEIGHT_S_MAX, 1e30}) {
    kd::uw_ms_weight_index(t.data(), s, &j, &f);
    EXPECT_EQ(j, UW_MS_WEIGHT_STEPS - 2) << s;
    EXPECT_NEAR(f, 1.0, 1e-3) << s;  // the last entry
  }
  // At s = 0 no light has scattered: every order 0, the glow's order 0 (unscattered) 1.
  double w[UW_MS_MAX_ORDERS + 1];
  kd::uw_ms_weights_at(t.data() + UW_MS_WEIGHT_HEADER, 2, 0, 4, 0, 0.0, w);
  for (int n = 0; n < 4; ++n) EXPECT_EQ(w[n], 0.0);
  kd::uw_ms_weights_at(kd::uw_ms_glow_weight_rows(t.data(), 2, 4), 2, 0, 5, 0, 0.0, w);
  EXPECT_DOUBLE_EQ(w[0], 1.0);
  // The band without scattering: no order anywhere; the glow's order 0 is its transmission.
  for (double s : {0.5, 5.0, 50.0}) {
    kd::uw_ms_weight_index(t.data(), s, &j, &f);
    kd::uw_ms_weights_at(t.data() + UW_MS_WEIGHT_HEADER, 2, 1, 4, j, f, w);
    for (int n = 0; n < 4; ++n) EXPECT_EQ(w[n], 0.0) << s;
    kd::uw_ms_weights_at(kd::uw_ms_glow_weight_rows(t.data(), 2, 4), 2, 1, 5, j, f, w);
    EXPECT_NEAR(w[0], std::exp(-0.2 * s), 1e-4 * std::exp(-0.2 * s) + 1e-7) << s;
    for (int n = 1; n <= 4; ++n) EXPECT_EQ(w[n], 0.0) << s;
  }  // The glow's last order where its Poisson tail is ~1e-38 (x = 0.004, 12 orders): summed where it is
  // small, not 1 minus the lower terms (which left ~1e-7 of rounding noise in float).
  float wf[UW_MS_MAX_ORDERS + 1];
  kf::uw_ms_glow_weights(0.6f, 0.004f, 1.0f, 12, wf);
  EXPECT_GE(wf[12], 0.0f);
  EXPECT_LT(wf[12], 1e-30f);
}

}  // namespace
