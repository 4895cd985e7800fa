// shafts_intervals_test.cpp — the math of the "intervals" shafts method (kernels/common/shafts_intervals.h)
// on the CPU, in float and double:
//  * each object's shadow interval against exact shadow rays point by point along random rays
//    (spheres, boxes, planes; lamps beside, above and inside objects);
//  * removing shadow intervals from the lit stretches;
//  * the integral over the lit stretches against the closed-form airlight of an isotropic point light
//    (Sun et al. 2005; two back-to-back 90° lamps make one isotropic lamp), to infinity and to a wall;
//  * finite, non-negative values at the stiff points: rays through the lamp, grazing a cone's
//    surface, ρκ = 0 and large, stretches reaching φ = π/2.
#include <gtest/gtest.h>

#include <ostream>

#include <cmath>
#include <cstdio>
#include <random>

#include "math/kernel_math.h"
#include "reference/shafts_reference.h"

namespace {

namespace kd = seasim::kmath_d;
namespace kf = seasim::kmath_f;

kf::real3 f3(kd::real3 v) { return kf::real3{float(v.x), float(v.y), float(v.z)}; }

// Exact shadow ray from p towards the lamp: blocked by the object in (0, |lamp - p|)?
enum class Kind { Sphere, Box, Plane };
struct Obj {
  Kind kind;
  kd::real3 a, b;  // sphere: centre, (radius, -, -); box: min, max; plane: point, normal
};

bool blocked(const Obj& o, kd::real3 p, kd::real3 lamp) {
  const kd::real3 w = lamp - p;
  const double s = kd::length(w);
  const kd::real3 dir = w / s;
  int axis = 0;
  switch (o.kind) {
    case Kind::Sphere: return kd::ray_sphere(p, dir, o.a, o.b.x, 0.0, s) > 0;
    case Kind::Box: return kd::ray_box(p, dir, o.a, o.b, 0.0, s, &axis) > 0;
    case Kind::Plane: return kd::ray_plane(p, dir, o.a, o.b, 0.0, s) > 0;
  }
  return false;
}

bool insideObject(const Obj& o, kd::real3 p) {
  if (o.kind == Kind::Sphere) return kd::length(p - o.a) < o.b.x;
  if (o.kind == Kind::Box)
    return p.x > o.a.x && p.x < o.b.x && p.y > o.a.y && p.y < o.b.y && p.z > o.a.z && p.z < o.b.z;
  return false;
}

kd::ShaftsShadowVolume volumeD(const Obj& o, kd::real3 lamp) {
  if (o.kind == Kind::Sphere) return kd::shafts_sphere_shadow(lamp, o.a, o.b.x);
  if (o.kind == Kind::Box) return kd::shafts_box_shadow(lamp, o.a, o.b);
  return kd::shafts_plane_shadow(lamp, o.a, o.b);
}
kf::ShaftsShadowVolume volumeF(const Obj& o, kd::real3 lamp) {
  if (o.kind == Kind::Sphere) return kf::shafts_sphere_shadow(f3(lamp), f3(o.a), float(o.b.x));
  if (o.kind == Kind::Box) return kf::shafts_box_shadow(f3(lamp), f3(o.a), f3(o.b));
  return kf::shafts_plane_shadow(f3(lamp), f3(o.a), f3(o.b));
}

Obj randomObject(std::mt19937& rng, int kind) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  if (kind == 0) return {Kind::Sphere, {2 * u(rng), 2 * u(rng), 2 * u(rng)}, {0.3 + 0.35 * (1 + u(rng)), 0, 0}};
  if (kind == 1) {
    const kd::real3 c{2 * u(rng), 2 * u(rng), 2 * u(rng)};
    const kd::real3 e{0.2 + 0.4 * (1 + u(rng)), 0.2 + 0.4 * (1 + u(rng)), 0.2 + 0.4 * (1 + u(rng))};
    return {Kind::Box, c - e, c + e};
  }
  return {Kind::Plane, {2 * u(rng), 2 * u(rng), 2 * u(rng)}, kd::normalize(kd::real3{u(rng), u(rng), u(rng)})};
}

