// shafts_math_test.cpp — the CPU side of the shafts model (paper 001): the closed-form airlight of
// Sun et al. 2005 against direct quadrature of the single-scattering integral it solves, F(u, v)
// at its limits, the shared math of kernels/common/shafts.h in float and double at the stiff
// points (s -> 0, ρκ large), the ray-object intersections, the ray's part inside a cone, the
// far-field closed form against quadrature to infinity, and the h-table's range.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "math/kernel_math.h"
#include "reference/shafts_reference.h"
#include "scene/scene_parser.h"
#include "util/error.h"

namespace {

namespace kd = seasim::kmath_d;
namespace kf = seasim::kmath_f;

// ∫_0^T σs I0/(4π) exp(-σt (x + d(x))) / d(x)² dx, d² = D² + x² - 2 D x cos γ, by composite
// Gauss–Legendre (5 points) on many panels, denser near the closest approach x = D cos γ.
double airlightByQuadrature(double ss, double st, double I0, double D, double gamma, double T) {
  const double xg[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831, 0.9061798459386640};
  const double wg[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665,
                        0.2369268850561891};
  auto f = [&](double x) {
    const double d2 = D * D + x * x - 2 * D * x * std::cos(gamma);
    return ss * I0 / (4 * M_PI) * std::exp(-st * (x + std::sqrt(d2))) / d2;
  };
  // Panels uniform in the angle seen from the light (the substitution that makes 1/d² smooth).
  const double h = D * std::sin(gamma), x0 = D * std::cos(gamma);
  const double a0 = std::atan((0 - x0) / h), a1 = std::atan((T - x0) / h);
  const int panels = 4000;
  double sum = 0;
  for (int p = 0; p < panels; ++p) {
    const double lo = a0 + (a1 - a0) * p / panels, hi = a0 + (a1 - a0) * (p + 1) / panels;
    for (int k = 0; k < 5; ++k) {
      const double a = 0.5 * (lo + hi) + 0.5 * (hi - lo) * xg[k];
      const double x = x0 + h * std::tan(a), dxda = h / (std::cos(a) * std::cos(a));
      sum += 0.5 * (hi - lo) * wg[k] * f(x) * dxda;
    }
  }
  return sum;
}

TEST(ShaftsAirlight, SunClosedFormMatchesQuadrature) {
  // Tolerance 1e-9 relative: both are double quadratures of smooth integrands.
  for (double st : {0.0, 0.02, 0.3, 2.0})
    for (double gamma : {0.05, 0.4, 1.2, 2.0, 3.0})
      for (double T : {0.5, 4.0, 30.0}) {
        const double D = 5.0, ss = 0.1, I0 = 50;
        const double closed = seasim::sunAirlight(ss, st, I0, D, gamma, T);
        const double quad = airlightByQuadrature(ss, st, I0, D, gamma, T);
        EXPECT_NEAR(closed, quad, 1e-9 * quad + 1e-300) << "st=" << st << " gamma=" << gamma << " T=" << T;
      }
}

TEST(ShaftsAirlight, FAtItsLimits) {
  EXPECT_DOUBLE_EQ(seasim::sunF(0.0, 1.0), 1.0);          // u = 0: ∫ dξ = v
  EXPECT_DOUBLE_EQ(seasim::sunF(3.0, 0.0), 0.0);
  EXPECT_NEAR(seasim::sunF(1.0, M_PI / 2), seasim::sunF(1.0, M_PI / 2 - 1e-12), 1e-9);  // integrable end
  EXPECT_LT(seasim::sunF(50.0, 1.0), 1.0 / 50 * 1.01);    // ≈ 1/u for large u
  EXPECT_GT(seasim::sunF(50.0, 1.0), 1.0 / 50 * 0.95);
}

TEST(ShaftsMath, HIsFiniteAtTheLampAndUnderExtremeExtinction) {
  // s -> 0: clamped at s_min, finite in float and double; ρκ (s + t) huge: exactly 0, not NaN.
  EXPECT_TRUE(std::isfinite(kf::shafts_h(0.0f, 1.0f, 1.0f, 0.05f, 1e-3f)));
  EXPECT_FLOAT_EQ(kf::shafts_h(0.0f, 0.0f, 1.0f, 0.0f, 1e-3f), 1e6f);
  EXPECT_EQ(kf::shafts_h(1.0f, 1e3f, 1.0f, 1e3f, 1e-3f), 0.0f);
  EXPECT_EQ(kd::shafts_h(1.0, 1e308, 1.0, 1e3, 1e-3), 0.0);
  EXPECT_DOUBLE_EQ(kd::shafts_h(2.0, 3.0, 0.5, 0.0, 1e-3), 0.5 / 4);  // ρκ = 0: no attenuation
  // h = ĥ / s², the table's smooth factor.
  EXPECT_NEAR(kd::shafts_h(2.0, 3.0, 0.5, 0.1, 1e-3), kd::shafts_h_scaled(2.0, 3.0, 0.5, 0.1) / 4, 1e-15);
}

TEST(ShaftsMath, ConeProfileIsAMonotoneSmoothEdge) {
  const double cone = 0.4, inner = 0.3;
  double prev = 1.0;
  for (int i = 0; i <= 100; ++i) {
    const double a = 0.5 * i / 100;
    const double p = kd::shafts_cone_profile(std::cos(a), std::cos(cone), std::cos(inner));
    EXPECT_LE(p, prev + 1e-15);
    EXPECT_GE(p, 0.0);
    EXPECT_LE(p, 1.0);
    if (a <= inner) EXPECT_EQ(p, 1.0);
    if (a >= cone) EXPECT_EQ(p, 0.0);
    prev = p;
  }
  // Zero falloff: a hard edge.
  EXPECT_EQ(kd::shafts_cone_profile(std::cos(0.39), std::cos(0.4), std::cos(0.4)), 1.0);
  EXPECT_EQ(kd::shafts_cone_profile(std::cos(0.41), std::cos(0.4), std::cos(0.4)), 0.0);
}

TEST(ShaftsMath, RayIntersections) {
  const kd::real3 o{0, 0, 0}, d{0, 0, -1};
  EXPECT_NEAR(kd::ray_sphere(o, d, kd::real3{0, 0, -5}, 1.0, 0.0, 1e30), 4.0, 1e-12);
  EXPECT_NEAR(kd::ray_sphere(kd::real3{0, 0, -5}, d, kd::real3{0, 0, -5}, 1.0, 0.0, 1e30), 1.0, 1e-12);  // inside
  EXPECT_LT(kd::ray_sphere(o, d, kd::real3{0, 3, -5}, 1.0, 0.0, 1e30), 0.0);
  EXPECT_LT(kd::ray_sphere(o, d, kd::real3{0, 0, -5}, 1.0, 0.0, 3.5), 0.0);  // beyond t_max
  int axis = -1;
  EXPECT_NEAR(kd::ray_box(o, d, kd::real3{-1, -1, -4}, kd::real3{1, 1, -2}, 0.0, 1e30, &axis), 2.0, 1e-12);
  EXPECT_EQ(axis, 2);
  const kd::real3 n = kd::box_normal(kd::real3{0, 0, -2}, kd::real3{-1, -1, -4}, kd::real3{1, 1, -2}, 2);
  EXPECT_EQ(n.z, 1.0);
  EXPECT_NEAR(kd::ray_plane(o, d, kd::real3{0, 0, -7}, kd::real3{0, 0, 1}, 0.0, 1e30), 7.0, 1e-12);
  EXPECT_LT(kd::ray_plane(o, kd::real3{1, 0, 0}, kd::real3{0, 0, -7}, kd::real3{0, 0, 1}, 0.0, 1e30), 0.0);  // parallel
}

// shafts_cone_interval against a brute-force walk along the ray testing "inside the cone" point by point,
// over random rays (camera inside and outside, lamps ahead and behind, cones up to 90°), in double and
// float: the interval's ends lie where the point test flips.
TEST(ShaftsMath, ConeIntervalMatchesAPointByPointWalk) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int hits = 0, unbounded = 0, cases = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const kd::real3 o{3 * u(rng), 3 * u(rng), 3 * u(rng)}, lamp{3 * u(rng), 3 * u(rng), 3 * u(rng)};
    const kd::real3 d = kd::normalize(kd::real3{u(rng), u(rng), u(rng)});
    const kd::real3 axis = kd::normalize(kd::real3{u(rng), u(rng), u(rng)});
    const double cone = trial % 10 == 0 ? M_PI / 2 : 0.05 + 1.4 * (0.5 + 0.5 * u(rng));
    const double c = std::cos(cone);
    auto inside = [&](double t) {
      const kd::real3 q = o + t * d - lamp;
      return kd::dot(q, axis) > c * kd::length(q) && kd::dot(q, axis) > 0;
    };
    double t0 = 0, t1 = 0;
    const int any = kd::shafts_cone_interval(o, d, lamp, axis, c, &t0, &t1);
    ++cases;
    // Walk [0, 60] in 6000 steps (the far end stands for infinity: every cone crossing of these rays
    // lies within 30 m of the origin unless the ray runs nearly along the cone's surface).
    int flips = 0;
    bool prev = inside(0.0);
    double first = prev ? 0.0 : -1, last = prev ? 0.0 : -1;
    for (int i = 1; i <= 6000; ++i) {
      const double t = 0.01 * i;
      const bool in = inside(t);
      if (in != prev) ++flips;
      if (in && first < 0) first = t;
      if (in) last = t;
      prev = in;
    }
    ASSERT_LE(flips, 2) << "a convex cone meets a ray in one interval";
    if (first < 0) {
      // Only a sliver the walk can miss, or nothing.
      if (any) EXPECT_LT(std::min(t1, 60.0) - t0, 0.02) << "trial " << trial;
      continue;
    }
    ASSERT_TRUE(any) << "trial " << trial;
    ++hits;
    EXPECT_NEAR(t0, first, 0.011) << "trial " << trial;
    if (last >= 60.0) {
      if (t1 < SHAFTS_T_INF) EXPECT_GT(t1, 59.99) << "trial " << trial;
      else ++unbounded;
    } else {
      EXPECT_NEAR(t1, last, 0.011) << "trial " << trial;
    }
    // Float agrees with double (the kernel's precision) at the ends, relative to the ray's scale.
    float f0 = 0, f1 = 0;
    const auto f3 = [](kd::real3 v) { return kf::real3{float(v.x), float(v.y), float(v.z)}; };
    ASSERT_TRUE(kf::shafts_cone_interval(f3(o), f3(d), f3(lamp), f3(axis), float(c), &f0, &f1) || t1 - t0 < 1e-3);
    EXPECT_NEAR(f0, t0, 1e-3 * (1 + t0)) << "trial " << trial;
  }
  std::printf("[ measured ] %d rays, %d meet the cone, %d never leave it\n", cases, hits, unbounded);
  EXPECT_GT(hits, 500);
  EXPECT_GT(unbounded, 100);
}

