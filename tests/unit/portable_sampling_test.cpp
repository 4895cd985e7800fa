// portable_sampling_test.cpp — the portable draws behind dataset jobs: exp, log, Φ and Φ⁻¹ against
// libm in long double; the distributions' bounds, moments and tails; and fixed values for fixed
// (seed, item, key), written as exact hex floats, so a machine whose arithmetic differs fails here.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <vector>

#include "math/portable_sampling.h"

using namespace seasim;

namespace {

long double cdfReference(long double x) { return 0.5L * std::erfc(-x / std::sqrt(2.0L)); }

double relError(long double got, long double want) {
  return static_cast<double>(std::fabs(got - want) / std::fabs(want));
}

constexpr double kInf = std::numeric_limits<double>::infinity();

}  // namespace

TEST(PortableSampling, ExpAndLogMatchLibmToAFewUlps) {
  double worst_exp = 0, worst_log = 0;
  for (double x = -708.0; x <= 709.0; x += 0.0137)
    worst_exp = std::max(worst_exp, relError(portableExp(x), std::exp(static_cast<long double>(x))));
  // Below e^-708 the result is subnormal: within a subnormal step or two of the true value.
  for (double x = -745.0; x < -708.0; x += 0.013)
    EXPECT_LE(std::fabs(static_cast<long double>(portableExp(x)) - std::exp(static_cast<long double>(x))), 1e-323L) << x;
  for (double x : {-1e-300, 1e-300, -1e-17, 1e-17, 0.0}) EXPECT_NEAR(portableExp(x), 1.0, 2e-16);
  for (double x = 1e-300; x < 1e300; x *= 1.37) worst_log = std::max(worst_log, relError(portableLog(x), std::log(static_cast<long double>(x))));
  // Near 1 the log is small: relative error of ln(1 + d) for tiny d.
  for (double d : {1e-15, -1e-12, 1e-9, -3e-6, 1e-3, -0.2, 0.4})
    worst_log = std::max(worst_log, relError(portableLog(1.0 + d), std::log(static_cast<long double>(1.0 + d))));
  EXPECT_LT(worst_exp, 4e-16);
  EXPECT_LT(worst_log, 4e-16);
  EXPECT_EQ(portableExp(-800.0), 0.0);
  EXPECT_TRUE(std::isinf(portableExp(800.0)));
  EXPECT_EQ(portableLog(1.0), 0.0);
  EXPECT_TRUE(std::isnan(portableLog(0.0)));
  EXPECT_TRUE(std::isnan(portableLog(-1.0)));
}

TEST(PortableSampling, NormalCdfIsRelativelyAccurateInBothTails) {
  double worst = 0, worst_upper = 0;
  for (double x = -37.0; x <= 8.0; x += 0.013) worst = std::max(worst, relError(normalCdf(x), cdfReference(x)));
  // The upper tail as 1 − Φ: only absolute accuracy is possible there.
  for (double x = 0.0; x <= 8.0; x += 0.013)
    worst_upper = std::max(worst_upper, static_cast<double>(std::fabs(normalCdf(x) - cdfReference(x))));
  EXPECT_LT(worst, 1e-13);
  EXPECT_LT(worst_upper, 5e-16);
  EXPECT_EQ(normalCdf(0.0), 0.5);
}

TEST(PortableSampling, NormalQuantileInvertsTheCdf) {
  double worst = 0, worst_tiny = 0;
  for (double p = 1e-300; p < 0.5; p *= 1.9) {
    const double x = normalQuantile(p);
    // Below 1e-100 (x < -21) φ(x)'s own rounding, x²/2 · 2^-53 relative, takes over.
    (p < 1e-100 ? worst_tiny : worst) = std::max(p < 1e-100 ? worst_tiny : worst, relError(cdfReference(x), p));
  }
  for (double p = 0.5; p < 1.0 - 1e-12; p = 1.0 - (1.0 - p) * 0.6) {
    const double x = normalQuantile(p);
    worst = std::max(worst, relError(1.0L - cdfReference(x), 1.0L - p) * (1.0 - p) / p);  // in p
  }
  EXPECT_LT(worst, 1e-13);
  EXPECT_LT(worst_tiny, 3e-13);
  EXPECT_EQ(normalQuantile(0.5), 0.0);
  EXPECT_NEAR(normalQuantile(0.975), 1.959963984540054, 1e-14);
  EXPECT_TRUE(std::isinf(normalQuantile(0.0)));
  EXPECT_TRUE(std::isinf(normalQuantile(1.0)));
}

