// whitecaps_test.cpp — sea-surface foam (kernels/common/whitecaps.h) on the CPU: Monahan &
// O'Muircheartaigh's coverage and the foam's reflectance as published, the Jacobian quantile, the
// foam's opacity by age with Koepke's mean 0.4, the mask's mip chain and footprint in double (the mean
// is kept, so a view straight down over whole tiles is 0.4 W of foam), the stiff limits; and the plan: the pass only when surface.whitecaps is asked for on an
// FFT sea, its key's errors naming the key.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "ocean/ocean_cpu.h"
#include "passes/ocean_pass.h"
#include "passes/whitecaps_math.h"
#include "passes/whitecaps_threshold.h"
#include "plan/memory_budget.h"
#include "plan/plan.h"
#include "scene/model_keys.h"
#include "scene/scene_parser.h"
#include "util/error.h"

namespace {

namespace wd = seasim::whitecaps_d;
namespace wf = seasim::whitecaps_f;

seasim::Scene shipped(const std::string& name, const std::vector<seasim::Override>& overrides = {}) {
  return seasim::loadScene(std::string(SEASIM_SOURCE_DIR) + "/scenes/" + name, overrides);
}

seasim::Override set(const std::string& key, const std::string& value) { return {key, value, {"<test>", 1}}; }

TEST(WhitecapsCoverage, IsMonahanAndOMuircheartaighsFit) {
  // W = 3.84e-6 U^3.41: 0.987 % at 10 m/s (their eq. 3 in per cent: 3.84e-4 U^3.41).
  EXPECT_NEAR(wd::whitecaps_coverage(10.0), 3.84e-6 * std::pow(10.0, 3.41), 1e-15);
  EXPECT_NEAR(wd::whitecaps_coverage(10.0), 0.00987, 0.00001);
  EXPECT_NEAR(wd::whitecaps_coverage(5.0), 0.000929, 0.000001);
  EXPECT_NEAR(wd::whitecaps_coverage(15.0), 0.0393, 0.0001);
  EXPECT_EQ(wd::whitecaps_coverage(0.0), 0.0);   // no wind, no foam
  EXPECT_EQ(wd::whitecaps_coverage(-3.0), 0.0);  // guarded, though the parser refuses it
  EXPECT_EQ(wd::whitecaps_coverage(60.0), 1.0);  // the extrapolation is held at full cover
  EXPECT_NEAR(wf::whitecaps_coverage(10.0f), wd::whitecaps_coverage(10.0), 1e-8);
  for (double u = 0.5; u < 40; u += 0.5) EXPECT_LE(wd::whitecaps_coverage(u), wd::whitecaps_coverage(u + 0.5));
}

TEST(WhitecapsReflectance, IsFreshFoamsInTheVisibleAndFrouinsDecreaseInTheInfrared) {
  EXPECT_DOUBLE_EQ(wd::whitecaps_reflectance(400.0), 0.55);
  EXPECT_DOUBLE_EQ(wd::whitecaps_reflectance(555.0), 0.55);
  EXPECT_NEAR(wd::whitecaps_reflectance(670.0), 0.55 * 0.889, 1e-12);
  EXPECT_NEAR(wd::whitecaps_reflectance(765.0), 0.55 * 0.760, 1e-12);
  EXPECT_NEAR(wd::whitecaps_reflectance(865.0), 0.55 * 0.645, 1e-12);
  EXPECT_NEAR(wd::whitecaps_reflectance(1000.0), 0.55 * 0.645, 1e-12);
  for (double l = 380; l < 900; l += 5) EXPECT_GE(wd::whitecaps_reflectance(l), wd::whitecaps_reflectance(l + 5));
}

TEST(WhitecapsThreshold, LeavesExactlyTheAskedShareOfDistinctTexelsBelowIt) {
  std::vector<float> j(4096);
  std::mt19937 rng(7);
  std::normal_distribution<float> normal(1.0f, 0.4f);
  for (float& v : j) v = normal(rng);
  for (double w : {0.0, 0.00093, 0.0099, 0.04, 0.5, 1.0}) {
    const float th = seasim::whitecapsFoamLevels(j, w).threshold;
    const long below = std::count_if(j.begin(), j.end(), [&](float v) { return v < th; });
    EXPECT_EQ(below, std::lround(w * 4096.0)) << "coverage " << w;
  }
}

TEST(WhitecapsThreshold, StiffInputs) {
  // J = 1 everywhere (no choppiness): ties at the quantile leave no texel below it.
  const std::vector<float> ones(1024, 1.0f);
  const seasim::WhitecapsFoamLevels tied = seasim::whitecapsFoamLevels(ones, 0.1);
  EXPECT_EQ(std::count_if(ones.begin(), ones.end(), [&](float v) { return v < tied.threshold; }), 0);
  // Equal nodes give a rank, not 0/0.
  EXPECT_EQ(wd::whitecaps_rank(1.0, tied.rank_j.data()), 0.0);
  EXPECT_EQ(wd::whitecaps_rank(2.0, tied.rank_j.data()), 1.0);
  EXPECT_THROW(seasim::whitecapsFoamLevels({}, 0.1), seasim::RuntimeError);
  EXPECT_THROW(seasim::whitecapsFoamLevels({1.0f, NAN}, 0.1), seasim::RuntimeError);
  EXPECT_THROW(seasim::whitecapsFoamLevels({1.0f, 2.0f}, 1.5), seasim::RuntimeError);
}

TEST(WhitecapsOpacity, FallsWithAgeFromOneToZeroWithKoepkesMeanEfficiency) {
  EXPECT_EQ(wd::whitecaps_opacity(0.0), 1.0);
  EXPECT_EQ(wd::whitecaps_opacity(1.0), 0.0);
  EXPECT_EQ(wd::whitecaps_opacity(-0.5), 1.0);
  EXPECT_EQ(wd::whitecaps_opacity(1.5), 0.0);
  // ∫0^1 (1 − q)^1.5 dq = 0.4 by the midpoint rule.
  double sum = 0;
  for (int i = 0; i < 100000; ++i) sum += wd::whitecaps_opacity((i + 0.5) / 100000);
  EXPECT_NEAR(sum / 100000, 0.4, 1e-9);
}

// The mask and its box mips in double, as whitecaps.cl builds them.
std::vector<double> maskMips(const std::vector<double>& jacobian, int n, const seasim::WhitecapsFoamLevels& levels) {
  std::vector<double> mips(static_cast<size_t>(wd::whitecaps_level_offset(n, wd::whitecaps_levels(n))));
  for (int t = 0; t < n * n; ++t) mips[t] = wd::whitecaps_mask(jacobian[t], levels.threshold, levels.rank_j.data());
  for (int level = 0; level + 1 < wd::whitecaps_levels(n); ++level) {
    const int nl = n >> level, m = nl >> 1;
    const double* src = mips.data() + wd::whitecaps_level_offset(n, level);
    double* dst = mips.data() + wd::whitecaps_level_offset(n, level + 1);
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i)
        dst[j * m + i] = wd::whitecaps_box(src[2 * j * nl + 2 * i], src[2 * j * nl + 2 * i + 1],
                                           src[(2 * j + 1) * nl + 2 * i], src[(2 * j + 1) * nl + 2 * i + 1]);
  }
  return mips;
}

