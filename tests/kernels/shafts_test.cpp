// shafts_test.cpp — kernels/shafts.cl on PoCL (float):
//  * the sampling-plane integrator (001 eq. 5) with fine n and its far-field closed form against the
//    closed-form airlight of an isotropic point light (Sun et al. 2005) from the eye to infinity,
//    over lamp positions (in the frustum, beside it, behind the camera) and extinctions (0 ... 0.5/m),
//    exact g and tables;
//  * spot_sphere (001 Figure 6) at the paper's n = 30, m = 6 against the double ray-marched
//    reference with exact shadow rays: RMS in 8-bit levels under the paper's 2.6 % of 256 levels,
//    and sub-sample planes reducing the error (m = 6 vs m = 1);
//  * stiff cases: camera inside a cone, a sample at the lamp (s -> 0), ρκ = 0 and ρκ large, a light
//    behind the camera, grazing planes (fov 170°): no NaN/Inf, and close to the reference, with every
//    method (quality.shafts_method "planes", "intervals" and "march");
//  * the march (quality.shafts_method "march") against the reference at the same steps: the same
//    quadrature in float and double, so equal to rounding, and converging with the steps.
// The planes tests set quality.shafts_method = "planes" (the default is intervals).
// Reduced resolutions keep the suite to a few seconds.
#include <gtest/gtest.h>

#include <ostream>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "device/device.h"
#include "test_device.h"
#include "quality/render_frame.h"
#include "passes/shafts_pass.h"
#include "plan/plan.h"
#include "reference/compare.h"
#include "reference/shafts_reference.h"
#include "scene/scene_parser.h"

namespace {

using seasim::Override;

seasim::Device& device() { return seasim::test::testDevice(); }

Override set(const std::string& key, const std::string& value) { return {key, value, {"test", 1}}; }

const std::string kSpotSphere = std::string(SEASIM_SOURCE_DIR) + "/scenes/spot_sphere.toml";

// Renders `scene` with the shafts pass and an explicit config; returns linear RGB.
seasim::Image renderWith(const seasim::Scene& scene, const seasim::ShaftsPass::Config& config) {
  const seasim::Plan plan = seasim::makePlan(scene);
  seasim::ShaftsPass pass(device(), scene, *plan.find("shafts"), config);
  pass.run();
  seasim::Image img;
  img.resize(scene.camera.width, scene.camera.height, 3);
  pass.readRgb(img.pixels);
  return img;
}

// ---- Sun et al. 2005: an isotropic point light, no objects. Two back-to-back half-space lamps
// (cone = 90°, no fall-off) at one point make it isotropic (the plane between them has measure zero).
struct SunCase {
  double lamp[3];
  double sigma_t;
  bool exact;
  bool march = false;  // quality.shafts_method = "march" at 4000 steps instead of 4000 planes
};
// The case as gtest prints it (its name, not the struct's bytes).
void PrintTo(const SunCase& c, std::ostream* os) {
  *os << "lamp (" << c.lamp[0] << ", " << c.lamp[1] << ", " << c.lamp[2] << "), sigma_t " << c.sigma_t
      << (c.march ? ", march" : c.exact ? ", exact" : ", planes");
}

class ShaftsVsSun : public ::testing::TestWithParam<SunCase> {};

TEST_P(ShaftsVsSun, FinePlanesTheFarFieldAndTheMarchMatchTheClosedFormToInfinity) {
  const SunCase c = GetParam();
  const double rho = 0.1;  // scattering coefficient, 1/m
  char text[1024];
  std::snprintf(text, sizeof text, R"(
[camera]
position = [0, 0, 0]
look_at = [0, 0, -1]
fov_deg = 60
width = 48
height = 32
[air]
density = %g
extinction = %g
phase = "hg"
g = 0
[[spotlights]]
position = [%g, %g, %g]
direction = [0, 0, 1]
intensity = 40
[[spotlights]]
position = [%g, %g, %g]
direction = [0, 0, -1]
intensity = 40
[quality]
shafts_exact = %s
shafts_method = "%s"
shafts_march_steps = 4000
)",
                rho, c.sigma_t / rho, c.lamp[0], c.lamp[1], c.lamp[2], c.lamp[0], c.lamp[1], c.lamp[2],
                c.exact ? "true" : "false", c.march ? "march" : "planes");
  seasim::Scene scene = seasim::parseScene(text, "sun.toml");
  for (auto& l : scene.spotlights) {
    l.cone = M_PI / 2;
    l.falloff = 0;
  }
  seasim::ShaftsPass::Config config;
  config.planes = 4000;
  config.subplanes = 1;
  config.march_steps = 4000;
  const seasim::Image img = renderWith(scene, config);

