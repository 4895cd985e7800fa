// underwater_lamps_test.cpp — spotlights in water (kernels/underwater_lamps.cl) on PoCL:
//   * the kernel against the double-precision CPU evaluation of the same math (common/underwater_lamps.h
//     in kmath_d) on a lamp-only scene (sun off, black sky): in-scattering and the lit bottom;
//   * the path tracer's single-scattering mode with lamps (reference.cl, next-event estimation) against
//     the pass with many planes: the two agree within the tracer's noise;
//   * stiff cases: a lamp inside an object adds nothing (every shadow ray is blocked); a cone of 0.1°
//     and turbid 9C water render without NaN/Inf; rov_lights.toml composes the lamps with the sun's
//     K_d, froxels and caustics, and the lamps only add light.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "math/kernel_math.h"
#include "quality/auto_quality.h"
#include "reference/compare.h"
#include "reference/underwater_reference.h"
#include "render/renderer.h"
#include "jobs/layer_image.h"
#include "scene/scene_parser.h"
#include "spectral/sensor.h"
#include "spectral/wavelength_grid.h"
#include "test_device.h"
#include "passes/underwater_lamps_pass.h"
#include "underwater/lamps_bottom_glow.h"
#include "underwater/lamps_ms_table.h"
#include "underwater/lamps_setup.h"
#include "underwater/underwater_setup.h"

namespace {

namespace kd = seasim::kmath_d;
using seasim::Override;
using seasim::Scene;

Override set(const std::string& key, const std::string& value) { return {key, value, {"test", 1}}; }

// A lamp-only scene: the sun off and a black sky, so the frame is the lamps' light alone.
const char* kLampScene = R"(
[camera]
position = [0.0, -4.0, 0.0]
look_at = [0.0, -5.0, -6.0]
fov_deg = 60.0
width = 40
height = 24
[sun]
enabled = false
[sky]
model = "uniform"
radiance = 0.0
[water]
jerlov = "3C"
g = 0.85
[bottom]
type = "flat"
depth = 7.0
albedo = 0.4
[[spotlights]]
position = [0.8, -4.2, -1.0]
direction = [-0.3, -0.4, -1.0]
cone_deg = 22.0
falloff_deg = 6.0
intensity = 30.0
temperature_k = 3200.0
[spectral]
count = 5
range_nm = [400.0, 700.0]
)";

Scene lampScene(const std::vector<Override>& overrides = {}) {
  return seasim::parseScene(kLampScene, "lamp_test.toml", overrides);
}

seasim::FrameResult render(const Scene& scene) {
  seasim::Renderer renderer(seasim::test::testDevice(), scene, seasim::shippedPasses());
  return renderer.render();
}

