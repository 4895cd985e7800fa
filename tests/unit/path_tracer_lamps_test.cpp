// path_tracer_lamps_test.cpp — how the path tracer samples point lamps in the water
// (kernels/common/path_tracer_lamps.h) in float and double: the equiangular pdf is the density the
// sampler draws (and 0 outside its interval), the balance heuristic's weights sum to 1 and survive 0
// and +inf pdfs, the clipped interval holds every point the cone lights (also for a 0.1° cone), and
// the two strategies combined estimate the single-scattering integral of a hard-edged lamp along a
// segment as quadrature does, with less variance than the equiangular sample on the whole segment.
// Fixed seeds; Monte Carlo tolerances are 5 standard errors.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "math/kernel_math.h"

namespace {

namespace kd = seasim::kmath_d;
namespace kf = seasim::kmath_f;

template <typename Real>
struct Math;
template <>
struct Math<float> {
  using real = float;
  using vec = kf::real3;
  using Range = kf::PtLampRange;
  static vec make(double x, double y, double z) { return vec{float(x), float(y), float(z)}; }
  static real sample(real a, real r, real t0, real t1, real u, real* pdf) {
    return kf::pt_sample_equiangular(a, r, t0, t1, u, pdf);
  }
  static real pdf(real a, real r, real t0, real t1, real t) { return kf::pt_equiangular_pdf(a, r, t0, t1, t); }
  static real dpdf(real c, real t) { return kf::pt_distance_pdf(c, t); }
  static real balance(real p, real q) { return kf::pt_mis_balance(p, q); }
  static int range(vec o, vec d, real S, vec l, vec ax, real cc, real smin, int clip, Range* rg) {
    return kf::pt_lamp_range(o, d, S, l, ax, cc, smin, clip, rg);
  }
  static real profile(vec p, vec l, vec ax, real cc, real ci) { return kf::uw_lamp_profile(p, l, ax, cc, ci); }
  static real hg(real c, real g) { return kf::hg_phase(c, g); }
  static real uniform(unsigned key, unsigned dim) { return kf::pt_uniform(key, dim); }
  static real distance(real c, real u) { return kf::pt_sample_distance(c, u); }
  static real infinite() { return 1e30f; }
};
template <>
struct Math<double> {
  using real = double;
  using vec = kd::real3;
  using Range = kd::PtLampRange;
  static vec make(double x, double y, double z) { return vec{x, y, z}; }
  static real sample(real a, real r, real t0, real t1, real u, real* pdf) {
    return kd::pt_sample_equiangular(a, r, t0, t1, u, pdf);
  }
  static real pdf(real a, real r, real t0, real t1, real t) { return kd::pt_equiangular_pdf(a, r, t0, t1, t); }
  static real dpdf(real c, real t) { return kd::pt_distance_pdf(c, t); }
  static real balance(real p, real q) { return kd::pt_mis_balance(p, q); }
  static int range(vec o, vec d, real S, vec l, vec ax, real cc, real smin, int clip, Range* rg) {
    return kd::pt_lamp_range(o, d, S, l, ax, cc, smin, clip, rg);
  }
  static real profile(vec p, vec l, vec ax, real cc, real ci) { return kd::uw_lamp_profile(p, l, ax, cc, ci); }
  static real hg(real c, real g) { return kd::hg_phase(c, g); }
  static real uniform(unsigned key, unsigned dim) { return kd::pt_uniform(key, dim); }
  static real distance(real c, real u) { return kd::pt_sample_distance(c, u); }
  static real infinite() { return 1e30; }
};

template <typename Real>
class PathTracerLamps : public ::testing::Test {};
using Precisions = ::testing::Types<float, double>;
TYPED_TEST_SUITE(PathTracerLamps, Precisions);

TYPED_TEST(PathTracerLamps, EquiangularPdfIsTheSamplersDensity) {
  using M = Math<TypeParam>;
  using real = TypeParam;
  const double tol = sizeof(real) == 4 ? 2e-4 : 1e-12;  // float: t - a rounded where r is 1 mm
  for (double t1 : {0.8, 3.0, 40.0, 1e30}) {
    for (double r : {1e-3, 0.05, 2.0}) {
      const real a = real(1.5), t0 = real(0.2);
      for (double u : {0.0, 0.01, 0.37, 0.5, 0.93, 1.0 - std::ldexp(1.0, -24)}) {
        real p_sampled;
        const real t = M::sample(a, real(r), t0, real(t1), real(u), &p_sampled);
        const real p = M::pdf(a, real(r), t0, real(t1), t);
        ASSERT_TRUE(std::isfinite(double(p)) && p > 0) << t1 << " " << r << " " << u;
        EXPECT_NEAR(double(p) / double(p_sampled), 1.0, tol) << t1 << " " << r << " " << u;
      }
      // Outside [t0, t1] and on an empty interval: 0.
      EXPECT_EQ(M::pdf(a, real(r), t0, real(t1), real(0.1)), real(0));
      if (t1 < 1e29) EXPECT_EQ(M::pdf(a, real(r), t0, real(t1), real(t1 * 1.01)), real(0));
      EXPECT_EQ(M::pdf(a, real(r), real(2), real(2), real(2)), real(0));
    }
  }
  // The free-flight pdf: σ_t e^{-σ_t t}, 0 for σ_t = 0 and underflowing to 0, never NaN, far away.
  EXPECT_NEAR(double(M::dpdf(real(0.4), real(2.5))), 0.4 * std::exp(-1.0), 1e-6);
  EXPECT_EQ(M::dpdf(real(0), real(2.5)), real(0));
  EXPECT_EQ(M::dpdf(real(50), real(1e4)), real(0));
}

TYPED_TEST(PathTracerLamps, BalanceWeightsSumToOneAndSurviveZeroAndInfinity) {
  using M = Math<TypeParam>;
  using real = TypeParam;
  const real inf = std::numeric_limits<real>::infinity();
  for (double p : {1e-30, 1e-6, 0.3, 1.0, 7.0, 1e20}) {
    for (double q : {1e-30, 1e-6, 0.3, 1.0, 7.0, 1e20}) {
      const real w1 = M::balance(real(p), real(q)), w2 = M::balance(real(q), real(p));
      EXPECT_GE(w1, real(0));
      EXPECT_LE(w1, real(1));
      EXPECT_NEAR(double(w1) + double(w2), 1.0, 1e-6) << p << " " << q;
      EXPECT_NEAR(double(w1), p / (p + q), 1e-6 * (1 + p / (p + q))) << p << " " << q;
    }
  }
  EXPECT_EQ(M::balance(real(0), real(0)), real(0));
  EXPECT_EQ(M::balance(real(0), real(2)), real(0));
  EXPECT_EQ(M::balance(real(2), real(0)), real(1));
  EXPECT_EQ(M::balance(inf, real(2)), real(1));
  EXPECT_EQ(M::balance(real(2), inf), real(0));
}

// The clipped interval holds every point the lamp's cone lights on the segment (the profile is 0
// outside it), for cones of 0.1° to 60°, segments that cross the beam, start inside it, run along it
// and pass the lamp behind it; a segment that misses the cone has no range.
TYPED_TEST(PathTracerLamps, ClippedRangeHoldsEveryLitPoint) {
  using M = Math<TypeParam>;
  using real = TypeParam;
  using vec = typename M::vec;
  const vec lamp = M::make(0.3, -2.0, -1.0);
  const vec axis = M::make(0.0, -0.6, -0.8);
  struct Seg {
    vec o, d;
  };
  auto unit = [](double x, double y, double z) {
    const double n = std::sqrt(x * x + y * y + z * z);
    return M::make(x / n, y / n, z / n);
  };
  const Seg segs[] = {{M::make(-3, -3.5, -3), unit(1, 0.05, 0)},      // across the beam
                      {M::make(0.3, -2.6, -1.8), unit(0.2, 0.3, 1)},  // from inside the beam outwards
                      {M::make(0.3, -2.0, -1.0), unit(0, -0.6, -0.8)},  // from the lamp down its axis
                      {M::make(-2, -1.5, 1.0), unit(1, 0, 0)}};       // behind the lamp
  for (double cone_deg : {0.1, 10.0, 30.0, 60.0}) {
    const double cone = cone_deg * M_PI / 180;
    const real cc = real(std::cos(cone)), ci = real(std::cos(0.8 * cone));
    for (const Seg& s : segs) {
      for (double S : {2.5, 1e30}) {
        typename M::Range rg;
        const int any = M::range(s.o, s.d, real(S), lamp, axis, cc, real(0.01), 1, &rg);
        const double top = S > 1e29 ? 20.0 : S;
        for (int i = 0; i < 20000; ++i) {
          const double t = (i + 0.5) * top / 20000;
          const real pr = M::profile(s.o + real(t) * s.d, lamp, axis, cc, ci);
          if (!(pr > 0)) continue;
          ASSERT_TRUE(any) << cone_deg << " " << t;
          const double slack = 1e-4 * (1 + t);  // the cone's edge in float
          EXPECT_GE(t, double(rg.t0) - slack) << cone_deg << " S " << S;
          EXPECT_LE(t, double(rg.t1) + slack) << cone_deg << " S " << S;
        }
        if (any) {
          EXPECT_GE(rg.t0, real(0));
          EXPECT_LE(double(rg.t1), double(real(S)));
          EXPECT_GT(rg.r, real(0));
        }
        // Unclipped: all of [0, S).
        typename M::Range all;
        ASSERT_TRUE(M::range(s.o, s.d, real(S), lamp, axis, cc, real(0.01), 0, &all));
        EXPECT_EQ(all.t0, real(0));
        EXPECT_EQ(double(all.t1), double(real(S)));
      }
    }
  }
  // A segment that stays out of a narrow cone: no range.
  typename M::Range rg;
  EXPECT_FALSE(M::range(M::make(-3, 0.0 - 0.5, 3), unit(1, 0, 0), real(6), lamp, axis, real(std::cos(0.1)), real(0.01), 1, &rg));
}

// The segment integral of a hard-edged lamp, L = ∫_0^S e^{-c t} b p_HG(cos α) I P e^{-c s}/max(s, s_min)² dt,
// by the two strategies combined (what reference.cl sums: the equiangular sample in the cone and the
// free-flight vertex, balance-weighted) against midpoint quadrature in double; and the combination's
// variance against the equiangular sample on the whole segment (the plain estimator).
TYPED_TEST(PathTracerLamps, CombinedEstimateMatchesQuadratureWithLessVariance) {
  using M = Math<TypeParam>;
  using real = TypeParam;
  using vec = typename M::vec;
  const double b = 0.3, c = 0.4, g = 0.9, s_min = 0.02;
  const vec lamp = M::make(0.0, -2.0, 0.0);
  const double ax[3] = {0.3, -1.0, 0.2};
  const double an = std::sqrt(ax[0] * ax[0] + ax[1] * ax[1] + ax[2] * ax[2]);
  const vec axis = M::make(ax[0] / an, ax[1] / an, ax[2] / an);
  const double cone = 20.0 * M_PI / 180;
  const real cc = real(std::cos(cone)), ci = cc;  // hard edge
  // A segment from the bottom (4 m below the lamp) up and across the beam, and a long one beside it.
  struct Seg {
    vec o, d;
    double S;
  };
  auto unit = [](double x, double y, double z) {
    const double n = std::sqrt(x * x + y * y + z * z);
    return M::make(x / n, y / n, z / n);
  };
  const Seg segs[] = {{M::make(1.5, -6.0, 0.5), unit(-0.5, 1.0, -0.1), 6.0}, {M::make(-4.0, -4.0, -0.5), unit(1, 0.05, 0.1), 1e30}};
  for (const Seg& sg : segs) {
    auto f = [&](double t) {  // p I P e^{-c s}/s², I = 1, in double at the precision's point
      const vec x = sg.o + real(t) * sg.d;
      const real pr = M::profile(x, lamp, axis, cc, ci);
      if (!(pr > 0)) return 0.0;
      const vec q = x - lamp;
      const double s = std::sqrt(double(q.x) * q.x + double(q.y) * q.y + double(q.z) * q.z);
      const double cos_a = -(double(q.x) * sg.d.x + double(q.y) * sg.d.y + double(q.z) * sg.d.z) / s;  // (x - lamp)/s · -d
      const double sc = std::max(s, s_min);
      return double(M::hg(real(cos_a), real(g))) * double(pr) * std::exp(-c * s) / (sc * sc);
    };
    // Quadrature: midpoints on a fine grid over [0, min(S, 60)] (e^{-c t} < 4e-11 past 60 m).
    const double top = std::min(sg.S, 60.0);
    const int steps = 400000;
    double exact = 0;
    for (int i = 0; i < steps; ++i) {
      const double t = (i + 0.5) * top / steps;
      exact += std::exp(-c * t) * b * f(t);
    }
    exact *= top / steps;
    ASSERT_GT(exact, 0);
    const int n = 200000;
    std::vector<double> mis(n), plain(n);
    typename M::Range rg, all;
    const int has = M::range(sg.o, sg.d, real(sg.S), lamp, axis, cc, real(s_min), 1, &rg);
    ASSERT_TRUE(has);
    ASSERT_TRUE(M::range(sg.o, sg.d, real(sg.S), lamp, axis, cc, real(s_min), 0, &all));
    for (int i = 0; i < n; ++i) {
      const unsigned key = kd::pt_hash(unsigned(i) * 7919u + 13u);
      double est = 0;
      // Equiangular in the cone, balance-weighted against free flight.
      real pe;
      const real te = M::sample(rg.a, rg.r, rg.t0, rg.t1, M::uniform(key, 0), &pe);
      if (pe > 0) est += double(M::balance(pe, M::dpdf(real(c), te))) * std::exp(-c * te) * b * f(te) / pe;
      // The free-flight vertex (weight b/c), balance-weighted against equiangular.
      const real td = M::distance(real(c), M::uniform(key, 1));
      if (double(td) < sg.S) {
        const real pe_d = M::pdf(rg.a, rg.r, rg.t0, rg.t1, td);
        est += double(M::balance(M::dpdf(real(c), td), pe_d)) * b / c * f(td);
      }
      mis[i] = est;
      // The plain estimator: equiangular on the whole segment.
      real pa;
      const real ta = M::sample(all.a, all.r, all.t0, all.t1, M::uniform(key, 0), &pa);
      plain[i] = pa > 0 ? std::exp(-c * ta) * b * f(ta) / pa : 0.0;
    }
    auto meanVar = [](const std::vector<double>& x, double* var) {
      double m = 0;
      for (double v : x) m += v;
      m /= x.size();
      double s2 = 0;
      for (double v : x) s2 += (v - m) * (v - m);
      *var = s2 / (x.size() - 1);
      return m;
    };
    double v_mis, v_plain;
    const double m_mis = meanVar(mis, &v_mis), m_plain = meanVar(plain, &v_plain);
    const double fl = sizeof(real) == 4 ? 1e-4 * exact : 0.0;  // float positions
    EXPECT_NEAR(m_mis, exact, 5 * std::sqrt(v_mis / n) + fl) << "S " << sg.S;
    EXPECT_NEAR(m_plain, exact, 5 * std::sqrt(v_plain / n) + fl) << "S " << sg.S;
    std::printf("segment S = %g: exact %.6g, combined %.6g (var %.3g), plain equiangular %.6g (var %.3g): "
                "variance ratio %.3g\n",
                sg.S, exact, m_mis, v_mis, m_plain, v_plain, v_plain / v_mis);
    EXPECT_LT(v_mis, v_plain) << "S " << sg.S;
  }
}

}  // namespace
