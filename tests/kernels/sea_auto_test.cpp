// sea_auto_test.cpp — `auto` quality of the sea's second order (host/quality/sea_auto.h, 000 §6.1) on
// PoCL, on a 32x18, 3-band flat sea (the search runs at the scene's own size):
//  * the chosen (n_z, n_d, M) meets the criterion when re-measured by independent renders: max
//    |L(n_z) - L(n_z + 1)|, |L(n_d) - L(next n_d)| and |L(M) - L(next M)| under 1 8-bit level;
//  * the decision is cached: a second call renders nothing and returns the same setting;
//  * a knob fixed in the scene stays fixed and is not searched;
//  * SeaSecondPass uses the search for "auto" knobs (same image as the chosen values given explicitly).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include <unistd.h>

#include "quality/render_frame.h"
#include "quality/sea_auto.h"
#include "plan/plan.h"
#include "reference/compare.h"
#include "scene/scene_parser.h"
#include "test_device.h"

namespace {

namespace fs = std::filesystem;
using seasim::Override;

const char* kScene = R"(
[scene]
name = "test_sea_auto"
[camera]
position = [0, 10, 0]
look_at = [0, 0, -60]
fov_deg = 70
width = 32
height = 18
exposure_ev = 2
[sun]
zenith_deg = 40
azimuth_deg = 270
[water]
jerlov = "IB"
[bottom]
type = "flat"
depth = 8
albedo = 0.3
[spectral]
count = 3
[sea]
second_order = true
)";

seasim::Device& device() { return seasim::test::testDevice(); }

Override set(const std::string& key, const std::string& value) { return {key, value, {"test", 1}}; }

seasim::Scene scene(const std::string& nz = "\"auto\"", const std::string& nd = "\"auto\"",
                    const std::string& map = "\"auto\"") {
  return seasim::parseScene(kScene, "test_sea_auto.toml",
                            {set("quality.sea_nz", nz), set("quality.sea_nd", nd), set("quality.sea_map_size", map)});
}

seasim::Image render(seasim::Scene s, int nz, int nd, int map) {
  s.quality["sea_nz"] = seasim::Knob{false, double(nz)};
  s.quality["sea_nd"] = seasim::Knob{false, double(nd)};
  s.quality["sea_map_size"] = seasim::Knob{false, double(map)};
  const seasim::FrameResult f = seasim::renderFrame(device(), s, seasim::makePlan(s));
  EXPECT_EQ(f.nonfinite, 0);
  return f.rgb;
}

double step(const seasim::Scene& s, int nz, int nd, int map, int nz2, int nd2, int map2) {
  return seasim::compareImages(render(s, nz2, nd2, map2), render(s, nz, nd, map), s.camera.exposure_ev).max_abs_8bit;
}

// A fresh cache folder per test process.
std::string cacheDir(const char* name) {
  const std::string dir = ::testing::TempDir() + "/seasim_sea_auto_" + name + "_" + std::to_string(getpid());
  fs::remove_all(dir);
  return dir;
}

int nextOn(const std::vector<int>& ladder, int v) {
  for (size_t i = 0; i + 1 < ladder.size(); ++i)
    if (ladder[i] == v) return ladder[i + 1];
  ADD_FAILURE() << v << " is not below the top of its ladder";
  return v;
}