TEST(PortableSampling, TruncatedNormalStaysInsideEvenFarInTheTails) {
  struct Range {
    double lo, hi;
  };
  for (const Range& r : {Range{-kInf, kInf}, Range{0, kInf}, Range{5, 6}, Range{-6, -5}, Range{29, 29.5},
                         Range{-kInf, -29}, Range{-0.1, 0.1}, Range{1e-9, 2e-9}, Range{-3, 30}}) {
    double mean = 0;
    const int n = 4000;
    for (int i = 0; i < n; ++i) {
      const double u = (i + 0.5) / n;
      const double x = truncatedNormal(u, r.lo, r.hi);
      ASSERT_TRUE(x >= r.lo && x <= r.hi) << r.lo << " " << r.hi << " u=" << u << " x=" << x;
      mean += x / n;
    }
    // The mean of a normal truncated to [a, b]: (φ(a) − φ(b)) / (Φ(b) − Φ(a)); by the tail's
    // side, so that [5, 6] is computed without cancellation.
    auto pdf = [](double x) { return std::isinf(x) ? 0.0 : std::exp(-0.5 * x * x) / std::sqrt(2 * std::numbers::pi); };
    const bool upper = r.lo > 0;
    const long double mass = upper ? cdfReference(-r.lo) - cdfReference(-r.hi) : cdfReference(r.hi) - cdfReference(r.lo);
    const double want = static_cast<double>((pdf(r.lo) - pdf(r.hi)) / mass);
    EXPECT_NEAR(mean, want, 1e-3 * std::max(1.0, std::fabs(want)) + 1e-3 * (r.hi - r.lo)) << r.lo << " " << r.hi;
  }
}

TEST(PortableSampling, DistributionsRespectBoundsAndMoments) {
  // u on an even grid: the maths of each distribution, apart from the generator's sampling noise.
  const int n = 20000;
  double sum_u = 0, sum_log = 0, sum_n = 0, sum_n2 = 0;
  std::vector<int> ints(4, 0), picks(3, 0);
  const std::vector<double> cumulative = {1, 4, 10};  // weights 1, 3, 6
  for (int i = 0; i < n; ++i) {
    const double u = (i + 0.5) / n;
    const double a = uniformIn(u, -2, 3), b = logUniformIn(u, 0.1, 1000), c = normalIn(u, 10, 2, 7, 100);
    const long long d = integerIn(u, -1, 2);
    ASSERT_TRUE(a >= -2 && a <= 3 && b >= 0.1 && b <= 1000 && c >= 7 && c <= 100 && d >= -1 && d <= 2);
    sum_u += a;
    sum_log += std::log10(b);
    sum_n += c;
    sum_n2 += c * c;
    ++ints[static_cast<size_t>(d + 1)];
    ++picks[weightedIndex(u, cumulative)];
  }
  EXPECT_NEAR(sum_u / n, 0.5, 1e-9);
  EXPECT_NEAR(sum_log / n, 1.0, 1e-6);  // log-uniform: log10 uniform on [-1, 3]
  // N(10, 2) truncated below at 7 (z = -1.5): mean 10 + 2 φ(1.5) / Φ(1.5) = 10.277580,
  // variance 4 (1 − 1.5 λ − λ²), λ = φ(1.5)/Φ(1.5) = 0.138790: sd 1.757900.
  const double mean = sum_n / n;
  EXPECT_NEAR(mean, 10.277580, 1e-4);
  EXPECT_NEAR(std::sqrt(sum_n2 / n - mean * mean), 1.757900, 1e-4);
  for (int k : ints) EXPECT_EQ(k, n / 4);
  EXPECT_NEAR(picks[0], n * 0.1, 1);
  EXPECT_NEAR(picks[1], n * 0.3, 1);
  EXPECT_NEAR(picks[2], n * 0.6, 1);
  EXPECT_EQ(integerIn(1e-17, 5, 5), 5);
  EXPECT_EQ(integerIn(1 - 1e-16, 0, 9), 9);
}

