// optics_test.cpp — the shared optics math (kernels/common/optics.h) checked on the CPU in float
// and double: Fresnel (004 eq. 35–44) at its stiff points, Snell refraction, Henyey–Greenstein and
// the shafts phase function (001 eq. 4) by quadrature, Beer–Lambert, and (e^x - 1)/x.
//
// Every physics check runs for both precisions through one typed test. References are computed in
// long double from the *same* (already rounded) inputs, so a tolerance measures only the error the
// formula adds. Float tolerances are looser than double because float has ε ≈ 6e-8 against
// double's 1.1e-16, and a formula that loses k bits loses them in both: a tolerance of a few ulp
// in double is ~1e-15, in float ~1e-6. Near the critical angle the Fresnel slope dR/dcos θi grows
// like 1/cos θt, so there the tolerance is scaled by ε/cos θt (stated where used).
#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <random>

#include "math/kernel_math.h"

namespace {

using ld = long double;
const ld kPi = 3.141592653589793238462643383279502884L;

// One struct per precision, so each TYPED_TEST runs in float and in double.
#define SEASIM_OPTICS_TRAITS(NAME, NS, EPS)                                                   \
  struct NAME {                                                                               \
    using real = NS::real;                                                                    \
    using real3 = NS::real3;                                                                  \
    static constexpr double eps = EPS; /* machine epsilon of `real` */                        \
    static real fresnel(real c, real n1, real n2) { return NS::fresnel_reflectance(c, n1, n2); } \
    static int refract(real3 d, real3 n, real eta, real3* out) {                              \
      return NS::refract_dir(d, n, eta, out);                                                 \
    }                                                                                         \
    static real3 reflect(real3 d, real3 n) { return NS::reflect_dir(d, n); }                  \
    static real hg(real c, real g) { return NS::hg_phase(c, g); }                             \
    static real shafts(real a) { return NS::shafts_phase(a); }                                \
    static real shaftsCos(real c) { return NS::shafts_phase_cos(c); }                         \
    static real beer(real s, real d) { return NS::beer_lambert(s, d); }                       \
    static real expm1x(real x) { return NS::expm1_over_x(x); }                                \
  }
SEASIM_OPTICS_TRAITS(FloatMath, seasim::kmath_f, FLT_EPSILON);
SEASIM_OPTICS_TRAITS(DoubleMath, seasim::kmath_d, DBL_EPSILON);
#undef SEASIM_OPTICS_TRAITS

template <class M>
class OpticsTest : public ::testing::Test {};
using Precisions = ::testing::Types<FloatMath, DoubleMath>;
struct PrecisionName {
  template <class T>
  static std::string GetName(int) {
    return std::is_same_v<T, FloatMath> ? "float" : "double";
  }
};
TYPED_TEST_SUITE(OpticsTest, Precisions, PrecisionName);

// ---- references in long double -----------------------------------------------------------------

// 004 eq. 44 as printed (sin/tan form): an independent formula for the same reflectance, valid
// away from θi = 0 (where it is 0/0) and below the critical angle.
ld fresnelEq44(ld cos_i, ld n1, ld n2) {
  ld ti = std::acos(cos_i);
  ld st = n1 / n2 * std::sin(ti);
  if (st >= 1) return 1;
  ld tt = std::asin(st);
  ld fs = std::sin(tt - ti) / std::sin(tt + ti);
  ld ts = std::tan(tt - ti) / std::tan(tt + ti);
  return 0.5L * (fs * fs + ts * ts);
}

// Amplitude form in long double (the same formula as optics.h; valid everywhere, used at θ = 0
// and beside the critical angle where eq. 44 itself loses digits).
ld fresnelRef(ld cos_i, ld n1, ld n2) {
  ld c = std::fabs(cos_i);
  ld ct2 = 1 - (n1 / n2) * (n1 / n2) * (1 - c) * (1 + c);
  if (ct2 <= 0) return 1;
  ld ct = std::sqrt(ct2);
  ld rs = (n1 * c - n2 * ct) / (n1 * c + n2 * ct);
  ld rp = (n2 * c - n1 * ct) / (n2 * c + n1 * ct);
  return 0.5L * (rs * rs + rp * rp);
}

// HG in long double. The denominator uses the exact identities 1 + g² - 2gc = (1 - g)² + 2g(1 - c)
// = (1 + g)² - 2g(1 + c) (the one with non-negative terms for the sign of g): written plainly it
// cancels to ~1e-8 for g = 0.9999, c = 1 and would cost even long double 11 digits, making the
// reference worse than the double function under test.
ld hgRef(ld c, ld g) {
  ld den = g >= 0 ? (1 - g) * (1 - g) + 2 * g * (1 - c) : (1 + g) * (1 + g) - 2 * g * (1 + c);
  return (1 - g) * (1 + g) / (4 * kPi * std::pow(den, 1.5L));
}

// Adaptive Simpson on [a, b] in long double. The per-interval test is relative to the interval's
// own integral, so a narrow spike (HG with g = 0.999 peaks at 1.6e5) is resolved as finely as the
// flat tail, and float-precision noise in f (~1e-7 relative) cannot force endless refinement as
// long as rel_tol is above it.
ld simpsonStep(const std::function<ld(ld)>& f, ld a, ld b, ld fa, ld fm, ld fb, ld whole,
               ld rel_tol, int depth) {
  ld m = (a + b) / 2, lm = (a + m) / 2, rm = (m + b) / 2;
  ld flm = f(lm), frm = f(rm);
  ld left = (m - a) / 6 * (fa + 4 * flm + fm);
  ld right = (b - m) / 6 * (fm + 4 * frm + fb);
  ld both = left + right;
  if (depth <= 0 || std::fabs(both - whole) <= 15 * rel_tol * std::fabs(both)) {
    return both + (both - whole) / 15;
  }
  return simpsonStep(f, a, m, fa, flm, fm, left, rel_tol, depth - 1) +
         simpsonStep(f, m, b, fm, frm, fb, right, rel_tol, depth - 1);
}
ld integrate(const std::function<ld(ld)>& f, ld a, ld b, ld rel_tol) {
  // Start from 16 panels so no feature hides between the first three samples.
  const int n = 16;
  ld sum = 0;
  for (int i = 0; i < n; ++i) {
    ld x0 = a + (b - a) * i / n, x1 = a + (b - a) * (i + 1) / n, xm = (x0 + x1) / 2;
    ld f0 = f(x0), fm = f(xm), f1 = f(x1);
    sum += simpsonStep(f, x0, x1, f0, fm, f1, (x1 - x0) / 6 * (f0 + 4 * fm + f1), rel_tol, 40);
  }
  return sum;
}

template <class V>
ld len(const V& v) {
  return std::sqrt(ld(v.x) * v.x + ld(v.y) * v.y + ld(v.z) * v.z);
}
template <class V>
ld dotl(const V& a, const V& b) {
  return ld(a.x) * b.x + ld(a.y) * b.y + ld(a.z) * b.z;
}
// |a × b| in long double.
template <class V>
ld crossLen(const V& a, const V& b) {
  ld x = ld(a.y) * b.z - ld(a.z) * b.y, y = ld(a.z) * b.x - ld(a.x) * b.z,
     z = ld(a.x) * b.y - ld(a.y) * b.x;
  return std::sqrt(x * x + y * y + z * z);
}

constexpr double kAir = 1.0;
constexpr double kWater = 1.333;

// ---- Fresnel -------------------------------------------------------------------------------------

TYPED_TEST(OpticsTest, FresnelNormalIncidenceIsExact) {
  using M = TypeParam;
  using real = typename M::real;
  // The 0/0 of eq. 44 at θ = 0: the amplitude form must give ((n1-n2)/(n1+n2))² to a few ulp.
  for (auto [n1, n2] : {std::pair{kAir, kWater}, std::pair{kWater, kAir}, std::pair{1.0, 1.5}}) {
    real r1 = real(n1), r2 = real(n2);
    ld expect = (ld(r1) - r2) / (ld(r1) + r2);
    expect *= expect;
    for (real c : {real(1), real(-1)}) {  // either side of the normal
      EXPECT_NEAR(M::fresnel(c, r1, r2), expect, 8 * M::eps * expect) << n1 << "->" << n2;
    }
    // Continuous into θ > 0: R(θ) - R(0) = O(θ²), tiny for θ = 1e-4.
    real c_small = real(std::cos(1e-4L));
    EXPECT_NEAR(M::fresnel(c_small, r1, r2), expect, 1e-8 + 8 * M::eps * expect);
  }
  // Equal indices: no interface, nothing reflected.
  EXPECT_NEAR(M::fresnel(real(0.7), real(1.333), real(1.333)), 0, M::eps);
}

TYPED_TEST(OpticsTest, FresnelMatchesEq44AwayFromStiffPoints) {
  using M = TypeParam;
  using real = typename M::real;
  for (auto [n1, n2] : {std::pair{kAir, kWater}, std::pair{kWater, kAir}}) {
    real r1 = real(n1), r2 = real(n2);
    ld crit = n1 > n2 ? std::asin(ld(n2) / n1) : kPi / 2;
    for (int i = 1; i < 90; ++i) {
      ld theta = i * kPi / 180;
      if (std::fabs(theta - crit) < 0.02L) continue;  // covered by the critical-angle test
      real c = real(std::cos(theta));
      ld expect = fresnelEq44(ld(c), ld(r1), ld(r2));
      // A handful of ulp of R, plus the condition number of cos θt near critical (ε / cos²θt).
      ld ct2 = 1 - ld(r1) * r1 / (ld(r2) * r2) * (1 - ld(c) * c);
      ld tol = 16 * M::eps * (ct2 > 0 ? 1 + 1 / ct2 : 1);
      EXPECT_NEAR(M::fresnel(c, r1, r2), expect, tol) << n1 << "->" << n2 << " θ=" << i << "°";
      EXPECT_GE(M::fresnel(c, r1, r2), real(0));
      EXPECT_LE(M::fresnel(c, r1, r2), real(1));
    }
  }
}

TYPED_TEST(OpticsTest, FresnelCriticalAngleIsContinuousAndTotalBeyond) {
  using M = TypeParam;
  using real = typename M::real;
  real n1 = real(kWater), n2 = real(kAir);
  ld crit = std::asin(ld(n2) / ld(n1));
  // Beyond the critical angle: exactly 1 (TIR), all the way to grazing.
  for (ld d : {1e-6L, 1e-3L, 0.1L, 0.5L}) {
    ld theta = std::min(crit + d, kPi / 2);
    EXPECT_EQ(M::fresnel(real(std::cos(theta)), n1, n2), real(1)) << "θc+" << double(d);
  }
  // At and just below: close to 1 and matching the long-double reference for the same rounded
  // input. R ≈ 1 - C sqrt(θc - θ), so at 1e-6 rad below, R ≈ 0.99; the float error there is
  // ε / cos²θt relative in cos²θt (cancellation in 1 - η² sin²θi), i.e. ~ε/(2 cos θt) in R.
  for (ld d : {0.0L, 1e-6L, 1e-5L, 1e-4L}) {
    real c = real(std::cos(crit - d));
    ld expect = fresnelRef(ld(c), ld(n1), ld(n2));
    ld ct2 = 1 - ld(n1) * n1 / (ld(n2) * n2) * (1 - ld(c) * c);
    ld tol = 16 * M::eps * (ct2 > 0 ? 1 + 1 / std::sqrt(ct2) : 1);
    real got = M::fresnel(c, n1, n2);
    EXPECT_NEAR(got, expect, tol) << "θc-" << double(d);
    EXPECT_LE(got, real(1));
    if (d == 1e-6L) {
      EXPECT_GT(got, real(0.98)) << "continuity: R(θc - 1e-6) -> 1";
    }
  }
  // Monotone up to the critical angle (no dip or jump at the switch to TIR), in the exact cosines.
  real prev = 0;
  for (int i = 0; i <= 2000; ++i) {
    real c = real(std::cos(crit * i / 2000));
    real r = M::fresnel(c, n1, n2);
    EXPECT_GE(r, prev - real(8 * M::eps)) << i;
    prev = r;
  }
}

TYPED_TEST(OpticsTest, FresnelGrazingTendsToOne) {
  using M = TypeParam;
  using real = typename M::real;
  for (auto [n1, n2] : {std::pair{kAir, kWater}, std::pair{kWater, kAir}}) {
    EXPECT_EQ(M::fresnel(real(0), real(n1), real(n2)), real(1));
    // R(cos θi = c) = 1 - O(c) towards grazing (≈ 1 - 4 c n / (n² - 1)^{1/2} air->water).
    real near = M::fresnel(real(1e-6), real(n1), real(n2));
    EXPECT_GT(near, real(1 - 2e-5));
    EXPECT_LE(near, real(1));
  }
}

TYPED_TEST(OpticsTest, FresnelIsReciprocal) {
  using M = TypeParam;
  using real = typename M::real;
  // Stokes reciprocity: R(n1->n2 at θi) = R(n2->n1 at θt) for the Snell pair (θi, θt).
  real n1 = real(kAir), n2 = real(kWater);
  for (int i = 0; i < 90; i += 3) {
    ld ti = i * kPi / 180;
    ld tt = std::asin(ld(n1) / ld(n2) * std::sin(ti));
    real a = M::fresnel(real(std::cos(ti)), n1, n2);
    real b = M::fresnel(real(std::cos(tt)), n2, n1);
    // b sits below water's critical angle; at i = 87° cos θt(air side) ≈ 0.05: allow ε/cos²θi.
    ld ci = std::cos(ti);
    EXPECT_NEAR(a, b, 32 * M::eps * (1 + 1 / (ci * ci))) << "θi=" << i << "°";
  }
}

// ---- Snell refraction and reflection ----------------------------------------------------------------

TYPED_TEST(OpticsTest, RefractObeysSnellAndIsUnit) {
  using M = TypeParam;
  using real = typename M::real;
  using real3 = typename M::real3;
  std::mt19937 rng(20240611);
  std::normal_distribution<double> gauss;
  auto randomUnit = [&]() {
    double x = gauss(rng), y = gauss(rng), z = gauss(rng), l = std::sqrt(x * x + y * y + z * z);
    return real3{real(x / l), real(y / l), real(z / l)};
  };
  int transmitted = 0, tir = 0;
  for (double eta : {kAir / kWater, kWater / kAir, 1.0, 1 / 1.5, 1.5}) {
    for (int k = 0; k < 2000; ++k) {
      real3 d = randomUnit(), n = randomUnit();
      ld cos_i = std::fabs(dotl(d, n)) / (len(d) * len(n));
      ld sin_i = std::sqrt(std::max(0.0L, 1 - cos_i * cos_i));
      ld s = eta * sin_i;  // sin θt by Snell
      if (std::fabs(s - 1) < 1e-3) continue;  // too close to call in float; tested elsewhere
      real3 t{};
      int ok = M::refract(d, n, real(eta), &t);
      if (s > 1) {
        ASSERT_EQ(ok, 0) << "TIR not reported, eta sinθi = " << double(s);
        ++tir;
        // On TIR *out is the mirror direction.
        real3 r = M::reflect(d, n);
        EXPECT_NEAR(t.x, r.x, 4 * M::eps);
        EXPECT_NEAR(t.y, r.y, 4 * M::eps);
        EXPECT_NEAR(t.z, r.z, 4 * M::eps);
        continue;
      }
      ASSERT_EQ(ok, 1) << "refraction refused, eta sinθi = " << double(s);
      ++transmitted;
      EXPECT_NEAR(len(t), 1, 8 * M::eps);
      // n1 sin θi = n2 sin θt  <=>  eta |d × n| = |t × n|.
      EXPECT_NEAR(eta * crossLen(d, n), crossLen(t, n), 16 * M::eps);
      // Transmitted ray continues on the far side: t·n has the sign of d·n.
      EXPECT_GT(dotl(t, n) * dotl(d, n), -8 * M::eps);
      // Coplanar with d and n.
      real3 c{real(ld(d.y) * n.z - ld(d.z) * n.y), real(ld(d.z) * n.x - ld(d.x) * n.z),
              real(ld(d.x) * n.y - ld(d.y) * n.x)};
      EXPECT_NEAR(dotl(t, c), 0, 16 * M::eps);
      // The normal's orientation does not matter.
      real3 t2{};
      real3 nn{-n.x, -n.y, -n.z};
      EXPECT_EQ(M::refract(d, nn, real(eta), &t2), 1);
      EXPECT_NEAR(t2.x, t.x, 4 * M::eps);
      EXPECT_NEAR(t2.y, t.y, 4 * M::eps);
      EXPECT_NEAR(t2.z, t.z, 4 * M::eps);
    }
  }
  EXPECT_GT(transmitted, 5000);
  EXPECT_GT(tir, 500);
}

TYPED_TEST(OpticsTest, RefractStiffCases) {
  using M = TypeParam;
  using real = typename M::real;
  using real3 = typename M::real3;
  real3 up{0, 1, 0};
  real eta = real(kWater / kAir);
  // Normal incidence passes straight through.
  real3 t{};
  ASSERT_EQ(M::refract(real3{0, -1, 0}, up, eta, &t), 1);
  EXPECT_EQ(t.x, real(0));
  EXPECT_NEAR(t.y, -1, 2 * M::eps);
  // Just inside / outside the critical angle from below the surface (water -> air, going up).
  ld crit = std::asin(1 / ld(eta));
  for (ld d : {-1e-4L, 1e-4L}) {
    ld th = crit + d;
    real3 dir{real(std::sin(th)), real(std::cos(th)), 0};
    int ok = M::refract(dir, up, eta, &t);
    EXPECT_EQ(ok, d < 0 ? 1 : 0) << double(d);
    EXPECT_NEAR(len(t), 1, 8 * M::eps);
    if (ok) {
      EXPECT_GT(t.y, real(0));  // leaves upwards, nearly grazing
    } else {
      EXPECT_LT(t.y, real(0));  // reflected back down
    }
  }
}

TYPED_TEST(OpticsTest, ReflectIsMirror) {
  using M = TypeParam;
  using real = typename M::real;
  using real3 = typename M::real3;
  real s = real(1 / std::sqrt(3.0L));
  real3 d{s, -s, s}, n{0, 1, 0};
  real3 r = M::reflect(d, n);
  EXPECT_NEAR(r.x, s, 2 * M::eps);
  EXPECT_NEAR(r.y, s, 2 * M::eps);
  EXPECT_NEAR(r.z, s, 2 * M::eps);
  real3 r2 = M::reflect(d, real3{0, -1, 0});  // either normal orientation
  EXPECT_NEAR(r2.y, s, 2 * M::eps);
  EXPECT_NEAR(len(r), 1, 4 * M::eps);
}

// ---- Phase functions ---------------------------------------------------------------------------------

TYPED_TEST(OpticsTest, HenyeyGreensteinNormalisedWithMeanCosineG) {
  using M = TypeParam;
  using real = typename M::real;
  // Quadrature over μ = cos θ with dΩ = 2π dμ. The quadrature's own relative tolerance sits above
  // float noise (1e-6) and well below the double check (1e-11). Measured: |norm - 1| ≤ 4e-8
  // (float, |g| ≤ 0.99), 8e-4 (float, g = 0.999, the staircase below), 3e-16 (double).
  const bool is_float = M::eps > 1e-10;
  const ld rel_tol = is_float ? 1e-6L : 1e-11L;
  for (double gd : {-0.99, -0.5, 0.0, 0.5, 0.9, 0.99, 0.999}) {
    real g = real(gd);
    // The function takes cos θ in `real`, so the integral sees p at the representable cosines: a
    // staircase with step h = 2^-24 (float) / 2^-53 (double) near |μ| = 1. The spike's half-width
    // in μ is w = (1 - |g|)²/(2|g|) (5e-7 for g = 0.999: only ~8 float steps), and the staircase
    // (a midpoint rule of step h) misses the integral by ≈ (h/w)²/12 — 1.2e-3 for float at
    // g = 0.999, 3e-7 at g = 0.99, nothing in double. That is a limit of float cosines, not of
    // the formula (checked pointwise below); the tolerance adds it to the formula's 5e-6 / 1e-12.
    ld h = is_float ? std::ldexp(1.0L, -24) : std::ldexp(1.0L, -53);
    ld w = std::fabs(gd) > 0 ? (1 - std::fabs(ld(g))) * (1 - std::fabs(ld(g))) / (2 * std::fabs(ld(g)))
                             : 1.0L;
    const double tol = (is_float ? 5e-6 : 1e-12) + double((h / w) * (h / w) / 6);
    auto p = [&](ld mu) { return 2 * kPi * ld(M::hg(real(mu), g)); };
    ld norm = integrate(p, -1, 1, rel_tol);
    EXPECT_NEAR(double(norm), 1.0, tol) << "g=" << gd;
    ld mean = integrate([&](ld mu) { return mu * p(mu); }, -1, 1, rel_tol);
    EXPECT_NEAR(double(mean), double(g), tol) << "g=" << gd;
  }
}

TYPED_TEST(OpticsTest, HenyeyGreensteinPointwiseNearSpike) {
  using M = TypeParam;
  using real = typename M::real;
  // Against the plain formula in long double at the same rounded inputs, including the peak for
  // |g| -> 1, where the plain formula in `real` would lose ~log10(1/(1-g)²) digits.
  for (double gd : {-0.999, -0.99, 0.0, 0.5, 0.99, 0.999, 0.9999}) {
    real g = real(gd);
    for (double cd : {-1.0, -0.999, -0.5, 0.0, 0.5, 0.999, 0.99999, 1.0}) {
      real c = real(cd);
      ld expect = hgRef(ld(c), ld(g));
      EXPECT_NEAR(M::hg(c, g), expect, 16 * M::eps * expect) << "g=" << gd << " cos=" << cd;
    }
  }
  EXPECT_NEAR(M::hg(real(0.3), real(0)), 1 / (4 * kPi), 2 * M::eps);
  // p(c, g) = p(-c, -g): forward and backward lobes are mirror images.
  EXPECT_NEAR(M::hg(real(0.9), real(0.99)), M::hg(real(-0.9), real(-0.99)),
              4 * M::eps * M::hg(real(0.9), real(0.99)));
  // Clamped outside [-1, 1] (a dot product of unit vectors can exceed 1 by an ulp).
  EXPECT_EQ(M::hg(real(1.0000001), real(0.5)), M::hg(real(1), real(0.5)));
}

TYPED_TEST(OpticsTest, ShaftsPhaseNormalisedWithRatioTen) {
  using M = TypeParam;
  using real = typename M::real;
  const double tol = M::eps > 1e-10 ? 2e-6 : 1e-12;
  const ld rel_tol = M::eps > 1e-10 ? 1e-7L : 1e-13L;  // above float noise, or it never stops
  ld by_cos = integrate([](ld mu) { return 2 * kPi * ld(M::shaftsCos(real(mu))); }, -1, 1, rel_tol);
  EXPECT_NEAR(double(by_cos), 1.0, tol);
  ld by_angle = integrate([](ld a) { return 2 * kPi * ld(M::shafts(real(a))) * std::sin(a); }, 0,
                          kPi, rel_tol);
  EXPECT_NEAR(double(by_angle), 1.0, tol);
  // 001 eq. 4: forward 1 + 9 = 10 times the backward value.
  EXPECT_NEAR(M::shafts(real(0)) / M::shafts(real(kPi)), 10, 10 * 8 * M::eps);
  EXPECT_NEAR(M::shaftsCos(real(1)) / M::shaftsCos(real(-1)), 10, 10 * 8 * M::eps);
  EXPECT_NEAR(M::shaftsCos(real(-1)), 1 / (8 * kPi), 4 * M::eps / (8 * kPi));
  // The two forms agree.
  for (int i = 0; i <= 36; ++i) {
    ld a = i * kPi / 36;
    real fa = M::shafts(real(a)), fc = M::shaftsCos(real(std::cos(a)));
    EXPECT_NEAR(fa, fc, 32 * M::eps * fa) << "α=" << i * 5 << "°";
  }
}

// ---- Beer–Lambert and (e^x - 1)/x ------------------------------------------------------------------

TYPED_TEST(OpticsTest, BeerLambertLimits) {
  using M = TypeParam;
  using real = typename M::real;
  EXPECT_EQ(M::beer(real(0.5), real(0)), real(1));
  EXPECT_EQ(M::beer(real(0), real(1e4)), real(1));
  EXPECT_NEAR(M::beer(real(2), real(0.5)), std::exp(-1.0L), 2 * M::eps);
  // Deep/dense: c = 100 m⁻¹ over 10 km underflows to exactly 0, never NaN or negative.
  real deep = M::beer(real(100), real(1e4));
  EXPECT_EQ(deep, real(0));
  // Clear water at 0.01 m⁻¹ over 1 mm: 1 - 1e-5 to relative ε.
  EXPECT_NEAR(M::beer(real(0.01), real(1e-3)), std::exp(-1e-5L), 2 * M::eps);
  // Multiplicative over path segments.
  real a = M::beer(real(0.3), real(1.25)), b = M::beer(real(0.3), real(2.5));
  EXPECT_NEAR(M::beer(real(0.3), real(3.75)), ld(a) * b, 8 * M::eps * ld(a) * b);
}

TYPED_TEST(OpticsTest, Expm1OverXAgainstLongDouble) {
  using M = TypeParam;
  using real = typename M::real;
  // Stated bounds: 1e-6 relative in float (≈ 8 ulp), 1e-14 in double (≈ 45 ulp).
  const double rel = M::eps > 1e-10 ? 1e-6 : 1e-14;
  const bool is_float = M::eps > 1e-10;
  auto expect_close = [&](real x) {
    const ld xl = ld(x);
    const ld expect = xl == 0 ? 1.0L : std::expm1(xl) / xl;
    const real got = M::expm1x(x);
    ASSERT_TRUE(std::isfinite(got)) << "x=" << double(x);
    EXPECT_NEAR(got / expect, 1.0L, rel) << "x=" << double(x);
  };
  // 0, ±tiny (down to the smallest subnormal), both sides of the switch at |x| = 0.5, ±large up to
  // just below exp's overflow (88.7 in float, 709.8 in double) and far below it.
  const real tiny = std::numeric_limits<real>::denorm_min();
  const real big = is_float ? real(88.0) : real(709.0);
  for (real x : {real(0), tiny, -tiny, std::numeric_limits<real>::min(), real(1e-30), real(-1e-30), real(1e-8),
                 real(-1e-8), real(1e-3), real(-1e-3), real(1e-2), real(-0.25), real(0.4999), real(-0.4999),
                 real(0.5), real(-0.5), real(0.5001), real(-0.5001), real(-0.7), real(1), real(-1), real(20),
                 real(50), real(-50), big, -big, real(-1e4), real(-1e30), -std::numeric_limits<real>::max()}) {
    expect_close(x);
  }
  // A dense sweep over [-100, 100] (both branches, every binade of the series part).
  for (int i = -20000; i <= 20000; ++i) {
    const real x = real(i) * real(0.005);
    if (x <= big) expect_close(x);  // beyond, float overflows (checked below)
  }
  for (int e = -140; e <= 0; ++e) {  // geometric: 2^e for both signs, into float's subnormals
    expect_close(real(std::ldexp(1.0, e)));
    expect_close(real(-std::ldexp(1.0, e)));
  }
  // Continuous across the switch from the series to (e^x - 1)/x at |x| = 0.5.
  for (double s : {1.0, -1.0}) {
    real below = std::nextafter(real(s * 0.5), real(0)), at = real(s * 0.5);
    EXPECT_NEAR(M::expm1x(below), M::expm1x(at), 4 * M::eps);
  }
  // Overflow: finite exactly where the previous form expm1(x)/x (in the same precision) was finite,
  // +Inf (never NaN) beyond; x -> -Inf gives +0.
  const real x0 = is_float ? real(88.0) : real(709.0);
  for (int i = 0; i < 400; ++i) {
    const real x = x0 + real(i) * real(0.005);
    const real old = std::expm1(x) / x;
    const real got = M::expm1x(x);
    EXPECT_FALSE(std::isnan(got)) << "x=" << double(x);
    EXPECT_EQ(std::isfinite(got), std::isfinite(old)) << "x=" << double(x);
  }
  EXPECT_EQ(M::expm1x(-std::numeric_limits<real>::infinity()), real(0));
}

}  // namespace
