// sky_preetham_test.cpp — the Preetham daylight sky of kernels/common/sky.h (SEASIM_SKY_PREETHAM,
// the spectral sky) in float and double:
//  - towards the zenith it gives the zenith chromaticity of Preetham et al. 1999's fit exactly (the
//    RGB is turned back into x, y by the inverse of the XYZ -> Rec. 709 matrix);
//  - the sky is blue overhead and whiter towards the horizon and in haze, brightest around the sun;
//  - the host's 256 x 512 cosine mean (the scale that gives the sky the configured irradiance) is
//    within 1e-3 of a 1024 x 2048 rule;
//  - the sun at and below the horizon, views at the horizon, both ends of the turbidity range:
//    finite, non-negative.
// Not shown: agreement with the paper's own published sky values (its figures and tables were not at
// hand); the coefficients are the paper's Appendix A.2, cited in sky.h.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "math/kernel_math.h"

namespace {

namespace kd = seasim::kmath_d;
namespace kf = seasim::kmath_f;

template <class T>
struct Sky;
#define SEASIM_SKY_BIND(T, NS)                                                                   \
  template <>                                                                                    \
  struct Sky<T> {                                                                                \
    using V = NS::real3;                                                                         \
    static V vec(double x, double y, double z) { return V{T(x), T(y), T(z)}; }                   \
    static void pack(V sun, T t, T* p) { NS::sky_preetham_pack(sun, t, p); }                     \
    static V rgb(const T* p, V d, V sun) { return NS::sky_preetham_rgb(p, d, sun); }              \
    static void zenith(T th, T t, T* x, T* y) { NS::sky_preetham_zenith_xy(th, t, x, y); }      \
    static T mean(const T* p, V sun, int a, int b) { return NS::sky_preetham_cosine_mean(p, sun, a, b); } \
  };
SEASIM_SKY_BIND(float, kf)
SEASIM_SKY_BIND(double, kd)
#undef SEASIM_SKY_BIND

template <class T>
class PreethamSky : public ::testing::Test {};
using Precisions = ::testing::Types<float, double>;
TYPED_TEST_SUITE(PreethamSky, Precisions);

template <class V>
V fromAngles(double zenith, double azimuth) {
  return V{decltype(V{}.x)(std::sin(zenith) * std::cos(azimuth)), decltype(V{}.x)(std::cos(zenith)),
           decltype(V{}.x)(std::sin(zenith) * std::sin(azimuth))};
}

// x, y of a linear Rec. 709 colour (the inverse of sky.h's matrix: the sRGB -> XYZ of IEC 61966-2-1).
void chromaticity(double r, double g, double b, double* x, double* y) {
  const double X = 0.4124564 * r + 0.3575761 * g + 0.1804375 * b;
  const double Y = 0.2126729 * r + 0.7151522 * g + 0.0721750 * b;
  const double Z = 0.0193339 * r + 0.1191920 * g + 0.9503041 * b;
  *x = X / (X + Y + Z);
  *y = Y / (X + Y + Z);
}

TYPED_TEST(PreethamSky, ZenithHasTheFittedChromaticity) {
  using T = TypeParam;
  using S = Sky<T>;
  for (double t : {2.0, 3.0, 6.0}) {
    for (double sun_zenith_deg : {0.0, 30.0, 60.0, 85.0}) {
      const auto sun = fromAngles<typename S::V>(sun_zenith_deg * M_PI / 180, 0.3);
      T packed[18];
      S::pack(sun, T(t), packed);
      const auto c = S::rgb(packed, S::vec(0, 1, 0), sun);
      double x, y;
      chromaticity(c.x, c.y, c.z, &x, &y);
      T xz, yz;
      S::zenith(T(sun_zenith_deg * M_PI / 180), T(t), &xz, &yz);
      const double tol = std::is_same_v<T, float> ? 2e-5 : 1e-6;  // the matrices' 7 digits
      EXPECT_NEAR(x, double(xz), tol) << "T " << t << " sun " << sun_zenith_deg;
      EXPECT_NEAR(y, double(yz), tol);
      // A clear sky's zenith is bluer than D65 (x 0.3127, y 0.3290).
      EXPECT_LT(x, 0.3127);
      EXPECT_LT(y, 0.3290);
    }
  }
}

TYPED_TEST(PreethamSky, BlueOverheadWhiterAtTheHorizonAndInHazeBrightAroundTheSun) {
  using T = TypeParam;
  using S = Sky<T>;
  const auto sun = fromAngles<typename S::V>(40 * M_PI / 180, 0.0);
  auto blueness = [&](double t, typename S::V d) {
    T packed[18];
    S::pack(sun, T(t), packed);
    const auto c = S::rgb(packed, d, sun);
    return double(c.z) / double(c.x);
  };
  const auto zenith = S::vec(0, 1, 0);
  const auto horizon_away = fromAngles<typename S::V>(89 * M_PI / 180, M_PI);
  EXPECT_GT(blueness(3, zenith), blueness(3, horizon_away));
  EXPECT_GT(blueness(2, zenith), blueness(8, zenith));
  T packed[18];
  S::pack(sun, T(3), packed);
  const auto near_sun = S::rgb(packed, fromAngles<typename S::V>(45 * M_PI / 180, 0.05), sun);
  const auto opposite = S::rgb(packed, fromAngles<typename S::V>(45 * M_PI / 180, M_PI), sun);
  const double y_near = kd::sky_luminance(kd::real3{double(near_sun.x), double(near_sun.y), double(near_sun.z)});
  const double y_far = kd::sky_luminance(kd::real3{double(opposite.x), double(opposite.y), double(opposite.z)});
  EXPECT_GT(y_near, 3 * y_far);
}

TYPED_TEST(PreethamSky, CosineMeanOfTheHostRuleIsConverged) {
  using T = TypeParam;
  using S = Sky<T>;
  for (double sun_zenith_deg : {10.0, 50.0, 85.0}) {
    const auto sun = fromAngles<typename S::V>(sun_zenith_deg * M_PI / 180, 1.0);
    T packed[18];
    S::pack(sun, T(3), packed);
    const double coarse = double(S::mean(packed, sun, 256, 512));
    // The fine rule in double (2 M terms summed in float would lose more than the rule's error).
    double packed_d[18];
    const kd::real3 sun_d{double(sun.x), double(sun.y), double(sun.z)};
    kd::sky_preetham_pack(sun_d, 3.0, packed_d);
    const double fine = kd::sky_preetham_cosine_mean(packed_d, sun_d, 1024, 2048);
    EXPECT_GT(fine, 0.0);
    EXPECT_NEAR(coarse, fine, 1e-3 * fine) << sun_zenith_deg;
  }
}

TYPED_TEST(PreethamSky, StiffCasesStayFiniteAndNonNegative) {
  using T = TypeParam;
  using S = Sky<T>;
  for (double t : {1.7, 10.0}) {
    for (double sun_zenith_deg : {0.0, 90.0, 95.0, 180.0}) {
      const auto sun = fromAngles<typename S::V>(sun_zenith_deg * M_PI / 180, 2.0);
      T packed[18];
      S::pack(sun, T(t), packed);
      for (const auto& d : {S::vec(0, 1, 0), fromAngles<typename S::V>(M_PI / 2, 0.5), S::vec(1, 0, 0), sun,
                            fromAngles<typename S::V>(M_PI / 2 + 0.1, 1.0)}) {
        const auto c = S::rgb(packed, d, sun);
        for (double v : {double(c.x), double(c.y), double(c.z)}) {
          EXPECT_TRUE(std::isfinite(v)) << "T " << t << " sun " << sun_zenith_deg;
          EXPECT_GE(v, 0.0);
        }
      }
    }
  }
}

}  // namespace
