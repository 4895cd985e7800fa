// water_spread_test.cpp — the water's point-spread's maths (kernels/common/water_spread.h,
// host/underwater/water_spread_setup.h) in float and double: the hit's and the in-scatter's share of
// light scattered by small angles, with its mean count and distance, against quadrature of their
// definitions, at and near the singular points (S -> 0, c - c' -> 0, the series' switch-overs, S at the
// kernel's 1e4 m cap); the layers' split; the delta-M peak's median angle and one scattering's median
// displacement against an independent numpy evaluation; the Gaussian taps and the blur's grid.
#include <gtest/gtest.h>

#include <cmath>
#include <tuple>
#include <vector>

#include "math/kernel_math.h"
#include "underwater/water_spread_setup.h"

namespace {

namespace kd = seasim::kmath_d;
namespace kf = seasim::kmath_f;

constexpr double kDeg = 3.14159265358979323846 / 180.0;

// The in-scatter's moments by the midpoint rule on their definitions (water_spread.h (4), (5)):
// share = int (e^{-c' x} - e^{-c x}) / int e^{-c' x}, count = (c - c') int x e^{-c' x} / int e^{-c' x},
// depth = int x (e^{-c' x} - e^{-c x}) / int e^{-c' x}, over [0, S].
struct Moments {
  double share, count, depth;
};
Moments quadrature(double c_dm, double delta, double S) {
  const int n = 400000;
  const double h = S / n;
  double a0 = 0, fwd = 0, cnt = 0, dep = 0;
  for (int i = 0; i < n; ++i) {
    const double x = (i + 0.5) * h;
    const double e0 = std::exp(-c_dm * x), e1 = std::exp(-(c_dm + delta) * x);
    a0 += e0 * h;
    fwd += (e0 - e1) * h;
    cnt += delta * x * e0 * h;
    dep += x * (e0 - e1) * h;
  }
  return {fwd / a0, cnt / a0, dep / a0};
}

template <typename F>
Moments kernelMoments(double c_dm, double delta, double S, F share_fn) {
  double count = 0, depth = 0;
  const double share = share_fn(c_dm, delta, S, &count, &depth);
  return {share, count, depth};
}

Moments doubleMoments(double c_dm, double delta, double S) {
  return kernelMoments(c_dm, delta, S, [](double c, double dl, double s, double* cnt, double* dep) {
    return kd::uws_inscatter_share_b(c, dl, s, std::expm1(-dl * s), cnt, dep);
  });
}

Moments floatMoments(double c_dm, double delta, double S) {
  return kernelMoments(c_dm, delta, S, [](double c, double dl, double s, double* cnt, double* dep) {
    float fc = 0, fd = 0;
    const float share = kf::uws_inscatter_share_b(float(c), float(dl), float(s), std::expm1(-float(dl) * float(s)),
                                                  &fc, &fd);
    *cnt = fc;
    *dep = fd;
    return double(share);
  });
}

TEST(WaterSpread, HitShareIsOneMinusTransmittance) {
  for (double tau : {0.0, 1e-9, 1e-4, 0.01, 0.3, 1.0, 5.0, 80.0, 1e3}) {
    EXPECT_NEAR(kd::uws_hit_share_b(std::expm1(-tau)), 1 - std::exp(-tau), 1e-15) << tau;
    EXPECT_NEAR(kf::uws_hit_share_b(std::expm1(-float(tau))), 1 - std::exp(-tau), 1e-7) << tau;
  }
}

// phi1 and phi2 against long double on both sides of their series' switch-overs (0.25 and 0.5).
TEST(WaterSpread, PhiFunctionsAreStableThroughTheirSwitchOvers) {
  for (double z :
       {0.0, 1e-8, 1e-4, 1e-3, 0.01, 0.05, 0.2499, 0.25, 0.2501, 0.4999, 0.5, 0.5001, 1.0, 10.0, 100.0, 1e4}) {
    const long double zl = z, e = std::exp(-zl);
    const long double phi1 = z == 0 ? 1.0L : (1 - e) / zl;
    const long double phi2 = z < 1e-6 ? 0.5L - zl / 3 : (1 - e * (1 + zl)) / (zl * zl);
    const float zf = float(z), ef = std::exp(-zf), rf = kf::uws_recip_b(zf);
    EXPECT_NEAR(kd::uws_phi1_b(z, std::exp(-z), kd::uws_recip_b(z)), double(phi1), 3e-9 * double(phi1)) << z;
    EXPECT_NEAR(kd::uws_phi2_b(z, std::exp(-z), kd::uws_recip_b(z)), double(phi2), 5e-8 * double(phi2)) << z;
    EXPECT_NEAR(kf::uws_phi1_b(zf, ef, rf), double(phi1), 1e-6 * double(phi1)) << z;
    EXPECT_NEAR(kf::uws_phi2_b(zf, ef, rf), double(phi2), 2e-6 * double(phi2)) << z;
  }
}

TEST(WaterSpread, InscatterMomentsMatchQuadrature) {
  struct Case {
    double c_dm, delta, S;
  };
  // Clear and turbid water at g = 0.9 (c' = a + b (1 - g^3), delta = b g^3), short and long rays, and the
  // corners: no peak (delta 0), no delta-M extinction (c' 0), a ray of 1 mm.
  for (const Case k : {Case{0.0435, 0.0365, 5.0}, Case{0.0435, 0.0365, 200.0}, Case{0.181, 0.219, 2.0},
                       Case{0.181, 0.219, 40.0}, Case{0.724, 0.876, 0.3}, Case{0.1, 0.0, 7.0}, Case{0.0, 0.2, 3.0},
                       Case{0.05, 0.05, 1e-3}, Case{0.3, 1e-7, 10.0}}) {
    const Moments q = quadrature(k.c_dm, k.delta, k.S);
    const Moments d = doubleMoments(k.c_dm, k.delta, k.S);
    const Moments f = floatMoments(k.c_dm, k.delta, k.S);
    // Relative, and absolute as a share of the in-scatter's light (float: 1 - phi1(cS)/phi1(c'S) cancels
    // where c S and c' S are close, which leaves ~1e-7 of the light, not of the share).
    for (const auto& [got, tol, floor, name] :
         {std::tuple{d, 1e-6, 1e-12, "double"}, std::tuple{f, 3e-4, 1e-7, "float"}}) {
      EXPECT_NEAR(got.share, q.share, tol * q.share + floor) << name << " c' " << k.c_dm << " delta " << k.delta << " S " << k.S;
      EXPECT_NEAR(got.count, q.count, tol * q.count + floor) << name << " c' " << k.c_dm << " delta " << k.delta << " S " << k.S;
      EXPECT_NEAR(got.depth, q.depth, tol * q.depth + floor * k.S) << name << " c' " << k.c_dm << " delta " << k.delta << " S " << k.S;
    }
  }
}

// Where the forward part vanishes its mean count tends to 1 (one scattering) and its distance stays
// within the ray; at the kernel's cap (S = 1e4 m, e^{-c' S} = 0 in float) all stay finite.
TEST(WaterSpread, InscatterMomentsAtTheirLimits) {
  for (double delta : {1e-6, 1e-8}) {
    const Moments d = doubleMoments(0.2, delta, 1.0);
    EXPECT_NEAR(d.count / d.share, 1.0, 1e-3) << delta;
    EXPECT_GT(d.depth / d.share, 0.0);
    EXPECT_LT(d.depth / d.share, 1.0);
  }
  const Moments zero = doubleMoments(0.2, 0.3, 0.0);
  EXPECT_EQ(zero.share, 0.0);
  EXPECT_EQ(zero.count, 0.0);
  EXPECT_EQ(zero.depth, 0.0);
  for (const Moments m : {floatMoments(0.05, 0.04, 1e4), floatMoments(2.0, 3.0, 1e4), floatMoments(1e-6, 1e-7, 1e4),
                          floatMoments(0.1, 0.0, 1e4), floatMoments(0.1, 0.2, 1e-7)}) {
    for (double v : {m.share, m.count, m.depth}) {
      EXPECT_TRUE(std::isfinite(v));
      EXPECT_GE(v, 0.0);
    }
    EXPECT_LE(m.share, 1.0);
    EXPECT_LE(m.depth, 1e4 * m.share * 1.0001 + 1e-9);
  }
  // Deep water: the forward share is 1 - c'/c, its mean distance 1/c' + 1/c (the integrals to infinity).
  const Moments deep = doubleMoments(0.0435, 0.0365, 1e4);
  EXPECT_NEAR(deep.share, 1 - 0.0435 / 0.08, 1e-9);
  EXPECT_NEAR(deep.depth / deep.share, 1 / 0.0435 + 1 / 0.08, 1e-6);
}

// The layers keep the light and the mean count: shares sum to 1 and sum_k share_k n_k = E in [1, 8].
TEST(WaterSpread, LayerSharesKeepTheLightAndTheMeanCount) {
  for (double e = 0.0; e <= 20.0; e += 0.0625) {
    double sum_d = 0, mean_d = 0, sum_f = 0, mean_f = 0;
    for (int k = 0; k < UWS_LAYERS; ++k) {
      const double sd = kd::uws_layer_share(e, k);
      const double sf = kf::uws_layer_share(float(e), k);
      EXPECT_GE(sd, 0.0);
      sum_d += sd;
      mean_d += sd * kd::uws_layer_count(k);
      sum_f += sf;
      mean_f += sf * kf::uws_layer_count(k);
    }
    const double expect = std::min(std::max(e, 1.0), 8.0);
    EXPECT_NEAR(sum_d, 1.0, 1e-12) << e;
    EXPECT_NEAR(mean_d, expect, 1e-12) << e;
    EXPECT_NEAR(sum_f, 1.0, 1e-6) << e;
    EXPECT_NEAR(mean_f, expect, 1e-5) << e;
  }
  EXPECT_EQ(kd::uws_layer_share(1.0, 0), 1.0);
  EXPECT_EQ(kd::uws_layer_share(8.0, UWS_LAYERS - 1), 1.0);
}

// The peak of HG less its three-term delta-M expansion: median angle and the median of one scattering's
// displacement seen from the camera (theta v, v uniform), against numpy (400,001 angles, trapezoid rule,
// Gauss-Legendre in v, bisection): 11.108, 7.057, 4.113 deg and 4.597, 2.930, 1.724 deg at g = 0.8, 0.9, 0.95.
TEST(WaterSpread, PeakMediansMatchAnIndependentEvaluation) {
  const struct {
    double g, angle_deg, displacement_deg;
  } cases[] = {{0.8, 11.108, 4.597}, {0.9, 7.057, 2.930}, {0.95, 4.113, 1.724}};
  for (const auto& c : cases) {
    EXPECT_NEAR(seasim::deltaMPeakMedianAngle(c.g, 3) / kDeg, c.angle_deg, 0.01) << c.g;
    EXPECT_NEAR(seasim::deltaMPeakDisplacementMedian(c.g, 3) / kDeg, c.displacement_deg, 0.01) << c.g;
    EXPECT_NEAR(seasim::singleScatterSpread(c.g, 3), seasim::deltaMPeakDisplacementMedian(c.g, 3) / std::sqrt(2 * std::log(2.0)),
                1e-12);
  }
  // Narrower with g; none without a forward peak.
  EXPECT_LT(seasim::deltaMPeakMedianAngle(0.95, 3), seasim::deltaMPeakMedianAngle(0.9, 3));
  EXPECT_EQ(seasim::deltaMPeakMedianAngle(0.0, 3), 0.0);
  EXPECT_EQ(seasim::deltaMPeakMedianAngle(-0.5, 3), 0.0);
  EXPECT_EQ(seasim::singleScatterSpread(0.0, 3), 0.0);
  EXPECT_EQ(seasim::deltaMPeakDisplacementMedian(0.005, 3), 0.0);  // f = 1.3e-7: no peak to speak of
}

TEST(WaterSpread, GaussianTapsSumToOne) {
  for (double sigma : {0.3, 1.0, 2.5, 7.0, 40.0}) {
    const std::vector<float> taps = seasim::gaussianTaps(sigma, 1000);
    ASSERT_EQ(int(taps.size()) - 1, int(std::ceil(3 * sigma)));
    double sum = taps[0];
    for (size_t j = 1; j < taps.size(); ++j) {
      sum += 2.0 * taps[j];
      EXPECT_LT(taps[j], taps[j - 1]);
    }
    EXPECT_NEAR(sum, 1.0, 1e-6) << sigma;
  }
  EXPECT_EQ(seasim::gaussianTaps(0.0, 10), std::vector<float>{1.0f});
  EXPECT_EQ(seasim::gaussianTaps(40.0, 10).size(), 11u);  // capped
}

// The grid: pixels where sigma_1 is a few pixels, cells of floor(sigma_1 / 2) pixels where it is wider,
// so that the layers' radii in cells stay the same at any resolution.
TEST(WaterSpread, GridFollowsTheSpreadsAngle) {
  const double t = std::tan(30 * kDeg);
  const seasim::WaterSpread small = seasim::makeWaterSpread(0.9, 3, t, 64, 36);
  EXPECT_NEAR(small.sigma1_px, seasim::singleScatterSpread(0.9, 3) / (2 * t / 36), 1e-9);
  EXPECT_EQ(small.params.factor, 1);
  EXPECT_EQ(small.params.low_width, 64);
  EXPECT_EQ(small.params.radius[0], int(std::ceil(3 * small.sigma1_px)));
  const seasim::WaterSpread big = seasim::makeWaterSpread(0.9, 3, t, 1920, 1080);
  EXPECT_EQ(big.params.factor, int(std::floor(big.sigma1_px / 2)));
  EXPECT_GT(big.params.factor, 10);
  EXPECT_EQ(big.params.low_width, (1920 + big.params.factor - 1) / big.params.factor);
  EXPECT_EQ(big.params.low_height, (1080 + big.params.factor - 1) / big.params.factor);
  for (int k = 0; k < UWS_LAYERS; ++k) {
    // sigma_1 in [2, 3) cells: the radii do not grow with the resolution.
    EXPECT_LE(big.params.radius[k], int(std::ceil(9 * std::sqrt(double(1 << k))))) << k;
    if (k > 0) {
      EXPECT_GT(big.params.radius[k], big.params.radius[k - 1]);
      EXPECT_EQ(big.params.tap_offset[k], big.params.tap_offset[k - 1] + big.params.radius[k - 1] + 1);
    }
  }
  EXPECT_EQ(int(big.taps.size()), big.params.tap_offset[UWS_LAYERS - 1] + big.params.radius[UWS_LAYERS - 1] + 1);
  EXPECT_THROW(seasim::makeWaterSpread(0.9, 3, 0.0, 64, 36), std::exception);
}

}  // namespace
