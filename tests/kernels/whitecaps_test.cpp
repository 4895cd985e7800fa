// whitecaps_test.cpp — kernels/whitecaps.cl on PoCL (float) against the double CPU evaluation of the
// same header (kernels/common/whitecaps.h through passes/whitecaps_math.h), over a real FFT ocean's
// Jacobian map: the mask's mips and the composited image. Also: the rendered foam against Monahan's
// W at three winds and one more, no wind leaving the sea's image bit for bit, extreme views and
// inputs giving no NaN/Inf, the whole frame with and without the pass, and the renderer's updates.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "passes/ocean_pass.h"
#include "passes/whitecaps_math.h"
#include "passes/whitecaps_pass.h"
#include "passes/whitecaps_threshold.h"
#include "plan/plan.h"
#include "quality/auto_quality.h"
#include "quality/render_frame.h"
#include "render/renderer.h"
#include "scene/scene_parser.h"
#include "spectral/sensor.h"
#include "spectral/wavelength_grid.h"
#include "test_device.h"

namespace {

namespace wd = seasim::whitecaps_d;

seasim::Override set(const std::string& key, const std::string& value) { return {key, value, {"<test>", 1}}; }

// The shipped windy sea, small: a 64² tile and a 96 x 54 image from 10 m up (sky, near and far sea).
seasim::Scene smallScene(std::vector<seasim::Override> extra = {}) {
  std::vector<seasim::Override> o = {set("camera.width", "96"), set("camera.height", "54"), set("surface.grid", "64"),
                                     set("surface.patch_size", "40.0")};
  o.insert(o.end(), extra.begin(), extra.end());
  return seasim::loadScene(std::string(SEASIM_SOURCE_DIR) + "/scenes/whitecaps.toml", o);
}

struct PassRun {
  std::vector<float> rgb_in, rgb_out, mips;
  std::vector<float> jacobian;
  seasim::WhitecapsFoamLevels levels;
  WhitecapsParams params{};
  std::vector<float> foam_bands;
};

// The ocean at the scene's time, its threshold for `coverage` (Monahan's W at the scene's wind when
// negative), and the pass over `rgb_in` (random radiances when empty).
PassRun runPass(const seasim::Scene& scene, std::vector<float> rgb_in = {}, double coverage = -1) {
  seasim::Device& device = seasim::test::testDevice();
  const seasim::Plan plan = seasim::makePlan(scene);
  const seasim::PassPlan* entry = plan.find("whitecaps");
  EXPECT_NE(entry, nullptr);
  seasim::OceanPass ocean(device, seasim::oceanConfigFromSurface(scene.surface));
  ocean.run(scene.surface.time);
  const seasim::WavelengthGrid grid = seasim::makeGrid(scene.spectral.count, scene.spectral.min_nm, scene.spectral.max_nm);
  const seasim::Sensor sensor = seasim::makeSensor(scene.spectral.sensor, grid, scene.spectral.white_balance);
  seasim::WhitecapsPass pass(device, scene, *entry, grid, sensor, ocean.n(), ocean.patchSize());
  PassRun r;
  const size_t pixels = size_t(scene.camera.width) * size_t(scene.camera.height);
  if (rgb_in.empty()) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.0f, 0.2f);
    rgb_in.resize(3 * pixels);
    for (float& v : rgb_in) v = u(rng);
  }
  r.rgb_in = rgb_in;
  r.jacobian = ocean.readJacobian();
  r.levels = seasim::whitecapsFoamLevels(r.jacobian, coverage < 0 ? wd::whitecaps_coverage(scene.surface.wind_speed)
                                                                   : coverage);
  cl::Buffer rgb(device.context(), CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, sizeof(float) * rgb_in.size(),
                 rgb_in.data());
  pass.run(ocean.jacobian(), r.levels, rgb);
  r.rgb_out.resize(rgb_in.size());
  device.queue().enqueueReadBuffer(rgb, CL_TRUE, 0, sizeof(float) * r.rgb_out.size(), r.rgb_out.data());
  r.mips = pass.readMips();
  r.params = pass.params();
  r.foam_bands = pass.foamBands();
  return r;
}

