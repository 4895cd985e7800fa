// lamps_stiff_cases_test.cpp — spotlights under water at their singular points, through both the fast
// frame (underwater_lamps.cl with the G-buffer) and the all-orders path tracer (reference.cl with
// common/path_tracer_lamps.h): a lamp inside an object, a cone of 0.1°, g -> 1, turbid Jerlov 9C water
// and a lamp 0.1 mm under the surface, aimed up into it and along it. Every image is finite (no
// NaN/Inf, the non-finite counter 0), and where the answer is known it is that answer: a lamp sealed
// in an object lights nothing in either renderer. The path tracer runs 32 paths per pixel: these are
// tests of finiteness, not of accuracy.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "quality/auto_quality.h"
#include "reference/underwater_reference.h"
#include "render/renderer.h"
#include "scene/scene_parser.h"
#include "spectral/sensor.h"
#include "spectral/wavelength_grid.h"
#include "jobs/layer_image.h"
#include "test_device.h"
#include "underwater/lamps_setup.h"
#include "underwater/underwater_setup.h"

namespace {

using seasim::Override;
using seasim::Scene;

Override set(const std::string& key, const std::string& value) { return {key, value, {"test", 1}}; }

// Lamps only (sun off, black sky), 4 bands of Jerlov 3C, a lamp beside the camera aimed ahead and down.
const char* kScene = R"(
[camera]
position = [0.0, -4.0, 0.0]
look_at = [0.0, -6.0, -4.0]
fov_deg = 60.0
width = 16
height = 10
[sun]
enabled = false
[sky]
model = "uniform"
radiance = 0.0
[water]
jerlov = "3C"
g = 0.9
[surface]
type = "flat"
[bottom]
type = "flat"
depth = 7.0
albedo = 0.5
[[spotlights]]
position = [0.4, -4.0, -0.3]
direction = [-0.05, -0.5, -1.0]
cone_deg = 20.0
falloff_deg = 0.0
intensity = 10.0
[underwater]
caustics = "none"
[spectral]
count = 4
range_nm = [400.0, 700.0]
)";

const char* kSphereAroundLamp = "\n[[objects]]\ntype = \"sphere\"\ncenter = [0.4, -4.0, -0.3]\nradius = 0.2\nalbedo = 0.5\n";

struct Images {
  seasim::Image fast, traced;
  long long fast_nonfinite = 0;
};

Images renderBoth(const std::string& text, const std::vector<Override>& overrides) {
  const Scene scene = seasim::parseScene(text, "lamps_stiff.toml", overrides);
  Images out;
  seasim::Renderer renderer(seasim::test::testDevice(), scene, seasim::shippedPasses());
  const seasim::FrameResult frame = renderer.render();
  out.fast = frame.rgb;
  out.fast_nonfinite = frame.nonfinite;
  const seasim::WavelengthGrid grid = seasim::makeGrid(scene.spectral.count, scene.spectral.min_nm, scene.spectral.max_nm);
  const seasim::Sensor sensor = seasim::makeSensor(scene.spectral.sensor, grid, scene.spectral.white_balance);
  const seasim::UnderwaterSetup setup = seasim::makeUnderwaterSetup(scene, grid, sensor);
  const seasim::UnderwaterLamps lamps = seasim::makeUnderwaterLamps(scene, grid);
  seasim::UnderwaterReferenceSettings settings;
  settings.samples_per_pixel = 32;
  settings.batch = 32;
  settings.lamps = &lamps;
  // Throws on any non-finite pixel (renderUnderwaterReference counts them).
  out.traced = seasim::renderUnderwaterReference(seasim::test::testDevice(), setup, settings).rgb;
  return out;
}

void expectFinite(const Images& im, const char* what) {
  EXPECT_EQ(im.fast_nonfinite, 0) << what;
  for (float v : im.fast.pixels) ASSERT_TRUE(std::isfinite(v)) << what << " (fast)";
  for (float v : im.traced.pixels) ASSERT_TRUE(std::isfinite(v)) << what << " (path tracer)";
}

double sumAbs(const seasim::Image& img) {
  double s = 0;
  for (float v : img.pixels) s += std::fabs(v);
  return s;
}

TEST(LampsStiffCases, LampInsideAnObjectLightsNothing) {
  const Images im = renderBoth(std::string(kScene) + kSphereAroundLamp, {});
  expectFinite(im, "lamp in a sphere");
  EXPECT_EQ(sumAbs(im.fast), 0.0);
  EXPECT_EQ(sumAbs(im.traced), 0.0);
  // The same sphere beside the lamp: both renderers do see the lamp (the test above is not vacuous).
  const Images moved = renderBoth(std::string(kScene) + kSphereAroundLamp, {set("objects[0].center", "[1.5, -4.0, -0.3]")});
  EXPECT_GT(sumAbs(moved.fast), 0.0);
  EXPECT_GT(sumAbs(moved.traced), 0.0);
}