// The same lamps in double on the CPU: per pixel the G-buffer hit (bottom only, no objects), then per
// band I(λ) [in-scattering + ρ_bottom × direct light], through the sensor weights.
// delta_m: the lamps see the water delta-M scaled, as the pass does with quality.lamps_delta_m = 1.
// orders: the "orders" model (quality.lamps_model = "orders", its default knobs): the plain medium's
// single scattering plus common/underwater_lamps_ms.h's orders, surfaces seen through T_view.
seasim::Image cpuDouble(const Scene& scene, int planes, int subplanes, bool delta_m, bool orders = false) {
  const seasim::WavelengthGrid grid = seasim::makeGrid(scene.spectral.count, scene.spectral.min_nm, scene.spectral.max_nm);
  const seasim::Sensor sensor = seasim::makeSensor(scene.spectral.sensor, grid, scene.spectral.white_balance);
  seasim::UnderwaterSetup setup = seasim::makeUnderwaterSetup(scene, grid, sensor);
  if (delta_m) seasim::deltaMScale(setup.params, setup.bands);
  const seasim::UnderwaterLamps lamps = seasim::makeUnderwaterLamps(scene, grid);
  const seasim::UnderwaterLampsPass::Config cfg = seasim::UnderwaterLampsPass::configFromScene(scene);
  const std::vector<float> ms_table = seasim::lampMsTable(lamps.lamps, setup.params.g, cfg.beta, cfg.orders);
  const std::vector<float> glow = seasim::lampBottomGlowTable(lamps.lamps, setup.params, setup.bands, lamps.params.s_min);
  const int glow_stride = seasim::lampGlowStride(static_cast<int>(setup.bands.size()));
  const UwParams& p = setup.params;
  seasim::Image img;
  img.width = p.width;
  img.height = p.height;
  img.channels = 3;
  img.pixels.assign(static_cast<size_t>(p.width) * p.height * 3, 0.0f);
  const kd::real3 o{p.cam_pos[0], p.cam_pos[1], p.cam_pos[2]};
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x) {
      const seasim::Vec3 dv = seasim::underwaterPixelDirection(p, x + 0.5, y + 0.5);
      const kd::real3 d{dv.x, dv.y, dv.z};
      kd::real3 n;
      int mat;
      const double S = kd::uw_scene_hit(setup.objects.data(), 0, p.bottom_depth, o, d, 0.0, &n, &mat);
      const double t_end = S >= 1e29 ? 1e30 : S;
      double rgb[3] = {0, 0, 0};
      for (int l = 0; l < lamps.params.lamp_count; ++l) {
        const UwLamp& L = lamps.lamps[l];
        const kd::real3 lamp{L.position[0], L.position[1], L.position[2]};
        const kd::real3 axis{L.direction[0], L.direction[1], L.direction[2]};
        const float* rows = ms_table.data() + static_cast<size_t>(l) * cfg.orders * UW_MS_ROW;
        for (size_t i = 0; i < setup.bands.size(); ++i) {
          const UwBand& b = setup.bands[i];
          double v = kd::uw_lamp_inscatter(o, d, lamp, axis, L.cos_cone, L.cos_inner, lamps.params.s_min, t_end, b.b,
                                           b.c, p.g, planes, subplanes);
          if (orders) {
            double c_min = setup.bands[0].c;
            for (const UwBand& other : setup.bands) c_min = std::min(c_min, double(other.c));
            v += kd::uw_ms_inscatter(o, d, lamp, axis, L.cos_cone, lamps.params.s_min, t_end, kd::uw_ms_ray_cap(c_min),
                                     b.a, b.b, p.g, cfg.kappa, c_min, rows, cfg.orders, cfg.ms_steps);
            // The bottom's glow (on the bottom itself its light is 0: the source's cos ψ there).
            const float* gl = glow.data() + static_cast<size_t>(l) * glow_stride;
            if (gl[3] > 0.0f)
              v += gl[4 + i] * kd::uw_ms_glow_inscatter(o, d, kd::real3{gl[0], gl[1], gl[2]}, kd::real3{0.0, 1.0, 0.0},
                                                        gl[3], t_end, kd::uw_ms_ray_cap(c_min), b.a, b.b, p.g,
                                                        cfg.orders, kd::uw_ms_glow_steps(cfg.ms_steps), nullptr);
            // The bottom's halo: its F exact at every step (the kernel reads it from its table).
            v += kd::uw_ms_halo_inscatter(o, d, p.bottom_depth, b.bottom_albedo, lamp, axis, lamps.params.s_min, t_end,
                                          kd::uw_ms_ray_cap(c_min), b.a, b.b, p.g, cfg.kappa, rows, cfg.orders,
                                          kd::uw_ms_glow_steps(cfg.ms_steps));
            if (mat == UW_MAT_BOTTOM) {
              const kd::real3 P = o + S * d;
              const double direct =
                  kd::uw_lamp_surface(P, n, 0.0, lamp, axis, L.cos_cone, L.cos_inner, lamps.params.s_min, b.c, 1.0);
              double view[UW_MS_MAX_ORDERS + 1];
              v += b.bottom_albedo *
                   (direct + kd::uw_ms_surface(P, n, lamp, axis, lamps.params.s_min, b.a, b.b, p.g, cfg.kappa, rows, cfg.orders)) *
                   kd::uw_ms_view_terms(b.a, b.b, p.g, S, cfg.orders, view);
              // The direct light blurred on its way to the eye in T_view's terms k >= 1.
              for (int k = 1; k <= cfg.orders; ++k) {
                const kd::UwMsBlur blur =
                    kd::uw_ms_blurred_bottom(o, d, p.bottom_depth, lamp, axis, L.cos_cone, L.cos_inner, lamps.params.s_min,
                                             kd::uw_ms_spread(p.g, k, UW_MS_VIEW_BETA));
                v += b.bottom_albedo * view[k] *
                     (blur.geometry * std::exp(-double(b.c) * blur.s_mean) - direct);
              }
            }
          } else if (mat == UW_MAT_BOTTOM)
            v += b.bottom_albedo * kd::uw_lamp_surface(o + S * d, n, S, lamp, axis, L.cos_cone, L.cos_inner,
                                                       lamps.params.s_min, b.c, 1.0);
          v *= lamps.spectra[l * setup.bands.size() + i];
          rgb[0] += v * b.w_r;
          rgb[1] += v * b.w_g;
          rgb[2] += v * b.w_b;
        }
      }
      for (int c = 0; c < 3; ++c) img.at(x, y, c) = static_cast<float>(rgb[c]);
    }
  return img;
}

double maxOf(const seasim::Image& img) { return *std::max_element(img.pixels.begin(), img.pixels.end()); }

double meanOf(const seasim::Image& img) {
  double s = 0;
  for (float v : img.pixels) s += v;
  return s / img.pixels.size();
}

