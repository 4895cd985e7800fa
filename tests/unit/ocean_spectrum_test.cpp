// ocean_spectrum_test.cpp — kernels/common/ocean_spectrum.h on the host in float and double: Philox
// known answers, Gaussian draws, the Phillips spectrum's limits and normalisation (RMS height
// √(Aπ) V²/g), dispersion (deep, finite depth, depth -> 0), loop quantisation, and the Jacobian
// eigen-decomposition including its degenerate and cancelling cases.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "math/kernel_math.h"

namespace {

namespace kf = seasim::kmath_f;
namespace kd = seasim::kmath_d;

TEST(OceanSpectrum, PhiloxKnownAnswers) {
  // Random123 kat_vectors, philox4x32_10.
  unsigned int a[4] = {0, 0, 0, 0};
  kd::philox4x32_10(a, 0, 0);
  EXPECT_EQ(a[0], 0x6627e8d5u);
  EXPECT_EQ(a[1], 0xe169c58du);
  EXPECT_EQ(a[2], 0xbc57ac4cu);
  EXPECT_EQ(a[3], 0x9b00dbd8u);
  unsigned int b[4] = {0xffffffffu, 0xffffffffu, 0xffffffffu, 0xffffffffu};
  kd::philox4x32_10(b, 0xffffffffu, 0xffffffffu);
  EXPECT_EQ(b[0], 0x408f276du);
  EXPECT_EQ(b[1], 0x41c83b0eu);
  EXPECT_EQ(b[2], 0xa20bc7c6u);
  EXPECT_EQ(b[3], 0x6d5451fdu);
  unsigned int c[4] = {0x243f6a88u, 0x85a308d3u, 0x13198a2eu, 0x03707344u};
  kd::philox4x32_10(c, 0xa4093822u, 0x299f31d0u);
  EXPECT_EQ(c[0], 0xd16cfe09u);
  EXPECT_EQ(c[1], 0x94fdccebu);
  EXPECT_EQ(c[2], 0x5001e420u);
  EXPECT_EQ(c[3], 0x24126ea1u);
}

TEST(OceanSpectrum, GaussianDrawsAreStandardNormal) {
  double sum = 0, sum2 = 0, sum4 = 0, cross = 0;
  int count = 0;
  for (int m = -200; m < 200; ++m)
    for (int q = -200; q < 200; ++q) {
      double xr, xi;
      kd::ocean_gaussian_pair(42u, m, q, &xr, &xi);
      float fr, fi;
      kf::ocean_gaussian_pair(42u, m, q, &fr, &fi);
      ASSERT_NEAR(fr, xr, 1e-5 * (1 + std::abs(xr)));  // same integer draws; float cos/log rounding only
      for (double x : {xr, xi}) {
        sum += x;
        sum2 += x * x;
        sum4 += x * x * x * x;
      }
      cross += xr * xi;
      count += 2;
    }
  const double mean = sum / count, var = sum2 / count, kurt = sum4 / count / (var * var);
  EXPECT_NEAR(mean, 0.0, 4 / std::sqrt(count));
  EXPECT_NEAR(var, 1.0, 4 * std::sqrt(2.0 / count));
  EXPECT_NEAR(kurt, 3.0, 4 * std::sqrt(96.0 / count));
  EXPECT_NEAR(cross / (count / 2), 0.0, 4 / std::sqrt(count / 2.0));
  // Another seed, other draws.
  double a, b, c2, d;
  kd::ocean_gaussian_pair(1u, 3, 4, &a, &b);
  kd::ocean_gaussian_pair(2u, 3, 4, &c2, &d);
  EXPECT_NE(a, c2);
}

TEST(OceanSpectrum, PhillipsLimitsAndDirection) {
  const double g = 9.81;
  // Wind 0 and k = 0: exactly 0, no NaN (004 eq. 23 has 1/(kL)² and 1/k⁴).
  EXPECT_EQ(kd::ocean_phillips(0.3, 0.1, 1, 0, 0.0, g, 1e-3, 2, 0), 0.0);
  EXPECT_EQ(kf::ocean_phillips(0.3f, 0.1f, 1, 0, 0.0f, 9.81f, 1e-3f, 2, 0), 0.0f);
  EXPECT_EQ(kd::ocean_phillips(0.0, 0.0, 1, 0, 10.0, g, 1e-3, 2, 0), 0.0);
  EXPECT_EQ(kf::ocean_phillips(1e-30f, 0.0f, 1, 0, 10.0f, 9.81f, 1e-3f, 2, 0), 0.0f);
  // Perpendicular to the wind: 0 for p > 0; p = 0 isotropic.
  EXPECT_EQ(kd::ocean_phillips(0.0, 0.2, 1, 0, 10.0, g, 1e-3, 2, 0), 0.0);
  EXPECT_DOUBLE_EQ(kd::ocean_phillips(0.0, 0.2, 1, 0, 10.0, g, 1e-3, 0, 0),
                   kd::ocean_phillips(0.2, 0.0, 1, 0, 10.0, g, 1e-3, 0, 0));
  // The closed form at 45° with p = 6 and ℓ = 0.5 m.
  const double k = 0.25, Lw = 100.0 / g, c = std::sqrt(0.5);
  const double expect = 1e-3 * std::exp(-1 / (k * Lw * k * Lw) - k * k * 0.25) / std::pow(k, 4) * std::pow(c, 6);
  EXPECT_NEAR(kd::ocean_phillips(k * c, k * c, 1, 0, 10.0, g, 1e-3, 6, 0.5), expect, 1e-12 * expect);
  EXPECT_NEAR(kf::ocean_phillips(float(k * c), float(k * c), 1, 0, 10.0f, 9.81f, 1e-3f, 6, 0.5f), expect, 1e-5 * expect);
  // Huge k (tiny patch, N = 2048): finite, tiny, positive.
  const float big = kf::ocean_phillips(6000.0f, 100.0f, 1, 0, 30.0f, 9.81f, 1.29e-3f, 2, 0);
  EXPECT_TRUE(std::isfinite(big));
  EXPECT_GT(big, 0.0f);
}

// <h²> = 2 Σ Ph Δk² -> A π (V²/g)² for p = 2 when the lattice resolves the spectrum.
TEST(OceanSpectrum, LatticeVarianceMatchesClosedForm) {
  const double g = 9.81, V = 10.0, A = 1.29e-3, Lw = V * V / g;
  const int n = 1024;
  const double L = 60 * Lw, dk = 2 * std::numbers::pi / L;
  double sum = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double kx = dk * kd::ocean_wave_index(i, n), kz = dk * kd::ocean_wave_index(j, n);
      sum += kd::ocean_phillips(kx, kz, 1, 0, V, g, A, 2, 0) * dk * dk;
    }
  const double variance = 2 * sum;
  EXPECT_NEAR(variance / (A * std::numbers::pi * Lw * Lw), 1.0, 0.01);
  // p = 6 (Figure 8): the angular integral ∫|cos θ|^6 dθ = 5π/8 instead of π.
  double sum6 = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double kx = dk * kd::ocean_wave_index(i, n), kz = dk * kd::ocean_wave_index(j, n);
      sum6 += kd::ocean_phillips(kx, kz, 1, 0, V, g, A, 6, 0) * dk * dk;
    }
  EXPECT_NEAR(sum6 / sum, 5.0 / 8.0, 0.01);
}