TEST(SeaAuto, ChosenSettingMeetsTheCriterionAndIsCached) {
  const seasim::Scene s = scene();
  seasim::SeaAutoOptions o;
  o.cache_dir = cacheDir("criterion");
  const seasim::SeaAutoResult r = seasim::chooseSeaSecondQuality(device(), s, o);
  std::printf("auto: n_z %d (step %.3f), n_d %d (step %.3f), map %d (step %.3f); %d frames, %.0f ms, %zu steps\n",
              r.n_z, r.nz_step_8bit, r.n_d, r.nd_step_8bit, r.map_size, r.map_step_8bit, r.renders, r.search_ms,
              r.steps.size());
  EXPECT_FALSE(r.from_cache);
  EXPECT_TRUE(r.met);
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.search_width, 32);
  EXPECT_EQ(r.search_height, 18);
  EXPECT_GT(r.renders, 3);
  ASSERT_FALSE(r.cache_file.empty());
  EXPECT_TRUE(fs::exists(r.cache_file));

  // Re-measure the criterion with independent renders at the chosen setting.
  const double dz = step(s, r.n_z, r.n_d, r.map_size, r.n_z + 1, r.n_d, r.map_size);
  const double dd = step(s, r.n_z, r.n_d, r.map_size, r.n_z, nextOn(o.nd_ladder, r.n_d), r.map_size);
  const double dm = step(s, r.n_z, r.n_d, r.map_size, r.n_z, r.n_d, nextOn(o.map_ladder, r.map_size));
  EXPECT_LT(dz, 1.0);
  EXPECT_LT(dd, 1.0);
  EXPECT_LT(dm, 1.0);
  EXPECT_NEAR(dz, r.nz_step_8bit, 1e-9);  // deterministic renders: the very numbers of the search
  EXPECT_NEAR(dd, r.nd_step_8bit, 1e-9);
  EXPECT_NEAR(dm, r.map_step_8bit, 1e-9);
  // The first rung below each choice missed the threshold (else it would have been chosen).
  if (r.n_z > 1) EXPECT_GE(step(s, r.n_z - 1, r.n_d, r.map_size, r.n_z, r.n_d, r.map_size), 1.0);

  // Second call: from the cache, nothing rendered, same answer.
  const seasim::SeaAutoResult again = seasim::chooseSeaSecondQuality(device(), s, o);
  EXPECT_TRUE(again.from_cache);
  EXPECT_EQ(again.renders, 0);
  EXPECT_TRUE(again.steps.empty());
  EXPECT_EQ(again.n_z, r.n_z);
  EXPECT_EQ(again.n_d, r.n_d);
  EXPECT_EQ(again.map_size, r.map_size);
  EXPECT_EQ(again.cache_file, r.cache_file);
  // A different threshold is a different entry.
  seasim::SeaAutoOptions loose = o;
  loose.threshold_levels = 4;
  EXPECT_NE(seasim::seaAutoKey(device(), s, loose), seasim::seaAutoKey(device(), s, o));
  fs::remove_all(o.cache_dir);
}

TEST(SeaAuto, FixedKnobsStayFixed) {
  const seasim::Scene s = scene("3", "\"auto\"", "16");
  seasim::SeaAutoOptions o;
  o.cache_dir = cacheDir("fixed");
  const seasim::SeaAutoResult r = seasim::chooseSeaSecondQuality(device(), s, o);
  EXPECT_EQ(r.n_z, 3);
  EXPECT_EQ(r.map_size, 16);
  for (const seasim::SeaAutoStep& st : r.steps) {
    EXPECT_EQ(st.knob, "sea_nd");
    EXPECT_EQ(st.n_z, 3);
    EXPECT_EQ(st.map_size, 16);
  }
  EXPECT_FALSE(seasim::seaSecondWantsAuto(scene("3", "64", "16")));
  fs::remove_all(o.cache_dir);
}

TEST(SeaAuto, PassUsesTheSearch) {
  // SeaSecondPass resolves "auto" through the default cache ($SEASIM_CACHE_DIR): the frame equals
  // the one rendered with the chosen values given explicitly.
  const seasim::Scene s = scene();
  const seasim::SeaAutoResult r = seasim::chooseSeaSecondQuality(device(), s);
  const seasim::FrameResult f = seasim::renderFrame(device(), s, seasim::makePlan(s));
  EXPECT_EQ(f.nonfinite, 0);
  const seasim::Image explicit_img = render(s, r.n_z, r.n_d, r.map_size);
  EXPECT_EQ(seasim::compareImages(f.rgb, explicit_img).max_abs_8bit, 0.0);
}

}  // namespace