// The kernel's frame of `scene` against the double CPU evaluation `cpu`: finite, every pixel within 2e-3 of the
// peak, and the image means within 1e-4.
void expectKernelMatchesCpu(const Scene& scene, const seasim::Image& cpu, const char* what) {
  const seasim::FrameResult frame = render(scene);
  ASSERT_EQ(frame.nonfinite, 0);
  const double peak = maxOf(cpu);
  ASSERT_GT(peak, 0);
  double worst = 0;
  for (size_t k = 0; k < cpu.pixels.size(); ++k)
    worst = std::max(worst, double(std::fabs(frame.rgb.pixels[k] - cpu.pixels[k])));
  std::printf("%s vs double CPU: max |difference| %.3g of a peak %.4g\n", what, worst, peak);
  EXPECT_LT(worst, 2e-3 * peak) << what << ": worst " << worst << " of peak " << peak;
  EXPECT_NEAR(meanOf(frame.rgb), meanOf(cpu), 1e-4 * meanOf(cpu)) << what;
}

TEST(UnderwaterLamps, KernelMatchesTheDoubleCpuEvaluation) {
  for (const bool delta_m : {false, true}) {
    const Scene scene = lampScene({set("quality.shafts_planes", "30"), set("quality.shafts_subplanes", "6"),
                                   set("quality.lamps_delta_m", delta_m ? "true" : "false")});
    expectKernelMatchesCpu(scene, cpuDouble(scene, 30, 6, delta_m), delta_m ? "kernel (delta-M)" : "kernel");
  }
}

TEST(UnderwaterLamps, PlanesBeyondOneBlockMatchTheDoubleCpuEvaluation) {
  // The kernel sums the planes in blocks of 32 (underwater_lamps.cl, LAMP_PLANE_BLOCK): 45 planes take a full
  // block and a part of a second, whose first plane's profile carries on from the first block's last.
  const Scene scene = lampScene({set("quality.shafts_planes", "45"), set("quality.shafts_subplanes", "3"),
                                 set("quality.lamps_delta_m", "false")});
  expectKernelMatchesCpu(scene, cpuDouble(scene, 45, 3, false), "kernel, 45 planes");
}

TEST(UnderwaterLamps, OrdersKernelMatchesTheDoubleCpuEvaluation) {
  // Every pixel evaluated (no lattice): the double evaluation below is per pixel.
  const Scene scene = lampScene({set("quality.shafts_planes", "30"), set("quality.shafts_subplanes", "6"),
                                 set("quality.lamps_model", "\"orders\""), set("quality.lamps_ms_cell_deg", "0")});
  expectKernelMatchesCpu(scene, cpuDouble(scene, 30, 6, false, true), "orders kernel");
}

TEST(UnderwaterLamps, OrdersKernelWithBandsPastOneRunOfLanesMatchesTheDoubleCpuEvaluation) {
  // 19 bands: the view ray's orders, glow and halo run the bands 16 lanes at a time (SEASIM_BAND_LANES), so a
  // second run holds 3 bands and 13 lanes that must add nothing.
  const Scene scene = lampScene({set("quality.shafts_planes", "30"), set("quality.shafts_subplanes", "6"),
                                 set("quality.lamps_model", "\"orders\""), set("quality.lamps_ms_cell_deg", "0"),
                                 set("spectral.count", "19")});
  ASSERT_EQ(scene.spectral.count, 19);
  expectKernelMatchesCpu(scene, cpuDouble(scene, 30, 6, false, true), "orders kernel, 19 bands");
}

