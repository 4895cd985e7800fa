// underwater_math_test.cpp — the underwater model of paper 002 (kernels/common/underwater.h) in float
// and double: eq. 4.7 against numerical quadrature of eq. 4.6 over a grid that crosses the singular line
// K_d d_y = σ_t, its limits (σ_s → 0, camera at the surface and at 1000 m, rays straight up and down,
// turbid water at long range), the surface terms and the scene ray cast.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "math/kernel_math.h"

namespace {

namespace kd = seasim::kmath_d;
namespace kf = seasim::kmath_f;

// e^{-K o_d} ∫_0^S e^{-c z} e^{K z d_y} dz: the integral inside 002 eq. 4.6 (σ_s E_D0 / 4π left out),
// composite Simpson in long double.
long double eq46Quadrature(double k, double c, double d_y, double o_d, double S, int intervals = 20000) {
  const long double h = static_cast<long double>(S) / intervals;
  auto f = [&](long double z) { return std::exp(-c * z - k * (o_d - z * d_y)); };
  long double sum = f(0) + f(S);
  for (int i = 1; i < intervals; ++i) sum += (i % 2 ? 4.0L : 2.0L) * f(i * h);
  return sum * h / 3.0L;
}

TEST(UnderwaterMath, Eq47MatchesQuadratureAcrossTheSingularLine) {
  // K_d d_y - σ_t takes negative, zero and positive values: K = 0.5, c = 0.25 crosses at d_y = 0.5.
  int checked = 0;
  for (double k : {0.02, 0.1, 0.5, 2.0}) {
    for (double c : {0.01, 0.25, 1.0, 5.0}) {
      std::vector<double> dys = {-1.0, -0.3, 0.0, 0.2, 0.7, 1.0};
      if (c < k) {  // the singular line and its neighbourhood
        const double d0 = c / k;
        for (double e : {0.0, 1e-9, -1e-9, 1e-6, -1e-6, 1e-3, -1e-3}) dys.push_back(d0 + e);
      }
      for (double d_y : dys) {
        if (d_y > 1.0) continue;
        for (double o_d : {0.0, 3.0, 20.0}) {
          for (double S : {0.0, 0.5, 5.0, 40.0}) {
            if (d_y > 0 && S * d_y > o_d) continue;  // the ray would leave the water
            const long double ref = eq46Quadrature(k, c, d_y, o_d, S);
            const double d = kd::kd_exp_integral(k, c, d_y, o_d, S);
            const float f = kf::kd_exp_integral(float(k), float(c), float(d_y), float(o_d), float(S));
            const double scale = std::max(static_cast<double>(ref), 1e-300);
            EXPECT_NEAR(d / scale, S == 0 ? 0.0 / scale : 1.0, 1e-9) << k << " " << c << " " << d_y << " " << o_d << " " << S;
            if (S > 0) {
              // float: inputs rounded to float move the exponent by ~1e-7 relative times its size.
              EXPECT_NEAR(f / scale, 1.0, 2e-5 * (1 + (k * o_d + c * S))) << k << " " << c << " " << d_y << " " << o_d << " " << S;
            }
            EXPECT_TRUE(std::isfinite(f));
            ++checked;
          }
        }
      }
    }
  }
  EXPECT_GT(checked, 500);
}

TEST(UnderwaterMath, SingularPointIsContinuousInFloat) {
  // Exactly on the line (x = 0) the integral is e^{-K o_d} S; just off it, it moves smoothly.
  const float k = 0.5f, c = 0.25f, o_d = 4.0f, S = 6.0f;
  const float on = kf::kd_exp_integral(k, c, 0.5f, o_d, S);
  EXPECT_NEAR(on, std::exp(-0.5 * 4.0) * 6.0, 1e-6);
  for (float e : {1e-7f, 1e-6f, 1e-5f, 1e-4f, 1e-3f}) {
    const double ref_p = kd::kd_exp_integral(0.5, 0.25, 0.5 + e, 4.0, 6.0);
    const double ref_m = kd::kd_exp_integral(0.5, 0.25, 0.5 - e, 4.0, 6.0);
    EXPECT_NEAR(kf::kd_exp_integral(k, c, 0.5f + e, o_d, S) / ref_p, 1.0, 1e-6) << e;
    EXPECT_NEAR(kf::kd_exp_integral(k, c, 0.5f - e, o_d, S) / ref_m, 1.0, 1e-6) << e;
    EXPECT_NEAR(ref_p / on, 1.0, 10 * e * S * k + 1e-6);  // derivative bounded: no jump at the line
  }
}

TEST(UnderwaterMath, RaysStraightUpAndDown) {
  // Straight down into deep water: ∫_0^∞ e^{-(c+K) z} dz e^{-K o_d} = e^{-K o_d} / (c + K).
  for (double o_d : {0.0, 10.0, 1000.0}) {
    EXPECT_NEAR(kd::kd_exp_integral(0.1, 0.4, -1.0, o_d, 1e30) / (std::exp(-0.1 * o_d) / 0.5), 1.0, 1e-12);
    EXPECT_TRUE(std::isfinite(kf::kd_exp_integral(0.1f, 0.4f, -1.0f, float(o_d), 1e30f)));
  }
  // Straight up to the surface from o_d: ∫_0^{o_d} e^{-c z - K (o_d - z)} dz = (e^{-c o_d} - e^{-K o_d})/(K - c).
  for (double o_d : {0.5, 10.0, 200.0}) {
    const double exact = (std::exp(-0.4 * o_d) - std::exp(-0.1 * o_d)) / (0.1 - 0.4);
    EXPECT_NEAR(kd::kd_exp_integral(0.1, 0.4, 1.0, o_d, o_d) / exact, 1.0, 1e-12);
    EXPECT_NEAR(kf::kd_exp_integral(0.1f, 0.4f, 1.0f, float(o_d), float(o_d)) / exact, 1.0, 1e-5);
  }
}

TEST(UnderwaterMath, CameraAtTheSurfaceAndAt1000m) {
  // o_d = 0 looking horizontally: (1 - e^{-c S}) / c.
  EXPECT_NEAR(kd::kd_exp_integral(0.2, 0.3, 0.0, 0.0, 10.0), (1 - std::exp(-3.0)) / 0.3, 1e-12);
  // 1000 m looking up with K > c: e^{-K o_d} underflows in float while e^{xS} alone would overflow;
  // the product stays finite and matches double.
  const double k = 2.0, c = 0.05, o_d = 1000.0;
  for (double d_y : {1.0, 0.5, 0.1}) {
    const double S = o_d / d_y;
    const double d = kd::kd_exp_integral(k, c, d_y, o_d, S);
    const float f = kf::kd_exp_integral(float(k), float(c), float(d_y), float(o_d), float(S));
    EXPECT_TRUE(std::isfinite(d) && std::isfinite(f)) << d_y;
    EXPECT_GT(d, 0.0);
    // Near the surface the integrand is e^{-c S} ≈ e^{-50 / d_y}: tiny but representable in double.
    EXPECT_NEAR(f, d, 1e-6 * d + 1e-37) << d_y;
    EXPECT_NEAR(d / static_cast<double>(eq46Quadrature(k, c, d_y, o_d, S, 200000)), 1.0, 1e-6) << d_y;
  }
}

TEST(UnderwaterMath, MultipleScatteringVanishesWithScattering) {
  for (double b : {0.0, 1e-12, 1e-6, 1e-3}) {
    const double v = kd::kd_multiple_scattering(b, 0.3, 0.1, 1.0, 0.0, 0.9, -0.2, 5.0, 30.0);
    const double per_b = kd::kd_multiple_scattering(1.0, 0.3, 0.1, 1.0, 0.0, 0.9, -0.2, 5.0, 30.0);
    EXPECT_NEAR(v, b * per_b, 1e-15 * per_b);  // linear in σ_s, exactly 0 at 0
  }
  EXPECT_EQ(kf::kd_multiple_scattering(0.0f, 0.3f, 0.1f, 1.0f, 0.5f, 0.9f, -0.2f, 5.0f, 30.0f), 0.0f);
}

TEST(UnderwaterMath, DirectSunSplitOffTheDiffuseLight) {
  // With e_direct0 = e_sun0 the ambient is (e_sky0 + e_sun0) e^{-K y} - e_sun0 e^{-(c/μ) y}; where
  // K = c/μ the sun's part cancels and only the sky's remains.
  const double c = 0.2, mu = 0.8, k = c / mu;
  const double both = kd::kd_multiple_scattering(0.1, c, k, 3.0, 2.0, mu, -0.3, 4.0, 25.0);
  const double sky_only = kd::kd_multiple_scattering(0.1, c, k, 1.0, 0.0, mu, -0.3, 4.0, 25.0);
  EXPECT_NEAR(both / sky_only, 1.0, 1e-12);
  // Irradiance split: E_dif + beam·μ = the whole E_D0 e^{-K y} when K = c/μ.
  const double y = 7.0, e_sky0 = 1.0, e_sun0 = 2.0;
  const double e_dif = kd::uw_diffuse_irradiance(e_sky0, e_sun0, e_sun0, k, c, mu, y);
  const double e_beam = kd::uw_beam_irradiance(e_sun0 / mu, c, mu, y);
  EXPECT_NEAR(e_dif + e_beam * mu, (e_sky0 + e_sun0) * std::exp(-k * y), 1e-12);
  // Clear water where K < c/μ would make the remainder negative: clamped to 0, never NaN.
  EXPECT_EQ(kd::uw_diffuse_irradiance(0.0, 1.0, 1.0, 0.01, 1.0, 0.5, 3.0) >= 0.0, true);
}

TEST(UnderwaterMath, TurbidWaterAtLongRangeStaysFinite) {
  // Jerlov 9C-like: c ≈ 10/m, K_d ≈ 3/m, 10 km rays, camera at 10 m and 1000 m, every direction.
  for (double o_d : {10.0, 1000.0}) {
    for (double d_y : {-1.0, -0.5, 0.0, 0.5, 1.0}) {
      const double S = d_y > 0 ? o_d / d_y : 1e4;
      const float f = kf::kd_multiple_scattering(9.0f, 10.0f, 3.0f, 1.0f, 0.4f, 0.7f, float(d_y), float(o_d), float(S));
      const double d = kd::kd_multiple_scattering(9.0, 10.0, 3.0, 1.0, 0.4, 0.7, d_y, o_d, S);
      EXPECT_TRUE(std::isfinite(f) && f >= 0) << o_d << " " << d_y;
      EXPECT_NEAR(f, d, 1e-5 * d + 1e-38) << o_d << " " << d_y;
    }
  }
}

TEST(UnderwaterMath, SceneHitFindsSurfaceBottomAndObjects) {
  UwObject sphere{};
  sphere.type = UW_SPHERE;
  sphere.a[0] = 0;
  sphere.a[1] = -5;
  sphere.a[2] = -10;
  sphere.a[3] = 1;
  kd::real3 n{};
  int mat = 0;
  // Towards the sphere.
  double t = kd::uw_scene_hit(&sphere, 1, 8.0, kd::real3{0, -5, 0}, kd::real3{0, 0, -1}, 0.0, &n, &mat);
  EXPECT_EQ(mat, 0);
  EXPECT_NEAR(t, 9.0, 1e-12);
  EXPECT_NEAR(n.z, 1.0, 1e-12);
  // Up to the surface from 5 m.
  t = kd::uw_scene_hit(&sphere, 1, 8.0, kd::real3{0, -5, 0}, kd::real3{0, 1, 0}, 0.0, &n, &mat);
  EXPECT_EQ(mat, UW_MAT_SURFACE);
  EXPECT_NEAR(t, 5.0, 1e-12);
  // Down to the bottom at 8 m; none without a bottom.
  t = kd::uw_scene_hit(&sphere, 1, 8.0, kd::real3{0, -5, 0}, kd::real3{0, -1, 0}, 0.0, &n, &mat);
  EXPECT_EQ(mat, UW_MAT_BOTTOM);
  EXPECT_NEAR(t, 3.0, 1e-12);
  t = kd::uw_scene_hit(&sphere, 1, 0.0, kd::real3{0, -5, 0}, kd::real3{0, -1, 0}, 0.0, &n, &mat);
  EXPECT_EQ(mat, UW_MAT_NONE);
  EXPECT_GE(t, 1e30);
}

// A sphere, a box and a plane through (0, plane_y, 0) with the unit normal n: the shadow rays' objects.
std::array<UwObject, 3> shadowTestObjects(float plane_y, kd::real3 n) {
  std::array<UwObject, 3> objs{};
  objs[0].type = UW_SPHERE;
  objs[0].a[0] = 0.3f, objs[0].a[1] = -5.0f, objs[0].a[2] = -2.0f, objs[0].a[3] = 0.7f;
  objs[1].type = UW_BOX;
  objs[1].a[0] = -1.5f, objs[1].a[1] = -6.0f, objs[1].a[2] = -1.0f;
  objs[1].b[0] = -0.5f, objs[1].b[1] = -5.2f, objs[1].b[2] = 0.5f;
  objs[2].type = UW_PLANE;
  objs[2].a[1] = plane_y;
  objs[2].b[0] = float(n.x), objs[2].b[1] = float(n.y), objs[2].b[2] = float(n.z);
  return objs;
}

// Uniform numbers in [lo, hi) from a linear congruential sequence started at `seed` (repeatable).
auto uniformFrom(unsigned seed) {
  return [state = seed](double lo, double hi) mutable {
    state = state * 1664525u + 1013904223u;
    return lo + (hi - lo) * (state >> 8) / double(1u << 24);
  };
}

// The shadow rays' test (uw_objects_block: any object in (t_min, t_max), first one found) against the
// nearest hit of uw_scene_hit: blocked exactly when an object is the nearest hit before t_max, over random
// segments among a sphere, a box and a tilted plane, from inside, outside and on their surfaces' sides.
TEST(UnderwaterMath, ObjectsBlockASegmentExactlyWhenTheNearestHitIsAnObjectBeforeItsEnd) {
  const std::array<UwObject, 3> all = shadowTestObjects(-7.5f, kd::normalize(kd::real3{0.2, 1.0, 0.1}));
  const UwObject* objs = all.data();
  auto uniform = uniformFrom(12345u);
  int blocked = 0, open = 0;
  for (int i = 0; i < 20000; ++i) {
    const kd::real3 p{uniform(-2.5, 2.5), uniform(-8.0, -3.0), uniform(-3.5, 1.5)};
    const kd::real3 q{uniform(-2.5, 2.5), uniform(-8.0, -3.0), uniform(-3.5, 1.5)};
    const kd::real3 w = q - p;
    const double s = kd::length(w);
    if (!(s > 1e-6)) continue;
    const kd::real3 d = w * (1.0 / s);
    kd::real3 n{};
    int mat = UW_MAT_NONE;
    const double t = kd::uw_scene_hit(objs, 3, 0.0, p, d, 0.0, &n, &mat);
    const bool nearest = mat >= 0 && t < s;
    const bool any = kd::uw_objects_block(objs, 3, UW_ALL_OBJECTS, p, d, 0.0, s) != 0;
    ASSERT_EQ(any, nearest) << i << " t " << t << " s " << s;
    (any ? blocked : open)++;
    const kf::real3 pf{float(p.x), float(p.y), float(p.z)}, df{float(d.x), float(d.y), float(d.z)};
    if (std::fabs(t - s) > 1e-3 && (mat < 0 || t > 1e-3)) EXPECT_EQ(kf::uw_objects_block(objs, 3, UW_ALL_OBJECTS, pf, df, 0.0f, float(s)) != 0, nearest) << i;
  }
  EXPECT_GT(blocked, 2000);  // both outcomes well covered
  EXPECT_GT(open, 2000);
  // No objects: nothing blocks.
  EXPECT_EQ(kd::uw_objects_block(objs, 0, UW_ALL_OBJECTS, kd::real3{0, -5, 0}, kd::real3{0, 0, -1}, 0.0, 100.0), 0);
}

// The shadow rays' cull (uw_objects_near_triangle): an object left out is in the way of no shadow ray from a
// point of the segment p1 p2 to p0 (checked with 64 rays per triangle), over random triangles near a
// sphere, a box and a plane, and a degenerate one (p0 on the segment's line). The point-triangle distance
// against a dense sampling of the triangle.
TEST(UnderwaterMath, ObjectsLeftOutOfAShadowFanBlockNoneOfItsRays) {
  const std::array<UwObject, 3> all = shadowTestObjects(-9.5f, kd::real3{0.0, 1.0, 0.0});
  const UwObject* objs = all.data();
  auto uniform = uniformFrom(777u);
  auto point = [&] { return kd::real3{uniform(-3.0, 3.0), uniform(-9.0, -2.0), uniform(-4.0, 2.0)}; };
  int culled = 0, kept = 0;
  for (int i = 0; i < 4000; ++i) {
    const kd::real3 p0 = point(), p1 = point(), p2 = point();
    const unsigned near = kd::uw_objects_near_triangle(objs, 3, p0, p1, p2);
    const unsigned near_f = kf::uw_objects_near_triangle(objs, 3, kf::real3{float(p0.x), float(p0.y), float(p0.z)},
                                                         kf::real3{float(p1.x), float(p1.y), float(p1.z)},
                                                         kf::real3{float(p2.x), float(p2.y), float(p2.z)});
    ASSERT_TRUE(near & 4u) << "a plane is always a candidate";
    for (int k = 0; k < 2; ++k) {
      ((near >> k) & 1u ? kept : culled)++;
      if ((near >> k) & 1u && (near_f >> k) & 1u) continue;
      for (int j = 0; j <= 63; ++j) {  // every shadow ray of the fan misses an object culled in either precision
        const kd::real3 p = p1 + (j / 63.0) * (p2 - p1), w = p0 - p;
        const double s = kd::length(w);
        ASSERT_EQ(kd::uw_objects_block(&objs[k], 1, UW_ALL_OBJECTS, p, w * (1.0 / s), 0.0, s), 0) << i << " " << k;
      }
    }
    // The distance against the triangle sampled on a 200 x 200 grid of barycentric points: never above it.
    if (i < 200) {
      const kd::real3 c{0.3, -5.0, -2.0};
      double best = 1e30;
      for (int u = 0; u <= 200; ++u)
        for (int v = 0; u + v <= 200; ++v) {
          const kd::real3 q = p0 + (u / 200.0) * (p1 - p0) + (v / 200.0) * (p2 - p0);
          best = std::min(best, kd::dot(c - q, c - q));
        }
      const double d2 = kd::uw_point_triangle_distance2(c, p0, p1, p2);
      EXPECT_LE(d2, best + 1e-12) << i;
      EXPECT_GE(std::sqrt(d2), std::sqrt(best) - 0.05) << i;  // the grid's spacing
    }
  }
  EXPECT_GT(culled, 1000);  // both outcomes well covered
  EXPECT_GT(kept, 1000);
  // Degenerate (the lamp on the segment's line: a view ray through the lamp): the fan is that line, and
  // the sphere it crosses stays a candidate; the box, 1.2 m beside it, does not.
  const kd::real3 lamp{0.3, -5.0, 2.0}, s1{0.3, -5.0, -6.0}, s2{0.3, -5.0, -8.0};
  EXPECT_EQ(kd::uw_objects_near_triangle(objs, 3, lamp, s1, s2), 1u | 4u);
  EXPECT_EQ(kf::uw_objects_near_triangle(objs, 3, kf::real3{0.3f, -5.0f, 2.0f}, kf::real3{0.3f, -5.0f, -6.0f},
                                         kf::real3{0.3f, -5.0f, -8.0f}),
            1u | 4u);
}

TEST(UnderwaterMath, SnellWindowAndBandRadiance) {
  // Looking straight up through a clear (b = 0) water column of 5 m: n² (1 - F(0)) L_sky e^{-a 5}.
  UwBand band{};
  band.a = 0.1f;
  band.b = 0.0f;
  band.c = 0.1f;
  band.kd = 0.12f;
  band.sky_radiance = 2.0f;
  const double ior = 1.333, f0 = std::pow((ior - 1) / (ior + 1), 2);
  const double expect = ior * ior * (1 - f0) * 2.0 * std::exp(-0.5);
  const double got = kd::uw_band_radiance(&band, UW_MAT_SURFACE, 5.0, kd::real3{0, -1, 0}, kd::real3{0, 1, 0}, 5.0,
                                          kd::real3{0, 1, 0}, 0.0, 1.0, ior, 0.0, 1, 1);
  EXPECT_NEAR(got / expect, 1.0, 1e-6);
  // Beyond the critical angle (cos θ < cos 48.6°) the sky is not seen: total internal reflection.
  const double d_y = 0.5;
  const double tir = kd::uw_band_radiance(&band, UW_MAT_SURFACE, 10.0, kd::real3{0, -1, 0},
                                          kd::real3{std::sqrt(1 - d_y * d_y), d_y, 0}, 5.0, kd::real3{0, 1, 0}, 0.0,
                                          1.0, ior, 0.0, 1, 1);
  EXPECT_EQ(tir, 0.0);  // b = 0: the reflected deep water is black
  // A lit Lambertian point straight below the sun: ρ/π (E_dif + E_beam) e^{-c S} + L_MS, float vs double.
  band.b = 0.05f;
  band.c = 0.15f;
  band.e_sky0 = 0.3f;
  band.e_sun0 = 0.9f;
  band.e_beam0 = 0.9f;
  const double d = kd::uw_band_radiance(&band, 0, 4.0, kd::real3{0, 1, 0}, kd::real3{0, -1, 0}, 3.0,
                                        kd::real3{0, 1, 0}, 0.4, 1.0, ior, 0.0, 1, 1);
  const float f = kf::uw_band_radiance(reinterpret_cast<const UwBand*>(&band), 0, 4.0f, kf::real3{0, 1, 0},
                                       kf::real3{0, -1, 0}, 3.0f, kf::real3{0, 1, 0}, 0.4f, 1.0f, float(ior), 0.0f, 1, 1);
  const double y = 7.0;
  const double e = (0.3 + 0.9) * std::exp(-0.12 * y) - 0.9 * std::exp(-0.15 * y) + 0.9 * std::exp(-0.15 * y);
  const double ms = kd::kd_multiple_scattering(0.05, 0.15, 0.12, 1.2, 0.9, 1.0, -1.0, 3.0, 4.0);
  // The band holds floats (0.12f ≠ 0.12): agree to float rounding of the inputs.
  EXPECT_NEAR(d / (0.4 / M_PI * e * std::exp(-0.15 * 4.0) + ms), 1.0, 1e-6);
  EXPECT_NEAR(f / d, 1.0, 1e-6);
}

}  // namespace