TEST(PortableSampling, DrawsAreUniformOverItemsForEverySeed) {
  // 40 seeds × 20,000 items in 20 bins: Pearson's χ² per seed (19 degrees of freedom; 43.8 is its
  // 0.1 % point) and the mean of u over all 800,000 draws (standard error 3.2e-4).
  const std::uint64_t key = nameHash("sun.zenith_deg");
  double total = 0, worst_chi2 = 0;
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    std::vector<int> bins(20, 0);
    for (std::uint64_t i = 0; i < 20000; ++i) {
      const double u = unitOpen(drawBits(seed, i, key, 0));
      ASSERT_TRUE(u > 0.0 && u < 1.0);
      total += u;
      ++bins[static_cast<size_t>(u * 20)];
    }
    double chi2 = 0;
    for (int b : bins) chi2 += (b - 1000.0) * (b - 1000.0) / 1000.0;
    worst_chi2 = std::max(worst_chi2, chi2);
  }
  EXPECT_NEAR(total / 800000, 0.5, 1e-3);
  EXPECT_LT(worst_chi2, 50.0);  // the worst of 40 seeds
}

TEST(PortableSampling, DrawsDependOnEveryWordOfTheirKey) {
  const std::uint64_t k = nameHash("sun.zenith_deg");
  const std::uint64_t base = drawBits(7, 3, k, 0);
  EXPECT_NE(base, drawBits(8, 3, k, 0));
  EXPECT_NE(base, drawBits(7, 4, k, 0));
  EXPECT_NE(base, drawBits(7, 3, nameHash("sun.azimuth_deg"), 0));
  EXPECT_NE(base, drawBits(7, 3, k, 1));
  EXPECT_NE(drawBits(1, 2, k, 0), drawBits(2, 1, k, 0));
}

// Fixed values: these bits are the contract "the same seed gives the same items on any machine".
// If this test fails on a new platform, the platform's arithmetic differs (an FMA the build did
// not turn off, x87 precision): fix the build, do not update the numbers.
TEST(PortableSampling, FixedSeedGivesFixedBitsOnEveryMachine) {
  const std::uint64_t key = nameHash("water.depth");
  // Computed once with GCC 12 at -O0 and -O2 (also -march=native) and Clang 14 at -O2, x86-64.
  EXPECT_EQ(nameHash("a"), 0xaf63dc4c8601ec8cULL);  // FNV-1a 64's published test vector
  EXPECT_EQ(key, 0xf20f34549f1821f3ULL);
  EXPECT_EQ(drawBits(42, 0, key, 0), 0xe5e0c623bb5fbd25ULL);
  const double u0 = unitOpen(drawBits(42, 0, key, 0)), u1 = unitOpen(drawBits(42, 999, key, 2));
  EXPECT_EQ(uniformIn(u0, -3, 7), 0x1.7eb1ef59546f6p+2);
  EXPECT_EQ(logUniformIn(u1, 0.5, 40), 0x1.336e084616475p-1);
  EXPECT_EQ(normalIn(u0, 20, 5, 0, 25), 0x1.7759fccba3543p+4);
  EXPECT_EQ(normalIn(u1, 0, 1, 3, 4), 0x1.e09cfa48fcfb4p+1);
  EXPECT_EQ(integerIn(u1, 1, 1000), 42);
  EXPECT_EQ(portableExp(1.0), 0x1.5bf0a8b14576ap+1);
  EXPECT_EQ(portableLog(10.0), 0x1.26bb1bbb55516p+1);
  EXPECT_EQ(normalQuantile(1e-20), -0x1.2865170b43a4cp+3);
}
