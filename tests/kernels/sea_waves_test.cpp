// sea_waves_test.cpp — kernels/sea_single.cl with FFT wave normals (SEASIM_HAS_WAVES) and with the
// analytic and image skies (SEASIM_SKY_MODEL 1, 2) on PoCL (float), against the double CPU reference
// (host/reference/sea_reference.cpp: the ocean from host/ocean/ocean_cpu.h in double, single
// scattering by quadrature). Also: wind 0 through the wave path gives the flat image; steep, folded
// waves and grazing views give no NaN/Inf.
#include <gtest/gtest.h>

#include <ostream>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "device/device.h"
#include "quality/render_frame.h"
#include "plan/plan.h"
#include "reference/reference_image.h"
#include "reference/sea_reference.h"
#include "scene/scene_parser.h"
#include "test_device.h"

namespace {

// Seen from 6 m up, looking down about 35°: hit points 5–25 m away, where a 64² grid over a 20 m
// patch (0.31 m texels) is sampled finely and float hit positions are exact to ~1e-5 texel. The sun
// is behind the camera and high, so its mirror image would need facets tilted ~35°: no glint, whose
// disk test (dot >= cos 0.27°) float and double could decide differently at the disk's edge.
const char* kScene = R"(
[scene]
name = "test_waves"
[camera]
position = [0, 6, 0]
look_at = [0, 0, -8.5]
fov_deg = 50
width = 48
height = 32
[sun]
zenith_deg = 30
azimuth_deg = 90
[sky]
radiance = 0.05
[water]
jerlov = "IB"
[surface]
type = "fft"
wind_speed = 8
patch_size = 20
grid = 64
time = 1.5
[bottom]
type = "flat"
depth = 6
albedo = 0.3
[spectral]
count = 6
[quality]
wave_filter = false             # one normal per pixel, as renderSeaReference's unfiltered path; the
                                # filtered variants below turn it on
)";

seasim::Device& device() { return seasim::test::testDevice(); }

seasim::Override set(const char* key, const std::string& value) { return {key, value, {"test", 1}}; }

// Max over pixels and channels of |kernel - reference| / (|reference| + floor), floor = 1e-3 of the
// image's largest reference value (as tests/kernels/sea_single_test.cpp).
double maxRelativeError(const seasim::Image& a, const seasim::Image& ref) {
  float peak = 0;
  for (float v : ref.pixels) peak = std::max(peak, std::fabs(v));
  double worst = 0;
  for (size_t i = 0; i < ref.pixels.size(); ++i)
    worst = std::max(worst, std::fabs(double(a.pixels[i]) - ref.pixels[i]) / (std::fabs(ref.pixels[i]) + 1e-3 * peak));
  return worst;
}

seasim::FrameResult render(const seasim::Scene& scene) {
  const seasim::FrameResult frame = seasim::renderFrame(device(), scene, seasim::makePlan(scene));
  EXPECT_EQ(frame.nonfinite, 0);
  for (float v : frame.rgb.pixels) EXPECT_TRUE(std::isfinite(v));  // (sensor RGB may be < 0: out of gamut)
  return frame;
}

double passMs(const seasim::FrameResult& frame, const std::string& name) {
  for (const auto& t : frame.timings)
    if (t.name == name) return t.ms;
  return -1;
}

struct Variant {
  const char* name;
  std::vector<seasim::Override> overrides;
  double tolerance;  // max relative error vs the double reference (measured values in the comments)
  bool remove_bottom = false;  // drop the [bottom] table: infinitely deep water
};
// The case as gtest prints it (its name, not the struct's bytes).
void PrintTo(const Variant& c, std::ostream* os) { *os << c.name; }

class SeaWavesKernel : public ::testing::TestWithParam<Variant> {};

TEST_P(SeaWavesKernel, MatchesDoubleReference) {
  std::string text = kScene;
  if (GetParam().remove_bottom) text.erase(text.find("[bottom]"), text.find("[spectral]") - text.find("[bottom]"));
  const seasim::Scene scene = seasim::parseScene(text, "test_waves.toml", GetParam().overrides);
  const seasim::FrameResult frame = render(scene);
  const auto t0 = std::chrono::steady_clock::now();
  const seasim::Image ref = seasim::renderSeaReference(scene, 2000);
  const double ref_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  const double err = maxRelativeError(frame.rgb, ref);
  EXPECT_LT(err, GetParam().tolerance) << GetParam().name;
  std::printf("[ numbers  ] %s: max rel error %.2e, ocean_fft %.2f ms, sea_single %.2f ms, reference %.0f ms\n",
              GetParam().name, err, passMs(frame, "ocean_fft"), passMs(frame, "sea_single"), ref_ms);
}

