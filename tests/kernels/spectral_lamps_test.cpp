// spectral_lamps_test.cpp — spotlights in air with a spectrum: a lamp with temperature_k
// renders through the scene's sensor (host/spectral/lamp_spectrum.h). Air is grey, so the frame of a
// spectral lamp is the frame of an RGB lamp whose colour is the spectrum's sensor RGB: checked to
// float rounding, and a warm lamp renders warm.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "quality/auto_quality.h"
#include "render/renderer.h"
#include "scene/scene_parser.h"
#include "spectral/lamp_spectrum.h"
#include "test_device.h"

namespace {

const char* kStage = R"(
[camera]
position = [0.0, 1.6, 9.0]
look_at = [0.0, 1.6, 0.0]
width = 48
height = 32
[air]
density = 0.04
extinction = 1.0
[[spotlights]]
position = [0.0, 5.2, -1.0]
direction = [0.0, -1.0, 0.0]
cone_deg = 24.0
intensity = 60.0
[[objects]]
type = "plane"
point = [0.0, 0.0, 0.0]
normal = [0.0, 1.0, 0.0]
albedo = 0.35
[quality]
shafts_planes = 30
shafts_subplanes = 6
[spectral]
count = 16
)";

TEST(SpectralLamps, AWarmLampInAirIsTheRgbLampOfItsSensorColour) {
  // The spectral key goes into the lamp's table (before the next table starts).
  std::string text = kStage;
  const std::string warm = text.insert(text.find("[[objects]]"), "temperature_k = 3200.0\n");
  const seasim::Scene scene = seasim::parseScene(warm, "stage.toml");
  const seasim::Vec3 rgb = seasim::shaftsLampRgb(scene.spotlights[0], scene.spectral);
  ASSERT_GT(rgb.x, rgb.z);  // 3200 K through the CIE observer: red over blue
  seasim::Renderer renderer(seasim::test::testDevice(), scene, seasim::shippedPasses());
  const seasim::FrameResult spectral = renderer.render();
  EXPECT_EQ(spectral.nonfinite, 0);
  // The same lamp as an RGB lamp: intensity 1 x colour = its sensor RGB.
  std::string as_rgb = kStage;
  as_rgb.replace(as_rgb.find("intensity = 60.0"), 16,
                 "intensity = 1.0\ncolor = [" + std::to_string(rgb.x) + ", " + std::to_string(rgb.y) + ", " +
                     std::to_string(rgb.z) + "]");
  seasim::Renderer rgb_renderer(seasim::test::testDevice(), seasim::parseScene(as_rgb, "stage.toml"),
                                seasim::shippedPasses());
  const seasim::FrameResult plain = rgb_renderer.render();
  double peak = 0, worst = 0, r = 0, b = 0;
  for (size_t k = 0; k < plain.rgb.pixels.size(); ++k) {
    peak = std::max(peak, double(std::fabs(plain.rgb.pixels[k])));
    worst = std::max(worst, double(std::fabs(spectral.rgb.pixels[k] - plain.rgb.pixels[k])));
    if (k % 3 == 0) r += spectral.rgb.pixels[k];
    if (k % 3 == 2) b += spectral.rgb.pixels[k];
  }
  ASSERT_GT(peak, 0);
  EXPECT_LT(worst, 1e-5 * peak);  // std::to_string keeps 6 decimals of the colour
  EXPECT_GT(r, b);
}

}  // namespace