  const double tan_half = std::tan(M_PI / 6), aspect = 1.5;
  const double D = std::sqrt(c.lamp[0] * c.lamp[0] + c.lamp[1] * c.lamp[1] + c.lamp[2] * c.lamp[2]);
  double worst = 0;
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 48; ++x) {
      const double u = (2.0 * (x + 0.5) / 48 - 1.0) * tan_half * aspect, v = (1.0 - 2.0 * (y + 0.5) / 32) * tan_half;
      const double len = std::sqrt(u * u + v * v + 1);
      const double d[3] = {u / len, v / len, -1 / len};
      const double cos_gamma = (d[0] * c.lamp[0] + d[1] * c.lamp[1] + d[2] * c.lamp[2]) / D;
      // Open medium: the whole ray, from the eye to infinity.
      const double expected = seasim::sunAirlight(rho, c.sigma_t, 40, D, std::acos(cos_gamma), INFINITY);
      const double got = img.at(x, y, 1);
      ASSERT_TRUE(std::isfinite(got));
      worst = std::max(worst, std::fabs(got - expected) / expected);
    }
  std::printf("[ measured ] lamp (%g, %g, %g), rho kappa = %g, %s: max relative error %.3g\n", c.lamp[0], c.lamp[1],
              c.lamp[2], c.sigma_t, c.march ? "march" : c.exact ? "exact g" : "tables", worst);
  EXPECT_LT(worst, 1e-3);  // measured 6e-6 ... 5e-4 (tables, and the 90° half-space edge through the lamp)
}

INSTANTIATE_TEST_SUITE_P(
    Configurations, ShaftsVsSun,
    ::testing::Values(SunCase{{0.5, 0.3, -5}, 0.0, true}, SunCase{{0.5, 0.3, -5}, 0.1, true},
                      SunCase{{0.5, 0.3, -5}, 0.5, true}, SunCase{{0.5, 0.3, -5}, 0.1, false},
                      SunCase{{6, -1, -3}, 0.1, true}, SunCase{{6, -1, -3}, 0.0, false},
                      SunCase{{0.5, 1, 4}, 0.1, true}, SunCase{{0.5, 1, 4}, 0.5, false},
                      SunCase{{-0.2, -0.7, -12}, 0.02, true}, SunCase{{0.5, 0.3, -5}, 0.1, true, true},
                      SunCase{{6, -1, -3}, 0.0, true, true}, SunCase{{0.5, 1, 4}, 0.5, true, true}));

// ---- spot_sphere against the ray-marched reference.
double rmsVsReference(const seasim::Scene& scene, const seasim::Image& ref, int n, int m) {
  seasim::ShaftsPass::Config config = seasim::ShaftsPass::configFromScene(scene);
  config.planes = n;
  config.subplanes = m;
  const seasim::Image img = renderWith(scene, config);
  const seasim::CompareResult c = seasim::compareImages(img, ref, scene.camera.exposure_ev);
  EXPECT_EQ(c.nonfinite, 0);
  return c.rmse_8bit;
}