// The orders model's smooth part on a lattice of every step-th pixel (quality.lamps_ms_cell_deg), against
// every pixel evaluated (step 1), on the lamp scene with a sphere and a box in the beam: a lattice pixel
// reads its own value; a pixel between reads its neighbours on the same surface and evaluates itself at
// a silhouette (where interpolating the bottom's light into a sphere's pixel, or open water's into the
// bottom's, would be off by far more than the bound), so every pixel stays close.
TEST(UnderwaterLamps, OrdersOnALatticeFollowEveryPixelAcrossSilhouettes) {
  const std::string objects = std::string(kLampScene) + R"(
[[objects]]
type = "sphere"
center = [0.2, -6.2, -5.0]
radius = 0.6
albedo = 0.6
[[objects]]
type = "box"
min = [-1.6, -7.0, -6.5]
max = [-0.7, -5.6, -5.5]
albedo = 0.3
)";
  const auto frame = [&](int step) {
    const Scene scene = seasim::parseScene(objects, "lamp_objects.toml",
                                           {set("quality.lamps_model", "\"orders\""),
                                            // 60° over 48 rows: 1.25° per pixel
                                            set("quality.lamps_ms_cell_deg", std::to_string(1.25 * step + 0.01)),
                                            set("camera.width", "80"), set("camera.height", "48")});
    const seasim::FrameResult f = render(scene);
    EXPECT_EQ(f.nonfinite, 0);
    return f.rgb;
  };
  const seasim::Image every = frame(1);
  const double peak = maxOf(every);
  ASSERT_GT(peak, 0);
  for (const int step : {2, 4}) {
    const seasim::Image lattice = frame(step);
    double own = 0, worst = 0, d2 = 0, e2 = 0;
    for (int y = 0; y < every.height; ++y)
      for (int x = 0; x < every.width; ++x)
        for (int c = 0; c < 3; ++c) {
          const double a = every.at(x, y, c), b = lattice.at(x, y, c), d = std::fabs(b - a);
          if (x % step == 0 && y % step == 0) own = std::max(own, d);
          worst = std::max(worst, d / (std::fabs(a) + 0.02 * peak));
          d2 += d * d;
          e2 += a * a;
        }
    std::printf("lattice step %d: its own pixels within %.3g of a peak %.4g; worst pixel %.3g of its value "
                "(+ 2 %% of the peak); image rel. L2 %.3g\n", step, own, peak, worst, std::sqrt(d2 / e2));
    EXPECT_LT(own, 1e-5 * peak);
    EXPECT_LT(worst, 0.08);  // measured 0.037 (step 2) and 0.062 (step 4); 0.29-0.41 reading the surface's part
                             // where the normal turns, 0.12-0.15 with no silhouette test
    EXPECT_LT(std::sqrt(d2 / e2), 0.01);  // 0.0037 and 0.0038; 0.045 with no lamp test
  }
}

// In the water the planes span the cone's exact interval, so their m sub-samples only follow the soft edge's
// ramp and the objects' shadows: the default m there is 2 (UnderwaterLampsPass::kSubplanesInWater), not the
// shafts' 6, unless the scene gives m. On the lamp scene with a soft edge and a sphere in the beam, against
// m = 24: m = 2 errs by 7.9e-5 (rel. L2; m = 6 by 7e-6, m = 1 by 5.9e-4), well under the lattice's own error
// (0.3 %, the test above).
TEST(UnderwaterLamps, TwoSubSamplesInTheWaterAreSixsImage) {
  EXPECT_EQ(seasim::UnderwaterLampsPass::configFromScene(lampScene()).subplanes, 2);
  EXPECT_EQ(seasim::UnderwaterLampsPass::configFromScene(lampScene({set("quality.shafts_subplanes", "\"auto\"")})).subplanes, 2);
  EXPECT_EQ(seasim::UnderwaterLampsPass::configFromScene(lampScene({set("quality.shafts_subplanes", "5")})).subplanes, 5);
  const std::string sphere = std::string(kLampScene) + R"(
[[objects]]
type = "sphere"
center = [0.1, -5.6, -4.5]
radius = 0.5
albedo = 0.5
)";
  const auto frame = [&](const std::string& m) {
    std::vector<Override> o = {set("quality.lamps_model", "\"single\""), set("camera.width", "80"), set("camera.height", "48")};
    if (!m.empty()) o.push_back(set("quality.shafts_subplanes", m));
    const seasim::FrameResult f = render(seasim::parseScene(sphere, "lamp_sphere.toml", o));
    EXPECT_EQ(f.nonfinite, 0);
    return f.rgb;
  };
  const seasim::Image converged = frame("24"), six = frame("6"), two = frame(""), one = frame("1");
  const auto relL2 = [&](const seasim::Image& a) { return seasim::compareImages(a, converged).rel_l2; };
  std::printf("against m = 24, rel. L2: m = 6 %.3g, m = 2 (default) %.3g, m = 1 %.3g\n", relL2(six), relL2(two), relL2(one));
  EXPECT_LT(relL2(two), 3e-4);
  EXPECT_LT(relL2(six), relL2(two));
  EXPECT_LT(relL2(two), relL2(one));
}

TEST(UnderwaterLamps, OrdersBottomGlowLightsTheWaterAboveTheLitBottom) {
  // The top row looks up into open water, past the bottom: only the lit bottom's glow there depends on
  // the bottom's albedo. A black bottom sends nothing back.
  const Scene grey = lampScene({set("quality.lamps_model", "\"orders\"")});
  const Scene black = lampScene({set("quality.lamps_model", "\"orders\""), set("bottom.albedo", "0.0")});
  const seasim::Image lit = render(grey).rgb, dark = render(black).rgb;
  double glow = 0.0, water = 0.0;
  for (int x = 0; x < lit.width; ++x) {
    EXPECT_GT(lit.at(x, 0, 1), dark.at(x, 0, 1)) << "x " << x;
    glow += lit.at(x, 0, 1) - dark.at(x, 0, 1);
    water += dark.at(x, 0, 1);
  }
  std::printf("the bottom's glow in the top row: %.3g of the lamp's light there\n", glow / water);
  EXPECT_GT(glow, 0.01 * water);
}

