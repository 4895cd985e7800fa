// underwater_caustic_map_test.cpp — `[underwater] caustics = "map"` on PoCL: the FFT ocean's
// flux-conservation caustics (004 §5.2.1, caustics.cl) splatted onto depth layers (CausticStack) and
// read by raycast.cl through common/caustic_map.h. Checks: every layer has mean 1 and real focusing
// under waves; the G-buffer's sun visibility equals the double-precision read of the same maps at the
// hit point; a calm sea (wind 0) gives uniform maps, so the frame equals the no-caustics frame; no
// NaN/Inf with steep, choppy waves and a grazing sun.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "math/kernel_math.h"
#include "passes/caustic_stack.h"
#include "passes/froxel_pass.h"
#include "quality/render_frame.h"
#include "device/enqueue.h"
#include "passes/underwater_setup_buffers.h"
#include "plan/plan.h"
#include "reference/froxel_reference.h"
#include "scene/scene_parser.h"
#include "spectral/sensor.h"
#include "spectral/wavelength_grid.h"
#include "test_device.h"
#include "util/error.h"
#include "underwater/underwater_setup.h"

namespace {

const char* kScene = R"(
[scene]
name = "test_caustic_map"
[camera]
position = [0, -2, 0]
look_at = [0, -4, -5]
fov_deg = 70
width = 40
height = 24
[sun]
zenith_deg = 25
azimuth_deg = 60
[sky]
radiance = 0.05
[water]
jerlov = "IB"
[surface]
type = "fft"
grid = 64
patch_size = 16.0
wind_speed = 6.0
[bottom]
type = "flat"
depth = 5
albedo = 0.3
[[objects]]
type = "sphere"
center = [-1, -4.2, -4]
radius = 0.7
albedo = 0.3
[underwater]
caustics = "map"
[quality]
caustic_map_size = 64
caustic_layers = 4
froxel_x = 20
froxel_y = 12
froxel_z = 16
[spectral]
count = 4
)";

seasim::Override set(const char* key, const std::string& value) { return {key, value, {"test", 1}}; }

struct Frame {
  seasim::Scene scene;
  seasim::UnderwaterSetup setup;
};

Frame load(std::vector<seasim::Override> overrides = {}) {
  Frame f{seasim::parseScene(kScene, "test_caustic_map.toml", overrides), {}};
  const seasim::WavelengthGrid grid = seasim::makeGrid(f.scene.spectral.count, f.scene.spectral.min_nm, f.scene.spectral.max_nm);
  f.setup = seasim::makeUnderwaterSetup(f.scene, grid, seasim::makeSensor(f.scene.spectral.sensor, grid, f.scene.spectral.white_balance, f.scene.spectral.camera_dir));
  return f;
}

TEST(UnderwaterCausticMap, LayersHaveMeanOneAndFocusUnderWaves) {
  Frame f = load();
  seasim::CausticStack stack(seasim::test::testDevice(), f.scene, f.setup);
  ASSERT_EQ(stack.layers(), 4);
  ASSERT_EQ(stack.mapSize(), 64);
  const size_t texels = 64 * 64;
  for (int k = 0; k < stack.layers(); ++k) {
    double sum = 0, sq = 0;
    float hi = 0;
    for (size_t t = 0; t < texels; ++t) {
      const float v = stack.hostMaps()[k * texels + t];
      ASSERT_TRUE(std::isfinite(v) && v >= 0) << "layer " << k << " texel " << t;
      sum += v;
      sq += double(v) * v;
      hi = std::max(hi, v);
    }
    const double mean = sum / texels, sd = std::sqrt(std::max(0.0, sq / texels - mean * mean));
    EXPECT_NEAR(mean, 1.0, 1e-4) << "layer " << k;
    // Waves of 6 m/s focus sunlight: a real pattern, not a constant (measured sd 0.2–0.6 here).
    EXPECT_GT(sd, 0.1) << "layer " << k;
    EXPECT_GT(hi, 1.5f) << "layer " << k;
  }
}

TEST(UnderwaterCausticMap, RaycastReadsTheMapsAsTheCpuDoes) {
  Frame f = load();
  const seasim::Plan plan = seasim::makePlan(f.scene);
  seasim::Device& device = seasim::test::testDevice();
  seasim::CausticStack stack(device, f.scene, f.setup);
  const seasim::UnderwaterSetupBuffers setup(device, f.setup);
  const seasim::PassPlan& raycast = *plan.find("raycast");
  const int w = f.setup.params.width, h = f.setup.params.height;
  std::vector<cl_float4> geom(size_t(w) * h);
  std::vector<float> vis(size_t(w) * h);
  cl::Kernel kernel(device.program(raycast.kernel_file, raycast.defines).program, "raycast");
  cl::Buffer geom_buffer(device.context(), CL_MEM_READ_WRITE, sizeof(cl_float4) * geom.size());
  cl::Buffer material_buffer(device.context(), CL_MEM_READ_WRITE, sizeof(cl_int) * geom.size());
  cl::Buffer vis_buffer(device.context(), CL_MEM_READ_WRITE, sizeof(float) * vis.size());
  int arg = 0;
  for (const cl::Buffer* b : std::initializer_list<const cl::Buffer*>{&setup.params, &setup.objects, &stack.maps(),
                                                                      &geom_buffer, &material_buffer, &vis_buffer})
    kernel.setArg(arg++, *b);
  seasim::runKernel2d(device, "raycast", kernel, (w + UW_RAYCAST_PIXELS - 1) / UW_RAYCAST_PIXELS, h);
  device.queue().enqueueReadBuffer(geom_buffer, CL_TRUE, 0, sizeof(cl_float4) * geom.size(), geom.data());
  device.queue().enqueueReadBuffer(vis_buffer, CL_TRUE, 0, sizeof(float) * vis.size(), vis.data());

  namespace kd = seasim::kmath_d;
  const UwParams& p = f.setup.params;
  int lit = 0;
  double worst = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      ASSERT_TRUE(std::isfinite(vis[i]));
      if (!(vis[i] > 0)) continue;  // in shadow, or open water / the surface (no sun term)
      const kd::real3 d = kd::uw_screen_dir(&p, (x + 0.5) / w, (y + 0.5) / h);
      const double S = geom[i].s[0];
      const double hx = p.cam_pos[0] + S * d.x, hy = p.cam_pos[1] + S * d.y, hz = p.cam_pos[2] + S * d.z;
      const double expected = kd::caustic_map_sample(stack.hostMaps().data(), p.caustic_map_size, p.caustic_layers,
                                                     p.caustic_extent, p.caustic_depth_max, hx, -hy, hz);
      // Float hit points differ from double ones by ~1e-6 m; the maps change by < 1e-3 over that.
      worst = std::max(worst, std::fabs(vis[i] - expected) / std::max(1.0, expected));
      ++lit;
    }
  EXPECT_GT(lit, w * h / 3);  // the bottom and the sphere fill most of the view
  EXPECT_LT(worst, 2e-3);
}

