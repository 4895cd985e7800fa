// sky_window_test.cpp — Snell's window of kd_multiple.cl on PoCL (float) shows the scene's [sky]
// through common/sky_view.h (one sky for every model), against the double evaluation of
// the host's sky interface (host/sky/sky_light.*): per pixel looking up from 3 m, with the multiple
// scattering and the froxel term off, the surface pixels are Σ_λ w(λ) e^{-c S} n² (1 - F) L_sky(λ, a)
// with a the refracted view in air (and black under total internal reflection). For the uniform,
// CIE clear, Preetham (T 3 and 9) and image (scenes/textures/sky_clear.exr) skies. Then the
// direction of the change: a Preetham sky brightens the
// window towards the sun and darkens it away from it, where a uniform sky is symmetric.
// The thesis's model, pinned: the expected value is its window term (the discrete-ordinates model, the default,
// attenuates the window by delta-M's c', adds the surface's reflection and blurs the forward light, so
// this closed form is not its own; underwater_ordinates_kernel_test.cpp checks that one against its
// double evaluation).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "math/kernel_math.h"
#include "plan/plan.h"
#include "quality/render_frame.h"
#include "scene/scene_parser.h"
#include "sky/sky_light.h"
#include "spectral/sensor.h"
#include "spectral/wavelength_grid.h"
#include "test_device.h"
#include "underwater/underwater_setup.h"

namespace {

namespace kd = seasim::kmath_d;

const char* kScene = R"(
[camera]
position = [0, -3, 0]
look_at = [0, 10, -0.001]
fov_deg = 110
width = 48
height = 48
[sun]
zenith_deg = 50
azimuth_deg = 30
[sky]
radiance = 0.05
[water]
jerlov = "IB"
[underwater]
model = "thesis"
single_scattering = false
multiple_scattering = false
caustics = "none"
[spectral]
count = 8
sensor = "cie1931"
)";

struct Frame {
  seasim::Image got, want;
  seasim::UnderwaterSetup setup;
};

Frame renderWithSky(const std::string& sky) {
  std::string text = kScene;
  text.insert(text.find("radiance = 0.05"), sky);
  const seasim::Scene scene = seasim::parseScene(text, "window.toml");
  const seasim::Plan plan = seasim::makePlan(scene);
  EXPECT_TRUE(plan.hasPass("kd_multiple"));
  const seasim::FrameResult frame = seasim::renderFrame(seasim::test::testDevice(), scene, plan);
  EXPECT_EQ(frame.nonfinite, 0);
  const seasim::WavelengthGrid grid = seasim::makeGrid(scene.spectral.count, scene.spectral.min_nm, scene.spectral.max_nm);
  const seasim::Sensor sensor = seasim::makeSensor(scene.spectral.sensor, grid, scene.spectral.white_balance,
                                                   scene.spectral.camera_dir);
  const seasim::SkyLight light = seasim::makeSkyLight(scene, grid);
  Frame f{frame.rgb, frame.rgb, seasim::makeUnderwaterSetup(scene, grid, sensor)};
  const UwParams& p = f.setup.params;
  const double ior = p.ior, o_d = -p.cam_pos[1];
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x) {
      const kd::real3 d = kd::uw_screen_dir(&p, (x + 0.5) / p.width, (y + 0.5) / p.height);
      double rgb[3] = {0, 0, 0};
      if (d.y > 0) {
        const kd::real3 a = kd::sky_window_air_dir(d, ior);
        for (std::size_t i = 0; i < grid.size(); ++i) {
          const UwBand& b = f.setup.bands[i];
          const double L = std::exp(-double(b.c) * o_d / d.y) *
                           kd::uw_window_radiance(d.y, ior, light.radiance(i, {a.x, a.y, a.z}), 0.0);
          rgb[0] += L * b.w_r, rgb[1] += L * b.w_g, rgb[2] += L * b.w_b;
        }
      }
      for (int c = 0; c < 3; ++c) f.want.at(x, y, c) = float(rgb[c]);
    }
  return f;
}

