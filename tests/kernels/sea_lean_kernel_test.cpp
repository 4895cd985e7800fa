// sea_lean_kernel_test.cpp — the wave filter of kernels/sea_single.cl (SEASIM_WAVE_FILTER)
// on PoCL against its reference, the same frame supersampled (quality.sea_supersample: n x n rays per
// pixel over the unfiltered full-resolution normals), which shares none of the filter's steps (no
// moments, no mip chain, no Gaussian, no quadrature, the sun as its real disk):
//  - near the horizon, where one normal per pixel aliases, the filtered frame is within 2 levels of
//    255 RMS of the reference, and the unfiltered frame is not;
//  - the glitter's total energy (sky and water off: the sun's reflection only) within 2 %;
//  - a calm sea: the filtered reflection equals the flat sea's sky × Fresnel within 1e-3.
// The kernel against its double CPU twin is in sea_waves_test.cpp ("waves_filtered*").
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "io/tonemap.h"
#include "quality/render_frame.h"
#include "plan/plan.h"
#include "scene/scene_parser.h"
#include "test_device.h"

namespace {

// A choppy sea (9 m/s, choppiness 1) from 10 m up under the CIE clear sky, the sun low ahead so the
// glitter path runs to the horizon, which sits at row ~22 of 72.
const char* kScene = R"(
[scene]
name = "test_lean"
[camera]
position = [0, 10, 0]
look_at = [0, 2, -60]
fov_deg = 50
width = 128
height = 72
exposure_ev = 2.0
[sun]
zenith_deg = 75
azimuth_deg = 270
[sky]
model = "analytic"
radiance = 0.05
[water]
jerlov = "IB"
g = 0.9
[surface]
type = "fft"
wind_speed = 9
patch_size = 100
grid = 256
choppiness = 1.0
small_wave = 0.1
time = 2.0
[spectral]
count = 8
)";

seasim::Override set(const char* key, const std::string& value) { return {key, value, {"test", 1}}; }

struct Frame {
  seasim::Image rgb;
  double ms;
};

Frame render(const std::vector<seasim::Override>& overrides) {
  const seasim::Scene scene = seasim::parseScene(kScene, "test_lean.toml", overrides);
  const auto t0 = std::chrono::steady_clock::now();
  const seasim::FrameResult frame = seasim::renderFrame(seasim::test::testDevice(), scene, seasim::makePlan(scene));
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(frame.nonfinite, 0);
  return {frame.rgb, ms};
}

// RMS over rows [y0, y1) of the tone-mapped difference, in 8-bit levels (the display transform of
// image.png, host/io/tonemap.h).
double rmsLevels(const seasim::Image& a, const seasim::Image& b, int y0, int y1, double exposure_ev) {
  seasim::Image da, db;
  seasim::toneMapImage(a, exposure_ev, da);
  seasim::toneMapImage(b, exposure_ev, db);
  double sum = 0;
  long count = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = 0; x < a.width; ++x)
      for (int c = 0; c < 3; ++c) {
        const size_t i = (static_cast<size_t>(y) * a.width + x) * 3 + c;
        const double d = 255.0 * (double(da.pixels[i]) - db.pixels[i]);
        sum += d * d, ++count;
      }
  return std::sqrt(sum / count);
}

// The sea rows whose centre ray is less than `elevation_deg` below the horizon: [first, last).
std::pair<int, int> horizonRows(const seasim::Scene& scene, double elevation_deg) {
  const auto& cam = scene.camera;
  const double tan_half = std::tan(cam.fov_y / 2);
  const double fy = cam.look_at.y - cam.position.y, fz = cam.look_at.z - cam.position.z;
  const double pitch = std::atan2(fy, -fz);  // camera looks along -z, tilted by pitch
  int first = -1, last = -1;
  for (int y = 0; y < cam.height; ++y) {
    const double v = (1.0 - 2.0 * (y + 0.5) / cam.height) * tan_half;
    const double elevation = pitch + std::atan(v);
    if (elevation < 0 && elevation > -elevation_deg * M_PI / 180) {
      if (first < 0) first = y;
      last = y + 1;
    }
  }
  return {first, last};
}

double total(const seasim::Image& img) {
  double s = 0;
  for (float v : img.pixels) s += v;
  return s;
}