TEST(LampsStiffCases, OrdersModelStaysFiniteAndSealedLampsDark) {
  // The "orders" model: a sealed lamp scatters nothing either; g -> 1, a 0.1° cone and turbid water finite.
  // Each also on its lattice at its widest cell: 10° at 32x20 (3° per pixel) is every third pixel.
  const std::vector<Override> every = {set("quality.lamps_model", "\"orders\"")};
  const std::vector<Override> lattice = {set("quality.lamps_model", "\"orders\""), set("camera.width", "32"),
                                         set("camera.height", "20"), set("quality.lamps_ms_cell_deg", "10")};
  for (const std::vector<Override>& orders : {every, lattice}) {
    const std::string how = orders.size() > 1 ? "orders on a lattice" : "orders";
    const Images sealed = renderBoth(std::string(kScene) + kSphereAroundLamp, orders);
    expectFinite(sealed, (how + ", lamp in a sphere").c_str());
    EXPECT_EQ(sumAbs(sealed.fast), 0.0) << how;
    for (const std::vector<Override>& extra :
         {std::vector<Override>{set("water.g", "0.999999")}, std::vector<Override>{set("spotlights[0].cone_deg", "0.1")},
          std::vector<Override>{set("water.jerlov", "\"9C\"")}}) {
      std::vector<Override> over = extra;
      over.insert(over.end(), orders.begin(), orders.end());
      const Images im = renderBoth(kScene, over);
      expectFinite(im, how.c_str());
    }
  }
}

TEST(LampsStiffCases, ConeOfATenthOfADegreeStaysFinite) {
  const Images im = renderBoth(kScene, {set("spotlights[0].cone_deg", "0.1")});
  expectFinite(im, "0.1 deg cone");
  EXPECT_GT(sumAbs(im.traced), 0.0);  // the thin beam's glow reaches the camera through multiple scattering
}

TEST(LampsStiffCases, ForwardPeakedPhaseStaysFinite) {
  for (const char* g : {"0.99", "0.9999"}) {
    const Images im = renderBoth(kScene, {set("water.g", g)});
    expectFinite(im, g);
    EXPECT_GT(sumAbs(im.fast), 0.0) << g;
    EXPECT_GT(sumAbs(im.traced), 0.0) << g;
  }
}

TEST(LampsStiffCases, TurbidWaterStaysFinite) {
  const Images im = renderBoth(kScene, {set("water.jerlov", "\"9C\"")});
  expectFinite(im, "9C");
  EXPECT_GT(sumAbs(im.fast), 0.0);
  EXPECT_GT(sumAbs(im.traced), 0.0);
}

TEST(LampsStiffCases, LampJustUnderTheSurfaceStaysFinite) {
  // 0.1 mm under the surface: aimed straight up (into Snell's window and total internal reflection
  // around it), along the surface, and down.
  for (const char* dir : {"[0.0, 1.0, 0.0]", "[0.0, 0.0, -1.0]", "[0.0, -1.0, -0.2]"}) {
    const Images im = renderBoth(kScene, {set("spotlights[0].position", "[0.4, -0.0001, -0.3]"),
                                          set("spotlights[0].direction", dir), set("spotlights[0].cone_deg", "40.0")});
    expectFinite(im, dir);
    // Aimed up, the cone holds only the 0.1 mm of water above the lamp: its light leaves through the
    // surface or comes back by the surface's reflection, which neither renderer draws (a point lamp seen
    // through a mirror: no path reaches it by next-event estimation), so that image is black.
    if (std::string(dir) != "[0.0, 1.0, 0.0]") EXPECT_GT(sumAbs(im.traced), 0.0) << dir;
  }
}

// The lamps' split layers (lamps_single, lamps_multiple) in every stiff case and model: finite, and
// their sum is the lamps layer.
TEST(LampsStiffCases, SplitLayersStayFiniteAndSumToTheLamps) {
  const std::vector<std::pair<std::string, std::vector<Override>>> cases = {
      {std::string(kScene) + kSphereAroundLamp, {}},
      {kScene, {set("water.g", "0.999999")}},
      {kScene, {set("spotlights[0].cone_deg", "0.1")}},
      {kScene, {set("water.jerlov", "\"9C\"")}},
      {kScene, {set("spotlights[0].position", "[0.4, -0.0001, -0.3]"), set("spotlights[0].direction", "[0.0, 1.0, 0.0]")}}};
  for (const char* model : {"single", "delta_m", "orders"})
    for (const auto& [text, extra] : cases) {
      std::vector<Override> over = extra;
      over.push_back(set("quality.lamps_model", std::string("\"") + model + "\""));
      over.push_back(set("outputs.layers", "[\"lamps\", \"lamps_single\", \"lamps_multiple\"]"));
      const Scene scene = seasim::parseScene(text, "lamps_stiff.toml", over);
      seasim::Renderer renderer(seasim::test::testDevice(), scene, seasim::shippedPasses());
      const seasim::FrameResult frame = renderer.render();
      EXPECT_EQ(frame.nonfinite, 0) << model;
      const seasim::Image img = seasim::imageWithLayers(frame, scene.outputs);
      auto at = [&](size_t pixel, const std::string& name) {
        const auto it = std::find(img.channel_names.begin(), img.channel_names.end(), name);
        return double(img.pixels[pixel * img.channels + static_cast<size_t>(it - img.channel_names.begin())]);
      };
      double peak = 0, worst = 0;
      for (size_t i = 0; i < img.pixelCount(); ++i)
        for (const char* c : {".R", ".G", ".B"}) {
          const double l = at(i, std::string("lamps") + c), sgl = at(i, std::string("lamps_single") + c),
                       mul = at(i, std::string("lamps_multiple") + c);
          ASSERT_TRUE(std::isfinite(l) && std::isfinite(sgl) && std::isfinite(mul)) << model;
          peak = std::max(peak, std::fabs(l));
          worst = std::max(worst, std::fabs(sgl + mul - l));
        }
      EXPECT_LE(worst, 1e-5 * peak + 1e-20) << model;
    }
}

}  // namespace
