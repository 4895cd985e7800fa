// sea_multiple_kernel_test.cpp — sea.model = "multiple" in kernels/sea_single.cl on PoCL (float) against
// the same closed form evaluated in double on the CPU (host/reference/sea_reference.cpp with the scene's
// sea.model), over the ordinary scene and its stiff variants; no NaN/Inf. Also: the model really is a
// different one (brighter than paper 000's over a shallow turbid bottom, equal with no water in the
// way), and the second-order pass is left out of its plan.
#include <gtest/gtest.h>

#include <ostream>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "device/device.h"
#include "math/kernel_math.h"
#include "plan/plan.h"
#include "quality/render_frame.h"
#include "reference/sea_reference.h"
#include "scene/scene_parser.h"
#include "test_device.h"
#include "underwater/underwater_setup.h"

namespace {

const char* kScene = R"(
[scene]
name = "test_sea_multiple"
[camera]
position = [0, 5, 0]
look_at = [0, 0, -5]
fov_deg = 60
width = 48
height = 27
[sun]
zenith_deg = 40
azimuth_deg = 90
[sky]
radiance = 0.05
[water]
jerlov = "III"
[bottom]
type = "flat"
depth = 5
albedo = 0.3
[sea]
model = "multiple"
[spectral]
count = 8
)";

seasim::Device& device() { return seasim::test::testDevice(); }

seasim::Override set(const char* key, const char* value) { return {key, value, {"test", 1}}; }

// Max over pixels and channels of |kernel - reference| / (|reference| + 1e-3 of the image's peak).
double maxRelativeError(const seasim::Image& a, const seasim::Image& ref) {
  float peak = 0;
  for (float v : ref.pixels) peak = std::max(peak, std::fabs(v));
  double worst = 0;
  for (size_t i = 0; i < ref.pixels.size(); ++i)
    worst = std::max(worst, std::fabs(double(a.pixels[i]) - ref.pixels[i]) / (std::fabs(ref.pixels[i]) + 1e-3 * peak));
  return worst;
}

double mean(const seasim::Image& img) {
  double s = 0;
  for (float v : img.pixels) s += v;
  return s / img.pixels.size();
}

struct Variant {
  const char* name;
  std::vector<seasim::Override> overrides;
  bool remove_bottom = false;
};
// The case as gtest prints it (its name, not the struct's bytes).
void PrintTo(const Variant& c, std::ostream* os) { *os << c.name; }

class SeaMultipleKernel : public ::testing::TestWithParam<Variant> {};

TEST_P(SeaMultipleKernel, MatchesDoubleEvaluationWithoutNaN) {
  std::string text = kScene;
  if (GetParam().remove_bottom) text.erase(text.find("[bottom]"), text.find("[sea]") - text.find("[bottom]"));
  const seasim::Scene scene = seasim::parseScene(text, "test_sea_multiple.toml", GetParam().overrides);
  const seasim::Plan plan = seasim::makePlan(scene);
  const seasim::FrameResult frame = seasim::renderFrame(device(), scene, plan);
  EXPECT_EQ(frame.nonfinite, 0);
  for (float v : frame.rgb.pixels) ASSERT_TRUE(std::isfinite(v));
  const seasim::Image ref = seasim::renderSeaReference(scene, 1);  // closed form: no quadrature steps
  const double err = maxRelativeError(frame.rgb, ref);
  std::printf("[ measured ] %s: max rel. error float kernel vs double %.3g\n", GetParam().name, err);
  EXPECT_LT(err, 2e-4) << GetParam().name;
}

