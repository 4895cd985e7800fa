// plan_test.cpp — the planner includes exactly the passes a scene needs (DESIGN.md "Leave out what a
// scene does not need"), with the feature defines that match the scene.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "passes/underwater_lamps_pass.h"
#include "plan/memory_budget.h"
#include "plan/plan.h"
#include "scene/scene_parser.h"
#include "underwater/froxel_setup.h"
#include "util/error.h"

namespace {

using seasim::makePlan;
using seasim::parseScene;
using seasim::Plan;

const char* kFlatSea = R"(
[camera]
position = [0, 10, 0]
look_at = [0, 0, -100]
[sun]
zenith_deg = 40
[water]
jerlov = "IB"
[bottom]
type = "flat"
depth = 8
)";

bool hasDefine(const Plan& plan, const std::string& pass, const std::string& define) {
  const auto* p = plan.find(pass);
  return p && std::find(p->defines.begin(), p->defines.end(), define) != p->defines.end();
}

TEST(Plan, FlatSeaNeedsOnlyTheSeaPassAndTheCheck) {
  const Plan plan = makePlan(parseScene(kFlatSea, "flat.toml"));
  ASSERT_EQ(plan.passes.size(), 2u);
  EXPECT_EQ(plan.passes[0].name, "sea_single");
  EXPECT_EQ(plan.passes[1].name, "nonfinite_check");
  for (const char* absent : {"shafts", "shadow_maps", "ocean_fft", "caustics", "froxel", "kd_multiple", "sea_second",
                             "raycast", "underwater_setup", "froxel_bands"}) {
    EXPECT_FALSE(plan.hasPass(absent)) << absent;
  }
  EXPECT_TRUE(hasDefine(plan, "sea_single", "SEASIM_HAS_BOTTOM=1"));
  EXPECT_TRUE(hasDefine(plan, "sea_single", "SEASIM_HAS_SUN=1"));
  EXPECT_TRUE(hasDefine(plan, "sea_single", "SEASIM_SPECTRAL_OUTPUT=0"));
  EXPECT_EQ(plan.kernelFiles(), (std::vector<std::string>{"sea_single.cl", "check.cl"}));
}

TEST(Plan, DeepWaterDropsTheBottomTerm) {
  std::string deep = kFlatSea;
  deep = deep.substr(0, deep.find("[bottom]"));
  const Plan plan = makePlan(parseScene(deep, "deep.toml"));
  EXPECT_TRUE(hasDefine(plan, "sea_single", "SEASIM_HAS_BOTTOM=0"));
}

TEST(Plan, SunBelowHorizonStillRendersWithoutSunTerms) {
  // Paper 000's single scattering is the sun's alone; "multiple" (the default) keeps its column, which
  // also holds the skylight scattered in the water.
  const Plan paper = makePlan(parseScene(kFlatSea, "flat.toml",
                                         {{"sun.enabled", "false", {"cli", 1}}, {"sea.model", "\"paper\"", {"cli", 2}}}));
  EXPECT_TRUE(hasDefine(paper, "sea_single", "SEASIM_HAS_SUN=0"));
  EXPECT_TRUE(hasDefine(paper, "sea_single", "SEASIM_HAS_SINGLE_SCATTERING=0"));
  const Plan plan = makePlan(parseScene(kFlatSea, "flat.toml", {{"sun.enabled", "false", {"cli", 1}}}));
  EXPECT_TRUE(hasDefine(plan, "sea_single", "SEASIM_HAS_SUN=0"));
  EXPECT_TRUE(hasDefine(plan, "sea_single", "SEASIM_HAS_SINGLE_SCATTERING=1"));
}

// The reflected sky comes from a table only for the analytic skies (the CIE clear sky and Preetham's,
// which depend on a view through cos theta and gamma alone) seen in a reflection; the uniform sky
// needs none, the image sky is a table already, and quality.sea_sky_table = 1 asks for the exact model.
TEST(Plan, ReflectedSkyTableOnlyForAnAnalyticSkyInAReflection) {
  const auto plan = [](std::vector<seasim::Override> o) { return makePlan(parseScene(kFlatSea, "flat.toml", o)); };
  const auto set = [](const char* k, const char* v) { return seasim::Override{k, v, {"cli", 1}}; };
  EXPECT_TRUE(hasDefine(plan({set("sky.model", "\"preetham\"")}), "sea_single", "SEASIM_SEA_SKY_TABLE=256"));
  EXPECT_TRUE(hasDefine(plan({set("sky.model", "\"analytic\"")}), "sea_single", "SEASIM_SEA_SKY_TABLE=256"));
  EXPECT_TRUE(hasDefine(plan({set("sky.model", "\"preetham\""), set("quality.sea_sky_table", "64")}), "sea_single",
                        "SEASIM_SEA_SKY_TABLE=64"));
  for (const Plan& p : {plan({}), plan({set("sky.model", "\"preetham\""), set("quality.sea_sky_table", "1")}),
                        plan({set("sky.model", "\"preetham\""), set("sea.reflection", "false")})}) {
    const auto* e = p.find("sea_single");
    ASSERT_NE(e, nullptr);
    for (const std::string& d : e->defines) EXPECT_EQ(d.rfind("SEASIM_SEA_SKY_TABLE", 0), std::string::npos) << d;
  }
}