TEST(ShaftsVsReference, SpotSphereAtThePapersSettingBeatsItsError) {
  const seasim::Scene scene =
      seasim::loadScene(kSpotSphere, {set("camera.width", "180"), set("camera.height", "120"),
                                      set("quality.shafts_method", "\"planes\"")});
  const seasim::Image ref = seasim::renderShaftsReference(scene, 600);
  const double rms_30_6 = rmsVsReference(scene, ref, 30, 6);
  const double rms_30_1 = rmsVsReference(scene, ref, 30, 1);
  std::printf("[ measured ] spot_sphere 180x120: RMS %.3f levels (n=30, m=6), %.3f (n=30, m=1); paper: 6.66\n",
              rms_30_6, rms_30_1);
  EXPECT_LT(rms_30_6, 0.026 * 256);  // 001 §5.1: 2.6 % of 256 levels
  EXPECT_LT(rms_30_6, 0.1);          // measured 0.010 with the per-lamp cone ranges (0.11 with global planes)
  EXPECT_LT(rms_30_6, rms_30_1);     // sub-sample planes remove shadow aliasing (001 §4.3)
}

TEST(ShaftsVsReference, StageWithFiveLightsAndAGoboBeatsThePapersError) {
  const std::string stage = std::string(SEASIM_SOURCE_DIR) + "/scenes/stage.toml";
  const seasim::Scene scene = seasim::loadScene(
      stage, {set("camera.width", "144"), set("camera.height", "96"), set("quality.shafts_method", "\"planes\"")});
  ASSERT_EQ(scene.spotlights.size(), 5u);
  const seasim::Image ref = seasim::renderShaftsReference(scene, 600);
  const double rms = rmsVsReference(scene, ref, 30, 6);
  std::printf("[ measured ] stage 144x96: RMS %.3f levels (n=30, m=6)\n", rms);
  EXPECT_LT(rms, 0.026 * 256);
}

TEST(ShaftsVsReference, RenderFrameRunsThePlannedPasses) {
  const seasim::Scene scene = seasim::loadScene(
      kSpotSphere, {set("camera.width", "72"), set("camera.height", "48"), set("quality.shafts_method", "\"planes\"")});
  const seasim::Plan plan = seasim::makePlan(scene);
  ASSERT_TRUE(plan.find("shafts")->implemented);
  const seasim::FrameResult frame = seasim::renderFrame(device(), scene, plan);
  EXPECT_EQ(frame.nonfinite, 0);
  ASSERT_EQ(frame.timings.size(), 3u);
  EXPECT_EQ(frame.timings[0].name, "shadow_maps");
  EXPECT_EQ(frame.timings[1].name, "shafts");
  double sum = 0;
  for (float v : frame.rgb.pixels) sum += v;
  EXPECT_GT(sum, 0);
}

// ---- the march: the reference's quadrature in the kernel.
seasim::Scene marchScene(const std::string& file, int width, int height, int steps) {
  return seasim::loadScene(file, {set("camera.width", std::to_string(width)), set("camera.height", std::to_string(height)),
                                  set("quality.shafts_method", "\"march\""),
                                  set("quality.shafts_march_steps", std::to_string(steps))});
}

// spot_sphere (a sphere's shadow) and stage (five lamps, a gobo light map, boxes): the kernel's march at
// N steps is the CPU reference at N steps (the same midpoint rule in the lamp's angle, the same exact
// shadow rays), float against double; and more steps come nearer the 2000-step reference.
TEST(ShaftsMarch, IsTheReferencesQuadratureAndConverges) {
  const std::string stage = std::string(SEASIM_SOURCE_DIR) + "/scenes/stage.toml";
  for (const std::string& file : {kSpotSphere, stage}) {
    const seasim::Image fine = seasim::renderShaftsReference(marchScene(file, 96, 64, 1), 2000);
    double previous = 1e30;
    for (int steps : {5, 20, 80}) {
      const seasim::Scene scene = marchScene(file, 96, 64, steps);
      const seasim::Plan plan = seasim::makePlan(scene);
      const seasim::FrameResult frame = seasim::renderFrame(device(), scene, plan);
      EXPECT_EQ(frame.nonfinite, 0);
      const seasim::Image same = seasim::renderShaftsReference(scene, steps);
      const seasim::CompareResult c = seasim::compareImages(frame.rgb, same, scene.camera.exposure_ev);
      const seasim::CompareResult f = seasim::compareImages(frame.rgb, fine, scene.camera.exposure_ev);
      std::printf("[ measured ] %s march %d steps: against the reference at %d steps RMS %.4f levels, rel L2 %.2g; "
                  "against 2000 steps RMS %.3f levels\n",
                  file.substr(file.rfind('/') + 1).c_str(), steps, steps, c.rmse_8bit, c.rel_l2, f.rmse_8bit);
      EXPECT_LT(c.rel_l2, 1e-3) << steps;
      EXPECT_LT(c.rmse_8bit, 0.05) << steps;
      EXPECT_LT(f.rmse_8bit, previous) << steps;
      previous = f.rmse_8bit;
    }
  }
}