TEST(ShaftsMath, ConeIntervalSpecialCases) {
  double t0 = 0, t1 = 0;
  // Camera on the axis inside the cone, looking along it: [0, ∞).
  ASSERT_TRUE(kd::shafts_cone_interval(kd::real3{0, 0, 2}, kd::real3{0, 0, 1}, kd::real3{0, 0, 0},
                                       kd::real3{0, 0, 1}, std::cos(0.3), &t0, &t1));
  EXPECT_EQ(t0, 0.0);
  EXPECT_EQ(t1, SHAFTS_T_INF);
  // Looking back at the lamp along the axis: [0, 2] (up to the apex).
  ASSERT_TRUE(kd::shafts_cone_interval(kd::real3{0, 0, 2}, kd::real3{0, 0, -1}, kd::real3{0, 0, 0},
                                       kd::real3{0, 0, 1}, std::cos(0.3), &t0, &t1));
  EXPECT_EQ(t0, 0.0);
  EXPECT_NEAR(t1, 2.0, 1e-12);
  // Behind the lamp looking away: nothing.
  EXPECT_FALSE(kd::shafts_cone_interval(kd::real3{0, 0, -1}, kd::real3{0, 0, -1}, kd::real3{0, 0, 0},
                                        kd::real3{0, 0, 1}, std::cos(0.3), &t0, &t1));
  // A 90° cone (a half-space) crossed side-on at x = 0: [1, ∞).
  ASSERT_TRUE(kd::shafts_cone_interval(kd::real3{-1, 0, 5}, kd::real3{1, 0, 0}, kd::real3{0, 0, 0},
                                       kd::real3{1, 0, 0}, std::cos(M_PI / 2), &t0, &t1));
  EXPECT_NEAR(t0, 1.0, 1e-12);
  EXPECT_EQ(t1, SHAFTS_T_INF);
}

