// sky_fourflow_test.cpp — the shallow-water frame (kernels/fourflow.cl ff_render) with the [sky]
// models (one sky for every model): on PoCL (float) against the same per-pixel steps in
// double on the host, where the sky a pixel sees above the horizon, and the one its flat surface
// reflects (F L_sky(mirrored view), 003 eq. 1), come from the host's sky interface
// (host/sky/sky_light.*, common/sky_view.h) and the bands' e_sky from its irradiance integral.
// Then the direction of the change: the Preetham sky is brighter towards the sun, in the sky and in
// its reflection, where the uniform sky is the same everywhere.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "math/kernel_math.h"
#include "passes/fourflow_pass.h"
#include "plan/plan.h"
#include "quality/render_frame.h"
#include "scene/scene_parser.h"
#include "spectral/sensor.h"
#include "spectral/wavelength_grid.h"
#include "test_device.h"

namespace {

namespace kd = seasim::kmath_d;

const char* kScene = R"(
[camera]
position = [0, 3, 0]
look_at = [0, 0.5, -10]
fov_deg = 70
width = 40
height = 24
[sun]
zenith_deg = 60
azimuth_deg = 270
[sky]
radiance = 0.05
[water]
jerlov = "IB"
[bottom]
type = "flat"
depth = 4
albedo = 0.4
[shallow]
texture_scale_m = 0.7
path = "exact"
[spectral]
count = 8
sensor = "cie1931"
)";

struct Frame {
  seasim::Image got, want;
};

Frame render(const std::string& sky) {
  std::string text = kScene;
  text.insert(text.find("radiance = 0.05"), sky);
  const seasim::Scene scene = seasim::parseScene(text, "shallow_sky.toml");
  const seasim::Plan plan = seasim::makePlan(scene);
  EXPECT_TRUE(plan.hasPass("fourflow"));
  const seasim::FrameResult frame = seasim::renderFrame(seasim::test::testDevice(), scene, plan);
  EXPECT_EQ(frame.nonfinite, 0);
  const seasim::WavelengthGrid grid = seasim::makeGrid(scene.spectral.count, scene.spectral.min_nm, scene.spectral.max_nm);
  const seasim::Sensor sensor = seasim::makeSensor(scene.spectral.sensor, grid, scene.spectral.white_balance,
                                                   scene.spectral.camera_dir);
  const seasim::FourFlowSetup s = seasim::makeFourFlowSetup(scene, grid, sensor);
  std::vector<double> sky(s.sky_buffer.begin(), s.sky_buffer.end());
  Frame f{frame.rgb, frame.rgb};
  for (int y = 0; y < s.view.height; ++y)
    for (int x = 0; x < s.view.width; ++x) {
      FfView view = s.view;
      const kd::real3 o{view.cam_pos[0], view.cam_pos[1], view.cam_pos[2]};
      const kd::real3 d = kd::ff_camera_dir(view, x, y);
      if (s.sky_params.model != 0) {
        const kd::real3 seen = kd::sky_view_rgb(s.sky_rgb_matrix.data(),
                                                kd::sky_view_shape(&s.sky_params, sky.data(), {d.x, std::fabs(d.y), d.z}));
        view.sky_rgb[0] = float(seen.x), view.sky_rgb[1] = float(seen.y), view.sky_rgb[2] = float(seen.z);
      }
      double want[3] = {view.sky_rgb[0], view.sky_rgb[1], view.sky_rgb[2]};
      kd::real3 b{}, dw{};
      double F = 0;
      if (kd::ff_enter_water(view, o, d, &b, &F, &dw)) {
        const double h = view.bottom_depth, l = h / std::max(-dw.y, 1e-6);
        kd::ff_shade(view, s.bands.data(), s.params, nullptr, 0, F, l, h, b + l * dw, want);
      }
      for (int c = 0; c < 3; ++c) f.want.at(x, y, c) = float(want[c]);
    }
  return f;
}

class SkyFourFlow : public ::testing::TestWithParam<std::string> {};

TEST_P(SkyFourFlow, FrameMatchesDoubleWithTheSkyModel) {
  const Frame f = render(GetParam());
  float peak = 0;
  for (float v : f.want.pixels) peak = std::max(peak, std::fabs(v));
  ASSERT_GT(peak, 0.0f);
  for (std::size_t i = 0; i < f.got.pixels.size(); ++i) {
    ASSERT_TRUE(std::isfinite(f.got.pixels[i]) && f.got.pixels[i] >= 0.0f);
    // As FourFlowKernelTest.FrameKernelMatchesDouble: float geometry, 1e-4 of the value + 1e-6 of the peak.
    EXPECT_LE(std::fabs(f.got.pixels[i] - f.want.pixels[i]), 1e-4 * std::fabs(f.want.pixels[i]) + 1e-6 * peak) << i;
  }
}

std::string skyName(const ::testing::TestParamInfo<std::string>& info) {
  const char* names[] = {"uniform", "cie_clear", "preetham", "image"};
  return names[info.index];
}

INSTANTIATE_TEST_SUITE_P(Skies, SkyFourFlow,
                         ::testing::Values(std::string(), std::string("model = \"analytic\"\n"),
                                           std::string("model = \"preetham\"\nturbidity = 3\n"),
                                           std::string("model = \"image\"\nimage = \"") + SEASIM_SOURCE_DIR +
                                               "/scenes/textures/sky_clear.exr\"\n"),
                         skyName);

TEST(SkyFourFlowDirection, PreethamSkyIsBrighterTowardsTheSunInTheSkyAndItsReflection) {
  // The sun at azimuth 270° is towards -z, ahead of the camera; the frame's left and right edges are
  // symmetric about it. Top row: sky; bottom row: reflection. Centre column against the edge column.
  const Frame u = render(""), p = render("model = \"preetham\"\nturbidity = 3\n");
  const int w = u.got.width, h = u.got.height;
  auto sum = [](const seasim::Image& im, int x, int y) { return im.at(x, y, 0) + im.at(x, y, 1) + im.at(x, y, 2); };
  EXPECT_NEAR(sum(u.got, w / 2, 0), sum(u.got, 0, 0), 1e-5 * sum(u.got, 0, 0));  // uniform: the same sky
  EXPECT_GT(sum(p.got, w / 2, 0), 1.2 * sum(p.got, 0, 0));
  // The reflection: F L_sky(mirrored) added to the same water: the Preetham frame's excess over the
  // uniform one is larger towards the sun.
  EXPECT_GT(sum(p.got, w / 2, h - 1) - sum(u.got, w / 2, h - 1), sum(p.got, 0, h - 1) - sum(u.got, 0, h - 1));
}

}  // namespace