// Walks [0, 40] along random rays: "inside the shadow interval" must be "an exact shadow ray is
// blocked" at every step away from the interval's ends and outside the object (the sphere's volume
// is cut at its silhouette plane, which differs from the shadow only inside the sphere).
TEST(ShaftsIntervals, ShadowIntervalsAreExactShadowRays) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int rays = 0, shadowed = 0, lit = 0, lamps_inside = 0, mismatches = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const int kind = trial % 3;
    const Obj o = randomObject(rng, kind);
    kd::real3 lamp{4 * u(rng), 4 * u(rng), 4 * u(rng)};
    // Every 7th box lamp straight above its top face (only one front face, four silhouette edges).
    if (kind == 1 && trial % 7 == 0) lamp = kd::real3{0.5 * (o.a.x + o.b.x), o.b.y + 2.0, 0.5 * (o.a.z + o.b.z)};
    const kd::real3 eye{6 * u(rng), 6 * u(rng), 6 * u(rng)};
    const kd::real3 d = kd::normalize(kd::real3{u(rng), u(rng), u(rng)});
    const kd::ShaftsShadowVolume vol = volumeD(o, lamp);
    if (vol.always > 0) ++lamps_inside;
    double lo = 0, hi = 0;
    const int any = kd::shafts_shadow_interval(vol, eye, d, &lo, &hi);
    ++rays;
    for (int i = 0; i <= 4000; ++i) {
      const double t = 0.01 * i;
      if (any && (std::fabs(t - lo) < 1e-6 * (1 + std::fabs(lo)) || std::fabs(t - hi) < 1e-6 * (1 + std::fabs(hi))))
        continue;
      const kd::real3 p = eye + t * d;
      if (insideObject(o, p) || kd::length(p - lamp) < 1e-9) continue;
      const bool in = any && t > lo && t < hi;
      const bool exact = blocked(o, p, lamp);
      if (in != exact) ++mismatches;
      (exact ? shadowed : lit) += 1;
    }
    // The packed form the kernel reads (float planes, narrowing the caller's range) gives the same.
    float packed[SHAFTS_OCC_PLANES][4];
    for (int k = 0; k < vol.plane_count; ++k) {
      packed[k][0] = float(vol.n[k].x);
      packed[k][1] = float(vol.n[k].y);
      packed[k][2] = float(vol.n[k].z);
      packed[k][3] = float(vol.b[k]);
    }
    double plo = 0, phi = 30;  // a lit range [0, 30]
    const int pany = kd::shafts_shadow_interval_packed(packed, vol.plane_count, vol.has_cone, vol.always, vol.apex,
                                                       vol.axis, vol.cos_cone, eye, d, &plo, &phi);
    const double clo = std::max(lo, 0.0), chi = std::min(hi, 30.0);
    if (any && chi - clo > 1e-3) {
      ASSERT_TRUE(pany) << "trial " << trial;
      EXPECT_NEAR(plo, clo, 1e-4 * (10 + std::fabs(clo))) << "trial " << trial;
      EXPECT_NEAR(phi, chi, 1e-4 * (10 + std::fabs(chi))) << "trial " << trial;
    } else if (!any || chi < clo - 1e-3) {
      EXPECT_FALSE(pany && phi - plo > 1e-3) << "trial " << trial;
    }
    // Float (the kernel's precision) agrees with double at the ends, relative to the scene's scale.
    float flo = 0, fhi = 0;
    const int fany = kf::shafts_shadow_interval(volumeF(o, lamp), f3(eye), f3(d), &flo, &fhi);
    if (any && hi - lo > 1e-2 && std::fabs(lo) < 1e3 && std::fabs(hi) < 1e3) {
      ASSERT_TRUE(fany) << "trial " << trial;
      EXPECT_NEAR(flo, lo, 2e-4 * (10 + std::fabs(lo))) << "trial " << trial;
      EXPECT_NEAR(fhi, hi, 2e-4 * (10 + std::fabs(hi))) << "trial " << trial;
    }
  }
  std::printf("[ measured ] %d rays, %d shadowed and %d lit steps, %d lamps inside their object, %d mismatches\n",
              rays, shadowed, lit, lamps_inside, mismatches);
  EXPECT_EQ(mismatches, 0);
  EXPECT_GT(shadowed, 100000);
  EXPECT_GT(lamps_inside, 4);
}