// The same in double: mask, mips, footprint and composite of common/whitecaps.h.
struct Reference {
  std::vector<double> mips, rgb;
};
Reference cpuReference(const PassRun& r) {
  const int n = r.params.ocean_n;
  Reference ref;
  ref.mips.resize(size_t(wd::whitecaps_level_offset(n, wd::whitecaps_levels(n))));
  for (int t = 0; t < n * n; ++t) ref.mips[t] = wd::whitecaps_mask(r.jacobian[t], r.levels.threshold, r.levels.rank_j.data());
  for (int level = 0; level + 1 < wd::whitecaps_levels(n); ++level) {
    const int nl = n >> level, m = nl >> 1;
    const double* src = ref.mips.data() + wd::whitecaps_level_offset(n, level);
    double* dst = ref.mips.data() + wd::whitecaps_level_offset(n, level + 1);
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i)
        dst[j * m + i] = wd::whitecaps_box(src[2 * j * nl + 2 * i], src[2 * j * nl + 2 * i + 1],
                                           src[(2 * j + 1) * nl + 2 * i], src[(2 * j + 1) * nl + 2 * i + 1]);
  }
  ref.rgb.assign(r.rgb_in.begin(), r.rgb_in.end());
  for (int y = 0; y < r.params.height; ++y)
    for (int x = 0; x < r.params.width; ++x) {
      double hx, hz, dx, dz, minor, major;
      if (!wd::whitecaps_pixel_footprint(&r.params, x, y, &hx, &hz, &dx, &dz, &minor, &major)) continue;
      const double f = wd::whitecaps_footprint(ref.mips.data(), n, r.params.ocean_patch, hx, hz, dx, dz, minor, major);
      const size_t pixel = size_t(y) * size_t(r.params.width) + size_t(x);
      for (int c = 0; c < 3; ++c) ref.rgb[3 * pixel + c] = wd::whitecaps_composite(r.rgb_in[3 * pixel + c], f, r.params.foam_rgb[c]);
    }
  return ref;
}

TEST(WhitecapsKernel, MatchesTheDoubleEvaluationOfItsHeader) {
  // 20 % cover (more than any wind's W) so that most pixels hold foam edges.
  const PassRun r = runPass(smallScene(), {}, 0.2);
  const Reference ref = cpuReference(r);
  double worst_mip = 0, worst = 0, foam_pixels = 0;
  for (size_t i = 0; i < ref.mips.size(); ++i) worst_mip = std::max(worst_mip, std::abs(r.mips[i] - ref.mips[i]));
  for (size_t i = 0; i < ref.rgb.size(); ++i) {
    worst = std::max(worst, std::abs(r.rgb_out[i] - ref.rgb[i]) / std::max(std::abs(ref.rgb[i]), 1e-3));
    foam_pixels += r.rgb_out[i] != r.rgb_in[i];
  }
  std::printf("mips: worst |float - double| %.3g; image: worst relative difference %.3g over %zu values, %.0f changed\n",
              worst_mip, worst, ref.rgb.size(), foam_pixels);
  EXPECT_LT(worst_mip, 1e-6);
  EXPECT_LT(worst, 1e-4);
  EXPECT_GT(foam_pixels, 0.2 * ref.rgb.size());
}

