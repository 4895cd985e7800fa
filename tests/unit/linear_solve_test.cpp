// linear_solve_test.cpp — the dense Gaussian elimination behind the discrete-ordinates solver and the
// discrete-ordinates model's fits (host/math/linear_solve.*): a system that needs its rows swapped, and singular
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

// Several right-hand sides in one elimination: each column the solution the system gives it alone, to the
// last bit (the same operations in the same order).
TEST(LinearSolve, SolvesSeveralRightHandSidesAsEachAlone) {
  const std::vector<double> a0 = {0, 2, 1, 1, 1, 1, 4, -1, 2};
  const std::vector<std::vector<double>> rhss = {{3, 2, 12}, {1, 0, -1}, {0.5, -7, 3.25}};
  std::vector<double> a = a0, many(9);
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) many[i * 3 + k] = rhss[k][i];
  ASSERT_TRUE(seasim::solveLinear(a, many, 3, 3));
  for (int k = 0; k < 3; ++k) {
    std::vector<double> alone_a = a0, alone = rhss[k];
    ASSERT_TRUE(seasim::solveLinear(alone_a, alone, 3));
    for (int i = 0; i < 3; ++i) EXPECT_EQ(many[i * 3 + k], alone[i]) << k << " " << i;
  }
  std::vector<double> dependent = {1, 2, 2, 4}, two = {1, 0, 2, 0};
  EXPECT_FALSE(seasim::solveLinear(dependent, two, 2, 2));
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