TEST(UnderwaterLamps, OrdersLightTheWaterOutsideTheBeam) {
  // Single scattering leaves every pixel whose ray misses the cone black; the orders light them all.
  const seasim::Image single = render(lampScene({set("quality.lamps_model", "\"single\"")})).rgb;
  const seasim::Image orders = render(lampScene({set("quality.lamps_model", "\"orders\"")})).rgb;
  int dark = 0, lit = 0;
  for (size_t k = 0; k < single.pixels.size(); k += 3)
    if (single.pixels[k] == 0.0f) {
      ++dark;
      if (orders.pixels[k] > 0.0f) ++lit;
    }
  ASSERT_GT(dark, 0);
  EXPECT_EQ(lit, dark);
  EXPECT_GT(meanOf(orders), meanOf(single));
}

TEST(UnderwaterLamps, DeltaMKeepsTheForwardScatteredLight) {
  // The scaled medium loses less of the beam (σ_t' < σ_t): a brighter lit bottom and a brighter frame.
  const double plain = meanOf(render(lampScene({set("quality.lamps_delta_m", "false")})).rgb);
  const double scaled = meanOf(render(lampScene({set("quality.lamps_delta_m", "true")})).rgb);
  EXPECT_GT(scaled, 1.2 * plain);
}

TEST(UnderwaterLamps, SpectralOutputHoldsTheLampsBands) {
  // spectral.exr holds the whole image per band: here (sun off, black sky) the lamps' bands alone,
  // which through the sensor weights give the RGB image.
  const Scene scene = lampScene({set("spectral.spectral_exr", "true")});
  const seasim::FrameResult frame = render(scene);
  const seasim::WavelengthGrid grid = seasim::makeGrid(scene.spectral.count, scene.spectral.min_nm, scene.spectral.max_nm);
  const seasim::Sensor sensor = seasim::makeSensor(scene.spectral.sensor, grid, scene.spectral.white_balance);
  const size_t nb = grid.size(), pixels = frame.rgb.pixels.size() / 3;
  ASSERT_EQ(frame.spectral.size(), pixels * nb);
  double peak = 0, worst = 0;
  for (size_t p = 0; p < pixels; ++p) {
    const std::array<double, 3> rgb = [&] {
      std::vector<double> bands(frame.spectral.begin() + p * nb, frame.spectral.begin() + (p + 1) * nb);
      return sensor.apply(bands.data());
    }();
    for (int c = 0; c < 3; ++c) {
      peak = std::max(peak, std::fabs(rgb[c]));
      worst = std::max(worst, std::fabs(rgb[c] - frame.rgb.pixels[3 * p + c]));
    }
  }
  ASSERT_GT(peak, 0);
  EXPECT_LT(worst, 1e-5 * peak + 1e-9);
}

// The lamps' layers of a render: per pixel lamps, lamps_single and lamps_multiple (R, G, B each).
struct LampLayers {
  std::vector<std::array<double, 3>> lamps, single, multiple;
};

LampLayers lampLayers(const std::string& model, std::vector<Override> extra = {}) {
  extra.push_back(set("quality.lamps_model", "\"" + model + "\""));
  extra.push_back(set("outputs.layers", "[\"lamps\", \"lamps_single\", \"lamps_multiple\"]"));
  const Scene scene = lampScene(extra);
  const seasim::FrameResult frame = render(scene);
  EXPECT_EQ(frame.nonfinite, 0);
  const seasim::Image img = seasim::imageWithLayers(frame, scene.outputs);
  auto channel = [&](const std::string& name) {
    const auto it = std::find(img.channel_names.begin(), img.channel_names.end(), name);
    EXPECT_NE(it, img.channel_names.end()) << name;
    return static_cast<size_t>(it - img.channel_names.begin());
  };
  LampLayers out;
  for (size_t i = 0; i < img.pixelCount(); ++i) {
    std::array<double, 3> l{}, s{}, m{};
    int c = 0;
    for (const char* rgb : {".R", ".G", ".B"}) {
      l[c] = img.pixels[i * img.channels + channel(std::string("lamps") + rgb)];
      s[c] = img.pixels[i * img.channels + channel(std::string("lamps_single") + rgb)];
      m[c] = img.pixels[i * img.channels + channel(std::string("lamps_multiple") + rgb)];
      ++c;
    }
    out.lamps.push_back(l);
    out.single.push_back(s);
    out.multiple.push_back(m);
  }
  return out;
}

double sumOf(const std::vector<std::array<double, 3>>& v) {
  double s = 0;
  for (const auto& p : v) s += p[0] + p[1] + p[2];
  return s;
}