double maxRelativeError(const seasim::Image& a, const seasim::Image& ref) {
  float peak = 0;
  for (float v : ref.pixels) peak = std::max(peak, std::fabs(v));
  double worst = 0;
  for (std::size_t i = 0; i < ref.pixels.size(); ++i)
    worst = std::max(worst, std::fabs(double(a.pixels[i]) - ref.pixels[i]) / (std::fabs(ref.pixels[i]) + 1e-4 * peak));
  return worst;
}

class SkyWindow : public ::testing::TestWithParam<std::string> {};

// The shipped environment image (scenes/textures/sky_clear.exr) as the sky.
std::string imageSky() {
  return std::string("model = \"image\"\nimage = \"") + SEASIM_SOURCE_DIR + "/scenes/textures/sky_clear.exr\"\n";
}

TEST_P(SkyWindow, KernelShowsTheSkyModelThroughTheWindow) {
  const Frame f = renderWithSky(GetParam());
  // Finite; not necessarily >= 0: the CIE 1931 sensor's sRGB primaries make a saturated blue sky
  // (the image's) negative in R, in the double evaluation as on the device.
  for (float v : f.got.pixels) ASSERT_TRUE(std::isfinite(v));
  float peak = 0;
  for (float v : f.want.pixels) peak = std::max(peak, v);
  EXPECT_GT(peak, 0.0f);
  // The image sky: its texel coordinates from atan2/acos in float move the bilinear weights, and the
  // R of its saturated blue crosses 0 (relative error large there); measured 2.2e-4.
  const double tolerance = GetParam().find("image") != std::string::npos ? 5e-4 : 1e-4;
  EXPECT_LT(maxRelativeError(f.got, f.want), tolerance) << GetParam();
}

std::string skyName(const ::testing::TestParamInfo<std::string>& info) {
  const char* names[] = {"uniform", "cie_clear", "preetham_t3", "preetham_t9", "image"};
  return names[info.index];
}

INSTANTIATE_TEST_SUITE_P(Skies, SkyWindow,
                         ::testing::Values(std::string(), std::string("model = \"analytic\"\n"),
                                           std::string("model = \"preetham\"\nturbidity = 3\n"),
                                           std::string("model = \"preetham\"\nturbidity = 9\n"), imageSky()),
                         skyName);

// Luminance-like sum of a pixel's RGB.
double sum(const seasim::Image& im, int x, int y) { return im.at(x, y, 0) + im.at(x, y, 1) + im.at(x, y, 2); }

TEST(SkyWindowDirection, PreethamBrightensTheWindowTowardsTheSun) {
  const Frame uniform = renderWithSky("");
  const Frame clear = renderWithSky("model = \"preetham\"\nturbidity = 3\n");
  // The pixel nearest the refracted sun and its mirror image through the window's centre.
  const UwParams& p = clear.setup.params;
  const kd::real3 s{p.sun_dir_water[0], p.sun_dir_water[1], p.sun_dir_water[2]};
  int best_x = 0, best_y = 0;
  double best = -2;
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x) {
      const kd::real3 d = kd::uw_screen_dir(&p, (x + 0.5) / p.width, (y + 0.5) / p.height);
      if (kd::dot(d, s) > best) best = kd::dot(d, s), best_x = x, best_y = y;
    }
  const int mx = p.width - 1 - best_x, my = p.height - 1 - best_y;
  EXPECT_NEAR(sum(uniform.got, best_x, best_y), sum(uniform.got, mx, my), 1e-3 * sum(uniform.got, mx, my));
  EXPECT_GT(sum(clear.got, best_x, best_y), 2.0 * sum(clear.got, mx, my));
  // E_D0's sky part comes from the sky's integral: bluer than the uniform sky's (tests/unit/sky_light_test).
  EXPECT_GT(clear.setup.bands.front().e_sky0 / uniform.setup.bands.front().e_sky0,
            clear.setup.bands.back().e_sky0 / uniform.setup.bands.back().e_sky0);
}

}  // namespace