// The G-buffer's casts in pixel lanes (underwater_hit_lanes.h, one lane on the host) against the scalar
// uw_scene_hit and uw_sun_visibility: the same material and visibility, the same distance and normal to
// rounding, over random rays among a sphere, a box and a tilted plane with the surface and a bottom, in
// double and in float (the kernel's), from inside the objects too.
TEST(UnderwaterMath, SceneHitInPixelLanesMatchesTheScalarCast) {
  const std::array<UwObject, 3> all = shadowTestObjects(-7.5f, kd::normalize(kd::real3{0.2, 1.0, 0.1}));
  const UwObject* objs = all.data();
  const kd::real3 sun = kd::normalize(kd::real3{0.3, 1.0, -0.2});
  auto uniform = uniformFrom(2468u);
  int hits[4] = {0, 0, 0, 0};  // objects, surface, bottom, none
  int float_material_differs = 0;
  for (int i = 0; i < 20000; ++i) {
    const kd::real3 o{uniform(-2.5, 2.5), uniform(-8.0, -0.5), uniform(-3.5, 1.5)};
    const kd::real3 d = kd::normalize(kd::real3{uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)});
    // Without the plane and the bottom now and then, so that rays leave into deep water too.
    const int count = i % 2 ? 3 : 2;
    const double bottom = i % 4 < 2 ? 9.0 : 0.0;
    kd::real3 n{};
    int mat = 0;
    const double t = kd::uw_scene_hit(objs, count, bottom, o, d, 0.0, &n, &mat);
    kd::real3b nb{};
    double mat_b = 0;
    const double tb = kd::uw_scene_hit_b(objs, count, bottom, kd::uw_splat3b(o), kd::uw_splat3b(d), 0.0, &nb, &mat_b);
    ASSERT_EQ(int(mat_b), mat) << i;
    EXPECT_NEAR(tb, t, 1e-12 * std::max(1.0, t)) << i;
    EXPECT_NEAR(nb.x, n.x, 1e-12) << i;
    EXPECT_NEAR(nb.y, n.y, 1e-12) << i;
    EXPECT_NEAR(nb.z, n.z, 1e-12) << i;
    ++hits[mat >= 0 ? 0 : mat == UW_MAT_SURFACE ? 1 : mat == UW_MAT_BOTTOM ? 2 : 3];
    if (mat >= 0 || mat == UW_MAT_BOTTOM) {
      const kd::real3 hit = o + t * d;
      EXPECT_EQ(kd::uw_sun_visibility_b(objs, count, kd::uw_splat3b(hit), nb, sun),
                kd::uw_sun_visibility(objs, count, hit, n, sun))
          << i;
    }
    // Float, the kernel's precision: a ray that grazes an edge may round to the other side, nothing more.
    const kf::real3 of{float(o.x), float(o.y), float(o.z)}, df{float(d.x), float(d.y), float(d.z)};
    kf::real3 nf{};
    int mat_f = 0;
    const float tf = kf::uw_scene_hit(objs, count, float(bottom), of, df, 0.0f, &nf, &mat_f);
    kf::real3b nfb{};
    float mat_fb = 0;
    const float tfb = kf::uw_scene_hit_b(objs, count, float(bottom), kf::uw_splat3b(of), kf::uw_splat3b(df), 0.0f, &nfb, &mat_fb);
    if (int(mat_fb) != mat_f) {
      ++float_material_differs;
      continue;
    }
    EXPECT_NEAR(tfb, tf, 1e-5f * std::max(1.0f, tf)) << i;
  }
  // Every kind of hit was cast.
  for (int k = 0; k < 4; ++k) EXPECT_GT(hits[k], 500) << k;
  EXPECT_LE(float_material_differs, 2);
}