TEST(UnderwaterCausticMap, FroxelInjectionReadsTheMapsAsTheCpuDoes) {
  Frame f = load();
  const seasim::Plan plan = seasim::makePlan(f.scene);
  seasim::Device& device = seasim::test::testDevice();
  seasim::CausticStack stack(device, f.scene, f.setup);
  seasim::FroxelPass froxels(device, f.scene, f.setup, plan.find("froxel")->defines);
  froxels.run(&stack.maps());
  std::vector<float> light;
  froxels.readLight(light);
  const seasim::FroxelCpuVolume cpu = seasim::froxelEvaluateCpu(
      f.setup, seasim::makeFroxelParams(f.setup, seasim::froxelConfigFromScene(f.scene)), &stack.hostMaps());
  ASSERT_EQ(light.size(), cpu.light.size());
  // V·C per froxel: float vs double positions (≲1e-3 on these maps) and rare shadow-map depth-compare
  // flips at the sphere's silhouette (counted).
  size_t flips = 0;
  double worst = 0, spread = 0;
  for (size_t i = 0; i < light.size(); ++i) {
    ASSERT_TRUE(std::isfinite(light[i]));
    const double diff = std::fabs(double(light[i]) - cpu.light[i]);
    if (diff > 5e-2) ++flips;
    else worst = std::max(worst, diff);
    spread = std::max(spread, std::fabs(double(cpu.light[i]) - 1.0));
  }
  EXPECT_LT(worst, 1e-2);
  EXPECT_LE(flips, light.size() / 200);
  EXPECT_GT(spread, 0.3);  // the maps do modulate the injected light
  EXPECT_THROW(seasim::froxelEvaluateCpu(f.setup, seasim::makeFroxelParams(f.setup, seasim::froxelConfigFromScene(f.scene))),
               seasim::RuntimeError);
}

TEST(UnderwaterCausticMap, LayerCountOutOfRangeIsAClearError) {
  Frame f = load({set("quality.caustic_layers", "65")});
  try {
    seasim::CausticStack stack(seasim::test::testDevice(), f.scene, f.setup);
    ADD_FAILURE() << "no error";
  } catch (const seasim::RuntimeError& e) {
    EXPECT_NE(std::string(e.what()).find("quality.caustic_layers must be in 1..64"), std::string::npos) << e.what();
  }
}

TEST(UnderwaterCausticMap, CalmSeaEqualsNoCaustics) {
  const std::vector<seasim::Override> calm = {set("surface.wind_speed", "0")};
  Frame f = load(calm);
  seasim::CausticStack stack(seasim::test::testDevice(), f.scene, f.setup);
  for (float v : stack.hostMaps()) ASSERT_NEAR(v, 1.0f, 1e-5f);

  std::vector<seasim::Override> none = calm;
  none.push_back(set("underwater.caustics", "\"none\""));
  const seasim::Scene with_map = seasim::parseScene(kScene, "test_caustic_map.toml", calm);
  const seasim::Scene without = seasim::parseScene(kScene, "test_caustic_map.toml", none);
  seasim::Device& device = seasim::test::testDevice();
  const seasim::FrameResult a = seasim::renderFrame(device, with_map, seasim::makePlan(with_map));
  const seasim::FrameResult b = seasim::renderFrame(device, without, seasim::makePlan(without));
  EXPECT_EQ(a.nonfinite, 0);
  double worst = 0, peak = 0;
  for (float v : b.rgb.pixels) peak = std::max(peak, double(v));
  for (size_t i = 0; i < a.rgb.pixels.size(); ++i)
    worst = std::max(worst, std::fabs(double(a.rgb.pixels[i]) - b.rgb.pixels[i]) / peak);
  EXPECT_LT(worst, 1e-5);
}

TEST(UnderwaterCausticMap, SteepChoppyWavesAndGrazingSunStayFinite) {
  for (const char* zenith : {"25", "89"}) {
    const seasim::Scene scene = seasim::parseScene(
        kScene, "test_caustic_map.toml",
        {set("surface.wind_speed", "20"), set("surface.choppiness", "2.5"), set("sun.zenith_deg", zenith)});
    const seasim::FrameResult frame = seasim::renderFrame(seasim::test::testDevice(), scene, seasim::makePlan(scene));
    EXPECT_EQ(frame.nonfinite, 0) << "zenith " << zenith;
    for (float v : frame.rgb.pixels) ASSERT_TRUE(std::isfinite(v)) << "zenith " << zenith << ": " << v;
  }
}

}  // namespace