// quality.fast_math marks every model pass's build (Device::program adds -cl-fast-relaxed-math for
// it) and shows in `seasim plan`; the NaN/Inf check is never built with finite-only maths.
TEST(Plan, FastMathMarksEveryModelPassButTheCheck) {
  for (const bool fast : {false, true}) {
    const Plan plan = makePlan(parseScene(std::string(kFlatSea) + "[sea]\nmodel = \"paper\"\nsecond_order = true\n[quality]\nfast_math = " +
                                              (fast ? "true" : "false") + "\n",
                                          "flat.toml"));
    ASSERT_TRUE(plan.hasPass("sea_second"));
    for (const auto& p : plan.passes) {
      const bool marked = hasDefine(plan, p.name, "SEASIM_FAST_MATH=1");
      EXPECT_EQ(marked, fast && p.name != "nonfinite_check") << p.name;
    }
    EXPECT_EQ(plan.toText().find("-DSEASIM_FAST_MATH=1") != std::string::npos, fast);
  }
}

// fast_math = "auto" (the default) is on except for the sea with FFT waves seen from above, the
// shipped scenes whose fast-maths image moved by more than 0.05 of a level (results/BENCHMARKS.md).
TEST(Plan, FastMathAutoIsOffOnlyForWavesSeenFromAbove) {
  const Plan flat = makePlan(parseScene(kFlatSea, "flat.toml"));
  EXPECT_TRUE(hasDefine(flat, "sea_single", "SEASIM_FAST_MATH=1"));
  const Plan waves = makePlan(parseScene(kFlatSea, "flat.toml", {{"surface.type", "\"fft\"", {"cli", 1}}}));
  EXPECT_FALSE(hasDefine(waves, "sea_single", "SEASIM_FAST_MATH=1"));
  const Plan forced =
      makePlan(parseScene(kFlatSea, "flat.toml",
                          {{"surface.type", "\"fft\"", {"cli", 1}}, {"quality.fast_math", "true", {"cli", 2}}}));
  EXPECT_TRUE(hasDefine(forced, "sea_single", "SEASIM_FAST_MATH=1"));
  EXPECT_FALSE(hasDefine(forced, "ocean_fft", "SEASIM_FAST_MATH=1"));  // built without the plan's defines
  const Plan off = makePlan(parseScene(kFlatSea, "flat.toml", {{"quality.fast_math", "false", {"cli", 1}}}));
  EXPECT_FALSE(hasDefine(off, "sea_single", "SEASIM_FAST_MATH=1"));
}

TEST(Plan, SecondOrderAddsScatteringMapsPass) {
  // Paper 000's model; "multiple" holds the second order in its closed form and plans no maps.
  const Plan plan = makePlan(parseScene(kFlatSea, "flat.toml",
                                        {{"sea.second_order", "true", {"cli", 1}}, {"sea.model", "\"paper\"", {"cli", 2}}}));
  ASSERT_TRUE(plan.hasPass("sea_second"));
  EXPECT_TRUE(plan.find("sea_second")->implemented);
  // It runs after the single-scattering pass and adds into its image.
  EXPECT_EQ(plan.passes[0].name, "sea_single");
  EXPECT_EQ(plan.passes[1].name, "sea_second");
}

TEST(Plan, WavesAddTheOceanPass) {
  const Plan plan = makePlan(parseScene(kFlatSea, "flat.toml", {{"surface.type", "\"fft\"", {"cli", 1}}}));
  EXPECT_TRUE(plan.hasPass("ocean_fft"));
  EXPECT_FALSE(plan.hasPass("caustics"));  // caustics only matter below the surface
}

TEST(Plan, WavesFeedTheirNormalsToTheSeaPass) {
  // FFT waves seen from above: the ocean runs first (implemented) and sea_single reads its normals.
  const Plan waves = makePlan(parseScene(kFlatSea, "flat.toml", {{"surface.type", "\"fft\"", {"cli", 1}}}));
  ASSERT_TRUE(waves.hasPass("ocean_fft"));
  EXPECT_TRUE(waves.find("ocean_fft")->implemented);
  EXPECT_TRUE(waves.find("sea_single")->implemented);
  EXPECT_TRUE(hasDefine(waves, "sea_single", "SEASIM_HAS_WAVES=1"));
  EXPECT_EQ(waves.passes[0].name, "ocean_fft");
  EXPECT_EQ(waves.passes[1].name, "sea_single");
  const auto& reads = waves.find("sea_single")->reads;
  EXPECT_NE(std::find(reads.begin(), reads.end(), "ocean_maps"), reads.end());
  // A flat sea: no ocean, no wave normals.
  const Plan flat = makePlan(parseScene(kFlatSea, "flat.toml"));
  EXPECT_FALSE(flat.hasPass("ocean_fft"));
  EXPECT_FALSE(hasDefine(flat, "sea_single", "SEASIM_HAS_WAVES=1"));
  EXPECT_TRUE(hasDefine(flat, "sea_single", "SEASIM_HAS_WAVES=0"));
}

TEST(Plan, SkyModelIsAKernelDefine) {
  EXPECT_TRUE(hasDefine(makePlan(parseScene(kFlatSea, "flat.toml")), "sea_single", "SEASIM_SKY_MODEL=0"));
  const Plan analytic = makePlan(parseScene(kFlatSea, "flat.toml", {{"sky.model", "\"analytic\"", {"cli", 1}}}));
  EXPECT_TRUE(hasDefine(analytic, "sea_single", "SEASIM_SKY_MODEL=1"));
  EXPECT_TRUE(analytic.find("sea_single")->implemented);
  const Plan image = makePlan(parseScene(std::string(kFlatSea) + "[sky]\nmodel = \"image\"\nimage = \"" + SEASIM_SOURCE_DIR +
                                             "/scenes/textures/sky_clear.exr\"\n",
                                         "flat.toml"));
  EXPECT_TRUE(hasDefine(image, "sea_single", "SEASIM_SKY_MODEL=2"));
  EXPECT_TRUE(image.find("sea_single")->implemented);
}