// The shadow test in lanes (uw_objects_block_b, one lane on the host; underwater_lamps.cl's beam tests 16 planes'
// shadow rays with it) against the scalar uw_objects_block: the same answer over random segments among a sphere,
// a box and a tilted plane, for every candidates mask (an object left out is never in the way), in double and
// in float but for a grazing segment or two.
TEST(UnderwaterMath, ObjectsBlockInPixelLanesMatchesTheScalarTest) {
  const std::array<UwObject, 3> all = shadowTestObjects(-7.5f, kd::normalize(kd::real3{0.2, 1.0, 0.1}));
  auto uniform = uniformFrom(97531u);
  int blocked = 0, float_differs = 0;
  const int segments = 20000;
  for (int i = 0; i < segments; ++i) {
    const kd::real3 o{uniform(-2.5, 2.5), uniform(-8.0, -0.5), uniform(-3.5, 1.5)};
    const kd::real3 d = kd::normalize(kd::real3{uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)});
    const double t_max = uniform(0.0, 8.0);
    const unsigned int candidates = static_cast<unsigned int>(i % 8);  // every subset of the three objects
    const int want = kd::uw_objects_block(all.data(), 3, candidates, o, d, 0.0, t_max);
    ASSERT_EQ(kd::uw_objects_block_b(all.data(), 3, candidates, kd::uw_splat3b(o), kd::uw_splat3b(d), 0.0, t_max) != 0,
              want != 0)
        << i;
    blocked += want != 0;
    const kf::real3 of{float(o.x), float(o.y), float(o.z)}, df{float(d.x), float(d.y), float(d.z)};
    float_differs += (kf::uw_objects_block_b(all.data(), 3, candidates, kf::uw_splat3b(of), kf::uw_splat3b(df), 0.0f,
                                             float(t_max)) != 0) !=
                     (kf::uw_objects_block(all.data(), 3, candidates, of, df, 0.0f, float(t_max)) != 0);
  }
  // A good share of the segments were blocked, and none by an object left out of the mask (mask 0 never blocks).
  EXPECT_GT(blocked, segments / 10);
  EXPECT_EQ(kd::uw_objects_block_b(all.data(), 3, 0u, kd::uw_splat3b(kd::real3{0, -5, 0}),
                                   kd::uw_splat3b(kd::real3{0, -1, 0}), 0.0, 100.0),
            0);
  EXPECT_LE(float_differs, 2);
}