TEST(OceanSpectrum, DispersionDeepFiniteAndShallowLimit) {
  const double g = 9.81;
  EXPECT_DOUBLE_EQ(kd::ocean_omega(0.5, g, 0.0), std::sqrt(g * 0.5));
  EXPECT_NEAR(kd::ocean_omega(0.5, g, 1e4), std::sqrt(g * 0.5), 1e-12);  // deep bottom = deep water
  EXPECT_NEAR(kd::ocean_omega(0.5, g, 2.0), std::sqrt(g * 0.5 * std::tanh(1.0)), 1e-12);
  // depth -> 0: ω -> k √(gD), no cancellation, in float and double.
  for (double D : {1e-3, 1e-6, 1e-12}) {
    const double k = 0.7;
    EXPECT_NEAR(kd::ocean_omega(k, g, D) / (k * std::sqrt(g * D)), 1.0, 1e-6) << D;
    const float wf = kf::ocean_omega(0.7f, 9.81f, static_cast<float>(D));
    EXPECT_NEAR(wf / (0.7 * std::sqrt(9.81 * static_cast<float>(D))), 1.0, 1e-5) << D;
  }
  EXPECT_TRUE(std::isfinite(kf::ocean_omega(0.7f, 9.81f, 1e-38f)));
  EXPECT_EQ(kf::ocean_omega(0.0f, 9.81f, 3.0f), 0.0f);
}