TEST(UnderwaterLamps, PathTracerSingleScatteringAgreesWithThePass) {
  // Black bottom: the frame is the lamp's single scattering, what the tracer's max_bounces = 1 estimates.
  // The lamp behind the camera, out of view: no view ray passes near it, where next-event estimation's
  // 1/s² has a variance that grows as 1/h³ with the ray's distance h to the lamp.
  // The pass's plain single scattering (no delta-M scaling): the integral the tracer's mode estimates.
  const Scene scene = lampScene({set("bottom.albedo", "0.0"), set("quality.shafts_planes", "200"),
                                 set("quality.lamps_delta_m", "false"),
                                 set("quality.shafts_subplanes", "16"), set("spotlights[0].position", "[0.3, -3.5, 1.0]"),
                                 set("spotlights[0].direction", "[-0.05, -0.4, -1.0]")});
  const seasim::FrameResult frame = render(scene);
  const seasim::WavelengthGrid grid = seasim::makeGrid(scene.spectral.count, scene.spectral.min_nm, scene.spectral.max_nm);
  const seasim::Sensor sensor = seasim::makeSensor(scene.spectral.sensor, grid, scene.spectral.white_balance);
  const seasim::UnderwaterSetup setup = seasim::makeUnderwaterSetup(scene, grid, sensor);
  const seasim::UnderwaterLamps lamps = seasim::makeUnderwaterLamps(scene, grid);
  seasim::UnderwaterReferenceSettings settings;
  settings.samples_per_pixel = 4096;  // single scattering only: about 10 s on 2 PoCL cores
  settings.batch = 512;
  settings.max_bounces = 1;
  settings.lamps = &lamps;
  const seasim::UnderwaterReferenceResult ref = seasim::renderUnderwaterReference(seasim::test::testDevice(), setup, settings);
  const double fast = meanOf(frame.rgb);
  ASSERT_GT(fast, 0);
  std::printf("lamps' single scattering, image mean: pass %.6g, path tracer %.6g +- %.2g (standard error)\n", fast,
              ref.image_mean, ref.image_mean_std_error);
  ASSERT_LT(ref.image_mean_std_error, 0.03 * fast);  // the comparison below is tight enough to mean something
  EXPECT_NEAR(ref.image_mean, fast, 4 * ref.image_mean_std_error + 0.01 * fast)
      << "standard error " << ref.image_mean_std_error;
  // The models with multiple scattering keep this single scattering apart in their lamps_single layer.
  for (const char* model : {"delta_m", "orders"}) {
    std::vector<Override> o = {set("bottom.albedo", "0.0"), set("quality.shafts_planes", "200"),
                               set("quality.shafts_subplanes", "16"), set("spotlights[0].position", "[0.3, -3.5, 1.0]"),
                               set("spotlights[0].direction", "[-0.05, -0.4, -1.0]")};
    const LampLayers l = lampLayers(model, o);
    const double single = sumOf(l.single) / (3.0 * l.single.size());
    EXPECT_NEAR(ref.image_mean, single, 4 * ref.image_mean_std_error + 0.01 * fast) << model;
    EXPECT_GT(sumOf(l.lamps) / (3.0 * l.lamps.size()), 1.2 * single) << model;
  }
  // Without lamps the tracer sees nothing in this scene: the lamps are what it measured.
  settings.lamps = nullptr;
  EXPECT_EQ(seasim::renderUnderwaterReference(seasim::test::testDevice(), setup, settings).image_mean, 0.0);
}

TEST(UnderwaterLamps, LayersSplitTheLampsIntoSingleAndMultipleScattering) {
  // Every model: lamps_single + lamps_multiple = lamps per pixel; lamps_single is 001's single scattering
  // in the water as it is (the plain model's whole light), the same whatever the model; the "single"
  // model has no multiple part, the other two a large one (3C water, g 0.85: multiple scattering is
  // several times the single).
  // The orders model also on its lattice, at 80x48 (1.25° per pixel; 2.6° cells: every second pixel).
  const std::vector<Override> larger = {set("camera.width", "80"), set("camera.height", "48")};
  std::vector<Override> lattice_on = larger;
  lattice_on.push_back(set("quality.lamps_ms_cell_deg", "2.6"));
  for (const std::string model : {"single", "delta_m", "orders", "orders on a lattice"}) {
    const bool lattice = model == "orders on a lattice";
    const LampLayers plain = lampLayers("single", lattice ? larger : std::vector<Override>{});
    double peak = 0;
    for (const auto& p : plain.lamps) peak = std::max({peak, p[0], p[1], p[2]});
    ASSERT_GT(peak, 0);
    const LampLayers l = lattice ? lampLayers("orders", lattice_on) : lampLayers(model);
    double split = 0, single = 0, plain_multiple = 0;
    for (size_t i = 0; i < l.lamps.size(); ++i)
      for (int c = 0; c < 3; ++c) {
        split = std::max(split, std::fabs(l.single[i][c] + l.multiple[i][c] - l.lamps[i][c]));
        single = std::max(single, std::fabs(l.single[i][c] - plain.lamps[i][c]));
        plain_multiple = std::max(plain_multiple, std::fabs(plain.multiple[i][c]));
      }
    EXPECT_LE(split, 1e-5 * peak) << model;
    EXPECT_LE(single, 1e-4 * peak) << model;
    EXPECT_EQ(plain_multiple, 0.0);
    std::printf("%s: lamps_multiple / lamps_single %.3f\n", model.c_str(), sumOf(l.multiple) / sumOf(l.single));
    if (model != "single") EXPECT_GT(sumOf(l.multiple), 0.5 * sumOf(l.single)) << model;
  }
}