TEST(Plan, UnderwaterCameraUsesUnderwaterPassesNotTheSeaSurface) {
  const Plan plan = makePlan(parseScene(kFlatSea, "flat.toml", {{"camera.position", "[0, -5, 0]", {"cli", 1}}}));
  EXPECT_FALSE(plan.hasPass("sea_single"));
  EXPECT_TRUE(plan.hasPass("froxel"));
  EXPECT_TRUE(plan.hasPass("kd_multiple"));
  EXPECT_TRUE(plan.hasPass("raycast"));
  EXPECT_TRUE(hasDefine(plan, "raycast", "SEASIM_HAS_OBJECTS=0"));
  EXPECT_TRUE(hasDefine(plan, "raycast", "SEASIM_CAUSTICS=1"));
  EXPECT_TRUE(hasDefine(plan, "kd_multiple", "SEASIM_HAS_FROXEL=1"));
  EXPECT_TRUE(hasDefine(plan, "kd_multiple", "SEASIM_HAS_MULTIPLE=1"));
  for (const auto& p : plan.passes) EXPECT_TRUE(p.implemented) << p.name;
}

seasim::Override at(const char* key, const char* value) { return {key, value, {"cli", 1}}; }

TEST(Plan, UnderwaterCausticMapRunsTheOceanOnlyWhenAsked) {
  // caustics = "map" under an FFT surface: the ocean and its caustic splat run before the G-buffer.
  Plan plan = makePlan(parseScene(kFlatSea, "flat.toml",
                                  {at("camera.position", "[0, -5, 0]"), at("surface.type", "\"fft\""),
                                   at("underwater.caustics", "\"map\"")}));
  ASSERT_TRUE(plan.hasPass("ocean_fft"));
  ASSERT_TRUE(plan.hasPass("caustics"));
  EXPECT_TRUE(hasDefine(plan, "raycast", "SEASIM_CAUSTICS=2"));
  EXPECT_TRUE(hasDefine(plan, "froxel", "SEASIM_CAUSTICS=2"));
  for (const auto& p : plan.passes) EXPECT_TRUE(p.implemented) << p.name;
  // The same waves with texture caustics: under water the model's surface is flat, so no ocean.
  plan = makePlan(parseScene(kFlatSea, "flat.toml",
                             {at("camera.position", "[0, -5, 0]"), at("surface.type", "\"fft\""),
                              at("underwater.caustics", "\"texture\"")}));
  EXPECT_FALSE(plan.hasPass("ocean_fft"));
  EXPECT_FALSE(plan.hasPass("caustics"));
  // Night: no caustics at all, so no ocean either.
  plan = makePlan(parseScene(kFlatSea, "flat.toml",
                             {at("camera.position", "[0, -5, 0]"), at("surface.type", "\"fft\""),
                              at("underwater.caustics", "\"map\""), at("sun.zenith_deg", "95")}));
  EXPECT_FALSE(plan.hasPass("ocean_fft"));
  EXPECT_FALSE(plan.hasPass("caustics"));
  EXPECT_TRUE(hasDefine(plan, "raycast", "SEASIM_CAUSTICS=0"));
}

TEST(Plan, UnderwaterLeavesOutWhatTheSceneTurnsOff) {
  // No single scattering: no froxel pass, and the shading does not split off the direct sun.
  Plan plan = makePlan(parseScene(kFlatSea, "flat.toml",
                                  {at("camera.position", "[0, -5, 0]"), at("underwater.single_scattering", "false")}));
  EXPECT_FALSE(plan.hasPass("froxel"));
  EXPECT_TRUE(hasDefine(plan, "kd_multiple", "SEASIM_HAS_FROXEL=0"));
  EXPECT_EQ(plan.find("kd_multiple")->reads, (std::vector<std::string>{"underwater_setup", "gbuffer"}));
  // Night: no sun, so no froxels, no shadow rays, no caustics.
  plan = makePlan(parseScene(kFlatSea, "flat.toml", {at("camera.position", "[0, -5, 0]"), at("sun.zenith_deg", "95")}));
  EXPECT_FALSE(plan.hasPass("froxel"));
  EXPECT_TRUE(hasDefine(plan, "raycast", "SEASIM_HAS_SUN=0"));
  EXPECT_TRUE(hasDefine(plan, "raycast", "SEASIM_CAUSTICS=0"));
  // Caustics off; RGB injection; no multiple scattering.
  plan = makePlan(parseScene(kFlatSea, "flat.toml",
                             {at("camera.position", "[0, -5, 0]"), at("underwater.caustics", "\"none\""),
                              at("underwater.froxel_injection", "\"rgb\""),
                              at("underwater.multiple_scattering", "false")}));
  EXPECT_TRUE(hasDefine(plan, "froxel", "SEASIM_CAUSTICS=0"));
  EXPECT_TRUE(hasDefine(plan, "froxel", "SEASIM_SPECTRAL_INJECTION=0"));
  EXPECT_TRUE(hasDefine(plan, "kd_multiple", "SEASIM_HAS_MULTIPLE=0"));
  // Above water none of the underwater passes appear.
  plan = makePlan(parseScene(kFlatSea, "flat.toml"));
  for (const char* absent : {"raycast", "froxel", "kd_multiple"}) EXPECT_FALSE(plan.hasPass(absent)) << absent;
}