// Tolerances: float kernel (with VkFFT's float normals) vs double (direct-DFT normals). Measured on
// PoCL: waves 7.1e-5 (exact and 64-entry LUT alike: the LUT's interpolation error is below the float
// normals'), no bottom 1.7e-5, analytic sky 1.5e-4, image sky 1.2e-4 (the sky's gradients amplify the
// normals' rounding); flat analytic 4.3e-5, flat analytic with the sun down 9e-7, flat image 3.4e-6.
// The bounds leave room for other devices' FFT rounding. Under sea.model = "multiple" (the default
// since these were measured): waves 2.2e-4, analytic sky 4.7e-4 on PoCL and 8.6e-4 on Intel's runtime
// (its bound 1.5e-3), image sky 1.1e-4, filtered 4.9e-5.
INSTANTIATE_TEST_SUITE_P(
    Scenes, SeaWavesKernel,
    ::testing::Values(Variant{"waves_exact", {set("quality.sea_lut_size", "1")}, 5e-4},
                      Variant{"waves_lut", {}, 5e-4},
                      Variant{"waves_no_bottom", {set("quality.sea_lut_size", "1")}, 5e-4, true},
                      Variant{"waves_analytic_sky", {set("quality.sea_sky_table", "1"), set("sky.model", "\"analytic\""), set("quality.sea_lut_size", "1")}, 1.5e-3},
                      Variant{"waves_image_sky",
                              {set("sky.model", "\"image\""),
                               set("sky.image", std::string("\"") + SEASIM_SOURCE_DIR + "/scenes/textures/sky_clear.exr\""),
                               set("quality.sea_lut_size", "1")},
                              5e-4},
                      // The wave filter (common/sea_lean.h) against its double CPU twin: the
                      // same moments, footprints and quadrature from the double ocean.
                      Variant{"waves_filtered", {set("quality.wave_filter", "true"), set("quality.sea_lut_size", "1")}, 5e-4},
                      Variant{"waves_filtered_analytic_sky",
                              {set("quality.sea_sky_table", "1"), set("quality.wave_filter", "true"), set("sky.model", "\"analytic\""),
                               set("quality.sea_lut_size", "1"), set("sun.azimuth_deg", "270")},
                              5e-4},
                      Variant{"waves_filtered_image_sky",
                              {set("quality.wave_filter", "true"), set("sky.model", "\"image\""),
                               set("sky.image", std::string("\"") + SEASIM_SOURCE_DIR + "/scenes/textures/sky_clear.exr\""),
                               set("quality.sea_lut_size", "1")},
                              5e-4},
                      Variant{"waves_filtered_preetham_sky",
                              {set("quality.sea_sky_table", "1"), set("quality.wave_filter", "true"), set("sky.model", "\"preetham\""),
                               set("sky.turbidity", "4"), set("quality.sea_lut_size", "1")},
                              5e-4},
                      Variant{"flat_preetham_sky",
                              {set("quality.sea_sky_table", "1"), set("surface.type", "\"flat\""), set("sky.model", "\"preetham\""),
                               set("camera.look_at", "[0, 4, -10]")},
                              2e-4},
                      // The reflected analytic sky from its table (common/sky_table.h, the default) against
                      // the reference's exact sky: the table's own error in the image (measured 1.0e-3
                      // and 1.6e-3, per pixel and channel; the others pin the exact sky).
                      Variant{"waves_filtered_preetham_sky_table",
                              {set("quality.wave_filter", "true"), set("sky.model", "\"preetham\""),
                               set("sky.turbidity", "4"), set("quality.sea_lut_size", "1")},
                              2.5e-3},
                      Variant{"flat_analytic_sky_table", {set("surface.type", "\"flat\""), set("sky.model", "\"analytic\"")}, 2.5e-3},
                      Variant{"waves_supersampled", {set("quality.sea_supersample", "3"), set("quality.sea_lut_size", "1")}, 5e-4},
                      Variant{"flat_analytic_sky", {set("quality.sea_sky_table", "1"), set("surface.type", "\"flat\""), set("sky.model", "\"analytic\"")}, 2e-4},
                      Variant{"flat_analytic_sky_sun_down",
                              {set("quality.sea_sky_table", "1"), set("surface.type", "\"flat\""), set("sky.model", "\"analytic\""), set("sun.zenith_deg", "100"),
                               set("camera.look_at", "[0, 3, -10]")},
                              2e-4},
                      Variant{"flat_image_sky",
                              {set("surface.type", "\"flat\""), set("sky.model", "\"image\""),
                               set("sky.image", std::string("\"") + SEASIM_SOURCE_DIR + "/scenes/textures/sky_clear.exr\""),
                               set("camera.look_at", "[0, 4, -10]")},
                              2e-4}),
    [](const ::testing::TestParamInfo<Variant>& info) { return std::string(info.param.name); });

