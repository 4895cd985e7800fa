// sea_bottom_caustics_test.cpp — the FFT ocean's caustics on the bottom seen from above
// (sea.bottom_caustics, SEASIM_BOTTOM_CAUSTICS): with only the bottom term on, the frame with caustics
// over the frame without is the focusing factor at each pixel's bottom point, so it must average ~1
// with a real spread under waves and be 1 under a calm sea (exactly on a flat bottom; within the floor
// splat's lattice ripple on a height field); the host maps are normalised; no NaN/Inf.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "passes/caustic_stack.h"
#include "passes/ocean_pass.h"
#include "quality/render_frame.h"
#include "plan/plan.h"
#include "reference/sea_reference.h"
#include "scene/scene_parser.h"
#include "test_device.h"
#include "util/error.h"

namespace {

const char* kShallow = R"(
[camera]
position = [0, 6, 0]
look_at = [0, 0, -10]
fov_deg = 60
width = 48
height = 32
[sun]
zenith_deg = 30
azimuth_deg = 250
[water]
jerlov = "IB"
[surface]
type = "fft"
grid = 64
patch_size = 16.0
wind_speed = 6.0
[bottom]
type = "flat"
depth = 4.0
albedo = 0.4
[sea]
reflection = false
single_scattering = false
bottom_caustics = true
[quality]
caustic_map_size = 128
[spectral]
count = 4
)";

seasim::Override set(const char* key, const std::string& value) { return {key, value, {"test", 1}}; }

// Per-pixel green ratio with / without caustics over pixels where the bottom term is visible.
struct Ratio {
  double mean = 0, sd = 0, lo = 1e30, hi = 0;
  int count = 0;
};

Ratio ratio(const std::string& text, std::vector<seasim::Override> overrides) {
  const seasim::Scene with = seasim::parseScene(text, "bottom_caustics.toml", overrides);
  overrides.push_back(set("sea.bottom_caustics", "false"));
  const seasim::Scene without = seasim::parseScene(text, "bottom_caustics.toml", overrides);
  EXPECT_TRUE(seasim::makePlan(with).hasPass("caustics"));
  EXPECT_FALSE(seasim::makePlan(without).hasPass("caustics"));
  const seasim::FrameResult a = seasim::renderFrame(seasim::test::testDevice(), with, seasim::makePlan(with));
  const seasim::FrameResult b = seasim::renderFrame(seasim::test::testDevice(), without, seasim::makePlan(without));
  EXPECT_EQ(a.nonfinite, 0);
  float peak = 0;
  for (float v : b.rgb.pixels) peak = std::max(peak, v);
  Ratio r;
  double sum2 = 0;
  for (size_t i = 1; i < b.rgb.pixels.size(); i += 3) {
    EXPECT_TRUE(std::isfinite(a.rgb.pixels[i]));
    if (!(b.rgb.pixels[i] > 1e-3f * peak)) continue;  // the sky above the horizon
    const double q = a.rgb.pixels[i] / b.rgb.pixels[i];
    r.mean += q;
    sum2 += q * q;
    r.lo = std::min(r.lo, q);
    r.hi = std::max(r.hi, q);
    ++r.count;
  }
  r.mean /= std::max(r.count, 1);
  r.sd = std::sqrt(std::max(0.0, sum2 / std::max(r.count, 1) - r.mean * r.mean));
  std::printf("bottom caustics: %d pixels, ratio mean %.4f sd %.4f range [%.3f, %.3f]\n", r.count, r.mean, r.sd, r.lo,
              r.hi);
  return r;
}

TEST(SeaBottomCaustics, FlatBottomUnderWavesFocusesAroundTheMean) {
  const Ratio r = ratio(kShallow, {});
  ASSERT_GT(r.count, 600);
  EXPECT_NEAR(r.mean, 1.0, 0.1);  // the pixels sample the periodic pattern (mean 1) unevenly
  EXPECT_GT(r.sd, 0.1);
  EXPECT_GT(r.hi, 1.5);
}

TEST(SeaBottomCaustics, CalmSeaChangesNothing) {
  const Ratio flat = ratio(kShallow, {set("surface.wind_speed", "0")});
  EXPECT_NEAR(flat.lo, 1.0, 1e-5);
  EXPECT_NEAR(flat.hi, 1.0, 1e-5);
  // A sloping height-field floor: the floor splat divided by its calm-sea value; the bilinear splat
  // of the ray lattice leaves a few-% ripple (caustics_floor_test.cpp).
  std::string hf = kShallow;
  hf.replace(hf.find("type = \"flat\"\ndepth = 4.0"), std::string("type = \"flat\"\ndepth = 4.0").size(),
             "type = \"heightfield\"\nheightfield = \"" SEASIM_SOURCE_DIR
             "/scenes/textures/seashore_bottom.exr\"\nmin_depth = 1\nmax_depth = 8\nextent = 60");
  const Ratio floor = ratio(hf, {set("surface.wind_speed", "0")});
  EXPECT_NEAR(floor.mean, 1.0, 0.02);
  EXPECT_GT(floor.lo, 0.9);
  EXPECT_LT(floor.hi, 1.1);
}

TEST(SeaBottomCaustics, HostMapsAreNormalised) {
  const seasim::Scene scene = seasim::parseScene(kShallow, "bottom_caustics.toml");
  seasim::OceanPass ocean(seasim::test::testDevice(), seasim::oceanConfigFromSurface(scene.surface));
  ocean.run(scene.surface.time);
  const seasim::SeaBottomCaustics c = seasim::seaBottomCaustics(seasim::test::testDevice(), scene, ocean.maps());
  ASSERT_EQ(c.map_size, 128);
  EXPECT_TRUE(c.periodic);
  EXPECT_DOUBLE_EQ(c.extent, 16.0);
  double sum = 0;
  for (float v : c.host) {
    ASSERT_TRUE(std::isfinite(v) && v >= 0);
    sum += v;
  }
  EXPECT_NEAR(sum / c.host.size(), 1.0, 1e-4);
}

TEST(SeaBottomCaustics, PlannedOnlyWithWavesABottomAndTheSun) {
  auto planned = [](std::vector<seasim::Override> o) {
    const seasim::Plan plan = seasim::makePlan(seasim::parseScene(kShallow, "bottom_caustics.toml", o));
    const auto* sea = plan.find("sea_single");
    const bool define = sea && std::find(sea->defines.begin(), sea->defines.end(), "SEASIM_BOTTOM_CAUSTICS=1") !=
                                   sea->defines.end();
    EXPECT_EQ(define, plan.hasPass("caustics"));
    return define;
  };
  EXPECT_TRUE(planned({}));
  EXPECT_FALSE(planned({set("sea.bottom_caustics", "false")}));
  EXPECT_FALSE(planned({set("surface.type", "\"flat\"")}));
  EXPECT_FALSE(planned({set("sun.zenith_deg", "95")}));
}

TEST(SeaBottomCaustics, TheReferenceRefusesWhatItDoesNotModel) {
  const seasim::Scene scene = seasim::parseScene(kShallow, "bottom_caustics.toml");
  EXPECT_THROW(seasim::renderSeaReference(scene, 10), seasim::RuntimeError);
}

}  // namespace