TEST(Plan, WaterSpreadOnlyForTheOrdinatesModelWithAForwardPhase) {
  // The discrete-ordinates model scales by delta-M: with g > 0 its forward light is kept apart and spread.
  Plan plan = makePlan(parseScene(kFlatSea, "flat.toml",
                                  {at("camera.position", "[0, -5, 0]"), at("underwater.model", "\"discrete_ordinates\""),
                                   at("water.g", "0.9")}));
  ASSERT_TRUE(plan.hasPass("water_spread"));
  EXPECT_TRUE(hasDefine(plan, "kd_multiple", "SEASIM_UWI_SPREAD=1"));
  EXPECT_EQ(plan.find("water_spread")->reads, (std::vector<std::string>{"underwater_setup", "gbuffer", "forward_light", "rgb"}));
  // After the shading that writes "rgb", before the check that reads it.
  const auto index = [&](const char* name) {
    return std::find_if(plan.passes.begin(), plan.passes.end(), [&](const auto& p) { return p.name == name; }) -
           plan.passes.begin();
  };
  EXPECT_LT(index("kd_multiple"), index("water_spread"));
  EXPECT_LT(index("water_spread"), index("nonfinite_check"));
  // The thesis's model, an isotropic phase, or the spread turned off: neither the pass nor the define.
  for (const std::vector<seasim::Override>& off :
       {std::vector<seasim::Override>{at("underwater.model", "\"thesis\""), at("water.g", "0.9")},
        std::vector<seasim::Override>{at("underwater.model", "\"discrete_ordinates\""), at("water.g", "0.0")},
        std::vector<seasim::Override>{at("underwater.model", "\"discrete_ordinates\""), at("water.g", "0.9"),
                                      at("underwater.point_spread", "false")}}) {
    std::vector<seasim::Override> overrides = off;
    overrides.push_back(at("camera.position", "[0, -5, 0]"));
    plan = makePlan(parseScene(kFlatSea, "flat.toml", overrides));
    EXPECT_TRUE(plan.hasPass("kd_multiple"));
    EXPECT_FALSE(plan.hasPass("water_spread")) << off[0].value_toml << " " << off[1].value_toml;
    EXPECT_TRUE(hasDefine(plan, "kd_multiple", "SEASIM_UWI_SPREAD=0"));
  }
  // Above the water there is nothing to spread.
  plan = makePlan(parseScene(kFlatSea, "flat.toml", {at("underwater.model", "\"discrete_ordinates\""), at("water.g", "0.9")}));
  EXPECT_FALSE(plan.hasPass("water_spread"));
}

TEST(Plan, SpotlightsInAirAddShaftsAndShadowMapsOnlyWithObjects) {
  const char* stage = R"(
[camera]
position = [0, 2, 10]
look_at = [0, 1, 0]
[air]
density = 1
extinction = 0.05
[[spotlights]]
position = [0, 5, 0]
direction = [0, -1, 0]
)";
  Plan plan = makePlan(parseScene(stage, "stage.toml"));
  EXPECT_TRUE(plan.hasPass("shafts"));
  EXPECT_FALSE(plan.hasPass("shadow_maps"));
  EXPECT_FALSE(plan.hasPass("sea_single"));
  std::string with_object = std::string(stage) + "[[objects]]\ntype = \"sphere\"\ncenter = [0, 1, 0]\nradius = 0.5\n";
  // The default method, intervals, casts exact shadow volumes: no shadow maps.
  plan = makePlan(parseScene(with_object, "stage.toml"));
  EXPECT_FALSE(plan.hasPass("shadow_maps"));
  EXPECT_TRUE(plan.hasPass("raycast"));
  const auto& defines = plan.find("shafts")->defines;
  EXPECT_NE(std::find(defines.begin(), defines.end(), "SEASIM_SHAFTS_INTERVALS=1"), defines.end());
  EXPECT_NE(plan.find("shafts")->why.find("intervals"), std::string::npos);
  // Paper 001's sampling planes read shadow maps.
  plan = makePlan(parseScene(with_object + "[quality]\nshafts_method = \"planes\"\n", "stage.toml"));
  EXPECT_TRUE(plan.hasPass("shadow_maps"));
  EXPECT_TRUE(plan.hasPass("raycast"));
  const auto& planes_defines = plan.find("shafts")->defines;
  EXPECT_NE(std::find(planes_defines.begin(), planes_defines.end(), "SEASIM_SHAFTS_INTERVALS=0"), planes_defines.end());
  // The march casts exact shadow rays: no shadow maps, its own define.
  plan = makePlan(parseScene(with_object + "[quality]\nshafts_method = \"march\"\n", "stage.toml"));
  EXPECT_FALSE(plan.hasPass("shadow_maps"));
  const auto& march_defines = plan.find("shafts")->defines;
  EXPECT_NE(std::find(march_defines.begin(), march_defines.end(), "SEASIM_SHAFTS_MARCH=1"), march_defines.end());
  EXPECT_NE(std::find(march_defines.begin(), march_defines.end(), "SEASIM_SHAFTS_INTERVALS=0"), march_defines.end());
  // More objects than the intervals kernel's stretch list holds: the planner falls back to planes.
  std::string many = stage;
  for (int i = 0; i < 16; ++i)
    many += "[[objects]]\ntype = \"sphere\"\ncenter = [" + std::to_string(i) + ", 1, 0]\nradius = 0.2\n";
  plan = makePlan(parseScene(many, "stage.toml"));
  EXPECT_TRUE(plan.hasPass("shadow_maps"));
  // Only the planes without shafts_exact build 001 eq. 6's table: the estimate counts it for them alone.
  const auto has_table = [](const std::string& text) {
    const seasim::Scene s = parseScene(text, "stage.toml");
    for (const seasim::BufferEstimate& b : seasim::estimateBuffers(s, makePlan(s)))
      if (b.what == "shafts integral table") return true;
    return false;
  };
  EXPECT_FALSE(has_table(with_object));
  EXPECT_FALSE(has_table(with_object + "[quality]\nshafts_method = \"march\"\n"));
  EXPECT_TRUE(has_table(with_object + "[quality]\nshafts_method = \"planes\"\n"));
  EXPECT_FALSE(has_table(with_object + "[quality]\nshafts_method = \"planes\"\nshafts_exact = true\n"));
  // "auto" written out is measured on the device before the Renderer plans (host/quality/
  // shafts_method_auto.h); a plan made before that is the rule's, on either side of the limit, and says so.
  plan = makePlan(parseScene(many + "[quality]\nshafts_method = \"auto\"\n", "stage.toml"));
  EXPECT_TRUE(plan.hasPass("shadow_maps"));
  EXPECT_NE(plan.find("shafts")->why.find("method planes"), std::string::npos);
  EXPECT_NE(plan.find("shafts")->why.find("method \"auto\": measured"), std::string::npos);
  plan = makePlan(parseScene(with_object + "[quality]\nshafts_method = \"auto\"\n", "stage.toml"));
  EXPECT_FALSE(plan.hasPass("shadow_maps"));
  EXPECT_NE(plan.find("shafts")->why.find("intervals"), std::string::npos);
  EXPECT_NE(plan.find("shafts")->why.find("measured"), std::string::npos);
  plan = makePlan(parseScene(with_object, "stage.toml"));  // the key absent: the rule, nothing measured
  EXPECT_EQ(plan.find("shafts")->why.find("measured"), std::string::npos);
}