TEST(SeaWavesKernel, WindZeroGivesTheFlatImage) {
  // Through the wave path (ocean at wind 0: every normal exactly (0, 1, 0)) the exact evaluation must
  // reproduce the flat sea; with the LUT the two paths index different tables (theta_ji vs theta_jo),
  // so they agree to the LUT's interpolation error only. Both built with exact maths: quality.fast_math
  // "auto" would build the flat scene with relaxed maths and the wave scene without.
  const std::vector<seasim::Override> exact = {set("quality.sea_lut_size", "1"), set("quality.fast_math", "false")};
  auto with = [](std::vector<seasim::Override> o, seasim::Override extra) {
    o.push_back(extra);
    return o;
  };
  for (const bool lut : {false, true}) {
    const std::vector<seasim::Override> base =
        lut ? std::vector<seasim::Override>{set("quality.fast_math", "false")} : exact;
    const seasim::FrameResult flat =
        render(seasim::parseScene(kScene, "test_waves.toml", with(base, set("surface.type", "\"flat\""))));
    const seasim::FrameResult calm =
        render(seasim::parseScene(kScene, "test_waves.toml", with(base, set("surface.wind_speed", "0"))));
    double worst = 0;
    size_t differing = 0;
    for (size_t i = 0; i < flat.rgb.pixels.size(); ++i) {
      const double a = flat.rgb.pixels[i], b = calm.rgb.pixels[i];
      worst = std::max(worst, std::fabs(a - b) / std::max(std::fabs(a), 1e-30));
      differing += a != b;
    }
    if (!lut) {
      EXPECT_EQ(differing, 0u) << "exact evaluation: the wave path at wind 0 must be bitwise the flat path";
    }
    EXPECT_LT(worst, lut ? 2e-4 : 1e-6);
    std::printf("[ numbers  ] wind 0 vs flat (%s): %zu of %zu values differ, max rel %.2e\n", lut ? "LUT" : "exact",
                differing, flat.rgb.pixels.size(), worst);
  }
}

TEST(SeaWavesKernel, MultipleModelAgreesWithThePathTracerThroughTheWaves) {
  // wavy_sea with the sun to the side (its glitter out of view: the tracer's sun's disk in the facets'
  // mirror is a rare event, too noisy for a test): the default sea model against all orders of
  // scattering traced through the same waves (kernels/reference.cl, SEASIM_PT_WAVES), image means per
  // channel. Measured 0.998 (tests/perf/sea_waves_vs_pathtracer.sh).
  const seasim::Scene scene = seasim::loadScene(std::string(SEASIM_SOURCE_DIR) + "/scenes/wavy_sea.toml",
                                                {set("camera.width", "48"), set("camera.height", "27"),
                                                 set("sun.azimuth_deg", "90")});
  const seasim::FrameResult fast = render(scene);
  seasim::ReferenceOptions options;
  options.device = seasim::test::testDeviceSelector();
  options.steps = 512;
  options.all_orders = true;
  const seasim::ReferenceImage pt = seasim::renderReference(scene, options);
  for (int c = 0; c < 3; ++c) {
    double m = 0, r = 0, se2 = 0;
    const size_t n = pt.rgb.pixelCount();
    for (size_t i = 0; i < n; ++i) {
      m += fast.rgb.pixels[3 * i + c];
      r += pt.rgb.pixels[3 * i + c];
      se2 += double(pt.std_error.pixels[3 * i + c]) * pt.std_error.pixels[3 * i + c];
    }
    const double se = std::sqrt(se2) / n;
    m /= n;
    r /= n;
    std::printf("[ numbers  ] channel %d: multiple %.5g, path tracer %.5g +- %.2g\n", c, m, r, se);
    EXPECT_NEAR(m / r, 1.0, 0.02 + 3 * se / r) << c;
  }
}

TEST(SeaWavesKernel, SteepFoldedWavesAndGrazingViewsStayFinite) {
  // A storm on a small patch (slopes beyond 45°), large choppiness (folded facets with downward
  // normals), the camera looking at the horizon, the sun grazing: no NaN/Inf, and
  // the image mean still close to the reference (pixels may differ where float and double take the
  // other side of a fold). The sun is a point (radius 0): with glints everywhere, one glint pixel
  // that float and double decide differently would outweigh the whole image.
  for (const char* look_at : {"[0, 6, -100]", "[0, 5.999, -100]", "[0, 0, -0.001]"}) {
    const seasim::Scene scene = seasim::parseScene(
        kScene, "test_waves.toml",
        {set("surface.wind_speed", "40"), set("surface.patch_size", "5"), set("surface.choppiness", "3"),
         set("sun.zenith_deg", "89.5"), set("sun.azimuth_deg", "270"), set("sun.angular_radius_deg", "0"),
         set("camera.look_at", look_at),
         set("water.g", "0.99"), set("quality.sea_lut_size", "\"auto\"")});
    const seasim::FrameResult frame = render(scene);
    const seasim::Image ref = seasim::renderSeaReference(scene, 400);
    double sum = 0, ref_sum = 0;
    for (size_t i = 0; i < ref.pixels.size(); ++i) sum += frame.rgb.pixels[i], ref_sum += ref.pixels[i];
    EXPECT_GT(ref_sum, 0.0);
    EXPECT_NEAR(sum / ref_sum, 1.0, 0.02) << look_at;
    std::printf("[ numbers  ] steep waves, look_at %s: image mean kernel / reference = %.5f\n", look_at, sum / ref_sum);
  }
}

}  // namespace
