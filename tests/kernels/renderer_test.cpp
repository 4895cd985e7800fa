// renderer_test.cpp — the persistent frame graph (render/renderer.h): which passes an update sets up
// and runs again, and that the incremental frame is the frame a fresh renderer makes (bit for bit:
// the same kernels on the same inputs; except caustic splats, whose float atomics may add in another
// order, compared within float rounding). Small images to keep PoCL time low.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "io/data_files.h"
#include "io/image_io.h"
#include "jobs/runner.h"
#include "quality/auto_quality.h"
#include "render/radiance_target.h"
#include "render/renderer.h"
#include "scene/scene_parser.h"
#include "spectral/sensor.h"
#include "spectral/wavelength_grid.h"
#include "test_device.h"
#include "underwater/underwater_setup.h"

namespace seasim {
namespace {

Override set(const std::string& key, const std::string& value) { return {key, value, {"renderer_test", 0}}; }

std::string sceneFile(const char* name) { return std::string(SEASIM_SOURCE_DIR) + "/scenes/" + name; }

std::vector<Override> small(std::vector<Override> extra) {
  std::vector<Override> o = {set("camera.width", "48"), set("camera.height", "32")};
  o.insert(o.end(), extra.begin(), extra.end());
  return o;
}

// Model passes that ran (the NaN check runs whenever the image it reads was written).
std::vector<std::string> models(const std::vector<std::string>& names) {
  std::vector<std::string> out;
  for (const auto& n : names)
    if (n != "nonfinite_check") out.push_back(n);
  return out;
}

bool has(const std::vector<std::string>& v, const std::string& s) { return std::find(v.begin(), v.end(), s) != v.end(); }

// The frame a new renderer makes of the same scene file and overrides.
FrameResult fresh(const char* scene, const std::vector<Override>& overrides) {
  Renderer renderer(test::testDevice(), sceneFile(scene), overrides, shippedPasses());
  return renderer.render();
}

double maxRelDiff(const Image& a, const Image& b) {
  EXPECT_EQ(a.pixels.size(), b.pixels.size());
  double worst = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i)
    worst = std::max(worst, std::fabs(double(a.pixels[i]) - b.pixels[i]) / std::max(1e-6, std::fabs(double(b.pixels[i]))));
  return worst;
}

TEST(Renderer, FirstFrameRunsEveryPassOfThePlanOnce) {
  Renderer renderer(test::testDevice(), sceneFile("wavy_sea.toml"), small({}), shippedPasses());
  const FrameResult f = renderer.render();
  EXPECT_EQ(renderer.lastExecuted(), (std::vector<std::string>{"ocean_fft", "sea_single", "nonfinite_check"}));
  EXPECT_EQ(renderer.lastPrepared(), renderer.lastExecuted());
  EXPECT_EQ(f.nonfinite, 0);
  // Nothing changed: nothing runs, and the image is the same.
  const FrameResult again = renderer.render();
  EXPECT_TRUE(renderer.lastExecuted().empty());
  EXPECT_EQ(again.rgb.pixels, f.rgb.pixels);
}

// surface.time on wavy_sea (with a bottom and its caustics): the ocean, the caustics and the sea
// run again, nothing is set up again, and the frame equals a fresh render at that time.
TEST(Renderer, SurfaceTimeRerunsOnlyOceanCausticsAndSea) {
  const std::vector<Override> base =
      small({set("bottom.type", "\"flat\""), set("bottom.depth", "6.0"), set("sea.bottom_caustics", "true"),
             set("surface.grid", "64")});
  Renderer renderer(test::testDevice(), sceneFile("wavy_sea.toml"), base, shippedPasses());
  const FrameResult first = renderer.render();
  ASSERT_TRUE(has(renderer.lastExecuted(), "caustics"));
  renderer.update({set("surface.time", "2.5")});
  const FrameResult later = renderer.render();
  EXPECT_EQ(models(renderer.lastExecuted()), (std::vector<std::string>{"ocean_fft", "caustics", "sea_single"}));
  EXPECT_TRUE(renderer.lastPrepared().empty());
  EXPECT_NE(later.rgb.pixels, first.rgb.pixels);  // the waves moved
  std::vector<Override> at = base;
  at.push_back(set("surface.time", "2.5"));
  EXPECT_LT(maxRelDiff(later.rgb, fresh("wavy_sea.toml", at).rgb), 1e-5);
}

// Shallow water over waves: a surface key re-prepares the fourflow pass (its R and T are averaged over
// the FFT patch, 003 eq. 10, when it is set up) and the frame equals a fresh render with that key.
TEST(Renderer, ShallowWaterWindRePreparesTheFourFlowPass) {
  const std::vector<Override> base = small({set("surface.type", "\"fft\""), set("surface.grid", "64")});
  Renderer renderer(test::testDevice(), sceneFile("mountain_lake.toml"), base, shippedPasses());
  const FrameResult before = renderer.render();  // the default wind, 10 m/s
  renderer.update({set("surface.wind_speed", "15")});
  const FrameResult windy = renderer.render();
  EXPECT_EQ(models(renderer.lastPrepared()), std::vector<std::string>{"fourflow"});
  EXPECT_NE(windy.rgb.pixels, before.rgb.pixels);  // rougher water: other R and T
  std::vector<Override> at = base;
  at.push_back(set("surface.wind_speed", "15"));
  EXPECT_LT(maxRelDiff(windy.rgb, fresh("mountain_lake.toml", at).rgb), 1e-5);
}

// A key given twice when the renderer was made (the later one in effect): updating it back to the
// earlier value is a change, not a no-op (found by the live preview).
TEST(Renderer, UpdateComparesWithTheOverrideInEffect) {
  const std::vector<Override> base = small({set("surface.grid", "64"), set("quality.sea_lut_size", "17"),
                                            set("quality.sea_lut_size", "9")});
  Renderer renderer(test::testDevice(), sceneFile("wavy_sea.toml"), base, shippedPasses());
  (void)renderer.render();
  EXPECT_EQ(renderer.scene().quality.at("sea_lut_size").value, 9);
  renderer.update({set("quality.sea_lut_size", "17")});
  EXPECT_EQ(renderer.scene().quality.at("sea_lut_size").value, 17);
  (void)renderer.render();
  EXPECT_EQ(models(renderer.lastExecuted()), std::vector<std::string>{"sea_single"});
  renderer.update({set("quality.sea_lut_size", "17")});  // now a real no-op
  EXPECT_EQ(renderer.scene().quality.at("sea_lut_size").value, 17);
}

// A quality knob of sea_single: only it is set up and runs again; the ocean does not run.
TEST(Renderer, SeaLutKnobRerunsOnlyTheSeaPass) {
  const std::vector<Override> base = small({set("surface.grid", "64")});
  Renderer renderer(test::testDevice(), sceneFile("wavy_sea.toml"), base, shippedPasses());
  (void)renderer.render();
  renderer.update({set("quality.sea_lut_size", "9")});
  const FrameResult f = renderer.render();
  EXPECT_EQ(models(renderer.lastExecuted()), std::vector<std::string>{"sea_single"});
  EXPECT_EQ(models(renderer.lastPrepared()), std::vector<std::string>{"sea_single"});
  std::vector<Override> at = base;
  at.push_back(set("quality.sea_lut_size", "9"));
  EXPECT_EQ(f.rgb.pixels, fresh("wavy_sea.toml", at).rgb.pixels);
}

// sea_second adds into sea_single's image: a knob of sea_second sets up only sea_second, but
// sea_single must run again first (else L² would be added twice); the frame equals a fresh one.
TEST(Renderer, SecondOrderKnobRerunsTheImageItAddsInto) {
  const std::vector<Override> base = small({set("quality.sea_map_size", "8"), set("quality.sea_nz", "4")});
  Renderer renderer(test::testDevice(), sceneFile("open_ocean.toml"), base, shippedPasses());
  (void)renderer.render();
  renderer.update({set("quality.sea_nz", "6")});
  const FrameResult f = renderer.render();
  EXPECT_EQ(models(renderer.lastPrepared()), std::vector<std::string>{"sea_second"});
  EXPECT_EQ(models(renderer.lastExecuted()), (std::vector<std::string>{"sea_single", "sea_second"}));
  std::vector<Override> at = base;
  at.push_back(set("quality.sea_nz", "6"));
  EXPECT_EQ(f.rgb.pixels, fresh("open_ocean.toml", at).rgb.pixels);
}

std::vector<Override> smallSeabed() {
  return small({set("quality.froxel_x", "12"), set("quality.froxel_y", "8"), set("quality.froxel_z", "16"),
                set("quality.shadow_map_size", "64")});
}

// Under water, a new sun rewrites the G-buffer pass's parameter blocks and runs it again (the sun
// visibility changes) but does not set it up again.
TEST(Renderer, UnderwaterSunDoesNotRebuildTheRaycast) {
  Renderer renderer(test::testDevice(), sceneFile("seabed.toml"), smallSeabed(), shippedPasses());
  const FrameResult first = renderer.render();
  ASSERT_TRUE(has(renderer.lastPrepared(), "raycast"));
  renderer.update({set("sun.zenith_deg", "55")});
  const FrameResult f = renderer.render();
  EXPECT_FALSE(has(renderer.lastPrepared(), "raycast"));
  EXPECT_TRUE(has(renderer.lastExecuted(), "raycast"));
  EXPECT_TRUE(has(renderer.lastExecuted(), "kd_multiple"));
  EXPECT_NE(f.rgb.pixels, first.rgb.pixels);
  std::vector<Override> at = smallSeabed();
  at.push_back(set("sun.zenith_deg", "55"));
  EXPECT_EQ(f.rgb.pixels, fresh("seabed.toml", at).rgb.pixels);
}

// underwater.model = "discrete_ordinates": the band table holds the start factors of the camera's integrals
// (e^{-k o_d} and its kin at the camera's depth, UWI_ROW_EXP_*), so a frame after the camera moved in
// depth (camera.* sets the G-buffer pass up again, band table included) is the frame a new renderer
// makes there.
TEST(Renderer, UnderwaterOrdinatesCameraMovedInDepthMatchesAFreshFrame) {
  std::vector<Override> at = smallSeabed();
  at.push_back(set("underwater.model", "\"discrete_ordinates\""));
  Renderer renderer(test::testDevice(), sceneFile("seabed.toml"), at, shippedPasses());
  const FrameResult first = renderer.render();
  const Override moved = set("camera.position", "[0.0, -2.0, 0.0]");
  renderer.update({moved});
  const FrameResult f = renderer.render();
  EXPECT_TRUE(has(renderer.lastExecuted(), "kd_multiple"));
  EXPECT_NE(f.rgb.pixels, first.rgb.pixels);
  at.push_back(moved);
  EXPECT_EQ(f.rgb.pixels, fresh("seabed.toml", at).rgb.pixels);
}

// The preview's orbit: the camera moves and turns at one depth. The set-up pass moves the camera in the
// setup it has (moveUnderwaterCamera) instead of solving the discrete ordinates again, and the frame is a
// new renderer's there, bit for bit; so is the set-up itself, field for field.
TEST(Renderer, UnderwaterCameraMovedAtOneDepthKeepsTheTablesAndMatchesAFreshFrame) {
  std::vector<Override> at = smallSeabed();
  at.push_back(set("underwater.caustics", "\"texture\""));
  Renderer renderer(test::testDevice(), sceneFile("seabed.toml"), at, shippedPasses());
  const FrameResult first = renderer.render();
  const Override moved = set("camera.position", "[0.4, -3.8, -0.3]"), turned = set("camera.look_at", "[1.0, -4.0, -8.0]"),
                 wider = set("camera.fov_deg", "70");
  renderer.update({moved, turned, wider});
  const FrameResult f = renderer.render();
  EXPECT_FALSE(has(renderer.lastPrepared(), "underwater_setup"));
  EXPECT_TRUE(has(renderer.lastExecuted(), "kd_multiple"));
  EXPECT_NE(f.rgb.pixels, first.rgb.pixels);
  std::vector<Override> after = at;
  after.insert(after.end(), {moved, turned, wider});
  EXPECT_EQ(f.rgb.pixels, fresh("seabed.toml", after).rgb.pixels);

  const Scene a = loadScene(sceneFile("seabed.toml"), at);
  const Scene b = loadScene(sceneFile("seabed.toml"), after);
  const WavelengthGrid grid = makeGrid(a.spectral.count, a.spectral.min_nm, a.spectral.max_nm);
  const Sensor sensor = makeSensor(a.spectral.sensor, grid, a.spectral.white_balance, a.spectral.camera_dir);
  UnderwaterSetup setup = makeUnderwaterSetup(a, grid, sensor);
  ASSERT_FALSE(setup.ordinates.empty());
  ASSERT_TRUE(moveUnderwaterCamera(setup, b));
  const UnderwaterSetup made = makeUnderwaterSetup(b, grid, sensor);
  EXPECT_EQ(std::memcmp(&setup.params, &made.params, sizeof(UwParams)), 0);
  ASSERT_EQ(setup.ordinates.size(), made.ordinates.size());
  EXPECT_EQ(std::memcmp(setup.ordinates.data(), made.ordinates.data(), sizeof(UwiBand) * made.ordinates.size()), 0);
  // Another depth: the tables follow it, so the setup is made again.
  const Scene deeper = loadScene(sceneFile("seabed.toml"), {set("camera.position", "[0.0, -2.0, 0.0]")});
  EXPECT_FALSE(moveUnderwaterCamera(setup, deeper));
  EXPECT_EQ(std::memcmp(&setup.params, &made.params, sizeof(UwParams)), 0);  // unchanged
}

// The preview's orbit above water: a camera moved, turned or widened at one image size keeps sea_single's
// and the foam's set-up (the sky's cosine means, the bands, the LUT) and the foam's mask while the ocean
// is unchanged; only their parameter blocks' camera changes. Each frame is a new renderer's, bit for
// bit; a new image size and a new ocean frame still set up and mask again.
TEST(Renderer, SeaCameraMovedKeepsTheSetupAndTheFoamMaskAndMatchesAFreshFrame) {
  const auto ran = [](const FrameResult& f, const char* name) {
    return std::any_of(f.timings.begin(), f.timings.end(), [&](const PassTiming& t) { return t.name == name; });
  };
  std::vector<Override> at = small({set("surface.grid", "64")});
  Renderer renderer(test::testDevice(), sceneFile("whitecaps.toml"), at, shippedPasses());
  ASSERT_TRUE(renderer.plan().hasPass("whitecaps"));
  const FrameResult first = renderer.render();
  EXPECT_TRUE(ran(first, "whitecaps_mask"));
  const auto step = [&](const Override& change, bool set_up_again, bool ocean_again) {
    renderer.update({change});
    at.push_back(change);
    const FrameResult f = renderer.render();
    EXPECT_EQ(has(renderer.lastPrepared(), "sea_single"), set_up_again) << change.key;
    EXPECT_EQ(has(renderer.lastPrepared(), "whitecaps"), set_up_again) << change.key;
    EXPECT_TRUE(has(renderer.lastExecuted(), "whitecaps")) << change.key;
    EXPECT_EQ(ran(f, "ocean_fft"), ocean_again) << change.key;
    EXPECT_EQ(ran(f, "whitecaps_mask"), ocean_again || set_up_again) << change.key;
    EXPECT_NE(f.rgb.pixels, first.rgb.pixels) << change.key;
    EXPECT_EQ(f.rgb.pixels, fresh("whitecaps.toml", at).rgb.pixels) << change.key;
  };
  step(set("camera.position", "[2.0, 14.0, 1.0]"), false, false);
  step(set("camera.look_at", "[6.0, 0.0, -40.0]"), false, false);
  step(set("camera.fov_deg", "50"), false, false);
  step(set("surface.time", "2.0"), false, true);  // a new ocean frame: the foam masked again
  step(set("camera.position", "[1.0, 15.0, 0.0]"), false, false);
  step(set("camera.width", "40"), true, false);
}

// An underwater animation: surface.time alone changes the waves' phase, which the underwater setup holds
// as one number (the caustics' time); the set-up pass patches it instead of remaking the setup (the
// discrete-ordinates model's per-band tables), and the frame is still the fresh renderer's, bit for bit, in a
// scene with texture caustics, which read that time.
TEST(Renderer, UnderwaterSurfaceTimeKeepsTheSetupAndMatchesAFreshFrame) {
  std::vector<Override> at = smallSeabed();
  at.push_back(set("underwater.model", "\"discrete_ordinates\""));
  at.push_back(set("underwater.caustics", "\"texture\""));
  Renderer renderer(test::testDevice(), sceneFile("seabed.toml"), at, shippedPasses());
  const FrameResult first = renderer.render();
  const Override later = set("surface.time", "1.75");
  renderer.update({later});
  const FrameResult f = renderer.render();
  EXPECT_TRUE(has(renderer.lastExecuted(), "kd_multiple"));
  EXPECT_NE(f.rgb.pixels, first.rgb.pixels);  // the caustics moved
  at.push_back(later);
  EXPECT_EQ(f.rgb.pixels, fresh("seabed.toml", at).rgb.pixels);
}

// Two updates before one frame, the sun and then the time: the set-up pass sees both (the keys changed
// since the last frame, not the last update's), so it remakes the setup rather than patching the time.
TEST(Renderer, UpdatesBetweenTwoFramesAllReachTheUnderwaterSetup) {
  std::vector<Override> at = smallSeabed();
  at.push_back(set("underwater.caustics", "\"texture\""));
  Renderer renderer(test::testDevice(), sceneFile("seabed.toml"), at, shippedPasses());
  (void)renderer.render();
  const Override sun = set("sun.zenith_deg", "50"), later = set("surface.time", "1.75");
  renderer.update({sun});
  renderer.update({later});
  const FrameResult f = renderer.render();
  EXPECT_FALSE(has(renderer.lastPrepared(), "raycast"));  // same sizes: the same buffers
  at.insert(at.end(), {sun, later});
  EXPECT_EQ(f.rgb.pixels, fresh("seabed.toml", at).rgb.pixels);
}

// Data files are read once per renderer (and per job, which shares them): a change of the band count
// makes the sensor again from the camera curves already read; a new Renderer on a scene that carries
// the same DataFiles reads nothing either.
TEST(Renderer, CameraCurvesAreReadOnceAcrossUpdates) {
  Renderer renderer(test::testDevice(), sceneFile("seabed.toml"), smallSeabed(), shippedPasses());
  (void)renderer.render();
  ASSERT_NE(renderer.scene().files, nullptr);
  const int reads = renderer.scene().files->reads();
  EXPECT_EQ(reads, 1);  // canon_eos_5d_mark_ii_rawtoaces.csv (the scene has no images)
  renderer.update({set("spectral.count", "8")});
  (void)renderer.render();
  EXPECT_EQ(renderer.scene().files->reads(), reads);
  Scene again = renderer.scene();
  Renderer second(test::testDevice(), again, shippedPasses());
  (void)second.render();
  EXPECT_EQ(renderer.scene().files->reads(), reads);
}

// A froxel knob sets up only the froxel pass; the G-buffer does not run again, the shading that
// reads the new volume does, and the water's point spread (the discrete-ordinates model, the default) that
// reads the shading.
TEST(Renderer, FroxelKnobRebuildsOnlyTheFroxelPass) {
  Renderer renderer(test::testDevice(), sceneFile("seabed.toml"), smallSeabed(), shippedPasses());
  (void)renderer.render();
  renderer.update({set("quality.froxel_z", "24")});
  const FrameResult f = renderer.render();
  EXPECT_TRUE(has(renderer.lastPrepared(), "froxel"));
  EXPECT_FALSE(has(renderer.lastPrepared(), "raycast"));
  EXPECT_EQ(models(renderer.lastExecuted()), (std::vector<std::string>{"froxel", "kd_multiple", "water_spread"}));
  std::vector<Override> at = smallSeabed();
  at.push_back(set("quality.froxel_z", "24"));
  EXPECT_EQ(f.rgb.pixels, fresh("seabed.toml", at).rgb.pixels);
}

// The froxel pass's sun shadow map depends on the objects and the sun, not on the camera: a moved camera
// (or a new time) sets the froxel pass up again but keeps the map; a moved object or a new sun computes
// it again. Every frame equals a fresh renderer's at the same settings.
TEST(Renderer, FroxelShadowMapIsKeptWhileOnlyTheCameraMoves) {
  const auto ran = [](const FrameResult& f, const char* name) {
    return std::any_of(f.timings.begin(), f.timings.end(), [&](const PassTiming& t) { return t.name == name; });
  };
  Renderer renderer(test::testDevice(), sceneFile("seabed.toml"), smallSeabed(), shippedPasses());
  EXPECT_TRUE(ran(renderer.render(), "froxel_shadow_map"));
  std::vector<Override> at = smallSeabed();
  const auto step = [&](const Override& change, bool map_again) {
    renderer.update({change});
    at.push_back(change);
    const FrameResult f = renderer.render();
    EXPECT_TRUE(has(renderer.lastPrepared(), "froxel")) << change.key;
    EXPECT_EQ(ran(f, "froxel_shadow_map"), map_again) << change.key;
    EXPECT_EQ(f.rgb.pixels, fresh("seabed.toml", at).rgb.pixels) << change.key;
  };
  step(set("camera.position", "[0.3, -3.5, 1.0]"), false);
  step(set("surface.time", "1.5"), false);
  step(set("objects[0].center", "[-1.0, -4.4, -5.5]"), true);
  step(set("camera.look_at", "[0.5, -4.8, -8.0]"), false);
  step(set("sun.zenith_deg", "40.0"), true);
}

// A change that changes the plan (the second order switched on) builds the new graph. Paper 000's
// model: "multiple" (the default) holds the second order in its closed form and plans no maps.
TEST(Renderer, PlanChangeBuildsTheNewGraph) {
  Renderer renderer(test::testDevice(), sceneFile("flat_sea.toml"), small({set("sea.model", "\"paper\"")}),
                    shippedPasses());
  (void)renderer.render();
  EXPECT_FALSE(renderer.plan().hasPass("sea_second"));
  renderer.update({set("sea.second_order", "true"), set("quality.sea_map_size", "8"), set("quality.sea_nz", "4")});
  const FrameResult f = renderer.render();
  EXPECT_TRUE(has(renderer.lastExecuted(), "sea_second"));
  EXPECT_EQ(f.rgb.pixels,
            fresh("flat_sea.toml", small({set("sea.model", "\"paper\""), set("sea.second_order", "true"),
                                          set("quality.sea_map_size", "8"),
                                          set("quality.sea_nz", "4")}))
                .rgb.pixels);
}

// The executor knows passes only through the registry and the plan: a hand-made plan of a test pass
// that fills the image with the sun's irradiance. A sun change reruns it; a key no pass claims sets
// everything up again.
class FillPass : public Pass {
 public:
  explicit FillPass(int* prepares) : prepares_(prepares) {}
  PassKeys keys() const override { return {{}, {"sun.*"}}; }
  void prepare(FrameContext& ctx, PassResources& res) override {
    ++*prepares_;
    auto target = std::make_shared<RadianceTarget>();
    target->pixels = size_t(ctx.scene().camera.width) * ctx.scene().camera.height;
    target->rgb = cl::Buffer(ctx.device().context(), CL_MEM_READ_WRITE, sizeof(float) * 3 * target->pixels);
    res.publish("rgb", target);
  }
  void execute(FrameContext& ctx, PassResources& res) override {
    RadianceTarget& t = res.read<RadianceTarget>("rgb");
    const float v = static_cast<float>(ctx.scene().sun.irradiance);
    ctx.device().queue().enqueueFillBuffer(t.rgb, v, 0, sizeof(float) * 3 * t.pixels);
    ctx.device().queue().finish();
    ctx.timings.push_back({"fill", 0.0});
  }