// The ocean's Jacobian (004 eq. 30) from the double FFTW reference at one wind speed.
std::vector<double> jacobianAt(double wind, int n) {
  seasim::OceanConfig c;
  c.grid = n;
  c.patch_size = 100.0;
  c.wind_speed = wind;
  c.choppiness = 1.0;
  c.small_wave = 0.1;
  c.seed = 4;
  seasim::OceanCpu ocean(c);
  ocean.run(3.0);
  return ocean.jacobian();
}

// Straight down from 100 m onto exactly one tile, one pixel per texel: the mean foam of the image.
double nadirCoverage(const std::vector<double>& mips, int n, double patch) {
  WhitecapsParams p{};
  const double h = 100.0;
  p.cam_pos[1] = static_cast<float>(h);
  p.cam_forward[1] = -1.0f;
  p.cam_right[0] = 1.0f;
  p.cam_up[2] = -1.0f;
  p.tan_half_fov_y = static_cast<float>(patch / 2 / h);
  p.aspect = 1.0f;
  p.pixel_angle = static_cast<float>(2 * patch / 2 / h / n);
  p.ocean_patch = static_cast<float>(patch);
  p.ocean_n = n;
  p.width = p.height = n;
  double sum = 0;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      double hx, hz, dx, dz, minor, major;
      EXPECT_TRUE(wd::whitecaps_pixel_footprint(&p, x, y, &hx, &hz, &dx, &dz, &minor, &major));
      sum += wd::whitecaps_footprint(mips.data(), n, patch, hx, hz, dx, dz, minor, major);
    }
  return sum / (double(n) * n);
}