TEST(OceanSpectrum, LoopQuantisation) {
  const double T = 20.0, w0 = 2 * std::numbers::pi / T;
  for (double w : {0.1, 0.31, 1.0, 2.5, 9.9}) {
    // Phase at τ = 1/2 is 2π frac(m/2): m = [[ω/ω0]] (004 eq. 18).
    const double m = std::floor(w / w0);
    EXPECT_NEAR(kd::ocean_phase(w, 0.0, T, 0.25), 2 * std::numbers::pi * (m * 0.25 - std::floor(m * 0.25)), 1e-12);
    EXPECT_LE(m * w0, w);
    EXPECT_GT(m * w0, w - w0);
  }
  EXPECT_DOUBLE_EQ(kd::ocean_phase(1.5, 2.0, 0.0, 0.0), 3.0);  // no loop: ω t
}

TEST(OceanSpectrum, JacobianEigenDecomposition) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-3, 3);
  for (int trial = 0; trial < 2000; ++trial) {
    const double jxx = u(rng), jzz = u(rng), jxz = u(rng);
    double jm, jp, ex, ez;
    kd::ocean_jacobian_eigen(jxx, jzz, jxz, &jm, &jp, &ex, &ez);
    // eq. 32 directly.
    const double mean = 0.5 * (jxx + jzz), r = 0.5 * std::sqrt((jxx - jzz) * (jxx - jzz) + 4 * jxz * jxz);
    ASSERT_NEAR(jm, mean - r, 1e-12 * (1 + std::abs(mean) + r));
    ASSERT_NEAR(jp, mean + r, 1e-12 * (1 + std::abs(mean) + r));
    ASSERT_LE(jm, jp);
    ASSERT_NEAR(jm * jp, jxx * jzz - jxz * jxz, 1e-10);
    ASSERT_NEAR(ex * ex + ez * ez, 1.0, 1e-12);
    // (J - J- I) e = 0 (eq. 31).
    ASSERT_NEAR((jxx - jm) * ex + jxz * ez, 0.0, 1e-10);
    ASSERT_NEAR(jxz * ex + (jzz - jm) * ez, 0.0, 1e-10);
    // eq. 33–34 where they are defined.
    if (std::abs(jxz) > 1e-3) {
      const double q = (jm - jxx) / jxz, s = 1 / std::sqrt(1 + q * q);
      ASSERT_NEAR(std::abs(ex), s, 1e-9);
      ASSERT_NEAR(std::abs(ez), std::abs(q) * s, 1e-9);
    }
  }
  // Isotropic (λ = 0): J- = J+ = 1, eigenvector (1, 0) instead of eq. 34's 0/0.
  float m, p, x, z;
  kf::ocean_jacobian_eigen(1.0f, 1.0f, 0.0f, &m, &p, &x, &z);
  EXPECT_EQ(m, 1.0f);
  EXPECT_EQ(p, 1.0f);
  EXPECT_EQ(x, 1.0f);
  EXPECT_EQ(z, 0.0f);
  // Diagonal, anisotropic: the axis of the smaller entry.
  kf::ocean_jacobian_eigen(2.0f, 0.5f, 0.0f, &m, &p, &x, &z);
  EXPECT_EQ(m, 0.5f);
  EXPECT_EQ(x, 0.0f);
  EXPECT_EQ(z, 1.0f);
  // J- << J+: J- = det / J+ keeps its digits in float where mean - r would lose them all.
  const double a = 1000.0, b2 = 0.001, c = 0.01;
  double dm, dp, dx, dz;
  kd::ocean_jacobian_eigen(a, b2, c, &dm, &dp, &dx, &dz);
  kf::ocean_jacobian_eigen(static_cast<float>(a), static_cast<float>(b2), static_cast<float>(c), &m, &p, &x, &z);
  EXPECT_NEAR(dm, (a * b2 - c * c) / dp, 1e-15);
  EXPECT_NEAR(m / dm, 1.0, 1e-5);
}

}  // namespace