// The march plans no shadow maps (its shadow rays are exact), says so, and compiles its own variant.
TEST(ShaftsMarch, PlansNoShadowMapsAndNamesItsSteps) {
  const seasim::Scene scene = marchScene(kSpotSphere, 64, 40, 12);
  const seasim::Plan plan = seasim::makePlan(scene);
  EXPECT_EQ(plan.find("shadow_maps"), nullptr);
  const seasim::PassPlan* shafts = plan.find("shafts");
  ASSERT_NE(shafts, nullptr);
  EXPECT_NE(shafts->why.find("method march"), std::string::npos) << shafts->why;
  bool march_define = false, intervals_define = false;
  for (const std::string& d : shafts->defines) {
    march_define = march_define || d == "SEASIM_SHAFTS_MARCH=1";
    intervals_define = intervals_define || d == "SEASIM_SHAFTS_INTERVALS=1";
  }
  EXPECT_TRUE(march_define);
  EXPECT_FALSE(intervals_define);
  const seasim::FrameResult frame = seasim::renderFrame(device(), scene, plan);
  ASSERT_EQ(frame.timings.size(), 2u);  // shafts and the NaN/Inf check
  EXPECT_EQ(frame.timings[0].name, "shafts");
}

// ---- stiff cases: no NaN/Inf, and the fast method still near the reference.
struct Stiff {
  const char* name;
  std::vector<Override> overrides;
  double max_rms;  // 8-bit levels vs the reference
  bool lit = true;  // the reference shows light (not all attenuated away)
  double max_rel_l2 = 0.05;
};
// The case as gtest prints it (its name, not the struct's bytes).
void PrintTo(const Stiff& c, std::ostream* os) { *os << c.name; }

class ShaftsStiff : public ::testing::TestWithParam<Stiff> {};

