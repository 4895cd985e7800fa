// expected_error_test.cpp — the expected error a render states (host/quality/expected_error.h): a scene
// inside a measured case reports that case and its table; a scene far from every case, or with a
// feature no case has, says "unmeasured here"; and the lookup's own error, leave-one-out over the
// shipped tables (printed; docs/error_vs_time.md quotes it).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "quality/expected_error.h"
#include "scene/scene_parser.h"

namespace {

using seasim::ExpectedError;
using seasim::MeasuredCase;

// tests/perf/underwater_regions.toml's case a 0.1, b 0.3, g 0.9, bottom 5 m, as a scene file.
const char* kUnderwater = R"(
[camera]
position = [0.0, -3.8, 0.0]
look_at = [0.0, -4.5, -8.0]
width = 32
height = 18
[sun]
zenith_deg = 30.0
[sky]
model = "uniform"
radiance = 0.05
[water]
wavelengths_nm = [400.0, 700.0]
a = [0.1, 0.1]
b = [0.3, 0.3]
g = 0.9
[surface]
type = "flat"
[bottom]
type = "flat"
depth = 5.0
[underwater]
caustics = "none"
)";

// tests/perf/lamp_glow.toml itself, the lamps' study scene: a 0.1, b 0.3, g 0.9, a 20° cone 3 m above the
// bottom (the lamp at y = -4, the bottom at 7 m), no daylight: the lamps' measured case.
std::string lampGlowText() {
  std::ifstream in(std::string(SEASIM_SOURCE_DIR) + "/tests/perf/lamp_glow.toml");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

seasim::Scene scene(const std::string& text, std::vector<std::pair<std::string, std::string>> sets = {}) {
  std::vector<seasim::Override> over;
  for (auto& [k, v] : sets) over.push_back(seasim::Override{k, v, seasim::SourceLoc{"test", 0}});
  return seasim::parseScene(text, "expected_error_test.toml", over);
}

TEST(ExpectedError, AMeasuredUnderwaterCaseReportsThatCaseAndItsTable) {
  const auto errors = seasim::expectedErrors(scene(kUnderwater));
  ASSERT_EQ(errors.size(), 1u);
  const ExpectedError& e = errors[0];
  EXPECT_EQ(e.view, "underwater");
  EXPECT_EQ(e.model, "discrete_ordinates");  // the default
  EXPECT_TRUE(e.measured);
  EXPECT_NEAR(e.distance, 0.0, 1e-9);
  EXPECT_NEAR(e.nearest.a, 0.1, 1e-9);
  EXPECT_NEAR(e.nearest.b, 0.3, 1e-9);
  EXPECT_NEAR(e.nearest.g, 0.9, 1e-9);
  EXPECT_NEAR(e.nearest.bottom_m, 5.0, 1e-9);
  EXPECT_EQ(e.table, "results/underwater/regions.csv");
  EXPECT_LT(e.max_abs_error, 0.05);  // results/BENCHMARKS.md: every discrete-ordinates region within 5 %
  const auto thesis = seasim::expectedErrors(scene(kUnderwater, {{"underwater.model", "\"thesis\""}}));
  EXPECT_EQ(thesis[0].model, "thesis");
  EXPECT_TRUE(thesis[0].measured);
  EXPECT_GT(thesis[0].max_abs_error, 0.05);
  const nlohmann::json j = seasim::expectedErrorJson(errors);
  EXPECT_EQ(j[0]["status"], "measured");
  EXPECT_EQ(j[0]["table"], "results/underwater/regions.csv");
}

TEST(ExpectedError, FarFromEveryCaseOrWithAnUnmeasuredFeatureSaysUnmeasured) {
  // Muddy, isotropic water under a grazing sun: many doublings of a and b from every case.
  const auto far = seasim::expectedErrors(scene(kUnderwater, {{"water.a", "[3.0, 3.0]"}, {"water.b", "[6.0, 6.0]"},
                                                              {"water.g", "0.0"}, {"sun.zenith_deg", "80.0"}}));
  ASSERT_EQ(far.size(), 1u);
  EXPECT_FALSE(far[0].measured);
  EXPECT_GT(far[0].distance, seasim::kExpectedErrorMaxDistance);
  EXPECT_EQ(seasim::expectedErrorJson(far)[0]["status"], "unmeasured here");
  EXPECT_NE(seasim::expectedErrorText(far).find("UNMEASURED HERE"), std::string::npos);
  // The measured case itself, with caustics the path tracer does not draw.
  const auto caustics = seasim::expectedErrors(scene(kUnderwater, {{"underwater.caustics", "\"texture\""}}));
  EXPECT_FALSE(caustics[0].measured);
  EXPECT_NEAR(caustics[0].distance, 0.0, 1e-9);
  ASSERT_EQ(caustics[0].unmeasured_features.size(), 1u);
  EXPECT_EQ(caustics[0].unmeasured_features[0], "caustics");
}

TEST(ExpectedError, ASkyIsLookedUpAmongTheCasesMeasuredUnderIt) {
  // Preetham's sky: the cases of tests/perf/underwater_regions_sky.sh, not the uniform sky's.
  const auto preetham = seasim::expectedErrors(scene(kUnderwater, {{"sky.model", "\"preetham\""}}));
  ASSERT_EQ(preetham.size(), 1u);
  EXPECT_TRUE(preetham[0].measured);
  EXPECT_EQ(preetham[0].nearest.sky, 3);
  EXPECT_EQ(preetham[0].table, "results/underwater/regions_sky_preetham_sun30.csv");
  EXPECT_EQ(seasim::expectedErrorJson(preetham)[0]["nearest_case"]["sky"], "Preetham");
  EXPECT_NE(seasim::expectedErrorText(preetham).find("Preetham sky"), std::string::npos);
  // The uniform sky keeps its own cases.
  EXPECT_EQ(seasim::expectedErrors(scene(kUnderwater))[0].nearest.sky, 0);
  // The CIE clear sky was never measured: the nearest case for orientation, flagged.
  const auto cie = seasim::expectedErrors(scene(kUnderwater, {{"sky.model", "\"analytic\""}}));
  EXPECT_FALSE(cie[0].measured);
  ASSERT_EQ(cie[0].unmeasured_features.size(), 1u);
  EXPECT_EQ(cie[0].unmeasured_features[0], "the sky (CIE clear)");
}

TEST(ExpectedError, AHeightFieldFloorIsLookedUpAmongTheFloorsMeasured) {
  MeasuredCase flat{0.1, 0.3, 0.9, 20.0, 40};
  flat.max_abs_error = 0.01;
  MeasuredCase floor = flat;  // a shipped scene's, farther in the water than the flat one
  floor.b = 0.6;
  floor.floor = 1;
  floor.max_abs_error = 0.05;
  MeasuredCase regime = flat;
  regime.floor = 1;
  const ExpectedError e = seasim::lookupExpectedError(regime, "sea", "multiple", {flat, floor}, {});
  EXPECT_EQ(e.nearest.floor, 1);
  EXPECT_DOUBLE_EQ(e.max_abs_error, 0.05);
  EXPECT_TRUE(e.unmeasured_features.empty());
  const ExpectedError none = seasim::lookupExpectedError(regime, "sea", "multiple", {flat}, {});
  ASSERT_EQ(none.unmeasured_features.size(), 1u);
  EXPECT_EQ(none.unmeasured_features[0], "a height-field bottom");
  EXPECT_FALSE(none.measured);
  // seashore itself: its own measurement (tests/perf/scene_vs_pathtracer.sh), not the flat grid's.
  const auto shore =
      seasim::expectedErrors(seasim::loadScene(std::string(SEASIM_SOURCE_DIR) + "/scenes/seashore.toml"));
  ASSERT_EQ(shore.size(), 1u);
  EXPECT_TRUE(shore[0].measured);
  EXPECT_EQ(shore[0].table, "results/sea_allorders/seashore_vs_pathtracer.csv");
}

TEST(ExpectedError, WavesAreLookedUpAmongTheWaveScenesMeasured) {
  MeasuredCase flat{0.1, 0.3, 0.9, -1.0, 40};
  flat.max_abs_error = 0.01;
  MeasuredCase wavy = flat;  // a wave scene's, under another sun than the flat case
  wavy.sun_zenith_deg = 70;
  wavy.surface = 1;
  wavy.max_abs_error = 0.03;
  MeasuredCase regime = flat;
  regime.surface = 1;
  const ExpectedError e = seasim::lookupExpectedError(regime, "sea", "multiple", {flat, wavy}, {});
  EXPECT_EQ(e.nearest.surface, 1);
  EXPECT_DOUBLE_EQ(e.max_abs_error, 0.03);
  EXPECT_TRUE(e.unmeasured_features.empty());
  EXPECT_EQ(seasim::expectedErrorJson({e})[0]["nearest_case"]["surface"], "FFT waves");
  const ExpectedError none = seasim::lookupExpectedError(regime, "sea", "multiple", {flat}, {});
  ASSERT_EQ(none.unmeasured_features.size(), 1u);
  EXPECT_EQ(none.unmeasured_features[0], "waves");
  EXPECT_FALSE(none.measured);
  // The shipped wave scenes seen from above: each its own measurement (tests/perf/sea_waves_vs_pathtracer.sh).
  for (const char* name : {"wavy_sea", "wavy_sea_image_sky", "tropical_lagoon"}) {
    const auto s = seasim::expectedErrors(seasim::loadScene(std::string(SEASIM_SOURCE_DIR) + "/scenes/" + name + ".toml"));
    ASSERT_EQ(s.size(), 1u);
    EXPECT_TRUE(s[0].measured) << name;
    EXPECT_EQ(s[0].nearest.surface, 1) << name;
    EXPECT_NE(s[0].table.find(std::string("(") + name + ")"), std::string::npos) << name << ": " << s[0].table;
  }
  // Foam has no counterpart in the path tracer: whitecaps stays unmeasured.
  const auto foam = seasim::expectedErrors(seasim::loadScene(std::string(SEASIM_SOURCE_DIR) + "/scenes/whitecaps.toml"));
  ASSERT_EQ(foam.size(), 1u);
  EXPECT_FALSE(foam[0].measured);
  EXPECT_EQ(foam[0].unmeasured_features, std::vector<std::string>{"whitecaps"});
  // Under water no wave case was measured: the waves stay a feature there.
  const auto below = seasim::expectedErrors(scene(kUnderwater, {{"surface.type", "\"fft\""}}));
  ASSERT_EQ(below.size(), 1u);
  EXPECT_FALSE(below[0].measured);
  EXPECT_NE(std::find(below[0].unmeasured_features.begin(), below[0].unmeasured_features.end(), "waves"),
            below[0].unmeasured_features.end());
}

TEST(ExpectedError, DistanceIsOneStepPerDoublingTenthOfGAndFifteenDegrees) {
  MeasuredCase c{0.1, 0.3, 0.9, -1, 30};
  MeasuredCase s = c;
  s.a = 0.2;
  EXPECT_NEAR(seasim::regimeDistance(s, c), 1.0, 1e-12);
  s = c;
  s.g = 0.8;
  EXPECT_NEAR(seasim::regimeDistance(s, c), 1.0, 1e-9);
  s = c;
  s.sun_zenith_deg = 45;
  EXPECT_NEAR(seasim::regimeDistance(s, c), 1.0, 1e-12);
  s = c;
  s.bottom_m = 1e4;  // a bottom too deep to see is no bottom
  EXPECT_NEAR(seasim::regimeDistance(s, c), 0.0, 1e-9);
}

TEST(ExpectedError, LampsUnderWaterHaveTheirOwnEntryPerModel) {
  const auto errors = seasim::expectedErrors(scene(lampGlowText()));
  ASSERT_EQ(errors.size(), 2u);
  // The daylight view no longer flags the lamps: they have their own entry.
  EXPECT_EQ(errors[0].view, "underwater");
  EXPECT_TRUE(errors[0].unmeasured_features.empty());
  const ExpectedError& lamps = errors[1];
  EXPECT_EQ(lamps.view, "lamps");
  EXPECT_EQ(lamps.model, "orders");  // the default
  EXPECT_EQ(lamps.subject, "spotlights[0]");
  EXPECT_TRUE(lamps.measured);
  EXPECT_NEAR(lamps.distance, 0.0, 1e-3);
  EXPECT_NEAR(lamps.nearest.cone_deg, 20.0, 1e-9);
  EXPECT_NEAR(lamps.nearest.lamp_bottom_m, 3.0 * std::sqrt(0.05 * 0.05 + 0.25 + 1.0) / 0.5, 1e-3);
  EXPECT_EQ(lamps.table, "results/underwater/lamp_orders_fit.csv");
  // The orders model's worst region there is outside the beam, 0.939 of all orders (a reference of 65536 paths).
  EXPECT_NEAR(lamps.max_abs_error, 0.0614, 1e-4);
  // Delta-M sends no light outside the cone: that region is all missing (results/underwater/lamp_orders_fit.csv).
  const auto delta_m = seasim::expectedErrors(scene(lampGlowText(), {{"quality.lamps_model", "\"delta_m\""}}));
  EXPECT_EQ(delta_m[1].model, "delta_m");
  EXPECT_TRUE(delta_m[1].measured);
  EXPECT_DOUBLE_EQ(delta_m[1].max_abs_error, 1.0);
  EXPECT_DOUBLE_EQ(delta_m[1].worst_ratio, 0.0);
  const auto orders = errors;
  const nlohmann::json j = seasim::expectedErrorJson(orders);
  EXPECT_EQ(j[1]["view"], "lamps");
  EXPECT_EQ(j[1]["subject"], "spotlights[0]");
  EXPECT_EQ(j[1]["nearest_case"]["cone_deg"], 20.0);
  EXPECT_FALSE(j[0].contains("subject"));
  EXPECT_NE(seasim::expectedErrorText(orders).find("lamps orders, spotlights[0]"), std::string::npos);
  EXPECT_NE(seasim::expectedErrorText(orders).find("cone 20 deg"), std::string::npos);
}

TEST(ExpectedError, ALampsRegimeWithObjectsIsLookedUpAmongTheCasesWithObjects) {
  // Objects in the light (the glow and the blur ignore their shadows): the only lamp case with objects is
  // rov_lights' own measurement (tests/perf/rov_lights_tiles.sh), so the scene itself is measured there...
  const auto rov = seasim::expectedErrors(seasim::loadScene(std::string(SEASIM_SOURCE_DIR) + "/scenes/rov_lights.toml"));
  ASSERT_EQ(rov.size(), 2u);
  EXPECT_EQ(rov[1].model, "orders");
  EXPECT_TRUE(rov[1].measured);
  EXPECT_NEAR(rov[1].distance, 0.0, 1e-3);
  EXPECT_EQ(rov[1].nearest.objects, 1);
  EXPECT_EQ(rov[1].table, "results/underwater/rov_lights_lamps_tiles.csv (rov_lights)");
  EXPECT_NEAR(rov[1].worst_ratio, 0.835, 1e-3);  // the far water above the beams (results/BENCHMARKS.md)
  // ...and lamp_glow's water with a rock is looked up there too, not among the cases without objects.
  const auto rocks = seasim::expectedErrors(scene(lampGlowText() + R"(
[[objects]]
type = "sphere"
center = [0.0, -6.0, -3.0]
radius = 0.3
)"));
  EXPECT_EQ(rocks[1].nearest.objects, 1);
  EXPECT_TRUE(rocks[1].unmeasured_features.empty());
  // Where no case has objects, they are a feature by name.
  MeasuredCase bare{0.1, 0.3, 0.9, -1, 0};
  bare.cone_deg = 20;
  MeasuredCase regime = bare;
  regime.objects = 1;
  const ExpectedError none = seasim::lookupExpectedError(regime, "lamps", "orders", {bare}, {});
  EXPECT_FALSE(none.measured);
  EXPECT_EQ(none.unmeasured_features, std::vector<std::string>{"objects in the lamps' light"});
}

TEST(ExpectedError, ALampsRegimeFollowsItsBeamAndKeepsTheWorstLamp) {
  // A lamp pointing up never meets the bottom: its beam is the open water's, f_l = 1, a share e^{-c l} of a
  // step from the measured case whose bottom is l = 6.71 m along the axis.
  const auto up = seasim::expectedErrors(scene(lampGlowText(), {{"spotlights[0].direction", "[0.0, 1.0, 0.0]"}}));
  const auto here = seasim::expectedErrors(scene(lampGlowText()));
  EXPECT_NEAR(up[1].distance, std::exp(-0.4 * here[1].nearest.lamp_bottom_m) / 0.25, 1e-3);
  // Two lamps: the entry is the worse one's. A 60° cone in the same water is a doubling and a half away.
  const auto two = seasim::expectedErrors(scene(lampGlowText() + R"(
[[spotlights]]
position = [-0.4, -4.0, -0.3]
direction = [0.05, -0.5, -1.0]
cone_deg = 60.0
intensity = 10.0
)"));
  ASSERT_EQ(two.size(), 2u);
  const auto first = seasim::expectedErrors(scene(lampGlowText()));
  EXPECT_GE(two[1].max_abs_error, first[1].max_abs_error);
  EXPECT_TRUE(two[1].subject == "spotlights[0]" || two[1].subject == "spotlights[1]");
  if (two[1].measured == first[1].measured && two[1].max_abs_error > first[1].max_abs_error)
    EXPECT_EQ(two[1].subject, "spotlights[1]");
  // A lamp's cone: one step per doubling; its beam: one step per quarter of the light taken before the bottom.
  MeasuredCase c{0.1, 0.3, 0.9, -1, 0};
  c.cone_deg = 20;
  c.lamp_bottom_m = -1;
  MeasuredCase s = c;
  s.cone_deg = 40;
  EXPECT_NEAR(seasim::regimeDistance(s, c), 1.0, 1e-12);
  s = c;
  s.lamp_bottom_m = -std::log(0.25) / 0.4;  // 75 % taken: a quarter from none
  EXPECT_NEAR(seasim::regimeDistance(s, c), 1.0, 1e-12);
  s.cone_deg = 0;  // a daylight regime against a lamp's case: no lamp terms
  EXPECT_NEAR(seasim::regimeDistance(s, c), 0.0, 1e-12);
  // Seen from above the lamps have no entry and stay a feature of the sea's.
  const auto above = seasim::expectedErrors(scene(lampGlowText(), {{"camera.position", "[0.0, 5.0, 0.0]"},
                                                          {"spotlights[0].position", "[0.4, 4.0, -0.3]"}}));
  ASSERT_EQ(above.size(), 1u);
  EXPECT_EQ(above[0].unmeasured_features, std::vector<std::string>{"spotlights"});
}

TEST(ExpectedError, TheLookupsOwnErrorLeaveOneOut) {
  // Each measured regime predicted from the nearest other regime (cases at distance 0, the other
  // views of the same regime, left out with it), where that one is within the threshold.
  for (const char* vm : {"sea/paper", "sea/multiple", "underwater/thesis", "underwater/discrete_ordinates",
                         "lamps/single", "lamps/delta_m", "lamps/orders"}) {
    const std::string view = std::string(vm).substr(0, std::string(vm).find('/'));
    const std::string model = std::string(vm).substr(view.size() + 1);
    const std::vector<MeasuredCase> cases = seasim::loadMeasuredCases(view, model);
    ASSERT_FALSE(cases.empty()) << vm;
    std::vector<double> miss;
    int unmeasured = 0;
    for (const MeasuredCase& c : cases) {
      std::vector<MeasuredCase> others;
      for (const MeasuredCase& o : cases)
        if (seasim::regimeDistance(c, o) > 1e-9 || o.sky != c.sky) others.push_back(o);
      const ExpectedError e = seasim::lookupExpectedError(c, view, model, others, {});
      if (!e.measured) {
        ++unmeasured;
        continue;
      }
      // The worst region of the regime (the largest error among its views) against the prediction.
      double actual = 0;
      for (const MeasuredCase& o : cases)
        if (seasim::regimeDistance(c, o) <= 1e-9 && o.sky == c.sky) actual = std::max(actual, o.max_abs_error);
      miss.push_back(std::fabs(e.max_abs_error - actual));
    }
    std::sort(miss.begin(), miss.end());
    const double median = miss.empty() ? 0 : miss[miss.size() / 2];
    const double p90 = miss.empty() ? 0 : miss[std::min(miss.size() - 1, miss.size() * 9 / 10)];
    std::printf("%s: %zu cases, %zu predicted, %d without a neighbour within the threshold; |predicted - measured| "
                "median %.3f, 90th percentile %.3f\n",
                vm, cases.size(), miss.size(), unmeasured, median, p90);
    EXPECT_FALSE(miss.empty()) << vm;
  }
}

}  // namespace
