// polynomial_trig_test.cpp — kernels/common/polynomial_trig.h against the C library, in float and
// double: A&S 4.4.49 and 4.4.46 within their bounds over every quadrant and at the singular points
// (the origin, the axes, the diagonal, ±1 for acos, tiny and huge arguments), never NaN or Inf; sin and
// cos on [0, π] within their truncation, exact at the ends and at π/2.
#include <gtest/gtest.h>

#include <cmath>

#include "math/kernel_math.h"

namespace {

namespace kd = seasim::kmath_d;
namespace kf = seasim::kmath_f;

// A&S's bound is 2e-8 for both (measured 1.4e-8 and 2.2e-8); float adds its own rounding of angles up
// to π (ulp 2.4e-7).
constexpr double kDoubleTol = 3e-8, kFloatTol = 6e-7;

// The library's atan2 with the same convention for a zero y (polynomial_trig.h: the sign of -0 is not kept).
double libraryAtan2(double y, double x) { return std::atan2(y == 0 ? 0.0 : y, x); }

TEST(PolynomialTrig, Atan2WithinTheBoundInEveryQuadrant) {
  double worst_d = 0, worst_f = 0;
  for (int i = 0; i < 3600; ++i) {
    const double a = -M_PI + 2 * M_PI * (i + 0.37) / 3600;
    for (double r : {1e-30, 1e-3, 1.0, 7.5, 1e30}) {
      const double y = r * std::sin(a), x = r * std::cos(a);
      const double d = kd::polynomial_atan2(y, x);
      const double f = kf::polynomial_atan2(float(y), float(x));
      ASSERT_TRUE(std::isfinite(d) && std::isfinite(f)) << y << " " << x;
      worst_d = std::max(worst_d, std::fabs(d - libraryAtan2(y, x)));
      worst_f = std::max(worst_f, std::fabs(f - libraryAtan2(double(float(y)), double(float(x)))));
    }
  }
  std::printf("[ measured ] atan2: max error %.2e rad (double), %.2e rad (float)\n", worst_d, worst_f);
  EXPECT_LE(worst_d, kDoubleTol);
  EXPECT_LE(worst_f, kFloatTol);
}

TEST(PolynomialTrig, Atan2AtTheSingularPoints) {
  // The origin: 0, as the library (a view straight up in the lat-long sky). A zero's sign is not kept:
  // atan2(0, -0) is 0 here and π in the library, one direction (the pole) either way.
  EXPECT_EQ(kd::polynomial_atan2(0.0, 0.0), 0.0);
  EXPECT_EQ(kf::polynomial_atan2(0.0f, 0.0f), 0.0f);
  EXPECT_EQ(kd::polynomial_atan2(0.0, -0.0), 0.0);
  // The axes and diagonals, exactly where the quadrant folds meet.
  const double pts[][2] = {{0, 1},  {1, 0},   {0, -1},  {-1, 0}, {1, 1},   {1, -1},
                           {-1, 1}, {-1, -1}, {-0.0, -1}, {1e-300, 1}, {1, 1e-300}, {4.9e-324, -1}};
  for (const auto& p : pts) {
    EXPECT_NEAR(kd::polynomial_atan2(p[0], p[1]), libraryAtan2(p[0], p[1]), kDoubleTol) << p[0] << " " << p[1];
    EXPECT_NEAR(kf::polynomial_atan2(float(p[0]), float(p[1])), libraryAtan2(double(float(p[0])), double(float(p[1]))),
                kFloatTol)
        << p[0] << " " << p[1];
  }
  // Either side of the diagonal by an ulp: continuous.
  const double next = std::nextafter(1.0, 2.0), prev = std::nextafter(1.0, 0.0);
  EXPECT_NEAR(kd::polynomial_atan2(next, 1.0), kd::polynomial_atan2(prev, 1.0), 1e-15 + 2 * kDoubleTol);
  // Denormal and huge floats stay finite.
  for (float v : {1e-45f, 1e-38f, 3e38f})
    for (float w : {1.0f, -1.0f, 3e38f, 1e-45f}) EXPECT_TRUE(std::isfinite(kf::polynomial_atan2(v, w))) << v << " " << w;
}

TEST(PolynomialTrig, AcosWithinTheBoundAndAtTheEnds) {
  double worst_d = 0, worst_f = 0;
  for (int i = 0; i <= 20000; ++i) {
    const double x = -1 + 2.0 * i / 20000;
    worst_d = std::max(worst_d, std::fabs(kd::polynomial_acos(x) - std::acos(x)));
    worst_f = std::max(worst_f, std::fabs(double(kf::polynomial_acos(float(x))) - std::acos(double(float(x)))));
  }
  std::printf("[ measured ] acos: max error %.2e rad (double), %.2e rad (float)\n", worst_d, worst_f);
  EXPECT_LE(worst_d, kDoubleTol);
  EXPECT_LE(worst_f, kFloatTol);
  // The ends and the middle, and an ulp inside ±1 (where acos' slope is infinite).
  for (double x : {-1.0, -0.5, 0.0, 0.5, 1.0, std::nextafter(1.0, 0.0), std::nextafter(-1.0, 0.0)}) {
    EXPECT_NEAR(kd::polynomial_acos(x), std::acos(x), kDoubleTol) << x;
    EXPECT_TRUE(std::isfinite(kf::polynomial_acos(float(x)))) << x;
  }
  EXPECT_NEAR(kd::polynomial_acos(1.0), 0.0, 1e-15);
  EXPECT_NEAR(kd::polynomial_acos(-1.0), M_PI, kDoubleTol);
}

TEST(PolynomialTrig, SinCosOnZeroToPiWithinTheTruncation) {
  // The series' first terms left out: 6.4e-9 (cos y, i.e. sin x) and 6.7e-10 (sin y) at the ends; float
  // adds its rounding of x up to π (ulp 2.4e-7), which moves sin and cos by as much.
  double worst_d = 0, worst_f = 0;
  const int n = 200000;
  for (int i = 0; i <= n; ++i) {
    const double x = M_PI * i / n;
    double c_d;
    const double s_d = kd::polynomial_sincos_0_pi(x, &c_d);
    worst_d = std::max({worst_d, std::fabs(s_d - std::sin(x)), std::fabs(c_d - std::cos(x))});
    const float xf = static_cast<float>(x);
    float c_f;
    const float s_f = kf::polynomial_sincos_0_pi(xf, &c_f);
    ASSERT_TRUE(std::isfinite(s_f) && std::isfinite(c_f)) << x;
    worst_f = std::max({worst_f, std::fabs(s_f - std::sin(double(xf))), std::fabs(c_f - std::cos(double(xf)))});
  }
  std::printf("[ measured ] sin, cos on [0, pi]: max error %.2e (double), %.2e (float)\n", worst_d, worst_f);
  EXPECT_LE(worst_d, 7.5e-9);
  EXPECT_LE(worst_f, 6e-7);
  // The ends and the middle: sin 0 = sin π = 0 and cos π/2 = 0 to the truncation; |sin|, |cos| <= 1.
  double c;
  EXPECT_NEAR(kd::polynomial_sincos_0_pi(0.0, &c), 0.0, 7.5e-9);
  EXPECT_NEAR(c, 1.0, 1e-9);
  EXPECT_NEAR(kd::polynomial_sincos_0_pi(M_PI, &c), 0.0, 7.5e-9);
  EXPECT_NEAR(c, -1.0, 1e-9);
  EXPECT_NEAR(kd::polynomial_sincos_0_pi(M_PI / 2, &c), 1.0, 1e-15);
  EXPECT_NEAR(c, 0.0, 1e-15);
  // The host's switch is the library (the double evaluation the kernels are tested against).
  EXPECT_EQ(kd::kernel_sincos_0_pi(1.25, &c), std::sin(1.25));
  EXPECT_EQ(c, std::cos(1.25));
}

}  // namespace
