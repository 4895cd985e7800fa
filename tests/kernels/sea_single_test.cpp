// sea_single_test.cpp — kernels/sea_single.cl on PoCL (float) against the double-precision CPU
// reference (host/reference/sea_reference.cpp: same scene, single scattering by quadrature), over the
// ordinary scene and its stiff variants. Also: no NaN/Inf anywhere.
#include <gtest/gtest.h>

#include <ostream>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "device/device.h"
#include "test_device.h"
#include "quality/render_frame.h"
#include "plan/plan.h"
#include "reference/sea_reference.h"
#include "scene/scene_parser.h"
#include "spectral/sensor.h"
#include "spectral/wavelength_grid.h"

namespace {

const char* kScene = R"(
[scene]
name = "test_sea"
[camera]
position = [0, 10, 0]
look_at = [0, 0, -60]
fov_deg = 70
width = 48
height = 32
[sun]
zenith_deg = 40
azimuth_deg = 90
[sky]
radiance = 0.05
[water]
jerlov = "IB"
[bottom]
type = "flat"
depth = 8
albedo = 0.3
[spectral]
count = 8
)";

seasim::Device& device() { return seasim::test::testDevice(); }

// Max over pixels and channels of |kernel - reference| / (|reference| + floor), floor = 1e-3 of the
// image's largest reference value (so near-black pixels are judged on an absolute scale).
double maxRelativeError(const seasim::Image& a, const seasim::Image& ref) {
  float peak = 0;
  for (float v : ref.pixels) peak = std::max(peak, std::fabs(v));
  double worst = 0;
  for (size_t i = 0; i < ref.pixels.size(); ++i) {
    worst = std::max(worst, std::fabs(double(a.pixels[i]) - ref.pixels[i]) / (std::fabs(ref.pixels[i]) + 1e-3 * peak));
  }
  return worst;
}

struct Variant {
  const char* name;
  std::vector<seasim::Override> overrides;
  bool remove_bottom = false;  // drop the [bottom] table: infinitely deep water
};
// The case as gtest prints it (its name, not the struct's bytes).
void PrintTo(const Variant& c, std::ostream* os) { *os << c.name; }

class SeaSingleKernel : public ::testing::TestWithParam<Variant> {};

TEST_P(SeaSingleKernel, MatchesDoubleReferenceWithoutNaN) {
  std::string text = kScene;
  if (GetParam().remove_bottom) text.erase(text.find("[bottom]"), text.find("[spectral]") - text.find("[bottom]"));
  const seasim::Scene scene = seasim::parseScene(text, "test_sea.toml", GetParam().overrides);
  const seasim::FrameResult frame = seasim::renderFrame(device(), scene, seasim::makePlan(scene));
  EXPECT_EQ(frame.nonfinite, 0);
  for (float v : frame.rgb.pixels) ASSERT_TRUE(std::isfinite(v));
  const seasim::Image ref = seasim::renderSeaReference(scene, 4000);
  EXPECT_LT(maxRelativeError(frame.rgb, ref), 2e-4) << GetParam().name;
}

seasim::Override set(const char* key, const char* value) { return {key, value, {"test", 1}}; }

INSTANTIATE_TEST_SUITE_P(
    Scenes, SeaSingleKernel,
    ::testing::Values(Variant{"ordinary", {}},
                      Variant{"no_bottom", {}, true},
                      Variant{"sun_below_horizon", {set("sun.zenith_deg", "100")}},
                      Variant{"grazing_sun", {set("sun.zenith_deg", "89.9")}},
                      Variant{"sun_overhead", {set("sun.zenith_deg", "0")}},
                      Variant{"looking_straight_down", {set("camera.look_at", "[0, 0, -0.001]")}},
                      Variant{"grazing_view", {set("camera.look_at", "[0, 10, -100]")}},
                      Variant{"very_clear_water",
                              {set("water", "{ wavelengths_nm = [400, 700], a = [1e-6, 1e-6], b = [1e-6, 1e-6] }")}},
                      Variant{"turbid_deep", {set("water.jerlov", "\"9C\""), set("bottom.depth", "10000")}},
                      Variant{"one_band", {set("spectral.count", "1")}},
                      Variant{"isotropic", {set("water.g", "0")}},
                      Variant{"strong_forward", {set("water.g", "0.99")}}),
    [](const ::testing::TestParamInfo<Variant>& info) { return std::string(info.param.name); });