TEST(WhitecapsMips, KeepTheMaskMeanUpToTheOneCellTop) {
  const int n = 64;
  const std::vector<double> j = jacobianAt(12.0, n);
  const seasim::WhitecapsFoamLevels levels = seasim::whitecapsFoamLevels(std::vector<float>(j.begin(), j.end()), 0.05);
  const std::vector<double> mips = maskMips(j, n, levels);
  const double mean0 = std::accumulate(mips.begin(), mips.begin() + n * n, 0.0) / (n * n);
  EXPECT_NEAR(mips.back(), mean0, 1e-15);
  // The foam texels' mean opacity is Koepke's efficiency factor (205 texels: the rank table's error).
  EXPECT_NEAR(mean0 / 0.05, 0.4, 0.01);
  // Far away (a footprint wider than the tile) the foam is the tile's mean.
  EXPECT_NEAR(wd::whitecaps_read(mips.data(), n, 100.0, 13.7, -250.0, 1e5), mean0, 1e-15);
}

// The image's foam against Monahan's W at three winds and one more that no choice in the model was
// made at (the threshold is computed, not tuned; 12.5 m/s is only tested here). The tile is 256²
// texels, so rounding W N² to whole texels is within 0.2 % of W at 5 m/s (61 texels). The foam's
// mean opacity is 0.4 (Koepke's efficiency factor), so the image is 0.4 W of foam.
TEST(WhitecapsCoverage, ANadirViewOverATileIsFoamAtMonahansFraction) {
  const int n = 256;
  for (double wind : {5.0, 10.0, 15.0, 12.5}) {
    const std::vector<double> j = jacobianAt(wind, n);
    const double w = wd::whitecaps_coverage(wind);
    const seasim::WhitecapsFoamLevels levels = seasim::whitecapsFoamLevels(std::vector<float>(j.begin(), j.end()), w);
    const double f = nadirCoverage(maskMips(j, n, levels), n, 100.0);
    std::printf("wind %.1f m/s: 0.4 x Monahan W %.6f, image %.6f (ratio %.4f)\n", wind, 0.4 * w, f, f / (0.4 * w));
    EXPECT_NEAR(f / (0.4 * w), 1.0, 0.03) << "wind " << wind;
  }
}

TEST(WhitecapsComposite, IsExactAtTheEndsAndFiniteForExtremeRadiances) {
  EXPECT_EQ(wf::whitecaps_composite(0.123f, 0.0f, 5.0f), 0.123f);
  EXPECT_EQ(wf::whitecaps_composite(0.123f, 1.0f, 5.0f), 5.0f);
  for (float sea : {0.0f, 1e-30f, 3.0e38f})
    for (float f : {0.0f, 0.3f, 1.0f}) EXPECT_TRUE(std::isfinite(wf::whitecaps_composite(sea, f, 1e3f)));
}

// ---- the plan ---------------------------------------------------------------------------------