 private:
  int* prepares_;
};

TEST(Renderer, RunsAHandMadePlanThroughTheRegistry) {
  int prepares = 0;
  PassRegistry registry = shippedPasses();
  registry.add("fill", [&](const PassPlan&, const Plan&, const Scene&) { return std::make_unique<FillPass>(&prepares); });
  Plan plan;
  plan.passes.push_back({"fill", "none.cl", {}, {"scene"}, {"rgb"}, "test", true, ""});
  plan.passes.push_back({"nonfinite_check", "check.cl", {}, {"rgb"}, {"status"}, "test", true, ""});
  Scene scene = loadScene(sceneFile("flat_sea.toml"), small({set("sun.irradiance", "2.0")}));
  Renderer renderer(test::testDevice(), scene, plan, registry);
  FrameResult f = renderer.render();
  EXPECT_EQ(f.rgb.pixels.front(), 2.0f);
  EXPECT_EQ(prepares, 1);
  scene.sun.irradiance = 3.0;
  renderer.update(scene, {"sun.irradiance"});
  f = renderer.render();
  EXPECT_EQ(f.rgb.pixels.back(), 3.0f);
  EXPECT_EQ(prepares, 1);
  EXPECT_EQ(renderer.lastExecuted(), (std::vector<std::string>{"fill", "nonfinite_check"}));
  renderer.update(scene, {"camera.fov_deg"});  // claimed by no pass of this plan
  (void)renderer.render();
  EXPECT_EQ(prepares, 2);
}

TEST(Renderer, PlanErrorsNameThePass) {
  const Scene scene = loadScene(sceneFile("flat_sea.toml"), small({}));
  Plan unknown;
  unknown.passes.push_back({"mystery", "mystery.cl", {}, {"scene"}, {"rgb"}, "test", true, ""});
  try {
    Renderer(test::testDevice(), scene, unknown, shippedPasses()).render();
    FAIL() << "an unregistered pass must be an error";
  } catch (const RuntimeError& e) {
    EXPECT_NE(std::string(e.what()).find("'mystery'"), std::string::npos) << e.what();
  }
  Plan backwards;  // the check reads "rgb" before any pass writes it
  backwards.passes.push_back({"nonfinite_check", "check.cl", {}, {"rgb"}, {"status"}, "test", true, ""});
  backwards.passes.push_back({"sea_single", "sea_single.cl", {}, {"scene"}, {"rgb"}, "test", true, ""});
  try {
    Renderer(test::testDevice(), scene, backwards, shippedPasses()).render();
    FAIL() << "a read before its write must be an error";
  } catch (const RuntimeError& e) {
    EXPECT_NE(std::string(e.what()).find("no earlier pass writes"), std::string::npos) << e.what();
  }
}

// A job's items on one scene file share a renderer (jobs/runner.cpp): each item's image is the one a
// fresh renderer makes of its scene, also when an item drops an override the item before had.
TEST(Renderer, JobItemsOnOneSceneShareARendererAndMatchFreshFrames) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(SEASIM_BUILD_DIR) / "renderer_test_job";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string scene = sceneFile("wavy_sea.toml");
  std::ofstream(dir / "job.toml") << "[job]\nname = \"reuse\"\noutput_dir = \"out\"\n"
                                  << "[[render]]\nname = \"t0\"\nscene = \"" << scene << "\"\n"
                                  << "overrides = { \"camera.width\" = 48, \"camera.height\" = 32, \"surface.grid\" = 64 }\noutputs = [\"exr\"]\n"
                                  << "[[render]]\nname = \"t2\"\nscene = \"" << scene << "\"\n"
                                  << "overrides = { \"camera.width\" = 48, \"camera.height\" = 32, \"surface.grid\" = 64, \"surface.time\" = 2.0, \"sun.zenith_deg\" = 60 }\noutputs = [\"exr\"]\n"
                                  << "[[render]]\nname = \"back\"\nscene = \"" << scene << "\"\n"
                                  << "overrides = { \"camera.width\" = 48, \"camera.height\" = 32, \"surface.grid\" = 64, \"surface.time\" = 2.0 }\noutputs = [\"exr\"]\n";
  RunOptions options;
  options.device = test::testDeviceSelector();  // the fresh frames below render on the test device
  const RunSummary summary = runJob((dir / "job.toml").string(), options);
  EXPECT_EQ(summary.rendered, 3);
  const std::vector<Override> base = small({set("surface.grid", "64")});
  std::vector<Override> t2 = base, back = base;
  t2.push_back(set("surface.time", "2.0"));
  t2.push_back(set("sun.zenith_deg", "60"));
  back.push_back(set("surface.time", "2.0"));
  const std::vector<std::pair<std::string, std::vector<Override>>> items = {{"t0", base}, {"t2", t2}, {"back", back}};
  for (const auto& [name, overrides] : items) {
    const Image written = readImage((dir / "out" / name / "image.exr").string());
    EXPECT_LT(maxRelDiff(written, fresh("wavy_sea.toml", overrides).rgb), 1e-6) << name;
  }
}

}  // namespace
}  // namespace seasim