TEST(SeaSingleKernel, SpectralOutputMatchesTheRgbSum) {
  // The spectral buffer holds each band's radiance; weighting it by the sensor must give the RGB.
  const seasim::Scene scene =
      seasim::parseScene(kScene, "test_sea.toml", {set("spectral.spectral_exr", "true"), set("spectral.count", "5")});
  const seasim::FrameResult frame = seasim::renderFrame(device(), scene, seasim::makePlan(scene));
  ASSERT_EQ(frame.spectral.size(), size_t(48 * 32 * 5));
  EXPECT_EQ(frame.wavelengths_nm.size(), 5u);
  EXPECT_EQ(frame.nonfinite, 0);
  for (float v : frame.spectral) EXPECT_GE(v, 0.0f);
}

// ---- The n² law across the surface (docs/radiometry.md): the same water seen from 1 mm above (the
// kernel, through the surface) and from 1 mm below (the CPU reference's in-water radiance along the
// refracted ray, seaUpwellingBelow) relates by (1 - R)/n², R from Fresnel's unpolarised formula
// written out here. Clear water (c = 0.05/m) so the 1 mm of water between the two views changes the
// radiance by under 6e-5; no sky, so nothing is reflected. Looking down 30° from the nadir.
TEST(SeaSingleKernel, SameWaterOneMillimetreAboveAndBelowRelatesByOneMinusROverNSquared) {
  const double n = 1.333, theta = 30 * M_PI / 180;
  char text[1024];
  std::snprintf(text, sizeof text, R"(
[camera]
position = [0, 0.001, 0]
look_at = [0, %.17g, %.17g]
fov_deg = 1
width = 3
height = 3
[sun]
zenith_deg = 40
azimuth_deg = 90
[sky]
radiance = 0
[water]
wavelengths_nm = [400, 700]
a = [0.02, 0.02]
b = [0.03, 0.03]
g = 0.9
ior = %.17g
[bottom]
type = "flat"
depth = 5
albedo = 0.3
[spectral]
count = 4
)",
                0.001 - std::cos(theta), -std::sin(theta), n);
  for (const bool bottom : {true, false}) {
    std::string t = text;
    if (!bottom) t.erase(t.find("[bottom]"), t.find("[spectral]") - t.find("[bottom]"));
    // Paper 000's single scattering, pinned: seaUpwellingBelow is its radiance below the surface.
    const seasim::Scene scene =
        seasim::parseScene(t, "n2.toml", {set("spectral.spectral_exr", "true"), set("sea.model", "\"paper\"")});
    const seasim::FrameResult frame = seasim::renderFrame(device(), scene, seasim::makePlan(scene));
    const size_t bands = frame.wavelengths_nm.size();
    ASSERT_EQ(bands, 4u);
    const size_t centre = 4;  // pixel (1, 1): its ray is the camera's axis
    // Fresnel, unpolarised, air to water at theta; the refracted ray.
    const double ci = std::cos(theta), st = std::sin(theta) / n, ct = std::sqrt(1 - st * st);
    const double rs = (ci - n * ct) / (ci + n * ct), rp = (ct - n * ci) / (ct + n * ci);
    const double R = 0.5 * (rs * rs + rp * rp);
    const seasim::Vec3 in_water{0, -ct, -st};
    const std::vector<double> below = seasim::seaUpwellingBelow(scene, in_water, 0.001, 20000);
    ASSERT_EQ(below.size(), bands);
    for (size_t i = 0; i < bands; ++i) {
      const double above = frame.spectral[centre * bands + i];
      const double expected = below[i] * (1 - R) / (n * n);
      std::printf("[ measured ] %s, %.0f nm: above %.6g, below %.6g, above/below %.6f, (1-R)/n² %.6f\n",
                  bottom ? "bottom at 5 m" : "deep", frame.wavelengths_nm[i], above, below[i], above / below[i],
                  (1 - R) / (n * n));
      EXPECT_GT(below[i], 0);
      EXPECT_NEAR(above / expected, 1.0, 1e-4) << "band " << i;
    }
  }
}