TEST(ShaftsIntervals, LampOnAPlaneCastsNoShadowAndLampInsideABoxShadowsEverything) {
  const kd::ShaftsShadowVolume on = kd::shafts_plane_shadow({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  double lo = 0, hi = 0;
  EXPECT_FALSE(kd::shafts_shadow_interval(on, {0, -1, 0}, {0, 1, 0}, &lo, &hi));
  const kd::ShaftsShadowVolume in = kd::shafts_box_shadow({0, 0, 0}, {-1, -1, -1}, {1, 1, 1});
  EXPECT_TRUE(kd::shafts_shadow_interval(in, {5, 5, 5}, {0, 1, 0}, &lo, &hi));
  EXPECT_LE(lo, 0);
  EXPECT_GE(hi, SHAFTS_T_INF);
}

TEST(ShaftsIntervals, SubtractingShadowsSplitsAndTrimsStretches) {
  double lo[SHAFTS_MAX_PIECES] = {0, 5}, hi[SHAFTS_MAX_PIECES] = {3, 9};
  int n = kd::shafts_pieces_subtract(lo, hi, 2, 1, 2);  // splits the first
  ASSERT_EQ(n, 3);
  EXPECT_EQ(lo[0], 0);
  EXPECT_EQ(hi[0], 1);
  EXPECT_EQ(lo[1], 2);
  EXPECT_EQ(hi[1], 3);
  n = kd::shafts_pieces_subtract(lo, hi, n, 2.5, 6);  // trims two
  ASSERT_EQ(n, 3);
  EXPECT_EQ(hi[1], 2.5);
  EXPECT_EQ(lo[2], 6);
  n = kd::shafts_pieces_subtract(lo, hi, n, -1, 100);  // removes all
  EXPECT_EQ(n, 0);
  n = kd::shafts_pieces_subtract(lo, hi, n, 1, 0);  // empty shadow: nothing changes
  EXPECT_EQ(n, 0);
}

// Sum over the two back-to-back 90° lamps at `lamp` of the intervals integral over the whole ray
// [0, T] (no objects): an isotropic point lamp of intensity 1 with phase 1/4π (HG, g = 0).
template <class real, class real3, class Lamp, class Fn>
double isotropicIntervals(real3 eye, real3 d, real3 lamp, double rho, double sigma_t, double T, double panel_deg,
                          Fn&& kernel) {
  double total = 0;
  for (int side = 0; side < 2; ++side) {
    Lamp L{};
    L.pos = lamp;
    L.axis = real3{0, 0, real(side ? -1 : 1)};
    L.right = real3{1, 0, 0};
    L.up = real3{0, real(side ? -1 : 1), 0};
    L.cos_cone = 0;
    L.cos_inner = 0;
    L.tan_cone = 1e6;
    L.map_w = L.map_h = 0;
    total += kernel(L, T, panel_deg);
  }
  return total;
}

struct SunCase {
  double lamp[3];
  double sigma_t;
  double T;  // ray length; infinity: no wall
};
// The case as gtest prints it (its name, not the struct's bytes).
void PrintTo(const SunCase& c, std::ostream* os) { *os << "lamp (" << c.lamp[0] << ", " << c.lamp[1] << ", " << c.lamp[2] << "), sigma_t " << c.sigma_t << ", ray " << c.T << " m"; }

class ShaftsIntervalsVsSun : public ::testing::TestWithParam<SunCase> {};

TEST_P(ShaftsIntervalsVsSun, MatchesTheClosedFormInFloatAndDouble) {
  const SunCase c = GetParam();
  const double rho = 0.1;
  const kd::real3 eye{0, 0, 0}, d{0, 0, -1}, lamp{c.lamp[0], c.lamp[1], c.lamp[2]};
  const double dist = kd::length(lamp - eye), gamma = std::acos(kd::dot(lamp - eye, d) / dist);
  const double exact = seasim::sunAirlight(rho, c.sigma_t, 1.0, dist, gamma, c.T);
  auto run = [&](auto tag, double panel_deg) {
    using K = decltype(tag);
    using real = typename K::real;
    using real3 = typename K::real3;
    using Lamp = typename K::Lamp;
    auto one = [&](const Lamp& L, double T, double pd) {
      const real3 o{real(eye.x), real(eye.y), real(eye.z)}, dir{real(d.x), real(d.y), real(d.z)};
      real lo[SHAFTS_MAX_PIECES], hi[SHAFTS_MAX_PIECES];
      if (!K::cone(o, dir, L.pos, L.axis, L.cos_cone, &lo[0], &hi[0])) return 0.0;
      hi[0] = std::isinf(T) ? hi[0] : std::min(hi[0], real(T));
      if (!(hi[0] > lo[0])) return 0.0;
      const real3 e = K::airlight(lo, hi, 1, 0, real(0), real(0), o, dir, L, nullptr, real(rho), real(c.sigma_t),
                                  real(0.02), 1, real(0), real(pd * M_PI / 180), real(1));
      EXPECT_TRUE(std::isfinite(e.x));
      return double(e.x);
    };
    const real3 lp{real(lamp.x), real(lamp.y), real(lamp.z)};
    return isotropicIntervals<real, real3, Lamp>(real3{0, 0, 0}, real3{0, 0, -1}, lp, rho, c.sigma_t, c.T, panel_deg,
                                                 one);
  };
  struct DoubleK {
    using real = double;
    using real3 = kd::real3;
    using Lamp = kd::ShaftsLamp;
    static int cone(real3 o, real3 dd, real3 l, real3 ax, real cc, real* a, real* b) {
      return kd::shafts_cone_interval(o, dd, l, ax, cc, a, b);
    }
    static real3 airlight(const real* lo, const real* hi, int n, int hi_, real t0, real t1, real3 o, real3 dd,
                          Lamp L, const float* map, real rho_, real st, real smin, int hg, real g, real pr, real mt) {
      return kd::shafts_interval_airlight(lo, hi, n, hi_, t0, t1, o, dd, L, map, rho_, st, smin, hg, g, pr, mt);
    }
  };
  struct FloatK {
    using real = float;
    using real3 = kf::real3;
    using Lamp = kf::ShaftsLamp;
    static int cone(real3 o, real3 dd, real3 l, real3 ax, real cc, real* a, real* b) {
      return kf::shafts_cone_interval(o, dd, l, ax, cc, a, b);
    }
    static real3 airlight(const real* lo, const real* hi, int n, int hi_, real t0, real t1, real3 o, real3 dd,
                          Lamp L, const float* map, real rho_, real st, real smin, int hg, real g, real pr, real mt) {
      return kf::shafts_interval_airlight(lo, hi, n, hi_, t0, t1, o, dd, L, map, rho_, st, smin, hg, g, pr, mt);
    }
  };
  const double d4 = run(DoubleK{}, 4.0), d1 = run(DoubleK{}, 1.0), f4 = run(FloatK{}, 4.0);
  std::printf("[ measured ] lamp (%g, %g, %g) sigma_t %g T %g: exact %.6e, rel. error double 4 deg %.2e, 1 deg %.2e, "
              "float 4 deg %.2e\n",
              c.lamp[0], c.lamp[1], c.lamp[2], c.sigma_t, c.T, exact, d4 / exact - 1, d1 / exact - 1, f4 / exact - 1);
  EXPECT_NEAR(d4 / exact, 1.0, 1e-4);
  EXPECT_NEAR(d1 / exact, 1.0, 1e-6);
  EXPECT_NEAR(f4 / exact, 1.0, 2e-4);
}

INSTANTIATE_TEST_SUITE_P(LampsAndExtinctions, ShaftsIntervalsVsSun,
                         ::testing::Values(SunCase{{0.5, 1.0, -4.0}, 0.05, INFINITY},  // in front
                                           SunCase{{0.5, 1.0, -4.0}, 0.0, INFINITY},   // no extinction
                                           SunCase{{0.5, 1.0, -4.0}, 0.5, INFINITY},   // dense
                                           SunCase{{3.0, 0.0, 1.0}, 0.05, INFINITY},   // behind, beside
                                           SunCase{{0.05, 0.0, -2.0}, 0.05, INFINITY}, // near the ray
                                           SunCase{{0.5, 1.0, -4.0}, 0.05, 6.0}));     // a wall at 6 m

// No NaN/Inf and no negative light at the stiff points, in float (the kernel's precision).
TEST(ShaftsIntervals, FiniteThroughTheLampAtConeEdgesAndGrazing) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  kf::ShaftsLamp L{};
  L.pos = kf::real3{0, 5, 0};
  L.axis = kf::real3{0, -1, 0};
  L.right = kf::real3{1, 0, 0};
  L.up = kf::real3{0, 0, 1};
  const float cone = 0.4f;
  L.cos_cone = std::cos(cone);
  L.cos_inner = std::cos(cone - 0.05f);
  L.tan_cone = std::tan(cone);
  int inside = 0;
  for (int i = 0; i < 20000; ++i) {
    kf::real3 o{float(3 * u(rng)), float(3 * u(rng)), float(3 * u(rng))};
    kf::real3 d = kf::normalize(kf::real3{float(u(rng)), float(u(rng)), float(u(rng))});
    if (i % 4 == 0) {  // aimed through the lamp (h = 0 up to rounding)
      d = kf::normalize(L.pos - o);
    } else if (i % 4 == 1) {  // along the cone's surface: a ray from the apex's side at the cone angle
      const float az = float(M_PI * u(rng));
      d = kf::real3{std::sin(cone) * std::cos(az), -std::cos(cone), std::sin(cone) * std::sin(az)};
      o = L.pos + kf::real3{float(1e-3 * u(rng)), 0, float(1e-3 * u(rng))};
    }
    const float sigma = i % 3 == 0 ? 0.0f : (i % 3 == 1 ? 0.04f : 20.0f);
    float lo[SHAFTS_MAX_PIECES], hi[SHAFTS_MAX_PIECES], ti0 = 0, ti1 = 0;
    if (!kf::shafts_cone_interval(o, d, L.pos, L.axis, L.cos_cone, &lo[0], &hi[0])) continue;
    ++inside;
    const int has_inner = kf::shafts_cone_interval(o, d, L.pos, L.axis, L.cos_inner, &ti0, &ti1);
    const kf::real3 e = kf::shafts_interval_airlight(lo, hi, 1, has_inner, ti0, ti1, o, d, L, nullptr, 0.04f, sigma,
                                                     0.02f, i % 2, 0.8f, float(4 * M_PI / 180), 1.0f);
    ASSERT_TRUE(std::isfinite(e.x) && e.x >= 0) << "ray " << i << " sigma " << sigma << " value " << e.x;
  }
  EXPECT_GT(inside, 5000);
}

}  // namespace
