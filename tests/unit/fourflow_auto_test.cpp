// fourflow_auto_test.cpp — quality.fourflow_table_size = "auto" (host/passes/fourflow_auto.h): the
// choice is the smallest power-of-two resolution meeting the interpolation budget, the one below it
// does not, and the error falls as the table grows.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "passes/fourflow_auto.h"
#include "underwater/fourflow_setup.h"

namespace {

std::vector<FfBand> lakeLikeBands() {
  std::vector<FfBand> bands;
  for (int i = 0; i < 8; ++i) {
    const double nm = 400 + 40 * i;
    seasim::FourFlowBandInput in;
    in.absorption = 0.01 + 0.5 * std::pow((nm - 400) / 300, 3);
    in.scattering = 0.05 * std::pow(500 / nm, 4);
    in.e_sun = 1.0, in.e_sky = 0.3;
    in.rho_a = 0.35, in.rho_b = 0.05, in.rho_mean = 0.25;
    in.rgb = {nm > 560 ? 0.1 : 0.0, nm > 480 && nm < 620 ? 0.1 : 0.0, nm < 520 ? 0.1 : 0.0};
    bands.push_back(seasim::makeFourFlowBand(in, std::cos(0.6), 1.333));
  }
  return bands;
}

FfParams lakeParams(int n_bands) {
  FfParams p{};
  p.n_bands = n_bands;
  p.l_max = float(std::log(1e4) / 0.06);
  p.h_max = 15.0f;
  p.gamma = 1.0f;
  for (int c = 0; c < 3; ++c) p.rgb_a[c] = 0.35f, p.rgb_b[c] = 0.05f;
  return p;
}

TEST(FourFlowAuto, PicksTheSmallestTableUnderTheBudget) {
  const auto bands = lakeLikeBands();
  const FfParams p = lakeParams(int(bands.size()));
  const double budget = 1.0 / 1024;
  const seasim::FourFlowTableChoice choice = seasim::chooseFourFlowTableSize(bands, p, budget, 256);
  EXPECT_LE(choice.error, budget);
  ASSERT_GT(choice.size, 8);  // a coarse table is not enough on this water
  const seasim::FourFlowTableChoice smaller = seasim::chooseFourFlowTableSize(bands, p, budget, choice.size / 2);
  EXPECT_GT(smaller.error, budget);
  EXPECT_GT(smaller.error, choice.error);
  std::printf("[ measured ] fourflow auto: size %d (error %.2e of the peak), size %d: %.2e\n", choice.size,
              choice.error, smaller.size, smaller.error);
}

}  // namespace