TEST(WhitecapsPlan, AbsentUnlessAskedForOnAnFftSea) {
  EXPECT_FALSE(seasim::makePlan(shipped("tropical_lagoon.toml")).hasPass("whitecaps"));  // the default is off
  EXPECT_FALSE(seasim::makePlan(shipped("whitecaps.toml", {set("surface.whitecaps", "false")})).hasPass("whitecaps"));
  EXPECT_FALSE(seasim::makePlan(shipped("flat_sea.toml", {set("surface.whitecaps", "true")})).hasPass("whitecaps"));
  // An FFT surface seen from below has no sea-from-above image to put foam on.
  EXPECT_FALSE(seasim::makePlan(shipped("whitecaps.toml", {set("camera.position", "[0.0, -5.0, 0.0]"),
                                                           set("camera.look_at", "[0.0, -6.0, -10.0]")}))
                   .hasPass("whitecaps"));
}

TEST(WhitecapsPlan, PresentAfterTheSeaWhenAskedReadingTheOceanAndTheImage) {
  const seasim::Plan plan = seasim::makePlan(shipped("whitecaps.toml"));
  ASSERT_TRUE(plan.hasPass("whitecaps"));
  std::vector<std::string> names;
  for (const auto& p : plan.passes) names.push_back(p.name);
  const auto at = [&](const char* name) { return std::find(names.begin(), names.end(), name) - names.begin(); };
  EXPECT_LT(at("ocean_fft"), at("whitecaps"));
  EXPECT_LT(at("sea_single"), at("whitecaps"));
  EXPECT_LT(at("whitecaps"), at("nonfinite_check"));
  const seasim::PassPlan* entry = plan.find("whitecaps");
  EXPECT_EQ(entry->reads, (std::vector<std::string>{"ocean_maps", "rgb"}));
  EXPECT_EQ(entry->writes, (std::vector<std::string>{"rgb"}));
  // With the second order, the foam covers it too.
  const seasim::Plan second = seasim::makePlan(
      shipped("whitecaps.toml", {set("sea.model", "\"paper\""), set("sea.second_order", "true")}));  // paper 000 has one
  std::vector<std::string> order;
  for (const auto& p : second.passes) order.push_back(p.name);
  EXPECT_LT(std::find(order.begin(), order.end(), "sea_second"), std::find(order.begin(), order.end(), "whitecaps"));
  // Its buffers are in the memory budget.
  bool mips = false;
  for (const auto& b : seasim::estimateBuffers(shipped("whitecaps.toml"), plan))
    mips = mips || (b.pass == "whitecaps" && b.bytes > 4.0 * 256 * 256);
  EXPECT_TRUE(mips);
}

TEST(WhitecapsPlan, AskedForOnASeaWithoutChoppinessIsAnErrorNamingTheKey) {
  try {
    (void)seasim::makePlan(shipped("wavy_sea.toml", {set("surface.whitecaps", "true")}));
    FAIL() << "no error";
  } catch (const seasim::InputError& e) {
    EXPECT_EQ(e.key(), "surface.whitecaps");
    EXPECT_NE(std::string(e.what()).find("choppiness"), std::string::npos) << e.what();
  }
}

TEST(WhitecapsKey, IsDeclaredByItsModelAndCheckedLikeAnyKey) {
  EXPECT_EQ(seasim::modelKey(shipped("tropical_lagoon.toml"), "surface.whitecaps"), 0.0);
  EXPECT_EQ(seasim::modelKey(shipped("ocean_noon.toml"), "surface.whitecaps"), 1.0);
  EXPECT_EQ(seasim::modelKey(shipped("whitecaps.toml"), "surface.whitecaps"), 1.0);
  EXPECT_EQ(seasim::modelKey(seasim::Scene{}, "surface.whitecaps"), 0.0);  // a scene built in code: the default
  try {
    (void)shipped("whitecaps.toml", {set("surface.whitecaps", "3")});
    FAIL() << "no error";
  } catch (const seasim::InputError& e) {
    EXPECT_EQ(e.key(), "surface.whitecaps");
    EXPECT_NE(std::string(e.what()).find("expected true or false"), std::string::npos) << e.what();
  }
  try {
    (void)shipped("whitecaps.toml", {set("surface.whitecap", "true")});
    FAIL() << "no error";
  } catch (const seasim::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("whitecaps"), std::string::npos) << e.what();  // did you mean
  }
}

}  // namespace