// Straight down from 100 m onto exactly one 100 m tile (256² texels, one pixel each): the image's
// mean foam opacity against 0.4 W (Monahan's W times Koepke's mean efficiency) at 5, 10 and 15 m/s and
// at 12.5 m/s, at which no choice in the model was made (the threshold is computed from W, nothing is
// fitted). Rounding W N² to whole texels is within 0.2 % of W at 5 m/s.
TEST(WhitecapsKernel, ANadirViewIsFoamAtMonahansCoverage) {
  for (double wind : {5.0, 10.0, 15.0, 12.5}) {
    const std::string w = std::to_string(wind);
    const seasim::Scene scene =
        seasim::loadScene(std::string(SEASIM_SOURCE_DIR) + "/scenes/whitecaps.toml",
                          {set("camera.position", "[0.0, 100.0, 0.0]"), set("camera.look_at", "[0.0, 0.0, -0.001]"),
                           set("camera.fov_deg", std::to_string(2 * std::atan(0.5) * 180 / M_PI)),
                           set("camera.width", "256"), set("camera.height", "256"), set("surface.grid", "256"),
                           set("surface.patch_size", "100.0"), set("surface.wind_speed", w)});
    const size_t pixels = 256 * 256;
    const PassRun r = runPass(scene, std::vector<float>(3 * pixels, 0.0f));
    double f = 0;
    for (size_t p = 0; p < pixels; ++p) f += r.rgb_out[3 * p + 1] / r.params.foam_rgb[1];
    f /= double(pixels);
    const double target = 0.4 * wd::whitecaps_coverage(wind);
    std::printf("wind %.1f m/s: 0.4 x Monahan W %.6f, rendered %.6f (ratio %.4f)\n", wind, target, f, f / target);
    EXPECT_NEAR(f / target, 1.0, 0.03) << "wind " << wind;
  }
}

TEST(WhitecapsKernel, NoWindLeavesTheSeaBitForBit) {
  const PassRun r = runPass(smallScene({set("surface.wind_speed", "0.0")}));
  EXPECT_EQ(r.rgb_out, r.rgb_in);
}

TEST(WhitecapsKernel, ExtremeViewsAndInputsStayFinite) {
  const std::vector<std::vector<seasim::Override>> cases = {
      // the horizon across the image, rays within a hair of it
      {set("camera.position", "[0.0, 0.01, 0.0]"), set("camera.look_at", "[0.0, 0.01, -100.0]")},
      // far up, a whole ocean per pixel
      {set("camera.position", "[0.0, 100000.0, 0.0]"), set("camera.look_at", "[0.0, 0.0, -50000.0]")},
      // a gale past Monahan's range: W held at 1 (every texel foam)
      {set("surface.wind_speed", "45.0")},
      // the sun below the horizon: the foam only has the sky's light
      {set("sun.zenith_deg", "100.0")}};
  for (const auto& c : cases) {
    const seasim::Scene scene = smallScene(c);
    std::vector<float> rgb(3 * size_t(scene.camera.width) * size_t(scene.camera.height));
    for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = i % 7 == 0 ? 3.0e38f : (i % 7 == 1 ? 0.0f : 1e-30f);
    const PassRun r = runPass(scene, rgb);
    long bad = 0;
    for (float v : r.rgb_out) bad += !std::isfinite(v);
    for (float v : r.mips) bad += !std::isfinite(v) || v < 0 || v > 1;
    EXPECT_EQ(bad, 0) << c.front().key << " = " << c.front().value_toml;
  }
}

// The whole frame through the renderer: the foam brightens the sea by about W (Lf - Lsea) on average,
// nothing non-finite, and without wind the frame is the one without the pass.
TEST(WhitecapsFrame, AddsFoamToTheRenderedSeaAndNothingWithoutWind) {
  seasim::Device& device = seasim::test::testDevice();
  auto frame = [&](std::vector<seasim::Override> o) {
    const seasim::Scene s = smallScene(o);
    return seasim::renderFrame(device, s, seasim::makePlan(s));
  };
  const seasim::FrameResult on = frame({}), off = frame({set("surface.whitecaps", "false")});
  EXPECT_EQ(on.nonfinite, 0);
  double sum_on = 0, sum_off = 0;
  for (float v : on.rgb.pixels) sum_on += v;
  for (float v : off.rgb.pixels) sum_off += v;
  std::printf("frame mean with foam %.6g, without %.6g\n", sum_on / on.rgb.pixels.size(), sum_off / off.rgb.pixels.size());
  EXPECT_GT(sum_on, sum_off);
  const seasim::FrameResult calm_on = frame({set("surface.wind_speed", "0.0")});
  const seasim::FrameResult calm_off = frame({set("surface.wind_speed", "0.0"), set("surface.whitecaps", "false")});
  EXPECT_EQ(calm_on.rgb.pixels, calm_off.rgb.pixels);
}