TEST(UnderwaterLamps, SingleLayerAloneIsWrittenWhenOnlyItIsAsked) {
  const Scene scene = lampScene({set("outputs.layers", "[\"lamps_single\"]")});
  const seasim::FrameResult frame = render(scene);
  const seasim::Image img = seasim::imageWithLayers(frame, scene.outputs);
  const std::vector<std::string> want = {"R", "G", "B", "lamps_single.R", "lamps_single.G", "lamps_single.B"};
  EXPECT_EQ(img.channel_names, want);
  double sum = 0;
  for (size_t i = 0; i < img.pixelCount(); ++i) sum += img.pixels[i * img.channels + 4];
  EXPECT_GT(sum, 0);
}

TEST(UnderwaterLamps, LampInsideAnObjectAddsNothing) {
  // The sun on, so the frame without the lamp is not black; a sphere around the lamp.
  const std::vector<Override> sun = {set("sun.enabled", "true"), set("sky.radiance", "0.05")};
  const std::string sphere = "\n[[objects]]\ntype = \"sphere\"\ncenter = [0.8, -4.2, -1.0]\nradius = 0.3\nalbedo = 0.5\n";
  auto withSphere = [&](const std::vector<Override>& o) {
    return seasim::parseScene(std::string(kLampScene) + sphere, "lamp_test.toml", o);
  };
  std::vector<Override> dark = sun;
  dark.push_back(set("spotlights[0].intensity", "0.0"));
  const seasim::FrameResult lit = render(withSphere(sun));
  const seasim::FrameResult off = render(withSphere(dark));
  ASSERT_EQ(lit.nonfinite, 0);
  EXPECT_EQ(lit.rgb.pixels, off.rgb.pixels);
  ASSERT_GT(meanOf(off.rgb), 0);
  // The same lamp outside the sphere does add light (the test above is not vacuous).
  std::vector<Override> moved = sun;
  moved.push_back(set("objects[0].center", "[3.0, -4.2, -1.0]"));
  EXPECT_GT(meanOf(render(withSphere(moved)).rgb), 1.01 * meanOf(off.rgb));
}

TEST(UnderwaterLamps, TurbidWaterStaysFinite) {
  const seasim::FrameResult f = render(lampScene({set("water.jerlov", "\"9C\"")}));
  EXPECT_EQ(f.nonfinite, 0);
  // Finite everywhere (sensor RGB may dip below 0 for colours outside the sRGB gamut: no sign test).
  for (float v : f.rgb.pixels) ASSERT_TRUE(std::isfinite(v));
  EXPECT_GT(meanOf(f.rgb), 0);
}

TEST(UnderwaterLamps, ConeOfATenthOfADegreeMatchesTheDoubleEvaluation) {
  // A 0.1° beam is a few mm wide: pixel rays generally miss it. Aim it across the ray of pixel (20, 12),
  // 2 m from the camera, from a lamp 0.5 m to the side, so that ray crosses the beam's axis.
  const Scene base = lampScene();
  const seasim::WavelengthGrid grid = seasim::makeGrid(base.spectral.count, base.spectral.min_nm, base.spectral.max_nm);
  const seasim::UnderwaterSetup setup =
      seasim::makeUnderwaterSetup(base, grid, seasim::makeSensor(base.spectral.sensor, grid, true));
  const seasim::Vec3 d = seasim::underwaterPixelDirection(setup.params, 20.5, 12.5);
  const seasim::Vec3 o = base.camera.position;
  const seasim::Vec3 target = o + d * 2.0, lamp = target + seasim::Vec3{0.5, 0.1, 0.2};
  const seasim::Vec3 axis = target - lamp;
  auto vec = [](seasim::Vec3 v) {
    return "[" + std::to_string(v.x) + ", " + std::to_string(v.y) + ", " + std::to_string(v.z) + "]";
  };
  const Scene scene = lampScene({set("spotlights[0].position", vec(lamp)), set("spotlights[0].direction", vec(axis)),
                                 set("spotlights[0].cone_deg", "0.1"), set("spotlights[0].falloff_deg", "0.05"),
                                 set("quality.fast_math", "false"), set("quality.lamps_model", "\"delta_m\"")});
  const seasim::FrameResult f = render(scene);
  EXPECT_EQ(f.nonfinite, 0);
  for (float v : f.rgb.pixels) ASSERT_TRUE(std::isfinite(v));
  const seasim::Image cpu = cpuDouble(scene, 30, 6, true);
  const double fast = f.rgb.at(20, 12, 1), exact = cpu.at(20, 12, 1);
  ASSERT_GT(exact, 0);  // the pixel sees the beam
  std::printf("0.1 deg cone, pixel (20, 12): kernel %.6g, double %.6g\n", fast, exact);
  EXPECT_NEAR(fast, exact, 0.02 * exact);
}

