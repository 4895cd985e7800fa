// path_tracer_math_test.cpp — the samplers of the underwater path tracer (kernels/common/path_tracer.h)
// in float and double: the counter-based RNG (uniformity, independence of dimensions, identical in both
// precisions), free-flight distances (mean 1/σ_t), Henyey–Greenstein sampling against the HG pdf of
// optics.h (χ² over bins of 1 - cos θ down to the |g| -> 1 spike, mean cosine = g), isotropic and
// cosine-hemisphere directions, the orthonormal basis, and the Fresnel choice (frequency = F).
// Fixed seeds: every statistic below is deterministic; tolerances are 5 standard errors (or a χ² at
// p ≈ 1e-6), computed from the sample itself where the variance is not known in closed form.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <vector>

#include "math/kernel_math.h"

namespace {

namespace kd = seasim::kmath_d;
namespace kf = seasim::kmath_f;

// The samplers of one precision, so each test runs for float and double alike.
struct Float {
  using real = float;
  using vec = kf::real3;
  static real uniform(unsigned key, unsigned dim) { return kf::pt_uniform(key, dim); }
  static real distance(real c, real u) { return kf::pt_sample_distance(c, u); }
  static real hg_omc(real g, real u) { return kf::pt_hg_one_minus_cos(g, u); }
  static real hg_cos(real g, real u) { return kf::pt_sample_hg_cos(g, u); }
  static vec hg(vec d, real g, real u1, real u2) { return kf::pt_sample_hg(d, g, u1, u2); }
  static vec iso(real u1, real u2) { return kf::pt_sample_isotropic(u1, u2); }
  static vec cosine(vec n, real u1, real u2) { return kf::pt_sample_cosine(n, u1, u2); }
  static void basis(vec n, vec* a, vec* b) { kf::pt_basis(n, a, b); }
  static int reflects(real dy, real ior, real u) { return kf::pt_fresnel_reflects(dy, ior, u); }
  static real fresnel(real dy, real ior) { return kf::fresnel_reflectance(dy, ior, 1.0f); }
  static real dot(vec a, vec b) { return kf::dot(a, b); }
  static vec make(double x, double y, double z) { return vec{float(x), float(y), float(z)}; }
  static real infinite() { return 1e30f; }
  static constexpr double eps = 1e-6;  // rounding of unit-length and orthogonality checks
};
struct Double {
  using real = double;
  using vec = kd::real3;
  static real uniform(unsigned key, unsigned dim) { return kd::pt_uniform(key, dim); }
  static real distance(real c, real u) { return kd::pt_sample_distance(c, u); }
  static real hg_omc(real g, real u) { return kd::pt_hg_one_minus_cos(g, u); }
  static real hg_cos(real g, real u) { return kd::pt_sample_hg_cos(g, u); }
  static vec hg(vec d, real g, real u1, real u2) { return kd::pt_sample_hg(d, g, u1, u2); }
  static vec iso(real u1, real u2) { return kd::pt_sample_isotropic(u1, u2); }
  static vec cosine(vec n, real u1, real u2) { return kd::pt_sample_cosine(n, u1, u2); }
  static void basis(vec n, vec* a, vec* b) { kd::pt_basis(n, a, b); }
  static int reflects(real dy, real ior, real u) { return kd::pt_fresnel_reflects(dy, ior, u); }
  static real fresnel(real dy, real ior) { return kd::fresnel_reflectance(dy, ior, 1.0); }
  static real dot(vec a, vec b) { return kd::dot(a, b); }
  static vec make(double x, double y, double z) { return vec{x, y, z}; }
  static real infinite() { return 1e30; }
  static constexpr double eps = 1e-13;
};

template <typename P>
class PathTracerMath : public ::testing::Test {};
using Precisions = ::testing::Types<Float, Double>;
TYPED_TEST_SUITE(PathTracerMath, Precisions);

// Mean and standard error of the mean of a sample.
struct Stats {
  double mean = 0, se = 0;
};
Stats stats(const std::vector<double>& x) {
  double m = 0;
  for (double v : x) m += v;
  m /= x.size();
  double var = 0;
  for (double v : x) var += (v - m) * (v - m);
  var /= (x.size() - 1);
  return {m, std::sqrt(var / x.size())};
}

// The HG probability of 1 - cos θ (measured from the lobe's side: x = 1 - sign(g) cos θ) in [lo, hi],
// 2π ∫ p dcos θ, by Simpson's rule in s = ln x (the spike at |g| -> 1 is smooth in ln x), from
// optics.h's hg_phase in double — independent of the sampler's inverse CDF.
double hgBinProbability(double g, double lo, double hi) {
  const double sg = g >= 0 ? 1.0 : -1.0;
  auto f = [&](double s) {
    const double x = std::exp(s);
    return 2 * M_PI * kd::hg_phase(sg * (1 - x), g) * x;  // dcos = dx = x ds
  };
  const int n = 400;  // even
  const double a = std::log(lo), b = std::log(hi), h = (b - a) / n;
  double sum = f(a) + f(b);
  for (int i = 1; i < n; ++i) sum += (i % 2 ? 4 : 2) * f(a + i * h);
  return sum * h / 3;
}

TYPED_TEST(PathTracerMath, UniformIsInRangeFlatAndTheSameInBothPrecisions) {
  using P = TypeParam;
  const int bins = 64, n = 1 << 20;
  std::vector<double> count(bins, 0.0);
  double corr = 0;
  for (int i = 0; i < n; ++i) {
    const unsigned key = kd::pt_path_key(7u, unsigned(i % 1024), unsigned(i / 1024));
    const double u = P::uniform(key, 3);
    const double v = P::uniform(key, 4);  // the next dimension of the same path
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    ASSERT_EQ(u, kd::pt_uniform(key, 3));  // exact in float: (h >> 8) 2^-24
    count[std::min(int(u * bins), bins - 1)] += 1;
    corr += (u - 0.5) * (v - 0.5);
  }
  double chi2 = 0;
  const double expected = double(n) / bins;
  for (double c : count) chi2 += (c - expected) * (c - expected) / expected;
  // χ² with 63 degrees of freedom: mean 63, sd 11.2; 63 + 5·11.2 ≈ 119.
  EXPECT_LT(chi2, 119.0);
  // Correlation of adjacent dimensions: E[(u-½)(v-½)] = 0 with sd (1/12)/sqrt(n) = 8.1e-5.
  EXPECT_LT(std::fabs(corr / n), 5 * (1.0 / 12) / std::sqrt(double(n)));
  // Keys of neighbouring pixels/samples/seeds differ (no aliasing of the three counters).
  EXPECT_NE(kd::pt_path_key(1, 2, 3), kd::pt_path_key(1, 3, 2));
  EXPECT_NE(kd::pt_path_key(1, 2, 3), kd::pt_path_key(2, 2, 3));
  EXPECT_EQ(kd::pt_path_key(1, 2, 3), kd::pt_path_key(1, 2, 3));
}

TYPED_TEST(PathTracerMath, FreeFlightMeanIsTheMeanFreePath) {
  using P = TypeParam;
  for (double c : {0.01, 0.5, 10.0, 100.0}) {
    std::vector<double> t;
    for (int i = 0; i < 200000; ++i) t.push_back(P::distance(typename P::real(c), P::uniform(kd::pt_hash(i), 0)));
    const Stats s = stats(t);
    EXPECT_NEAR(s.mean * c, 1.0, 5 * s.se * c) << c;  // se ≈ 1/(c sqrt(n)): 0.22 %
    // P(t >= S) = e^{-c S} (the transmittance the estimator relies on), at S = 1/c: e^{-1}.
    double beyond = 0;
    for (double v : t) beyond += v >= 1.0 / c ? 1 : 0;
    const double p = std::exp(-1.0);
    EXPECT_NEAR(beyond / t.size(), p, 5 * std::sqrt(p * (1 - p) / t.size())) << c;
  }
  // Stiff ends: σ_t = 0 never scatters; the largest u gives a finite distance (1 - u >= 2^-24).
  EXPECT_GE(P::distance(0, 0.5), P::infinite());
  const double u_max = 1.0 - std::ldexp(1.0, -24);
  EXPECT_NEAR(P::distance(1, typename P::real(u_max)), 24 * std::log(2.0), 1e-5);
  EXPECT_EQ(P::distance(1, 0), 0.0);
}

TYPED_TEST(PathTracerMath, HenyeyGreensteinMatchesItsPdf) {
  using P = TypeParam;
  for (double g : {0.0, 0.9, -0.5, 0.999, -0.999}) {
    // Bins of x = 1 - sign(g) cos θ: geometric from 2 down to 1e-9, one last bin [0, 1e-9].
    const int geo = 45;
    std::vector<double> edges;  // descending
    for (int k = 0; k <= geo; ++k) edges.push_back(2.0 * std::pow(1e-9 / 2.0, double(k) / geo));
    std::vector<double> expect(geo + 1, 0.0), count(geo + 1, 0.0);
    double covered = 0;
    for (int k = 0; k < geo; ++k) covered += expect[k] = hgBinProbability(g, edges[k + 1], edges[k]);
    expect[geo] = 1.0 - covered;
    EXPECT_GE(expect[geo], -1e-9) << g;
    const int n = 400000;
    std::vector<double> cosines;
    cosines.reserve(n);
    const double sg = g >= 0 ? 1 : -1;
    for (int i = 0; i < n; ++i) {
      const typename P::real u = P::uniform(kd::pt_hash(i + 12345), 1);
      const double omc = P::hg_omc(typename P::real(std::fabs(g)), u);  // x itself, with its digits
      ASSERT_TRUE(omc >= 0 && omc <= 2) << g << " " << u;
      cosines.push_back(P::hg_cos(typename P::real(g), u));
      ASSERT_NEAR(cosines.back(), sg * (1 - omc), (std::is_same_v<P, Float> ? 1e-7 : 1e-15));
      int k = 0;
      while (k < geo && omc < edges[k + 1]) ++k;
      count[k] += 1;
    }
    // χ² over bins with at least 20 expected samples, the rest pooled.
    double chi2 = 0, pool_e = 0, pool_o = 0;
    int dof = -1;
    for (int k = 0; k <= geo; ++k) {
      const double e = expect[k] * n;
      if (e >= 20) {
        chi2 += (count[k] - e) * (count[k] - e) / e;
        ++dof;
      } else {
        pool_e += e;
        pool_o += count[k];
      }
    }
    if (pool_e > 0) {
      chi2 += (pool_o - pool_e) * (pool_o - pool_e) / std::max(pool_e, 1.0);
      ++dof;
    }
    // p ≈ 1e-6: mean dof, sd sqrt(2 dof); 5 sd above the mean.
    EXPECT_LT(chi2, dof + 5 * std::sqrt(2.0 * dof)) << "g=" << g << " dof=" << dof;
    // The mean cosine of HG is g.
    const Stats s = stats(cosines);
    EXPECT_NEAR(s.mean, g, 5 * s.se + 1e-12) << g;
  }
}

TYPED_TEST(PathTracerMath, HenyeyGreensteinStableFormAgreesWithTheTextbookForm) {
  using P = TypeParam;
  // cos θ = (1 + g² - s²)/(2g), s = (1 - g²)/(1 - g + 2 g v), in double where it is well conditioned.
  // For g < 0 the sampler mirrors |g|, which runs the inverse CDF from the other end: v = 1 - u.
  for (double g : {0.1, 0.5, 0.8, -0.3, -0.8}) {
    for (double u : {0.0, 0.01, 0.3, 0.5, 0.9, 0.999}) {
      const double v = g >= 0 ? u : 1 - u;
      const double s = (1 - g * g) / (1 - g + 2 * g * v);
      const double textbook = (1 + g * g - s * s) / (2 * g);
      EXPECT_NEAR(P::hg_cos(typename P::real(g), typename P::real(u)), textbook, 50 * P::eps) << g << " " << u;
    }
  }
  // g = 0 without a special case: cos θ = 2u - 1; ends u = 0 and u -> 1 give backward and forward.
  EXPECT_NEAR(P::hg_cos(0, typename P::real(0.25)), -0.5, P::eps);
  EXPECT_NEAR(P::hg_cos(typename P::real(0.7), 0), -1.0, 10 * P::eps);
  EXPECT_NEAR(P::hg_cos(typename P::real(-0.7), 0), 1.0, 10 * P::eps);
  // |g| -> 1: 1 - cos θ keeps its relative digits where cos θ itself rounds to 1 (float).
  const double g = typename P::real(0.999), u = 0.5, s = (1 - g * g) / (1 - g + 2 * g * u);  // g as P holds it
  const double omc_exact = (1 - g) * (1 - u) * (s + 1 - g) / (1 - g + 2 * g * u);
  EXPECT_NEAR(P::hg_omc(typename P::real(g), typename P::real(u)) / omc_exact, 1.0, 1e-5);
  // g = 1 exactly (the delta) and u = 0: no 0/0.
  EXPECT_EQ(P::hg_omc(1, 0), 0.0);
  EXPECT_EQ(P::hg_omc(1, typename P::real(0.3)), 0.0);
}

TYPED_TEST(PathTracerMath, DirectionsAreUnitAndDistributedAroundTheirAxis) {
  using P = TypeParam;
  const std::vector<typename P::vec> axes = {P::make(0, 0, 1), P::make(0, 0, -1), P::make(1, 0, 0),
                                             P::make(0, -1, 0), P::make(0.48, -0.6, 0.64),
                                             P::make(0, -std::sqrt(1 - 1e-12), 1e-6)};
  for (const auto& a : axes) {
    typename P::vec t1, t2;
    P::basis(a, &t1, &t2);
    EXPECT_NEAR(P::dot(t1, t1), 1.0, 10 * P::eps);
    EXPECT_NEAR(P::dot(t2, t2), 1.0, 10 * P::eps);
    EXPECT_NEAR(P::dot(t1, t2), 0.0, 10 * P::eps);
    EXPECT_NEAR(P::dot(t1, a), 0.0, 10 * P::eps);
    EXPECT_NEAR(P::dot(t2, a), 0.0, 10 * P::eps);
    for (double g : {0.0, 0.9, -0.5}) {
      std::vector<double> c, side;
      for (int i = 0; i < 100000; ++i) {
        const unsigned key = kd::pt_hash(i);
        const auto d = P::hg(a, typename P::real(g), P::uniform(key, 0), P::uniform(key, 1));
        ASSERT_NEAR(P::dot(d, d), 1.0, 10 * P::eps);
        c.push_back(P::dot(d, a));
        side.push_back(P::dot(d, t1));  // azimuth uniform: no preferred side
      }
      const Stats s = stats(c), t = stats(side);
      EXPECT_NEAR(s.mean, g, 5 * s.se + 1e-12) << g;
      EXPECT_NEAR(t.mean, 0.0, 5 * t.se) << g;
    }
    // Cosine hemisphere: E[cos] = 2/3, E[cos²] = 1/2, never below the surface.
    std::vector<double> c, c2;
    for (int i = 0; i < 100000; ++i) {
      const unsigned key = kd::pt_hash(i + 777);
      const auto d = P::cosine(a, P::uniform(key, 0), P::uniform(key, 1));
      ASSERT_NEAR(P::dot(d, d), 1.0, 10 * P::eps);
      c.push_back(P::dot(d, a));
      c2.push_back(c.back() * c.back());
      ASSERT_GE(c.back(), -10 * P::eps);
    }
    const Stats s = stats(c), s2 = stats(c2);
    EXPECT_NEAR(s.mean, 2.0 / 3.0, 5 * s.se);
    EXPECT_NEAR(s2.mean, 0.5, 5 * s2.se);
  }
  // Isotropic: E[d] = 0, E[d_y²] = 1/3.
  std::vector<double> x, y2;
  for (int i = 0; i < 100000; ++i) {
    const unsigned key = kd::pt_hash(i + 99);
    const auto d = P::iso(P::uniform(key, 0), P::uniform(key, 1));
    ASSERT_NEAR(P::dot(d, d), 1.0, 10 * P::eps);
    x.push_back(d.x);
    y2.push_back(d.y * d.y);
  }
  const Stats sx = stats(x), sy = stats(y2);
  EXPECT_NEAR(sx.mean, 0.0, 5 * sx.se);
  EXPECT_NEAR(sy.mean, 1.0 / 3.0, 5 * sy.se);
}

TYPED_TEST(PathTracerMath, FresnelChoiceReflectsWithProbabilityF) {
  using P = TypeParam;
  const double ior = 1.333;
  for (double dy : {1.0, 0.9, 0.7, 0.67}) {  // inside Snell's window (critical cos ≈ 0.661)
    const double F = P::fresnel(typename P::real(dy), typename P::real(ior));
    double hits = 0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) hits += P::reflects(typename P::real(dy), typename P::real(ior), P::uniform(kd::pt_hash(i), 5));
    EXPECT_NEAR(hits / n, F, 5 * std::sqrt(F * (1 - F) / n) + 1e-12) << dy;
  }
  // Outside the window: total internal reflection, always reflected (F = 1, u < 1 always).
  for (double dy : {0.6, 0.3, 0.0}) {
    EXPECT_EQ(P::reflects(typename P::real(dy), typename P::real(ior), typename P::real(1.0 - std::ldexp(1.0, -24))), 1);
  }
}