// The renderer's updates: a new time reruns the ocean, the sea and the foam without setting them up
// again; a new sun sets up the foam again (its radiance) after the sea; each frame equals a fresh one.
TEST(WhitecapsFrame, UpdatesRerunTheFoamAndMatchAFreshRender) {
  seasim::Device& device = seasim::test::testDevice();
  const std::string file = std::string(SEASIM_SOURCE_DIR) + "/scenes/whitecaps.toml";
  const std::vector<seasim::Override> base = {set("camera.width", "96"), set("camera.height", "54"),
                                              set("surface.grid", "64"), set("surface.patch_size", "40.0")};
  seasim::Renderer renderer(device, file, base, seasim::shippedPasses());
  (void)renderer.render();
  for (const seasim::Override& change : {set("surface.time", "2.5"), set("sun.zenith_deg", "60.0")}) {
    renderer.update({change});
    const seasim::FrameResult frame = renderer.render();
    const auto& ran = renderer.lastExecuted();
    EXPECT_NE(std::find(ran.begin(), ran.end(), "whitecaps"), ran.end()) << change.key;
    const auto& prepared = renderer.lastPrepared();
    EXPECT_EQ(std::find(prepared.begin(), prepared.end(), "whitecaps") != prepared.end(), change.key == "sun.zenith_deg");
    std::vector<seasim::Override> at = base;
    at.push_back(set("surface.time", "2.5"));
    if (change.key == "sun.zenith_deg") at.push_back(change);
    const seasim::Scene fresh_scene = seasim::loadScene(file, at);
    const seasim::FrameResult fresh = seasim::renderFrame(device, fresh_scene, seasim::makePlan(fresh_scene));
    ASSERT_EQ(frame.rgb.pixels.size(), fresh.rgb.pixels.size());
    double worst = 0;
    for (size_t i = 0; i < fresh.rgb.pixels.size(); ++i)
      worst = std::max(worst, std::abs(double(frame.rgb.pixels[i]) - fresh.rgb.pixels[i]) /
                                  std::max(std::abs(double(fresh.rgb.pixels[i])), 1e-6));
    EXPECT_LT(worst, 1e-5) << change.key;
  }
}

// With spectral output the foam goes into the bands too (SEASIM_SPECTRAL_OUTPUT): the RGB frame is the
// one without spectral output, every band stays finite and the bands' sum grows by the foam.
TEST(WhitecapsFrame, SpectralOutputCompositesTheBandsToo) {
  seasim::Device& device = seasim::test::testDevice();
  auto frame = [&](std::vector<seasim::Override> o) {
    const seasim::Scene s = smallScene(o);
    return seasim::renderFrame(device, s, seasim::makePlan(s));
  };
  const seasim::FrameResult rgb_only = frame({});
  const seasim::FrameResult on = frame({set("spectral.spectral_exr", "true")});
  const seasim::FrameResult off = frame({set("spectral.spectral_exr", "true"), set("surface.whitecaps", "false")});
  ASSERT_EQ(on.spectral.size(), off.spectral.size());
  ASSERT_FALSE(on.spectral.empty());
  EXPECT_EQ(on.nonfinite, 0);
  double worst = 0, sum_on = 0, sum_off = 0;
  for (size_t i = 0; i < on.rgb.pixels.size(); ++i)
    worst = std::max(worst, std::abs(double(on.rgb.pixels[i]) - rgb_only.rgb.pixels[i]) /
                                std::max(std::abs(double(rgb_only.rgb.pixels[i])), 1e-6));
  long bad = 0;
  for (size_t i = 0; i < on.spectral.size(); ++i) {
    bad += !std::isfinite(on.spectral[i]);
    sum_on += on.spectral[i];
    sum_off += off.spectral[i];
  }
  EXPECT_LT(worst, 1e-6);
  EXPECT_EQ(bad, 0);
  EXPECT_GT(sum_on, sum_off);
}

}  // namespace
