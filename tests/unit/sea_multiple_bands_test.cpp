// sea_multiple_bands_test.cpp — sea.model "multiple" on the band lanes (kernels/common/sea_multiple_bands.h,
// one band per lane on the host) against sea_multiple.h's scalar functions, in double (the same formulas:
// to rounding) and in float (against the double scalar): the column, the bottom and the surface's
// return, over no bottom, a bottom at the surface, clear water (k -> 0, the series branch), turbid deep
// water, a grazing view and a grazing sun, isotropic and strongly forward water, and without the column.
// tests/kernels/sea_multiple_kernel_test.cpp runs the lanes on PoCL in floatN against the double evaluation.
#include <gtest/gtest.h>

#include <cmath>

#include "math/kernel_math.h"

namespace {

namespace kd = seasim::kmath_d;
namespace kf = seasim::kmath_f;

struct Case {
  const char* name;
  double a, b, g, H, cos_io, cos_ji, phase, focus, albedo;
};

const Case kCases[] = {
    {"ordinary", 0.06, 0.2, 0.9, 8.0, 0.85, 0.7, 0.05, 1.0, 0.3},
    {"no_bottom", 0.06, 0.2, 0.9, -1.0, 0.85, 0.7, 0.05, 1.0, 0.3},
    {"bottom_at_surface", 0.06, 0.2, 0.9, 0.0, 0.85, 0.7, 0.05, 1.0, 0.3},
    {"clear_water", 1e-6, 2e-6, 0.9, 5.0, 0.9, 0.8, 0.05, 1.0, 0.5},
    {"no_water", 0.0, 0.0, 0.9, 5.0, 0.9, 0.8, 0.05, 1.0, 0.5},
    {"turbid_deep", 2.0, 9.0, 0.95, 1000.0, 0.66, 0.9, 2.0, 1.0, 0.8},
    {"grazing_view", 0.1, 0.3, 0.9, 8.0, 0.66, 1e-4, 0.02, 1.0, 0.2},
    {"grazing_sun", 0.1, 0.3, 0.9, 8.0, 1e-4, 0.7, 0.02, 1.0, 0.2},
    {"isotropic_focused", 0.05, 0.5, 0.0, 3.0, 0.8, 0.6, 0.0796, 3.5, 0.6},
};

// What one band's terms take besides the case: the sun and sky at the surface and the pixel's cosines.
constexpr double kSun = 1.2, kTin = 0.97, kSky = 0.4, kIor = 1.333, kSkyFresnel = 0.066;

struct Terms {
  double column, bottom, surface_return_with, surface_return_without;
};

Terms scalarTerms(const Case& c) {
  const double c_f = kd::hg_forward_fraction(c.g), mu_sky = kd::sea_sky_mean_cosine(kIor);
  const double r_below = kd::sea_surface_reflectance_below(kSkyFresnel, kIor);
  const double mu_ret = kd::sea_reflected_mean_cosine(r_below, kIor);
  return {kd::sea_multiple_column(kSun, kTin, kSky, c.a, c.b, c_f, c.H, c.cos_io, c.cos_ji, c.phase, mu_sky),
          kd::sea_multiple_bottom(kSun, kTin, kSky, c.a, c.b, c_f, c.albedo, c.H, c.cos_io, c.cos_ji, mu_sky, c.focus),
          kd::sea_multiple_surface_return(kSun, kTin, kSky, c.a, c.b, c_f, c.albedo, c.H, c.cos_io, c.cos_ji, mu_sky,
                                          c.focus, r_below, mu_ret, 1),
          kd::sea_multiple_surface_return(kSun, kTin, kSky, c.a, c.b, c_f, c.albedo, c.H, c.cos_io, c.cos_ji, mu_sky,
                                          c.focus, r_below, mu_ret, 0)};
}

template <typename K, typename Real>
Terms lanesTerms(const Case& c) {
  const Real c_f = K::hg_forward_fraction(Real(c.g)), mu_sky = K::sea_sky_mean_cosine(Real(kIor));
  const Real r_below = K::sea_surface_reflectance_below(Real(kSkyFresnel), Real(kIor));
  const Real mu_ret = K::sea_reflected_mean_cosine(r_below, Real(kIor));
  const auto f = K::sea_multiple_factors_b(Real(c.a), Real(c.b), c_f);
  const Real H = Real(c.H), cos_io = Real(c.cos_io), cos_ji = Real(c.cos_ji), focus = Real(c.focus);
  // The hemisphere factors the kernel has from SeaParams, once per frame.
  const Real hemisphere[3] = {K::sea_column_hemisphere(cos_io), K::sea_column_hemisphere(mu_sky),
                              K::sea_column_hemisphere(mu_ret)};
  return {K::sea_multiple_column_b(&f, Real(kSun), Real(kTin), Real(kSky), Real(c.a), Real(c.b), H, cos_io, cos_ji,
                                   Real(c.phase), mu_sky),
          K::sea_multiple_bottom_b(&f, Real(kSun), Real(kTin), Real(kSky), Real(c.albedo), H, cos_io, cos_ji, mu_sky,
                                   focus),
          K::sea_multiple_surface_return_b(&f, Real(kSun), Real(kTin), Real(kSky), Real(c.albedo), H, cos_io, cos_ji,
                                           mu_sky, focus, r_below, mu_ret, 1, hemisphere),
          K::sea_multiple_surface_return_b(&f, Real(kSun), Real(kTin), Real(kSky), Real(c.albedo), H, cos_io, cos_ji,
                                           mu_sky, focus, r_below, mu_ret, 0, hemisphere)};
}

struct KF {
  static float hg_forward_fraction(float g) { return kf::hg_forward_fraction(g); }
  static float sea_sky_mean_cosine(float n) { return kf::sea_sky_mean_cosine(n); }
  static float sea_surface_reflectance_below(float r, float n) { return kf::sea_surface_reflectance_below(r, n); }
  static float sea_reflected_mean_cosine(float r, float n) { return kf::sea_reflected_mean_cosine(r, n); }
  static float sea_column_hemisphere(float mu) { return kf::sea_column_hemisphere(mu); }
  static auto sea_multiple_factors_b(float a, float b, float c_f) { return kf::sea_multiple_factors_b(a, b, c_f); }
  template <typename... A>
  static float sea_multiple_column_b(A... a) { return kf::sea_multiple_column_b(a...); }
  template <typename... A>
  static float sea_multiple_bottom_b(A... a) { return kf::sea_multiple_bottom_b(a...); }
  template <typename... A>
  static float sea_multiple_surface_return_b(A... a) { return kf::sea_multiple_surface_return_b(a...); }
};
struct KD {
  static double hg_forward_fraction(double g) { return kd::hg_forward_fraction(g); }
  static double sea_sky_mean_cosine(double n) { return kd::sea_sky_mean_cosine(n); }
  static double sea_surface_reflectance_below(double r, double n) { return kd::sea_surface_reflectance_below(r, n); }
  static double sea_reflected_mean_cosine(double r, double n) { return kd::sea_reflected_mean_cosine(r, n); }
  static double sea_column_hemisphere(double mu) { return kd::sea_column_hemisphere(mu); }
  static auto sea_multiple_factors_b(double a, double b, double c_f) { return kd::sea_multiple_factors_b(a, b, c_f); }
  template <typename... A>
  static double sea_multiple_column_b(A... a) { return kd::sea_multiple_column_b(a...); }
  template <typename... A>
  static double sea_multiple_bottom_b(A... a) { return kd::sea_multiple_bottom_b(a...); }
  template <typename... A>
  static double sea_multiple_surface_return_b(A... a) { return kd::sea_multiple_surface_return_b(a...); }
};

void expectClose(double got, double expected, double rel, const char* what, const char* name) {
  EXPECT_TRUE(std::isfinite(got)) << what << " " << name;
  EXPECT_NEAR(got, expected, rel * std::fabs(expected) + 1e-30) << what << " " << name;
}

TEST(SeaMultipleBands, LanesMatchTheScalarClosedFormInDoubleAndFloat) {
  for (const Case& c : kCases) {
    const Terms s = scalarTerms(c);
    const Terms d = lanesTerms<KD, double>(c);
    const Terms f = lanesTerms<KF, float>(c);
    expectClose(d.column, s.column, 1e-13, "column (double)", c.name);
    expectClose(d.bottom, s.bottom, 1e-13, "bottom (double)", c.name);
    expectClose(d.surface_return_with, s.surface_return_with, 1e-13, "return (double)", c.name);
    expectClose(d.surface_return_without, s.surface_return_without, 1e-13, "return without column (double)", c.name);
    expectClose(f.column, s.column, 2e-5, "column (float)", c.name);
    expectClose(f.bottom, s.bottom, 2e-5, "bottom (float)", c.name);
    expectClose(f.surface_return_with, s.surface_return_with, 2e-5, "return (float)", c.name);
    expectClose(f.surface_return_without, s.surface_return_without, 2e-5, "return without column (float)", c.name);
  }
}

// The factors computed once per step are the scalar ones, u = 0 where the water neither absorbs nor
// scatters (k = 0) rather than 0/0.
TEST(SeaMultipleBands, FactorsAreTheScalarOnesAndFiniteWithoutWater) {
  for (const Case& c : kCases) {
    const double c_f = kd::hg_forward_fraction(c.g);
    const kd::SeaMultipleFactors s = kd::sea_multiple_factors(c.a, c.b, c_f);
    const kd::SeaMultipleFactorsB l = kd::sea_multiple_factors_b(c.a, c.b, c_f);
    EXPECT_EQ(l.bb, s.bb) << c.name;
    EXPECT_EQ(l.k, s.k) << c.name;
    EXPECT_EQ(l.u, s.u) << c.name;
    EXPECT_EQ(l.d_c, s.d_c) << c.name;
    EXPECT_EQ(l.d_b, s.d_b) << c.name;
    EXPECT_EQ(l.orders, s.orders) << c.name;
  }
  const kf::SeaMultipleFactorsB none = kf::sea_multiple_factors_b(0.0f, 0.0f, 0.9f);
  EXPECT_EQ(none.u, 0.0f);
  EXPECT_EQ(none.orders, 1.0f);
}

}  // namespace
