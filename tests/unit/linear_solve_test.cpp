// linear_solve_test.cpp — the dense Gaussian elimination behind the discrete-ordinates solver and the
// improved model's fits (host/math/linear_solve.*): a system that needs its rows swapped, and singular
// ones reported rather than divided by.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "math/linear_solve.h"

namespace {

TEST(LinearSolve, SolvesASystemThatNeedsPivoting) {
  // a[0][0] = 0: without a row swap the first pivot would be 0. Solution (1, -2, 3).
  std::vector<double> a = {0, 2, 1, 1, 1, 1, 4, -1, 2};
  const std::vector<double> x = {1, -2, 3};
  std::vector<double> rhs(3, 0.0);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) rhs[i] += a[i * 3 + j] * x[j];
  ASSERT_TRUE(seasim::solveLinear(a, rhs, 3));
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(rhs[i], x[i], 1e-14);
}

TEST(LinearSolve, ReportsSingularSystems) {
  std::vector<double> dependent = {1, 2, 2, 4}, rhs = {1, 2};
  EXPECT_FALSE(seasim::solveLinear(dependent, rhs, 2));
  std::vector<double> zero(4, 0.0), rhs0 = {0, 0};
  EXPECT_FALSE(seasim::solveLinear(zero, rhs0, 2));
  std::vector<double> nan = {std::nan(""), 0, 0, 1}, rhs1 = {1, 1};
  EXPECT_FALSE(seasim::solveLinear(nan, rhs1, 2));
}

}  // namespace