INSTANTIATE_TEST_SUITE_P(
    Scenes, SeaMultipleKernel,
    ::testing::Values(Variant{"ordinary", {}},
                      Variant{"no_bottom", {}, true},
                      Variant{"second_order_asked_for", {set("sea.second_order", "true")}},
                      Variant{"shallow_turbid", {set("water.jerlov", "\"9C\""), set("bottom.depth", "0.2")}},
                      Variant{"bottom_at_the_surface", {set("bottom.depth", "0")}},
                      Variant{"deep", {set("bottom.depth", "10000")}},
                      Variant{"sun_below_horizon", {set("sun.zenith_deg", "100")}},
                      // The sky's light in the water column stays when the sun is off (the plan once
                      // dropped the column with the sun).
                      Variant{"sun_off", {set("sun.enabled", "false")}},
                      Variant{"sun_of_zero_irradiance", {set("sun.irradiance", "0")}},
                      Variant{"grazing_sun", {set("sun.zenith_deg", "89.9")}},
                      Variant{"grazing_view", {set("camera.look_at", "[0, 5, -100]")}},
                      Variant{"looking_straight_down", {set("camera.look_at", "[0, 0, -0.001]")}},
                      Variant{"very_clear_water",
                              {set("water", "{ wavelengths_nm = [400, 700], a = [1e-6, 1e-6], b = [1e-6, 1e-6] }")}},
                      Variant{"isotropic", {set("water.g", "0")}},
                      Variant{"strong_forward", {set("water.g", "0.99")}},
                      Variant{"no_sky", {set("sky.radiance", "0")}},
                      Variant{"no_single_scattering_bottom_only", {set("sea.single_scattering", "false")}}),
    [](const ::testing::TestParamInfo<Variant>& info) { return std::string(info.param.name); });

TEST(SeaMultipleKernel, PlanShowsTheModelAndLeavesOutTheSecondOrder) {
  const seasim::Scene multiple = seasim::parseScene(kScene, "m.toml", {set("sea.second_order", "true")});
  const seasim::Plan plan = seasim::makePlan(multiple);
  ASSERT_TRUE(plan.hasPass("sea_single"));
  const auto& defines = plan.find("sea_single")->defines;
  EXPECT_NE(std::find(defines.begin(), defines.end(), "SEASIM_SEA_MODEL=1"), defines.end());
  EXPECT_FALSE(plan.hasPass("sea_second"));  // all orders are in the closed form
  EXPECT_NE(plan.toText().find("-DSEASIM_SEA_MODEL=1"), std::string::npos);
  const seasim::Scene paper =
      seasim::parseScene(kScene, "p.toml", {set("sea.model", "\"paper\""), set("sea.second_order", "true")});
  const seasim::Plan paper_plan = seasim::makePlan(paper);
  const auto& paper_defines = paper_plan.find("sea_single")->defines;
  EXPECT_NE(std::find(paper_defines.begin(), paper_defines.end(), "SEASIM_SEA_MODEL=0"), paper_defines.end());
  EXPECT_TRUE(paper_plan.hasPass("sea_second"));
}

TEST(SeaMultipleKernel, BrighterThanPaperOverAShallowTurbidBottomAndEqualWithoutWater) {
  // Jerlov III over 2 m: paper 000's bottom (eq. 9, c both ways) is nearly black; the bottom seen
  // through forward-scattering water is not.
  const seasim::Scene m = seasim::parseScene(kScene, "m.toml", {set("bottom.depth", "2")});
  const seasim::Scene p = seasim::parseScene(kScene, "p.toml", {set("bottom.depth", "2"), set("sea.model", "\"paper\"")});
  const double lm = mean(seasim::renderFrame(device(), m, seasim::makePlan(m)).rgb);
  const double lp = mean(seasim::renderFrame(device(), p, seasim::makePlan(p)).rgb);
  std::printf("[ measured ] Jerlov III over 2 m: image mean multiple %.4g, paper %.4g\n", lm, lp);
  EXPECT_GT(lm, 2 * lp);
  // Without water between the surface and the bottom (depth 0) and without sky, both models show the
  // sun on the bottom, ρ/π E T_i T_o; "multiple" with the bottom-surface bounces 1/(1 - ρ r_below).
  const std::vector<seasim::Override> dry = {set("bottom.depth", "0"), set("sky.radiance", "0")};
  std::vector<seasim::Override> dry_paper = dry;
  dry_paper.push_back(set("sea.model", "\"paper\""));
  const seasim::Scene m0 = seasim::parseScene(kScene, "m0.toml", dry);
  const seasim::Scene p0 = seasim::parseScene(kScene, "p0.toml", dry_paper);
  const double l0m = mean(seasim::renderFrame(device(), m0, seasim::makePlan(m0)).rgb);
  const double l0p = mean(seasim::renderFrame(device(), p0, seasim::makePlan(p0)).rgb);
  EXPECT_GT(l0p, 0);
  const double r_below = seasim::kmath_d::sea_surface_reflectance_below(seasim::skyFresnelMean(1.333), 1.333);
  EXPECT_NEAR(l0m / l0p, 1.0 / (1.0 - 0.3 * r_below), 1e-5);
}

}  // namespace