// A lamp under water, beneath a camera in Jerlov IB water (the camera's defaults: 60°, 640x360).
const char* kLampUnderWater = R"(
[camera]
position = [0, -2, 0]
look_at = [0, -3, -10]
[water]
jerlov = "IB"
[[spotlights]]
position = [0, -1, 0]
direction = [0, -1, -1]
)";

// Spotlights under water: the water's passes and the lamps' pass, which adds into the rgb
// kd_multiple wrote (so it comes after it), and none of the air shafts' passes.
TEST(Plan, SpotlightsUnderWaterAddTheLampsPassAfterTheShading) {
  const char* text = kLampUnderWater;
  const Plan plan = makePlan(parseScene(text, "rov.toml"));
  const seasim::PassPlan* lamps = plan.find("underwater_lamps");
  ASSERT_NE(lamps, nullptr);
  EXPECT_TRUE(lamps->implemented);
  EXPECT_EQ(lamps->kernel_file, "underwater_lamps.cl");
  EXPECT_TRUE(hasDefine(plan, "underwater_lamps", "SEASIM_HAS_OBJECTS=0"));
  std::vector<std::string> order;
  for (const auto& p : plan.passes) order.push_back(p.name);
  const auto kd = std::find(order.begin(), order.end(), "kd_multiple");
  const auto lp = std::find(order.begin(), order.end(), "underwater_lamps");
  ASSERT_NE(kd, order.end());
  EXPECT_LT(kd - order.begin(), lp - order.begin());
  EXPECT_NE(std::find(lamps->reads.begin(), lamps->reads.end(), "gbuffer"), lamps->reads.end());
  EXPECT_NE(std::find(lamps->reads.begin(), lamps->reads.end(), "rgb"), lamps->reads.end());
  for (const char* absent : {"shafts", "shadow_maps", "sea_single", "sea_second", "ocean_fft"})
    EXPECT_FALSE(plan.hasPass(absent)) << absent;
  // Without lamps the same water has no lamps pass.
  const std::string no_lamps = std::string(text).substr(0, std::string(text).find("[[spotlights]]"));
  EXPECT_FALSE(makePlan(parseScene(no_lamps, "rov.toml")).hasPass("underwater_lamps"));
}

// The froxel pass reads the G-buffer (to skip the froxels no pixel reads) only for a grid of at least 8
// froxels per pixel: seabed's defaults (80x45x32 at 320x180, 2 per pixel) evaluate them all.
TEST(Plan, FroxelCullingOnlyForGridsMuchFinerThanTheImage) {
  const auto reads_gbuffer = [](const Plan& plan) {
    const seasim::PassPlan* f = plan.find("froxel");
    EXPECT_NE(f, nullptr);
    return f && std::find(f->reads.begin(), f->reads.end(), "gbuffer") != f->reads.end();
  };
  const std::string seabed = std::string(SEASIM_SOURCE_DIR) + "/scenes/seabed.toml";
  EXPECT_FALSE(reads_gbuffer(makePlan(seasim::loadScene(seabed))));
  const auto set = [](const std::string& k, const std::string& v) { return seasim::Override{k, v, {"test", 1}}; };
  // 160x90x64 at 320x180: 16 per pixel; 160x90x32: 8.
  EXPECT_TRUE(reads_gbuffer(
      makePlan(seasim::loadScene(seabed, {set("quality.froxel_columns", "160"), set("quality.froxel_z", "64")}))));
  EXPECT_TRUE(reads_gbuffer(makePlan(seasim::loadScene(seabed, {set("quality.froxel_columns", "160")}))));
  EXPECT_FALSE(reads_gbuffer(makePlan(seasim::loadScene(
      seabed, {set("quality.froxel_columns", "160"), set("camera.width", "640"), set("camera.height", "360")}))));
}