// e^z E_n(z) against direct quadrature of its integral, and the far field against quadrature of
// 001 eq. 2's attenuation factor to infinity (t = a + h tan φ maps [t_c, ∞) onto [φ_c, π/2)).
TEST(ShaftsMath, ScaledExponentialIntegralMatchesQuadrature) {
  for (int n : {2, 4})
    for (double z : {1e-8, 1e-4, 0.01, 0.5, 0.999, 1.0, 1.001, 3.0, 30.0, 1e3, 1e6}) {
      double expected = 0;
      if (z < 1e-3) {
        // E_1(z) = -γ - ln z + z - z²/4 (A&S 5.1.11), E_{k+1} = (e^{-z} - z E_k)/k (5.1.14), times e^z.
        const double e1 = -0.57721566490153286 - std::log(z) + z - z * z / 4 + z * z * z / 18;
        double en = e1;
        for (int k = 1; k < n; ++k) en = (std::exp(-z) - z * en) / k;
        expected = std::exp(z) * en;
      } else if (z < 100) {
        // e^z E_n(z) = ∫_0^∞ e^{-z v} (1 + v)^{-n} dv = ∫_0^1 e^{-z(1/y - 1)} y^{n-2} dy (y = 1/(1+v)).
        const int N = 200000;
        for (int i = 0; i < N; ++i) {
          const double y = (i + 0.5) / N;
          expected += std::exp(-z * (1 / y - 1)) * std::pow(y, n - 2) / N;
        }
      } else {
        // Asymptotic series (A&S 5.1.51): (1/z)(1 - n/z + n(n+1)/z² - n(n+1)(n+2)/z³), error ~ 1e-13 here.
        expected = (1 - n / z + n * (n + 1) / (z * z) - n * (n + 1) * (n + 2) / (z * z * z)) / z;
      }
      const double d = kd::shafts_expint_scaled(n, z);
      EXPECT_NEAR(d, expected, 1e-8 * expected) << "n=" << n << " z=" << z;
      const float f = kf::shafts_expint_scaled(n, float(z));
      EXPECT_NEAR(f, expected, 3e-6 * expected) << "float n=" << n << " z=" << z;
    }
  EXPECT_EQ(kd::shafts_expint_scaled(2, 0.0), 1.0);  // E_n(0) = 1/(n - 1)
  EXPECT_DOUBLE_EQ(kd::shafts_expint_scaled(4, 0.0), 1.0 / 3);
}

