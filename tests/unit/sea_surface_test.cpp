// sea_surface_test.cpp — the flat-sea terms of paper 000 (kernels/common/sea_surface.h) in float and
// double: eq. 5 against numerical quadrature of the integral it solves, its stiff limits, and the
// Henyey–Greenstein forward fraction c_f against quadrature of the phase function.
#include <gtest/gtest.h>

#include <cmath>

#include "math/kernel_math.h"

namespace {

namespace kd = seasim::kmath_d;
namespace kf = seasim::kmath_f;

// The integral behind 000 eq. 5: beam irradiance E T_i / cos_io in the water, scattered by beta into
// the view ray, attenuated with k on the way down and up; midpoint rule over depth, long double.
long double singleScatteringQuadrature(double E, double ti, double to, double beta, double k, double cos_io,
                                       double cos_ji, double z_d, int steps) {
  const long double sec_sum = 1.0L / cos_ji + 1.0L / cos_io;
  const long double dz = static_cast<long double>(z_d) / steps;
  long double sum = 0;
  for (int s = 0; s < steps; ++s) sum += std::exp(-k * (s + 0.5L) * dz * sec_sum);
  return E * ti / cos_io * beta * to * sum * dz / cos_ji;
}

TEST(SeaSurface, SingleScatteringClosedFormMatchesQuadrature) {
  const double c = 0.3, albedo = 0.6, c_f = 0.9;
  const double k = c * (1 - albedo * c_f);
  for (double cos_io : {1.0, 0.8, 0.3}) {
    for (double cos_ji : {1.0, 0.7, 0.1}) {
      for (double z : {0.5, 5.0, 40.0}) {
        const long double ref = singleScatteringQuadrature(1.2, 0.97, 0.95, 0.02, k, cos_io, cos_ji, z, 200000);
        const double d = kd::sea_single_scattering(1.2, 0.97, 0.95, 0.02, c, albedo, c_f, cos_io, cos_ji, z);
        const float f = kf::sea_single_scattering(1.2f, 0.97f, 0.95f, 0.02f, float(c), float(albedo), float(c_f),
                                                  float(cos_io), float(cos_ji), float(z));
        EXPECT_NEAR(d / ref, 1.0, 1e-8) << cos_io << " " << cos_ji << " " << z;
        EXPECT_NEAR(f / ref, 1.0, 2e-6) << cos_io << " " << cos_ji << " " << z;
      }
    }
  }
}

TEST(SeaSurface, SingleScatteringStaysFiniteAsAttenuationVanishes) {
  // k -> 0: (1 - exp(-k X)) / k -> X. The naive form loses every digit in float.
  const double cos_io = 0.9, cos_ji = 0.8, z = 10;
  const double X = z * (1 / cos_io + 1 / cos_ji);
  for (double c : {1e-3, 1e-6, 1e-9, 1e-12, 0.0}) {
    const double limit = 1.0 * 1.0 * 1.0 * 0.01 * X / (cos_io + cos_ji);
    const double d = kd::sea_single_scattering(1, 1, 1, 0.01, c, 0.0, 0.5, cos_io, cos_ji, z);
    const float f = kf::sea_single_scattering(1, 1, 1, 0.01f, float(c), 0.0f, 0.5f, float(cos_io), float(cos_ji),
                                              float(z));
    EXPECT_NEAR(d / limit, 1.0, c * X + 1e-12) << c;
    EXPECT_NEAR(f / limit, 1.0, c * X + 1e-6) << c;
    EXPECT_TRUE(std::isfinite(f));
  }
}

TEST(SeaSurface, InfiniteDepthIsTheLimitOfDeepWater) {
  const double deep = kd::sea_single_scattering(1, 0.98, 0.97, 0.01, 0.2, 0.5, 0.8, 0.9, 0.6, 1e4);
  const double inf = kd::sea_single_scattering(1, 0.98, 0.97, 0.01, 0.2, 0.5, 0.8, 0.9, 0.6, -1.0);
  EXPECT_NEAR(deep / inf, 1.0, 1e-12);
  EXPECT_GT(kd::sea_single_scattering(1, 0.98, 0.97, 0.01, 0.2, 0.5, 0.8, 0.9, 0.6, 5.0), 0.0);
}

TEST(SeaSurface, GrazingRaysDoNotBlowUp) {
  for (double cos_ji : {1e-4, 1e-3}) {
    const float f = kf::sea_single_scattering(1, 1, 0.1f, 0.01f, 0.2f, 0.5f, 0.8f, 1e-4f, float(cos_ji), 8.0f);
    const float b = kf::sea_bottom_reflection(1, 1, 0.1f, 0.3f, 0.2f, 8.0f, 1e-4f, float(cos_ji));
    EXPECT_TRUE(std::isfinite(f));
    EXPECT_TRUE(std::isfinite(b));
    EXPECT_GE(b, 0.0f);
  }
}

TEST(SeaSurface, BottomTermVanishesWithDepthAndMatchesLambertAtZeroDepth) {
  // At z = 0 the bottom is a Lambertian surface under horizontal irradiance E T_i: L = T_o E T_i a / pi.
  EXPECT_NEAR(kd::sea_bottom_reflection(2.0, 0.9, 0.8, 0.3, 0.5, 0.0, 0.7, 0.6), 0.8 * 2.0 * 0.9 * 0.3 / M_PI, 1e-15);
  EXPECT_LT(kd::sea_bottom_reflection(2.0, 0.9, 0.8, 0.3, 0.5, 200.0, 0.7, 0.6), 1e-100);
  EXPECT_EQ(kf::sea_bottom_reflection(2.0f, 0.9f, 0.8f, 0.3f, 0.5f, 1e4f, 0.7f, 0.6f), 0.0f);  // underflow to 0, not NaN
}

TEST(SeaSurface, ForwardFractionMatchesPhaseQuadrature) {
  for (double g : {-0.9, -0.3, -1e-4, 0.0, 1e-4, 1e-3, 0.01, 0.05, 0.3, 0.8, 0.95}) {
    // 2 pi int_0^1 p(mu) dmu by Simpson with many intervals (smooth for |g| <= 0.95).
    const int n = 400000;
    long double sum = 0;
    for (int i = 0; i <= n; ++i) {
      const double mu = double(i) / n;
      const double w = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
      sum += w * kd::hg_phase(mu, g);
    }
    const double ref = double(2 * M_PI * sum / (3.0L * n));
    EXPECT_NEAR(kd::hg_forward_fraction(g), ref, 1e-9) << g;
    EXPECT_NEAR(kf::hg_forward_fraction(float(g)), ref, 2e-6) << g;
  }
  EXPECT_NEAR(kd::hg_forward_fraction(0.0), 0.5, 1e-15);
}

}  // namespace
