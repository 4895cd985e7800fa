// underwater_regions_refine_test.cpp — `seasim underwater-regions --target-noise`: the
// path count a too-noisy reference is traced again at. Noise falls as 1/√paths, so reaching the target
// from `noise` at `spp` needs spp (noise/target)² paths, rounded up to a power-of-two multiple of spp;
// a case that would need more than max_spp keeps spp (0 says so) rather than spending the budget.
#include <gtest/gtest.h>

#include <cmath>

#include "cli/underwater_regions_command.h"

namespace {

using seasim::refinedPathCount;

TEST(UnderwaterRegionsRefine, QuietEnoughOrOffKeepsThePathCount) {
  EXPECT_EQ(refinedPathCount(2048, 0.01, 0.018, 16384), 2048);
  EXPECT_EQ(refinedPathCount(2048, 0.018, 0.018, 16384), 2048);  // at the target: enough
  EXPECT_EQ(refinedPathCount(2048, 0.5, 0.0, 16384), 2048);      // 0: off
  EXPECT_EQ(refinedPathCount(2048, 0.0, 0.018, 16384), 2048);    // no noise (an empty region)
}

TEST(UnderwaterRegionsRefine, ThePowerOfTwoThatReachesTheTarget) {
  // 2.5 %: (2.5/1.8)² = 1.93 -> 2x; 3.59 %: 3.98x -> 4x; 3.7 %: 4.2x -> 8x; 5.09 %: 7.996x -> 8x.
  EXPECT_EQ(refinedPathCount(2048, 0.025, 0.018, 16384), 4096);
  EXPECT_EQ(refinedPathCount(2048, 0.0359, 0.018, 16384), 8192);
  EXPECT_EQ(refinedPathCount(2048, 0.037, 0.018, 16384), 16384);
  EXPECT_EQ(refinedPathCount(2048, 0.0509, 0.018, 16384), 16384);
  // Each answer brings the 1/√paths noise to the target or under it, and half as many paths would not.
  for (double noise : {0.019, 0.03, 0.045, 0.05}) {
    const int n = refinedPathCount(2048, noise, 0.018, 1 << 20);
    EXPECT_LE(noise * std::sqrt(2048.0 / n), 0.018 + 1e-12) << noise;
    EXPECT_GT(noise * std::sqrt(2048.0 / (n / 2)), 0.018) << noise;
  }
}

TEST(UnderwaterRegionsRefine, BeyondTheBudgetSaysZero) {
  EXPECT_EQ(refinedPathCount(2048, 0.06, 0.018, 16384), 0);  // needs 11x: 32768 > 16384
  EXPECT_EQ(refinedPathCount(2048, 1.4, 0.018, 16384), 0);   // the coastal water at 20 m
  EXPECT_EQ(refinedPathCount(2048, 0.06, 0.018, 32768), 32768);
}

}  // namespace