TEST(SeaLeanKernel, FilteredHorizonMatchesSupersampledReference) {
  // Sky reflection and water colour (the sun off: its glitter in a 0.27° disk is found by too few of
  // the reference's rays to converge per pixel; its energy is checked below). 32 x 32 rays per pixel:
  // 12 x 12 still differed from 32 x 32 by up to 2.6 levels RMS in a horizon row.
  const std::vector<seasim::Override> no_sun = {set("sun.enabled", "false")};
  auto with = [&](seasim::Override extra) {
    auto o = no_sun;
    o.push_back(extra);
    return o;
  };
  const Frame filtered = render(no_sun);
  const Frame unfiltered = render(with(set("quality.wave_filter", "false")));
  const Frame reference = render(with(set("quality.sea_supersample", "32")));
  const seasim::Scene scene = seasim::parseScene(kScene, "test_lean.toml", no_sun);
  const auto [y0, y1] = horizonRows(scene, 6.0);
  ASSERT_GT(y1 - y0, 4);
  const double ev = scene.camera.exposure_ev;
  const double err_filtered = rmsLevels(filtered.rgb, reference.rgb, y0, y1, ev);
  const double err_unfiltered = rmsLevels(unfiltered.rgb, reference.rgb, y0, y1, ev);
  const double all_filtered = rmsLevels(filtered.rgb, reference.rgb, y0, scene.camera.height, ev);
  const double all_unfiltered = rmsLevels(unfiltered.rgb, reference.rgb, y0, scene.camera.height, ev);
  std::printf("[ numbers  ] horizon rows %d-%d (< 6 deg): RMS vs 32x32 supersampled: filtered %.2f levels, "
              "unfiltered %.2f levels; whole sea: filtered %.2f, unfiltered %.2f; times: filtered %.0f ms, "
              "unfiltered %.0f ms, reference %.0f ms\n",
              y0, y1, err_filtered, err_unfiltered, all_filtered, all_unfiltered, filtered.ms, unfiltered.ms,
              reference.ms);
  EXPECT_LT(err_filtered, 2.0);
  EXPECT_LT(all_filtered, 2.0);
  EXPECT_GT(err_unfiltered, 5.0 * err_filtered) << "the unfiltered frame should alias at the horizon";
}

TEST(SeaLeanKernel, GlitterEnergyMatchesSupersampledReference) {
  // The sun's reflection alone: no sky, no water colour. A sun of 2 deg radius lets the reference's
  // n x n rays find it often enough for its total to be known to well under 1 %.
  const std::vector<seasim::Override> glint_only = {set("sky.radiance", "0"), set("sea.single_scattering", "false"),
                                                    set("sun.angular_radius_deg", "2.0")};
  auto with = [&](seasim::Override extra) {
    auto o = glint_only;
    o.push_back(extra);
    return o;
  };
  const Frame filtered = render(glint_only);
  const Frame reference = render(with(set("quality.sea_supersample", "16")));
  const double ratio = total(filtered.rgb) / total(reference.rgb);
  std::printf("[ numbers  ] glitter total energy filtered / 16x16 supersampled = %.4f (filtered %.0f ms, reference %.0f ms)\n",
              ratio, filtered.ms, reference.ms);
  EXPECT_GT(total(reference.rgb), 0.0);
  EXPECT_NEAR(ratio, 1.0, 0.02);
}

TEST(SeaLeanKernel, CalmSeaReflectsSkyTimesFresnel) {
  // Wind 0 through the filter: every slope 0, the variance at its floor. Reflection only (no sun, no
  // water colour) must equal the flat sea's F × L_sky within 1e-3, pixel by pixel.
  const std::vector<seasim::Override> calm = {set("surface.wind_speed", "0"), set("sea.single_scattering", "false"),
                                              set("sun.enabled", "false"), set("quality.fast_math", "false")};
  const Frame waves = render(calm);
  auto flat_overrides = calm;
  flat_overrides.push_back(set("surface.type", "\"flat\""));
  const Frame flat = render(flat_overrides);
  double worst = 0;
  for (size_t i = 0; i < flat.rgb.pixels.size(); ++i)
    worst = std::max(worst, std::fabs(double(waves.rgb.pixels[i]) - flat.rgb.pixels[i]) /
                                std::max(std::fabs(double(flat.rgb.pixels[i])), 1e-12));
  std::printf("[ numbers  ] calm sea, filtered vs flat: max relative difference %.2e\n", worst);
  EXPECT_LT(worst, 1e-3);
}

}  // namespace