TEST(ShaftsMath, FarFieldTailMatchesQuadratureToInfinity) {
  const double rho = 0.1;
  double worst_d = 0, worst_f = 0;
  for (double sigma : {0.0, 0.01, 0.3, 3.0})
    for (double h : {1e-3, 0.2, 2.0})
      for (double a : {-5.0, 0.0, 4.0})
        for (double xk : {8.0, 20.0, 200.0}) {
          const double x = xk * h;
          const double phi_c = std::atan(x / h);
          const int N = 400000;
          double quad = 0;
          for (int i = 0; i < N; ++i) {
            const double phi = phi_c + (i + 0.5) * (M_PI / 2 - phi_c) / N;
            const double xx = h * std::tan(phi), s = h / std::cos(phi);
            // ρ e^{-σ(s+t)} / s² dt, dt = h sec²φ dφ = s²/h dφ
            quad += rho * std::exp(-sigma * (s + a + xx)) / h * (M_PI / 2 - phi_c) / N;
          }
          const double d = kd::shafts_tail_from(x, a, h, rho, sigma);
          const float f = kf::shafts_tail_from(float(x), float(a), float(h), float(rho), float(sigma));
          if (quad < 1e-250) continue;
          worst_d = std::max(worst_d, std::fabs(d - quad) / quad);
          if (quad > 1e-30) worst_f = std::max(worst_f, std::fabs(f - quad) / quad);
          EXPECT_TRUE(std::isfinite(f));
        }
  std::printf("[ measured ] far field vs quadrature: max relative error %.2g (double), %.2g (float)\n", worst_d,
              worst_f);
  EXPECT_LT(worst_d, 2e-5);  // the dropped h⁴/w⁶ term: ≤ (1/2K)⁴ = 1.5e-5
  EXPECT_LT(worst_f, 1e-4);
}

TEST(ShaftsTableRange, CoversThePlanesUpToTheBackWallOfSpotSphere) {
  const seasim::Scene scene = seasim::loadScene(std::string(SEASIM_SOURCE_DIR) + "/scenes/spot_sphere.toml");
  const seasim::ShaftsRange r = seasim::shaftsTableRange(scene);
  // Camera at z = 9 looking down -z at a wall at z = -6: no plane lies beyond the wall's corners.
  EXPECT_GT(r.t_max, 1.0);
  EXPECT_LT(r.t_max, 15.0 / std::cos(std::atan(std::tan(scene.camera.fov_y / 2) *
                                               std::hypot(1.0, double(scene.camera.width) / scene.camera.height))) *
                         1.02);
  EXPECT_GT(r.s_max, 1.0);
}

TEST(ShaftsRange, HeightFieldObjectsWithSpotlightsAreAnErrorNamingFileLineAndKey) {
  const seasim::Scene scene = seasim::parseScene(R"([air]
density = 0.04
[[spotlights]]
position = [0, 5, -1]
[[objects]]
type = "sphere"
[[objects]]
type = "heightfield"
heightfield = "textures/polka_dot.png"
)",
                                                 std::string(SEASIM_SOURCE_DIR) + "/scenes/hf_spot.toml");
  for (int which = 0; which < 2; ++which) {
    try {
      if (which == 0) (void)seasim::shaftsTableRange(scene);
      else (void)seasim::renderShaftsReference(scene, 4);
      ADD_FAILURE() << "no error";
    } catch (const seasim::InputError& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find("hf_spot.toml:7: key 'objects[1].type': \"heightfield\" objects are not supported"),
                std::string::npos)
          << m;
    }
  }
}

}  // namespace