// The orders model's lattice (quality.lamps_ms_cell_deg): planned where a cell holds at least two pixels
// of the image's height, with as many pixels per cell as fit; absent where the pixels are wider, at 0,
// and for the single and delta-M models, which have no smooth part.
TEST(Plan, TheLampsLatticeFollowsTheCellsAngleAndTheModel) {
  const auto set = [](const std::string& k, const std::string& v) { return seasim::Override{k, v, {"test", 1}}; };
  const auto scene = [&](std::vector<seasim::Override> over) {
    over.insert(over.begin(), {set("camera.fov_deg", "60"), set("camera.width", "320"), set("camera.height", "180")});
    return parseScene(kLampUnderWater, "rov.toml", over);
  };
  // 60° over 180 rows: 1/3° per pixel.
  EXPECT_EQ(seasim::lampsMsLatticeStep(scene({})), 3);
  EXPECT_EQ(seasim::lampsMsLatticeStep(scene({set("quality.lamps_ms_cell_deg", "0.7")})), 2);
  EXPECT_EQ(seasim::lampsMsLatticeStep(scene({set("quality.lamps_ms_cell_deg", "0.5")})), 1);
  EXPECT_EQ(seasim::lampsMsLatticeStep(scene({set("quality.lamps_ms_cell_deg", "0")})), 1);
  EXPECT_EQ(seasim::lampsMsLatticeStep(scene({set("camera.height", "45")})), 1);  // 1.33° pixels
  EXPECT_EQ(seasim::lampsMsLatticeStep(scene({set("camera.height", "720")})), 12);
  EXPECT_TRUE(hasDefine(makePlan(scene({})), "underwater_lamps", "SEASIM_LAMPS_MS_LATTICE=1"));
  for (const auto& off : {scene({set("quality.lamps_ms_cell_deg", "0.5")}), scene({set("camera.height", "45")}),
                          scene({set("quality.lamps_model", "\"delta_m\"")}),
                          scene({set("quality.lamps_model", "\"single\"")})}) {
    const Plan plan = makePlan(off);
    ASSERT_TRUE(plan.hasPass("underwater_lamps"));
    EXPECT_FALSE(hasDefine(plan, "underwater_lamps", "SEASIM_LAMPS_MS_LATTICE=1"));
  }
}

// rov_lights.toml: ray cast, froxels (sun up, single scattering), K_d shading, the water's point spread
// around the objects (the discrete-ordinates model, the default), the lamps, the check;
// texture caustics need no ocean and no caustic maps; nothing of the sea seen from above or of air.
TEST(Plan, RovLightsRunsTheUnderwaterPassesAndTheLampsOnly) {
  const Plan plan = makePlan(seasim::loadScene(std::string(SEASIM_SOURCE_DIR) + "/scenes/rov_lights.toml"));
  std::vector<std::string> order;
  for (const auto& p : plan.passes) order.push_back(p.name);
  const std::vector<std::string> expected = {"underwater_setup", "raycast",      "froxel",
                                             "sand_share",       "kd_multiple",  "water_spread",
                                             "underwater_lamps", "nonfinite_check"};
  EXPECT_EQ(order, expected);
  EXPECT_TRUE(hasDefine(plan, "underwater_lamps", "SEASIM_HAS_OBJECTS=1"));
  for (const auto& p : plan.passes) EXPECT_TRUE(p.implemented) << p.name;
}

// The objects' share lattice only where a share can be below 1: the discrete-ordinates model with objects
// (over a bottom, or in open water for the light from above they hold off) and a step above 1 (seabed); not
// for the thesis's model, water without objects, no multiple scattering, step 1, or the sea seen from above.
TEST(Plan, SandShareLatticeOnlyForObjectsInTheOrdinatesModel) {
  const std::string seabed = std::string(SEASIM_SOURCE_DIR) + "/scenes/seabed.toml";
  auto plan = [&](std::vector<seasim::Override> o) { return makePlan(seasim::loadScene(seabed, o)); };
  auto set = [](const char* k, const char* v) { return seasim::Override{k, v, {"test", 1}}; };
  const Plan with = plan({});
  ASSERT_TRUE(with.hasPass("sand_share"));
  EXPECT_TRUE(hasDefine(with, "kd_multiple", "SEASIM_SAND_SHARE_MAP=1"));
  // The regions study's scene (seabed's rocks) in open water.
  EXPECT_TRUE(makePlan(seasim::loadScene(std::string(SEASIM_SOURCE_DIR) + "/tests/perf/underwater_regions.toml",
                                         {set("bottom.type", "\"none\"")}))
                  .hasPass("sand_share"));
  EXPECT_FALSE(plan({set("objects", "[]")}).hasPass("sand_share"));
  EXPECT_FALSE(plan({set("underwater.model", "\"thesis\"")}).hasPass("sand_share"));
  EXPECT_FALSE(plan({set("quality.sand_share_step", "1")}).hasPass("sand_share"));
  EXPECT_FALSE(hasDefine(plan({set("quality.sand_share_step", "1")}), "kd_multiple", "SEASIM_SAND_SHARE_MAP=1"));
  EXPECT_FALSE(plan({set("underwater.multiple_scattering", "false")}).hasPass("sand_share"));
  EXPECT_FALSE(makePlan(seasim::loadScene(std::string(SEASIM_SOURCE_DIR) + "/scenes/flat_sea.toml")).hasPass("sand_share"));
}

