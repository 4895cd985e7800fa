// sea_multiple_test.cpp — sea.model = "multiple" (kernels/common/sea_multiple.h) in float and double:
// its parts against independent quadrature of the integrals they stand for, the mean cosine of the
// skylight in the water against quadrature over Snell's cone, its limits (no bottom, k -> 0, very deep
// bottom, b -> 0 is paper 000's eq. 5) and its stiff inputs.
#include <gtest/gtest.h>

#include <cmath>

#include "math/kernel_math.h"

namespace {

namespace kd = seasim::kmath_d;
namespace kf = seasim::kmath_f;

TEST(SeaMultiple, SkyMeanCosineMatchesQuadratureOverSnellsCone) {
  // Uniform radiance inside the cone of half-angle θ_c: mean cosine E_d / E_0 = ∫ cos sin / ∫ sin over [0, θ_c].
  for (double n : {1.0, 1.2, 1.333, 1.5}) {
    const double theta_c = std::asin(1.0 / n);
    const int steps = 250000;
    long double num = 0, den = 0;
    for (int i = 0; i < steps; ++i) {
      const long double t = (i + 0.5L) * theta_c / steps;
      num += std::cos(t) * std::sin(t);
      den += std::sin(t);
    }
    EXPECT_NEAR(kd::sea_sky_mean_cosine(n), static_cast<double>(num / den), 1e-8) << n;
    EXPECT_NEAR(kf::sea_sky_mean_cosine(float(n)), static_cast<double>(num / den), 1e-6) << n;
  }
  EXPECT_DOUBLE_EQ(kd::sea_sky_mean_cosine(1.0), 0.5);  // the open hemisphere (n = 1)
}

TEST(SeaMultiple, SurfaceReflectanceBelowMatchesFresnelQuadratureWithTotalInternalReflection) {
  // Uniform radiance from below: r = ∫ F(μ) 2μ dμ over the upper hemisphere, F from water to air
  // (1 beyond the critical angle); from above the same with F from air to water.
  for (double n : {1.0, 1.333, 1.5}) {
    const int steps = 200000;
    long double below = 0, above = 0;
    for (int i = 0; i < steps; ++i) {
      const double mu = (i + 0.5) / steps;
      below += kd::fresnel_reflectance(mu, n, 1.0) * 2 * mu / steps;
      above += kd::fresnel_reflectance(mu, 1.0, n) * 2 * mu / steps;
    }
    EXPECT_NEAR(kd::sea_surface_reflectance_below(static_cast<double>(above), n), static_cast<double>(below), 2e-5) << n;
    EXPECT_NEAR(kf::sea_surface_reflectance_below(float(above), float(n)), static_cast<double>(below), 2e-5) << n;
  }
  EXPECT_NEAR(kd::sea_surface_reflectance_below(0.0663, 1.333), 0.474, 1e-3);  // water: about half goes back down
}

TEST(SeaMultiple, DepthFactorIsOneMinusExpAndStableAsKVanishes) {
  for (double k : {2.0, 0.3, 1e-3}) {
    for (double H : {0.0, 0.5, 5.0, 50.0}) {
      const double ref = 1.0 - std::exp(-k * H * 2.5);
      EXPECT_NEAR(kd::sea_depth_factor(k, H, 2.5), ref, 1e-14 + 1e-12 * ref) << k << " " << H;
      EXPECT_NEAR(kf::sea_depth_factor(float(k), float(H), 2.5f), ref, 1e-6 * ref + 1e-7) << k << " " << H;
    }
  }
  // k -> 0: 1 - e^{-x} ~ x, where the naive float form returns 0.
  for (double k : {1e-8, 1e-12, 0.0}) {
    EXPECT_NEAR(kd::sea_depth_factor(k, 10.0, 2.0), 20.0 * k, 1e-6 * 20.0 * k + 1e-300);
    EXPECT_NEAR(kf::sea_depth_factor(float(k), 10.0f, 2.0f), 20.0 * k, 1e-6 * 20.0 * k + 1e-30);
  }
  EXPECT_EQ(kd::sea_depth_factor(0.3, -1.0, 2.0), 1.0);  // no bottom
  EXPECT_EQ(kf::sea_depth_factor(0.3f, -1.0f, 2.0f), 1.0f);
}

// The QSSA integral the sky term solves: E_sky/μ_sky e^{-k y/μ_sky} scattered by b_b/(2π) into the view
// at y = z cos_ji, attenuated by e^{-k z D_C} back up; midpoint rule to depth H (long double).
long double skyQuadrature(double e_sky, double mu_sky, double bb, double k, double cos_ji, double d_c, double H) {
  const int steps = 200000;
  const long double S = H / cos_ji, dz = S / steps;
  long double sum = 0;
  for (int i = 0; i < steps; ++i) {
    const long double z = (i + 0.5L) * dz;
    sum += std::exp(-k * z * cos_ji / mu_sky - k * z * d_c);
  }
  return e_sky / mu_sky * bb / (2 * M_PI) * sum * dz;
}

TEST(SeaMultiple, SkyTermMatchesQuadrature) {
  // With D_C = 1 the deep value times the depth factor is exactly the integral; with D_C != 1 the
  // depth factor stretches the view leg (Lee 1999) and the deep value is unchanged.
  const double e_sky = 0.4, mu_sky = 0.83, bb = 0.02, k = 0.09;
  for (double cos_ji : {1.0, 0.75, 0.2}) {
    for (double H : {0.5, 5.0, 200.0}) {
      const long double ref = skyQuadrature(e_sky, mu_sky, bb, k, cos_ji, 1.0, H);
      const double d =
          kd::sea_sky_backscatter_deep(e_sky, mu_sky, bb, k, cos_ji) * kd::sea_depth_factor(k, H, 1 / mu_sky + 1 / cos_ji);
      const float f = kf::sea_sky_backscatter_deep(float(e_sky), float(mu_sky), float(bb), float(k), float(cos_ji)) *
                      kf::sea_depth_factor(float(k), float(H), float(1 / mu_sky + 1 / cos_ji));
      EXPECT_NEAR(d / ref, 1.0, 1e-7) << cos_ji << " " << H;  // the midpoint rule: 1.3e-8 at the deepest
      EXPECT_NEAR(f / ref, 1.0, 3e-6) << cos_ji << " " << H;
    }
  }
}

TEST(SeaMultiple, FactorsFollowLee1999) {
  // g = 0.9: b_b / b = 1 - c_f; u = b_b / (a + b_b); D_C, D_B and the orders' factor at that u.
  const double a = 0.0646, b = 0.98, c_f = kd::hg_forward_fraction(0.9);
  const kd::SeaMultipleFactors f = kd::sea_multiple_factors(a, b, c_f);
  const double bb = b * (1 - c_f), u = bb / (a + bb);
  EXPECT_NEAR(1 - c_f, 0.0234, 5e-4);  // HG g = 0.9 sends 2.3 % of its light backwards
  EXPECT_NEAR(f.bb, bb, 1e-15);
  EXPECT_NEAR(f.k, a + bb, 1e-15);
  EXPECT_NEAR(f.k, (a + b) * (1 - b / (a + b) * c_f), 1e-12);  // paper 000's k = c (1 - ω₀ c_f)
  EXPECT_NEAR(f.u, u, 1e-15);
  EXPECT_NEAR(f.d_c, 1.03 * std::sqrt(1 + 2.4 * u), 1e-15);
  EXPECT_NEAR(f.d_b, 1.04 * std::sqrt(1 + 5.4 * u), 1e-15);
  EXPECT_NEAR(f.orders, (0.084 + 0.170 * u) * u / (0.084 * u), 1e-12);
  const kf::SeaMultipleFactors ff = kf::sea_multiple_factors(float(a), float(b), float(c_f));
  EXPECT_NEAR(ff.u, u, 1e-6);
  EXPECT_NEAR(ff.d_b, f.d_b, 1e-6);
  // No water at all (a = b = 0): u = 0, no division by 0.
  const kf::SeaMultipleFactors zero = kf::sea_multiple_factors(0.0f, 0.0f, float(c_f));
  EXPECT_EQ(zero.u, 0.0f);
  EXPECT_EQ(zero.orders, 1.0f);
}

// The integral sea_sun_backscatter stands for, with D_C = 1: E/(μ_s μ_v) ∫_0^H [b p e^{-c y/μ_s} +
// b_b/(2π) (e^{-k y/μ_s} - e^{-c y/μ_s})] e^{-k y/μ_v} dy, by the midpoint rule in long double.
long double sunQuadrature(double e, double b, double phase, double bb, double c, double k, double H, double mu_s,
                          double mu_v) {
  const int steps = 250000;
  const long double dy = H / steps;
  long double sum = 0;
  for (int i = 0; i < steps; ++i) {
    const long double y = (i + 0.5L) * dy;
    const long double beam = std::exp(-c * y / mu_s), all = std::exp(-k * y / mu_s);
    sum += (b * phase * beam + bb / (2 * M_PI) * (all - beam)) * std::exp(-k * y / mu_v);
  }
  return e / (mu_s * mu_v) * sum * dy;
}

TEST(SeaMultiple, SunTermMatchesQuadratureOfBeamAndSpreadLight) {
  // Jerlov III-like water at g = 0.9: b_f = c - k is most of c, so the two parts differ a lot.
  const double a = 0.12, b = 0.35, c_f = kd::hg_forward_fraction(0.9), bb = b * (1 - c_f), k = a + bb, c = a + b;
  const double phase = kd::hg_phase(-0.95, 0.9);
  for (double mu_s : {0.87, 0.3}) {
    for (double mu_v : {1.0, 0.75, 0.2}) {
      for (double H : {0.5, 5.0, 400.0}) {
        const long double ref = sunQuadrature(1.3, b, phase, bb, c, k, H, mu_s, mu_v);
        const double d = kd::sea_sun_backscatter(1.3, b, phase, bb, c, k, H, mu_s, mu_v, 1.0);
        const float f = kf::sea_sun_backscatter(1.3f, float(b), float(phase), float(bb), float(c), float(k), float(H),
                                                float(mu_s), float(mu_v), 1.0f);
        EXPECT_NEAR(d / ref, 1.0, 1e-7) << mu_s << " " << mu_v << " " << H;
        EXPECT_NEAR(f / ref, 1.0, 3e-6) << mu_s << " " << mu_v << " " << H;
      }
      // No bottom: the deep closed form, which a 400 m bottom (x_k >= 35) already reaches.
      const double deep = kd::sea_sun_backscatter(1.3, b, phase, bb, c, k, -1.0, mu_s, mu_v, 1.0);
      EXPECT_NEAR(deep / double(sunQuadrature(1.3, b, phase, bb, c, k, 400.0, mu_s, mu_v)), 1.0, 1e-7);
    }
  }
  // The spread light's share is real: here it is most of the sun's term, not a correction.
  const double beam_only = 1.3 * b * phase / (c * 0.75 + k * 0.87);
  EXPECT_GT(kd::sea_sun_backscatter(1.3, b, phase, bb, c, k, -1.0, 0.87, 0.75, 1.0), 2.0 * beam_only);
}

TEST(SeaMultiple, ColumnWithLittleScatteringIsPaper000Eq5) {
  // As b -> 0 nothing has been scattered before the first scattering: the beam is all of the sun's
  // light, c -> k -> a, u -> 0, and the column is eq. 5 of the same water (deep, no sky).
  const double a = 0.06, b = 1e-7, g = 0.9, c_f = kd::hg_forward_fraction(g);
  const double cos_io = 0.87, cos_ji = 0.8, phase = 0.01;
  const double col = kd::sea_multiple_column(1.0, 0.97, 0.0, a, b, c_f, -1.0, cos_io, cos_ji, phase, 0.83);
  const double eq5 = kd::sea_single_scattering(1.0, 0.97, 1.0, b * phase, a + b, b / (a + b), c_f, cos_io, cos_ji, -1.0);
  EXPECT_NEAR(col / eq5, 1.0, 1e-5);
}

TEST(SeaMultiple, BottomTermMatchesItsClosedFormAndVanishesWithoutABottom) {
  const double a = 0.08, b = 1.06, c_f = kd::hg_forward_fraction(0.9), mu_sky = kd::sea_sky_mean_cosine(1.333);
  const kd::SeaMultipleFactors f = kd::sea_multiple_factors(a, b, c_f);
  for (double H : {0.0, 2.0, 20.0}) {
    // The light bouncing between bottom and surface, summed bounce by bounce (each a round trip of a
    // diffuse flux, e^{-2kH} each way, reflected by the surface with 0.47 and by the bottom with 0.3).
    double bounces = 0, term = 1;
    for (int n = 0; n < 200; ++n, term *= 0.3 * 0.47 * std::exp(-4 * f.k * H)) bounces += term;
    const double ref = 0.3 / M_PI * (0.7 * 0.98 * std::exp(-f.k * H / 0.87) + 0.14 * std::exp(-f.k * H / mu_sky)) *
                       bounces * std::exp(-f.k * H * f.d_b / 0.6);
    const double d = kd::sea_multiple_bottom(0.7, 0.98, 0.14, a, b, c_f, 0.3, H, 0.87, 0.6, mu_sky, 1.0, 0.47);
    const float fl = kf::sea_multiple_bottom(0.7f, 0.98f, 0.14f, float(a), float(b), float(c_f), 0.3f, float(H), 0.87f,
                                             0.6f, float(mu_sky), 1.0f, 0.47f);
    EXPECT_NEAR(d / ref, 1.0, 1e-12) << H;
    EXPECT_NEAR(fl / ref, 1.0, 2e-6) << H;
  }
  EXPECT_EQ(kd::sea_multiple_bottom(0.7, 0.98, 0.14, a, b, c_f, 0.3, -1.0, 0.87, 0.6, mu_sky, 1.0, 0.47), 0.0);
  // The bottom's light is attenuated by k = a + b_b, not by c (eq. 9): at 2 m of Jerlov 3C it is
  // hundreds of times brighter than eq. 9's.
  const double eq9 = kd::sea_bottom_reflection(0.7, 0.98, 1.0, 0.3, a + b, 2.0, 0.87, 0.6);
  EXPECT_GT(kd::sea_multiple_bottom(0.7, 0.98, 0.0, a, b, c_f, 0.3, 2.0, 0.87, 0.6, mu_sky, 1.0, 0.0), 100 * eq9);
}

TEST(SeaMultiple, DeepBottomTendsToNoBottomAndEverythingStaysFinite) {
  const double a = 0.06, b = 0.3, c_f = kd::hg_forward_fraction(0.9), mu = kd::sea_sky_mean_cosine(1.333);
  const double none = kd::sea_multiple_column(0.7, 0.98, 0.14, a, b, c_f, -1.0, 0.87, 0.6, 0.003, mu) +
                      kd::sea_multiple_bottom(0.7, 0.98, 0.14, a, b, c_f, 0.3, -1.0, 0.87, 0.6, mu, 1.0, 0.47);
  const double deep = kd::sea_multiple_column(0.7, 0.98, 0.14, a, b, c_f, 1e4, 0.87, 0.6, 0.003, mu) +
                      kd::sea_multiple_bottom(0.7, 0.98, 0.14, a, b, c_f, 0.3, 1e4, 0.87, 0.6, mu, 1.0, 0.47);
  EXPECT_NEAR(deep / none, 1.0, 1e-12);
  // Stiff inputs in float: grazing cosines (the callers clamp at 1e-4), huge and zero depths, clear and
  // very turbid water, g at its ends: finite and >= 0.
  for (float g : {-0.99f, 0.0f, 0.9f, 0.99999f}) {
    const float cf = kf::hg_forward_fraction(g);
    for (float H : {-1.0f, 0.0f, 1e-6f, 3.0f, 1e6f}) {
      for (float cos_v : {1e-4f, 0.5f, 1.0f}) {
        for (float aa : {0.0f, 1e-6f, 2.0f}) {
          for (float bb : {0.0f, 1e-6f, 50.0f}) {
            const float col = kf::sea_multiple_column(1.0f, 0.97f, 0.2f, aa, bb, cf, H, 1e-4f, cos_v, 0.5f, 0.83f);
            const float bot = kf::sea_multiple_bottom(1.0f, 0.97f, 0.2f, aa, bb, cf, 0.3f, H, 1e-4f, cos_v, 0.83f, 2.0f, 1.0f);
            EXPECT_TRUE(std::isfinite(col) && col >= 0.0f) << g << " " << H << " " << cos_v << " " << aa << " " << bb;
            EXPECT_TRUE(std::isfinite(bot) && bot >= 0.0f) << g << " " << H << " " << cos_v << " " << aa << " " << bb;
          }
        }
      }
    }
  }
}

}  // namespace