TEST_P(ShaftsStiff, FiniteAndNearTheReference) {
  std::vector<Override> o = {set("camera.width", "64"), set("camera.height", "40")};
  for (const auto& x : GetParam().overrides) o.push_back(x);
  const seasim::Image ref = seasim::renderShaftsReference(seasim::loadScene(kSpotSphere, o), 2000);
  double ref_sum = 0;
  for (float v : ref.pixels) ref_sum += v;
  // Every method: the sampling planes, the intervals and the march (at its default steps).
  for (const char* method : {"planes", "intervals", "march"}) {
    std::vector<Override> om = o;
    om.push_back(set("quality.shafts_method", std::string("\"") + method + "\""));
    const seasim::Scene scene = seasim::loadScene(kSpotSphere, om);
    const seasim::FrameResult frame = seasim::renderFrame(device(), scene, seasim::makePlan(scene));
    EXPECT_EQ(frame.nonfinite, 0) << method;
    for (float v : frame.rgb.pixels) ASSERT_TRUE(std::isfinite(v) && v >= 0) << method;
    const seasim::CompareResult c = seasim::compareImages(frame.rgb, ref, scene.camera.exposure_ev);
    std::printf("[ measured ] %s, %s: RMS %.3f levels, max %.2f, rel L2 %.3g\n", GetParam().name, method, c.rmse_8bit,
                c.max_abs_8bit, c.rel_l2);
    EXPECT_LT(c.rmse_8bit, GetParam().max_rms) << method;
    if (GetParam().lit) {
      EXPECT_GT(ref_sum, 0);
      EXPECT_LT(c.rel_l2, GetParam().max_rel_l2) << method;
    } else {
      EXPECT_LT(ref_sum, 1e-20);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(
    Cases, ShaftsStiff,
    ::testing::Values(
        Stiff{"camera_inside_cone", {set("camera.position", "[0.3, 1.0, -1.5]"), set("camera.look_at", "[0, 0, -4]")}, 0.5},
        Stiff{"no_extinction", {set("air.extinction", "0")}, 0.5},
        Stiff{"huge_extinction", {set("air.density", "1"), set("air.extinction", "1000")}, 0.5, false},
        Stiff{"light_behind_camera",
              {set("spotlights[0].position", "[0, 1.8, 12]"), set("spotlights[0].direction", "[0, -0.1, -1]")}, 0.5},
        Stiff{"grazing_planes",
              {set("camera.fov_deg", "170"), set("camera.width", "256"), set("camera.height", "64"),
               set("camera.look_at", "[-10, 1.6, 7]"), set("camera.exposure_ev", "3")},
              0.5, true, 0.01},  // rel L2 1e-4 (0.03 with global planes: long intervals Δz / cos θ)
        Stiff{"hg_phase", {set("air.phase", "\"hg\""), set("air.g", "0.7")}, 0.5},
        Stiff{"exact_g", {set("quality.shafts_exact", "true")}, 0.5}),
    [](const ::testing::TestParamInfo<Stiff>& info) { return std::string(info.param.name); });

TEST(ShaftsStiffLamp, ASampleExactlyAtTheLampStaysFinite) {
  // Odd resolution: the centre pixel's ray is the optical axis, through the lamp at depth 4.5 (h = 0,
  // the far field starts at 4.5 + 8 mm; plane midpoints come within 0.45 mm of the lamp), camera
  // inside the lamp's cone.
  seasim::Scene scene = seasim::parseScene(R"(
[camera]
position = [0, 0, 0]
look_at = [0, 0, -1]
width = 33
height = 21
[air]
density = 0.05
extinction = 1
[[spotlights]]
position = [0, 0, -4.5]
direction = [0, 0, 1]
cone_deg = 30
)",
                                           "lamp.toml");
  for (int variant = 0; variant < 3; ++variant) {  // planes exact, planes tables, intervals
    const bool exact = variant != 1;
    scene.quality["shafts_exact"].value = exact;
    scene.quality["shafts_method"] = seasim::Knob{false, variant == 2 ? 1.0 : 0.0};
    seasim::ShaftsPass::Config config;
    config.planes = 10;
    config.subplanes = 1;
    const seasim::Image img = renderWith(scene, config);
    for (float v : img.pixels) ASSERT_TRUE(std::isfinite(v));
    EXPECT_GT(img.at(16, 10, 0), img.at(0, 0, 0));  // the lamp itself is the brightest
  }
}

// ---- a lamp behind the camera shining away: no part of any view ray is in its cone.
namespace away {

TEST(ShaftsConeRanges, AConeBehindTheCameraGivesZeroAirlightAndNoNaN) {
  // The lamp behind the camera (z = 12 > 9) shining away from the scene (+z): no light.
  const seasim::Scene scene = seasim::loadScene(
      kSpotSphere, {set("camera.width", "64"), set("camera.height", "40"), set("spotlights[0].position", "[0, 1.8, 12]"),
                    set("spotlights[0].direction", "[0, 0.1, 1]")});
  const seasim::ShaftsRange r = seasim::ShaftsPass::rangeFor(scene);
  EXPECT_TRUE(std::isfinite(r.t_max) && r.t_max > 0 && std::isfinite(r.s_max) && r.s_max > 0);
  const seasim::Image img = renderWith(scene, seasim::ShaftsPass::configFromScene(scene));
  for (float v : img.pixels) {
    ASSERT_TRUE(std::isfinite(v));
    EXPECT_EQ(v, 0.0f);  // nothing lit: no airlight and no lit surface
  }
}

}  // namespace away

}  // namespace