// Equiangular sampling about a point light (path_tracer.h): the pdf it reports integrates to 1 over
// the segment and is the derivative of the sampled CDF (dt/du = 1/pdf), for a finite and an infinite
// segment; an empty segment gives pdf 0; float stays finite at u = 1 - 2^-24 on an infinite segment.
TEST(PathTracerEquiangular, PdfIsNormalisedAndIsTheSamplesDensity) {
  const double a = 1.5, r = 0.05, t0 = 0.0;
  for (double t1 : {3.0, 40.0, 1e30}) {
    const bool infinite = t1 >= 1e29;
    // dt/du · pdf = 1 at a few points (finite differences in u).
    for (double u : {0.01, 0.3, 0.5, 0.7, 0.99}) {
      double p, p2;
      const double t = kd::pt_sample_equiangular(a, r, t0, t1, u, &p);
      const double t2 = kd::pt_sample_equiangular(a, r, t0, t1, u + 1e-7, &p2);
      EXPECT_GE(t, t0);
      if (!infinite) EXPECT_LE(t, t1);
      EXPECT_NEAR((t2 - t) / 1e-7 * p, 1.0, 1e-4) << t1 << " " << u;
    }
    // ∫ pdf dt by the trapezoid rule on a grid dense near t0 (the light is at t = 1.5, 5 cm off the ray).
    const double top = infinite ? 1e5 : t1;
    double integral = 0, prev_t = t0, prev_p = 0;
    (void)kd::pt_sample_equiangular(a, r, t0, t1, 0.0, &prev_p);
    const int m = 400000;
    for (int i = 1; i <= m; ++i) {
      const double t = t0 + (top - t0) * std::pow(double(i) / m, 3);
      const double th0 = std::atan((t0 - a) / r), th1 = infinite ? M_PI / 2 : std::atan((t1 - a) / r);
      const double p = r / ((th1 - th0) * (r * r + (t - a) * (t - a)));
      integral += 0.5 * (p + prev_p) * (t - prev_t);
      prev_t = t;
      prev_p = p;
    }
    // The infinite segment's tail beyond 1e5 m holds r/(π/2 + atan(a/r)) / 1e5 ≈ 3e-7 of it.
    EXPECT_NEAR(integral, 1.0, 1e-4) << t1;
  }
  double pdf = 1;
  (void)kd::pt_sample_equiangular(0.0, 1.0, 2.0, 2.0, 0.5, &pdf);
  EXPECT_EQ(pdf, 0.0);
  float pf;
  const float tf = kf::pt_sample_equiangular(0.0f, 1e-3f, 0.0f, 1e30f, 1.0f - std::ldexp(1.0f, -24), &pf);
  EXPECT_TRUE(std::isfinite(tf) && std::isfinite(pf) && pf > 0);
}

}  // namespace

