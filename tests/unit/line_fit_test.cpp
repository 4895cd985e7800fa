// line_fit_test.cpp — host/math/line_fit.h: exact lines, a known noisy fit (worked by hand), the
// degenerate inputs (all x equal, flat y, too few points) and large offsets.
#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

#include "math/line_fit.h"

namespace {

TEST(LineFit, RecoversAnExactLine) {
  const seasim::LineFit f = seasim::fitLine({1, 2, 4, 8}, {3.5, 5.5, 9.5, 17.5});  // y = 1.5 + 2 x
  EXPECT_NEAR(f.intercept, 1.5, 1e-12);
  EXPECT_NEAR(f.slope, 2.0, 1e-12);
  EXPECT_NEAR(f.r2, 1.0, 1e-12);
}

TEST(LineFit, MatchesAHandWorkedNoisyFit) {
  // x = 0, 1, 2, 3; y = 1, 3, 2, 5: mean x 1.5, mean y 2.75, Sxy = 5.5, Sxx = 5, Syy = 8.75.
  const seasim::LineFit f = seasim::fitLine({0, 1, 2, 3}, {1, 3, 2, 5});
  EXPECT_NEAR(f.slope, 1.1, 1e-12);
  EXPECT_NEAR(f.intercept, 2.75 - 1.1 * 1.5, 1e-12);
  EXPECT_NEAR(f.r2, 5.5 * 5.5 / (5.0 * 8.75), 1e-12);
}

TEST(LineFit, DegenerateInputs) {
  const seasim::LineFit same_x = seasim::fitLine({4, 4, 4}, {1, 2, 6});
  EXPECT_EQ(same_x.slope, 0.0);
  EXPECT_NEAR(same_x.intercept, 3.0, 1e-12);
  EXPECT_EQ(same_x.r2, 1.0);
  const seasim::LineFit flat = seasim::fitLine({1, 2, 3}, {7, 7, 7});
  EXPECT_EQ(flat.slope, 0.0);
  EXPECT_NEAR(flat.intercept, 7.0, 1e-12);
  EXPECT_EQ(flat.r2, 1.0);
  EXPECT_THROW(seasim::fitLine({1}, {1}), std::invalid_argument);
  EXPECT_THROW(seasim::fitLine({1, 2}, {1}), std::invalid_argument);
}

TEST(LineFit, StableFarFromTheOrigin) {
  std::vector<double> x, y;
  for (int i = 0; i < 5; ++i) x.push_back(1e8 + i), y.push_back(3.0 + 0.25 * (1e8 + i));
  const seasim::LineFit f = seasim::fitLine(x, y);
  EXPECT_NEAR(f.slope, 0.25, 1e-9);
  EXPECT_NEAR(f.r2, 1.0, 1e-9);
}

}  // namespace