// The froxel grid is set by its angular spacing (froxel_setup.h): 80 columns across the wider side, at
// most one per pixel, the other side in proportion; the buffer estimate `seasim plan` prints names it. (The plan's own text
// does not: a knob there would make every change of it build a new graph.)
TEST(Plan, FroxelGridFollowsTheImageAndThePlanNamesIt) {
  const std::string seabed = std::string(SEASIM_SOURCE_DIR) + "/scenes/seabed.toml";
  auto at_size = [&](const char* w, const char* h, std::vector<seasim::Override> more = {}) {
    more.push_back({"camera.width", w, {"test", 1}});
    more.push_back({"camera.height", h, {"test", 1}});
    return seasim::loadScene(seabed, more);
  };
  auto grid = [](const seasim::Scene& s) {
    const seasim::FroxelConfig c = seasim::froxelConfigFromScene(s);
    return std::to_string(c.nx) + "x" + std::to_string(c.ny) + "x" + std::to_string(c.nz);
  };
  EXPECT_EQ(grid(at_size("320", "180")), "80x45x32");
  EXPECT_EQ(grid(at_size("640", "360")), "80x45x32");
  EXPECT_EQ(grid(at_size("3840", "2160")), "80x45x32");
  EXPECT_EQ(grid(at_size("96", "54")), "80x45x32");
  EXPECT_EQ(grid(at_size("64", "36")), "64x36x32");      // at most one column per pixel
  EXPECT_EQ(grid(at_size("180", "320")), "45x80x32");    // across the wider side
  EXPECT_EQ(grid(at_size("320", "180", {{"quality.froxel_columns", "160", {"test", 1}}})), "160x90x32");
  for (const char* bad : {"0", "1.5", "\"many\""})  // a count: a whole number >= 1 or "auto"
    EXPECT_THROW((void)at_size("320", "180", {{"quality.froxel_columns", bad, {"test", 1}}}), seasim::InputError) << bad;
  EXPECT_EQ(grid(at_size("320", "180", {{"quality.froxel_x", "33", {"test", 1}}})), "33x45x32");
  const seasim::Scene s = at_size("320", "180");
  bool named = false;
  for (const seasim::BufferEstimate& b : seasim::estimateBuffers(s, makePlan(s)))
    if (b.pass == "froxel" && b.what == "froxel volume") {
      named = true;
      EXPECT_EQ(b.values, (std::vector<double>{80, 45, 32}));
      EXPECT_EQ(b.bytes, 20.0 * 80 * 45 * 32);
    }
  EXPECT_TRUE(named);
}

// The underwater set-up is a pass of its own, first, with no kernel; the froxels' term per band is
// planned only where spectral.exr asks for it, after the shading it adds into, and builds froxel.cl
// with the froxel pass's defines.
TEST(Plan, UnderwaterSetupComesFirstAndTheFroxelBandsOnlyWithSpectralOutput) {
  const std::string seabed = std::string(SEASIM_SOURCE_DIR) + "/scenes/seabed.toml";
  const Plan plan = makePlan(seasim::loadScene(seabed));
  ASSERT_FALSE(plan.passes.empty());
  EXPECT_EQ(plan.passes[0].name, "underwater_setup");
  EXPECT_EQ(plan.passes[0].kernel_file, "");
  EXPECT_TRUE(plan.passes[0].defines.empty());
  EXPECT_NE(plan.toText().find("underwater_setup  (host only)"), std::string::npos);
  for (const std::string& file : plan.kernelFiles()) EXPECT_FALSE(file.empty());
  EXPECT_TRUE(plan.hasPass("froxel"));
  EXPECT_FALSE(plan.hasPass("froxel_bands"));

  const Plan spectral = makePlan(seasim::loadScene(seabed, {at("spectral.spectral_exr", "true")}));
  const seasim::PassPlan* bands = spectral.find("froxel_bands");
  ASSERT_NE(bands, nullptr);
  EXPECT_EQ(bands->defines, spectral.find("froxel")->defines);
  EXPECT_EQ(bands->writes, std::vector<std::string>{"rgb"});
  size_t kd = 0, term = 0;
  for (size_t i = 0; i < spectral.passes.size(); ++i) {
    if (spectral.passes[i].name == "kd_multiple") kd = i;
    if (spectral.passes[i].name == "froxel_bands") term = i;
  }
  EXPECT_EQ(term, kd + 1);

  const Plan no_froxels = makePlan(seasim::loadScene(
      seabed, {at("spectral.spectral_exr", "true"), at("underwater.single_scattering", "false")}));
  EXPECT_FALSE(no_froxels.hasPass("froxel_bands"));
}

// Spotlights with the camera above the water are not composed: the plan holds a shafts pass marked
// not implemented, naming the lamp's file and line, so the render stops before writing anything.
TEST(Plan, SpotlightsOverTheSeaSeenFromAboveArePlannedAsNotImplementedNamingTheLamp) {
  const char* text = R"(
[camera]
position = [0, 2, 0]
look_at = [0, -3, -10]
[water]
jerlov = "IB"
[[spotlights]]
position = [0, 5, 0]
direction = [0, -1, -1]
)";
  const Plan plan = makePlan(parseScene(text, "lamp_over_sea.toml"));
  const seasim::PassPlan* shafts = plan.find("shafts");
  ASSERT_NE(shafts, nullptr);
  EXPECT_FALSE(shafts->implemented);
  EXPECT_NE(shafts->why.find("lamp_over_sea.toml:7"), std::string::npos) << shafts->why;
  EXPECT_FALSE(plan.hasPass("underwater_lamps"));
  EXPECT_TRUE(plan.hasPass("sea_single"));  // the water itself is planned as before
}

TEST(Plan, TextHasOnePassPerLineWithKernelAndDefines) {
  const Plan plan = makePlan(parseScene(kFlatSea, "flat.toml"));
  const std::string text = plan.toText();
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 2);
  EXPECT_NE(text.find("kernels/sea_single.cl"), std::string::npos);
  EXPECT_NE(text.find("-DSEASIM_HAS_BOTTOM=1"), std::string::npos);
}