TEST(UnderwaterLamps, RovLightsComposesLampsWithTheSunsPasses) {
  const std::string file = std::string(SEASIM_SOURCE_DIR) + "/scenes/rov_lights.toml";
  const std::vector<Override> small = {set("camera.width", "64"), set("camera.height", "36")};
  seasim::Renderer renderer(seasim::test::testDevice(), file, small, seasim::shippedPasses());
  const seasim::FrameResult with = renderer.render();
  ASSERT_EQ(with.nonfinite, 0);
  const std::vector<std::string> ran = renderer.lastExecuted();
  EXPECT_NE(std::find(ran.begin(), ran.end(), "underwater_lamps"), ran.end());
  EXPECT_NE(std::find(ran.begin(), ran.end(), "froxel"), ran.end());
  // Lamps off: the same frame less their light; every pixel at most as bright.
  std::vector<Override> off = small;
  off.push_back(set("spotlights[0].intensity", "0.0"));
  off.push_back(set("spotlights[1].intensity", "0.0"));
  seasim::Renderer dark(seasim::test::testDevice(), file, off, seasim::shippedPasses());
  const seasim::FrameResult without = dark.render();
  for (size_t k = 0; k < with.rgb.pixels.size(); ++k) ASSERT_GE(with.rgb.pixels[k], without.rgb.pixels[k]) << k;
  EXPECT_GT(meanOf(with.rgb), 1.2 * meanOf(without.rgb));
  // A moved camera sets the lamps' pass up again, keeping the orders' host tables (nothing in them depends
  // on the camera): the frame is the one a renderer made afresh at that camera gives.
  {
    seasim::Renderer moved(seasim::test::testDevice(), file, small, seasim::shippedPasses());
    (void)moved.render();
    moved.update({set("camera.position", "[0.3, -8.0, 0.2]")});
    const seasim::FrameResult again = moved.render();
    std::vector<Override> there = small;
    there.push_back(set("camera.position", "[0.3, -8.0, 0.2]"));
    seasim::Renderer fresh(seasim::test::testDevice(), file, there, seasim::shippedPasses());
    const seasim::FrameResult made = fresh.render();
    ASSERT_EQ(again.rgb.pixels.size(), made.rgb.pixels.size());
    for (size_t k = 0; k < made.rgb.pixels.size(); ++k) ASSERT_EQ(again.rgb.pixels[k], made.rgb.pixels[k]) << k;
  }
  // A change of the sun reruns the lamps' pass (it adds into the frame kd_multiple rewrote) but does not
  // set it up again.
  renderer.update({set("sun.zenith_deg", "50.0")});
  (void)renderer.render();
  const auto& prepared = renderer.lastPrepared();
  EXPECT_EQ(std::find(prepared.begin(), prepared.end(), "underwater_lamps"), prepared.end());
  const auto& executed = renderer.lastExecuted();
  EXPECT_NE(std::find(executed.begin(), executed.end(), "underwater_lamps"), executed.end());
  // A knob of the lamps' pass sets up only that pass; the G-buffer and the froxels do not run again,
  // kd_multiple does (the lamps add into the image it writes, so it is written afresh first).
  renderer.update({set("quality.shafts_planes", "12")});
  const seasim::FrameResult knob = renderer.render();
  EXPECT_EQ(renderer.lastPrepared(), std::vector<std::string>{"underwater_lamps"});
  const auto& rerun = renderer.lastExecuted();
  for (const char* absent : {"raycast", "froxel"})
    EXPECT_EQ(std::find(rerun.begin(), rerun.end(), absent), rerun.end()) << absent;
  EXPECT_NE(std::find(rerun.begin(), rerun.end(), "kd_multiple"), rerun.end());
  // The same frame as a new renderer's: nothing added twice.
  std::vector<Override> fresh_overrides = small;
  fresh_overrides.push_back(set("sun.zenith_deg", "50.0"));
  fresh_overrides.push_back(set("quality.shafts_planes", "12"));
  seasim::Renderer fresh(seasim::test::testDevice(), file, fresh_overrides, seasim::shippedPasses());
  EXPECT_EQ(knob.rgb.pixels, fresh.render().rgb.pixels);
}

}  // namespace