// ---- The band lanes (SEASIM_BAND_LANES bands per step, common/sea_bands.h) with band counts
// that do not fill the lanes: 1, 3, 17 and 31 bands (16 lanes by default: one partly filled step, a
// full step and one of 1, a full step and one of 15), from the LUT and from the exact eq. 5. The RGB
// must match the double reference (the padding lanes must add nothing), and the spectral buffer, which
// the lanes write only up to the band count, must sum through the sensor to the RGB (a lane written
// past the end would overwrite the next pixel's first bands).
struct LaneCase {
  int bands;
  bool lut;
};
// The case as gtest prints it (its name, not the struct's bytes).
void PrintTo(const LaneCase& c, std::ostream* os) { *os << c.bands << (c.lut ? " bands, LUT" : " bands, exact"); }

class SeaSingleLanes : public ::testing::TestWithParam<LaneCase> {};

TEST_P(SeaSingleLanes, BandCountsThatDoNotFillTheLanesMatchTheReferenceAndTheSpectrum) {
  const LaneCase c = GetParam();
  const std::string count = std::to_string(c.bands);
  std::vector<seasim::Override> overrides = {set("spectral.count", count.c_str()), set("spectral.spectral_exr", "true"),
                                             set("camera.width", "24"), set("camera.height", "16")};
  if (!c.lut) overrides.push_back(set("quality.sea_lut_size", "1"));  // exact eq. 5 (SEASIM_SEA_LUT=0)
  const seasim::Scene scene = seasim::parseScene(kScene, "test_sea.toml", overrides);
  const seasim::FrameResult frame = seasim::renderFrame(device(), scene, seasim::makePlan(scene));
  EXPECT_EQ(frame.nonfinite, 0);
  const seasim::Image ref = seasim::renderSeaReference(scene, 4000);
  const double error = maxRelativeError(frame.rgb, ref);
  std::printf("[ measured ] %d bands, %s: max relative error against the double reference %.3g\n", c.bands,
              c.lut ? "LUT" : "exact eq. 5", error);
  EXPECT_LT(error, 2e-4);

  const size_t bands = static_cast<size_t>(c.bands), pixels = 24 * 16;
  ASSERT_EQ(frame.spectral.size(), pixels * bands);
  const seasim::WavelengthGrid grid = seasim::makeGrid(scene.spectral.count, scene.spectral.min_nm, scene.spectral.max_nm);
  const seasim::Sensor sensor = seasim::makeSensor(scene.spectral.sensor, grid, scene.spectral.white_balance);
  ASSERT_EQ(sensor.size(), bands);
  float peak = 0;
  for (float v : frame.rgb.pixels) peak = std::max(peak, std::fabs(v));
  double worst = 0;
  for (size_t px = 0; px < pixels; ++px) {
    std::vector<double> values(frame.spectral.begin() + px * bands, frame.spectral.begin() + (px + 1) * bands);
    const std::array<double, 3> rgb = sensor.apply(values.data());
    for (int ch = 0; ch < 3; ++ch) {
      const double kernel = frame.rgb.pixels[3 * px + ch];
      worst = std::max(worst, std::fabs(rgb[ch] - kernel) / (std::fabs(kernel) + 1e-3 * peak));
    }
  }
  EXPECT_LT(worst, 1e-5) << "the spectral buffer does not sum to the RGB";
}

INSTANTIATE_TEST_SUITE_P(BandCounts, SeaSingleLanes,
                         ::testing::Values(LaneCase{1, true}, LaneCase{3, true}, LaneCase{17, true}, LaneCase{31, true},
                                           LaneCase{1, false}, LaneCase{3, false}, LaneCase{17, false},
                                           LaneCase{31, false}),
                         [](const ::testing::TestParamInfo<LaneCase>& info) {
                           return std::to_string(info.param.bands) + (info.param.lut ? "_bands_lut" : "_bands_exact");
                         });

}  // namespace