// The view directions of a row's pixels in lanes (uw_screen_dir_b) are uw_screen_dir's, corners included.
TEST(UnderwaterMath, ScreenDirectionsInPixelLanesMatchTheScalarOnes) {
  UwParams p{};
  const kd::real3 fwd = kd::normalize(kd::real3{0.2, -0.4, -1.0});
  const kd::real3 right = kd::normalize(kd::cross(fwd, kd::real3{0, 1, 0}));
  const kd::real3 up = kd::cross(right, fwd);
  for (int k = 0; k < 3; ++k) {
    p.cam_forward[k] = float((&fwd.x)[k]);
    p.cam_right[k] = float((&right.x)[k]);
    p.cam_up[k] = float((&up.x)[k]);
  }
  p.tan_half_fov_y = float(std::tan(0.5));
  p.aspect = 16.0f / 9.0f;
  for (double sx : {0.0, 0.013, 0.5, 0.77, 1.0})
    for (double sy : {0.0, 0.31, 1.0}) {
      const kd::real3 want = kd::uw_screen_dir(&p, sx, sy);
      const kd::real3b got = kd::uw_screen_dir_b(&p, sx, sy);
      EXPECT_NEAR(got.x, want.x, 1e-15) << sx << " " << sy;
      EXPECT_NEAR(got.y, want.y, 1e-15) << sx << " " << sy;
      EXPECT_NEAR(got.z, want.z, 1e-15) << sx << " " << sy;
    }
}