TEST(Plan, HeightFieldBottomDefineOnlyWithAHeightField) {
  // 000 §5.4: a height-field floor is a bottom (SEASIM_HAS_BOTTOM=1) walked per pixel and tabulated for
  // the second order (SEASIM_BOTTOM_HEIGHTFIELD=1, both sea passes, both implemented); flat and deep
  // water never carry the define.
  const std::string dir = ::testing::TempDir();
  { std::FILE* f = std::fopen((dir + "/hf_plan.exr").c_str(), "wb"); ASSERT_NE(f, nullptr); std::fclose(f); }
  std::string hf = kFlatSea;
  hf = hf.substr(0, hf.find("[bottom]")) + "[bottom]\ntype = \"heightfield\"\nheightfield = \"hf_plan.exr\"\n";
  const auto second = std::vector<seasim::Override>{{"sea.second_order", "true", {"cli", 1}}, {"sea.model", "\"paper\"", {"cli", 2}}};
  Plan plan = makePlan(parseScene(hf, dir + "/hf.toml", second));
  for (const char* pass : {"sea_single", "sea_second"}) {
    ASSERT_TRUE(plan.hasPass(pass)) << pass;
    EXPECT_TRUE(plan.find(pass)->implemented) << pass;
    EXPECT_TRUE(hasDefine(plan, pass, "SEASIM_BOTTOM_HEIGHTFIELD=1")) << pass;
    EXPECT_TRUE(hasDefine(plan, pass, "SEASIM_HAS_BOTTOM=1")) << pass;
  }
  std::string deep = kFlatSea;
  deep = deep.substr(0, deep.find("[bottom]"));
  for (const std::string& text : {std::string(kFlatSea), deep}) {
    plan = makePlan(parseScene(text, "flat.toml", second));
    for (const auto& p : plan.passes)
      for (const auto& d : p.defines) EXPECT_EQ(d.find("SEASIM_BOTTOM_HEIGHTFIELD"), std::string::npos) << p.name;
  }
}

}  // namespace

namespace {

const char* kShallowLake = R"(
[camera]
position = [0, 3, 49]
look_at = [0, 0, 20]
[water]
jerlov = "I"
[bottom]
albedo = 0.35
[shallow]
slope_depths_m = [0, 15]
)";

TEST(Plan, ShallowWaterGetsTheFourFlowPassInsteadOfTheSeaModel) {
  const Plan plan = makePlan(parseScene(kShallowLake, "lake.toml"));
  ASSERT_EQ(plan.passes.size(), 2u);
  EXPECT_EQ(plan.passes[0].name, "fourflow");
  EXPECT_EQ(plan.passes[1].name, "nonfinite_check");
  EXPECT_FALSE(plan.hasPass("sea_single"));
  EXPECT_FALSE(plan.hasPass("sea_second"));
  EXPECT_TRUE(hasDefine(plan, "fourflow", "SEASIM_FF_TABLES=1"));     // path = "table" by default
  EXPECT_TRUE(hasDefine(plan, "fourflow", "SEASIM_FF_HEIGHTFIELD=1"));  // the slope is a height field
  EXPECT_FALSE(hasDefine(plan, "fourflow", "SEASIM_FAST_MATH=1"));     // not measured under relaxed maths
  EXPECT_EQ(plan.kernelFiles(), (std::vector<std::string>{"fourflow.cl", "check.cl"}));

  const Plan exact = makePlan(parseScene(std::string(kShallowLake) + "path = \"exact\"\n", "lake.toml"));
  EXPECT_TRUE(hasDefine(exact, "fourflow", "SEASIM_FF_TABLES=0"));
  const Plan eq24 = makePlan(parseScene(std::string(kShallowLake) + "path = \"table_eq24\"\n", "lake.toml"));
  EXPECT_TRUE(hasDefine(eq24, "fourflow", "SEASIM_FF_TABLES=2"));
  // A flat [bottom] without the slope: no height field.
  const Plan flat = makePlan(parseScene(
      "[camera]\nposition = [0, 3, 0]\n[water]\njerlov = \"I\"\n[bottom]\ntype = \"flat\"\ndepth = 4\n[shallow]\n",
      "flat_lake.toml"));
  EXPECT_TRUE(hasDefine(flat, "fourflow", "SEASIM_FF_HEIGHTFIELD=0"));
  EXPECT_TRUE(hasDefine(flat, "fourflow", "SEASIM_SPECTRAL_OUTPUT=0"));
  // Spectral output: the frame kernel writes the bands too.
  const Plan spectral = makePlan(parseScene(std::string(kShallowLake) + "[spectral]\nspectral_exr = true\n", "lake.toml"));
  EXPECT_TRUE(hasDefine(spectral, "fourflow", "SEASIM_SPECTRAL_OUTPUT=1"));
  // Waves: their R and T are averaged on the host (003 eq. 10), so no FFT pass runs for them.
  const Plan wavy = makePlan(parseScene(std::string(kShallowLake) + "[surface]\ntype = \"fft\"\n", "lake.toml"));
  EXPECT_TRUE(wavy.hasPass("fourflow"));
  EXPECT_FALSE(wavy.hasPass("ocean_fft"));
  EXPECT_EQ(wavy.passes.size(), 2u);
}

TEST(Plan, OnlyShallowScenesGetTheFourFlowPass) {
  // The same water without [shallow] is the sea model; no other shipped kind of scene plans fourflow.
  EXPECT_FALSE(makePlan(parseScene(kFlatSea, "flat.toml")).hasPass("fourflow"));
  const char* others[] = {"flat_sea", "tropical", "seabed", "deep_ocean", "wavy_sea", "stage", "spot_sphere", "seashore"};
  for (const char* name : others) {
    const std::string path = std::string(SEASIM_SOURCE_DIR) + "/scenes/" + name + ".toml";
    EXPECT_FALSE(makePlan(seasim::loadScene(path)).hasPass("fourflow")) << name;
  }
  for (const char* name : {"mountain_lake", "tropical_shallows", "muddy_coast"}) {
    const std::string path = std::string(SEASIM_SOURCE_DIR) + "/scenes/" + name + ".toml";
    const Plan plan = makePlan(seasim::loadScene(path));
    EXPECT_TRUE(plan.hasPass("fourflow")) << name;
    EXPECT_FALSE(plan.hasPass("sea_single")) << name;
  }
}

}  // namespace
