// froxel_test.cpp — kernels/froxel.cl (002 §5: single scattering of the sun beam by froxels, §5.3
// caustic textures) on PoCL (float) against
//   * the double-precision CPU evaluation of the same froxel algorithm (host/reference/froxel_reference),
//   * the exact closed form of a horizontal ray in a uniform medium (one slice and 256 slices),
//   * the brute-force integral along every pixel's ray (midpoint quadrature, exact shadow rays):
//     the error table over the slice count nz, spectral and RGB injection,
// plus a shadowing sphere, turbid 9C-like water at long range, the camera at 1000 m, and caustics that
// move light around without changing the mean. No NaN/Inf anywhere.
#include <gtest/gtest.h>

#include <ostream>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "math/kernel_math.h"
#include "passes/froxel_pass.h"
#include "reference/froxel_reference.h"
#include "scene/scene_parser.h"
#include "spectral/sensor.h"
#include "spectral/wavelength_grid.h"
#include "seabed_objects_scene.h"
#include "test_device.h"
#include "underwater/underwater_setup.h"
#include "util/error.h"

namespace {

namespace kf = seasim::kmath_f;

// 32×18 pixels over the tests' seabed (seabed_objects_scene.h) with g = 0.8 and the bottom at 6 m.
const char* kFroxelTables = R"([underwater]
caustics = "none"
froxel_near_m = 0.05
froxel_far_m = 200
[spectral]
count = 8
sensor = "nikon_d5100_npl"
[quality]
froxel_x = 32
froxel_y = 18
froxel_z = 64
shadow_map_size = 256
)";

seasim::test::SeabedObjectsScene froxelScene() {
  return {.name = "test_froxel", .width = 32, .height = 18, .g = 0.8, .bottom_depth = 6, .rest = kFroxelTables};
}

const std::string kScene = seasim::test::seabedObjectsScene(froxelScene());

seasim::Override set(const char* key, const std::string& value) { return {key, value, {"test", 1}}; }

seasim::Scene scene(const std::vector<seasim::Override>& overrides = {}, const std::string& text = kScene) {
  return seasim::parseScene(text, "test_froxel.toml", overrides);
}

seasim::UnderwaterSetup setupOf(const seasim::Scene& s) {
  const seasim::WavelengthGrid grid = seasim::makeGrid(s.spectral.count, s.spectral.min_nm, s.spectral.max_nm);
  const seasim::Sensor sensor = seasim::makeSensor(s.spectral.sensor, grid, s.spectral.white_balance, s.spectral.camera_dir);
  return seasim::makeUnderwaterSetup(s, grid, sensor);
}

struct KernelRun {
  std::vector<float> rgb, volume, light, shadow_map;
  FroxelParams params{};
  double ms = 0;
};

// The froxel pass on the test device, read per pixel at distances S (the G-buffer's S, computed here).
KernelRun runKernel(const seasim::UnderwaterSetup& setup, const seasim::FroxelConfig& config) {
  seasim::Device& device = seasim::test::testDevice();
  seasim::FroxelPass pass(device, setup, config, {});
  KernelRun out;
  out.ms = pass.run();
  out.params = pass.params();
  const int w = setup.params.width, h = setup.params.height;
  const std::vector<double> S = seasim::froxelPixelDistances(setup);
  std::vector<float> geom(4 * S.size(), 0.0f);
  for (size_t i = 0; i < S.size(); ++i) geom[4 * i] = static_cast<float>(std::min(S[i], 1e30));
  cl::Buffer geom_buf(device.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(float) * geom.size(), geom.data());
  cl::Buffer rgb_buf(device.context(), CL_MEM_WRITE_ONLY, sizeof(float) * 3 * S.size());
  pass.resolve(geom_buf, w, h, rgb_buf);
  out.rgb.resize(3 * S.size());
  device.queue().enqueueReadBuffer(rgb_buf, CL_TRUE, 0, sizeof(float) * out.rgb.size(), out.rgb.data());
  pass.readVolume(out.volume);
  pass.readLight(out.light);
  pass.readShadowMap(out.shadow_map);
  return out;
}

// sqrt(Σ (a - ref)²) / sqrt(Σ ref²) over pixels and channels.
template <typename A>
double relativeL2(const std::vector<A>& a, const std::vector<double>& ref) {
  double num = 0, den = 0;
  for (size_t i = 0; i < ref.size(); ++i) {
    num += (double(a[i]) - ref[i]) * (double(a[i]) - ref[i]);
    den += ref[i] * ref[i];
  }
  return std::sqrt(num / std::max(den, 1e-300));
}

// max |a - ref| / (|ref| + 1e-3 peak).
template <typename A>
double maxRelative(const std::vector<A>& a, const std::vector<double>& ref) {
  double peak = 0, worst = 0;
  for (double v : ref) peak = std::max(peak, std::fabs(v));
  for (size_t i = 0; i < ref.size(); ++i)
    worst = std::max(worst, std::fabs(double(a[i]) - ref[i]) / (std::fabs(ref[i]) + 1e-3 * peak));
  return worst;
}

template <typename A>
double mean(const std::vector<A>& v) {
  double s = 0;
  for (A x : v) s += double(x);
  return s / std::max<size_t>(v.size(), 1);
}

void expectFiniteNonNegative(const std::vector<float>& v, const char* what) {
  for (float x : v) {
    ASSERT_TRUE(std::isfinite(x)) << what;
    ASSERT_GE(x, 0.0f) << what;
  }
}

// The volume's R, G, B are light (finite, >= 0); its 4th float is its column's d_y, in [-1, 1].
void expectVolumeValid(const std::vector<float>& v, const char* what) {
  for (size_t i = 0; i < v.size(); ++i) {
    ASSERT_TRUE(std::isfinite(v[i])) << what << " at " << i;
    if (i % 4 == 3) {
      ASSERT_LE(std::fabs(v[i]), 1.0f) << what << " at " << i;
    } else {
      ASSERT_GE(v[i], 0.0f) << what << " at " << i;
    }
  }
}

struct Variant {
  const char* name;
  std::vector<seasim::Override> overrides;
};
// The case as gtest prints it (its name, not the struct's bytes).
void PrintTo(const Variant& c, std::ostream* os) { *os << c.name; }

class FroxelKernel : public ::testing::TestWithParam<Variant> {};

TEST_P(FroxelKernel, MatchesDoubleCpuEvaluation) {
  const seasim::Scene s = scene(GetParam().overrides);
  const seasim::UnderwaterSetup setup = setupOf(s);
  const seasim::FroxelConfig config = seasim::froxelConfigFromScene(s);
  const KernelRun k = runKernel(setup, config);
  const seasim::FroxelCpuVolume cpu = seasim::froxelEvaluateCpu(setup, k.params);
  expectFiniteNonNegative(k.rgb, "rgb");
  expectVolumeValid(k.volume, "volume");
  // Shadow map: the same distances (float rounding of t; a texel grazing a silhouette may flip).
  ASSERT_EQ(k.shadow_map.size(), cpu.shadow_map.size());
  size_t map_flips = 0;
  for (size_t i = 0; i < cpu.shadow_map.size(); ++i) {
    const double a = k.shadow_map[i], b = cpu.shadow_map[i];
    if (std::fabs(a - b) > 1e-4 * (1 + std::fabs(b))) ++map_flips;
  }
  EXPECT_LE(map_flips, cpu.shadow_map.size() / 1000) << GetParam().name;
  // V·C per froxel: identical but for float rounding — PCF weights (1e-6), the caustic lines' steep
  // flanks (|Δ| up to ~1e-2, float positions at 2e-7 of a tile) — and rare depth-compare flips (jumps
  // of O(0.1 .. 1), counted).
  size_t light_flips = 0;
  double light_diff = 0;
  for (size_t i = 0; i < cpu.light.size(); ++i) {
    const double diff = std::fabs(k.light[i] - cpu.light[i]);
    if (diff > 5e-2) ++light_flips;
    else light_diff = std::max(light_diff, diff);
  }
  EXPECT_LT(light_diff, 2e-2) << GetParam().name;
  EXPECT_LE(light_flips, cpu.light.size() / 1000) << GetParam().name;
  // The image read per pixel: the same within float rounding (measured in the report).
  const std::vector<double> S = seasim::froxelPixelDistances(setup);
  const std::vector<double> ref = seasim::froxelResolveCpu(k.params, cpu.volume, S, setup.params.width, setup.params.height);
  const double err = maxRelative(k.rgb, ref);
  std::printf("%-14s kernel vs double CPU: image max rel %.2e, light max |diff| %.1e, flips %zu/%zu, map flips %zu\n",
              GetParam().name, err, light_diff, light_flips, cpu.light.size(), map_flips);
  EXPECT_LT(err, 5e-5) << GetParam().name;  // measured <= 1.1e-5 (caustics), 2e-6 otherwise
  EXPECT_GT(mean(ref), 0.0);
}

INSTANTIATE_TEST_SUITE_P(
    Scenes, FroxelKernel,
    ::testing::Values(Variant{"ordinary", {}},
                      Variant{"caustics", {set("underwater.caustics", "\"texture\"")}},
                      Variant{"rgb_injection", {set("underwater.froxel_injection", "\"rgb\"")}},
                      Variant{"grid_16x9x256", {set("quality.froxel_x", "16"), set("quality.froxel_y", "9"),
                                                 set("quality.froxel_z", "256")}},
                      Variant{"looking_up", {set("camera.look_at", "[0, 4, -8]")}},
                      Variant{"one_band", {set("spectral.count", "1")}}),
    [](const ::testing::TestParamInfo<Variant>& info) { return std::string(info.param.name); });

TEST(FroxelKernelExact, HorizontalRayOneAndManySlices) {
  // One pixel looking horizontally at 5 m with no bottom or objects: E_beam is constant along the ray,
  //   L_SS = Σ_bands w b p(θ) E_beam(5 m) (1 - e^{-c z_far}) / c   exactly (S = ∞ reads at z_far),
  // for 1 slice and for 256 (the slice integral is exact for constant in-scatter).
  seasim::test::SeabedObjectsScene open_water = froxelScene();
  open_water.bottom_depth = 0;
  open_water.objects = open_water.shadow_sphere = false;
  const std::string text = seasim::test::seabedObjectsScene(open_water);
  const seasim::Scene s = scene({set("camera.position", "[0, -5, 0]"), set("camera.look_at", "[0, -5, -10]"),
                                 set("camera.width", "1"), set("camera.height", "1"), set("camera.fov_deg", "1")},
                                text);
  const seasim::UnderwaterSetup setup = setupOf(s);
  const UwParams& p = setup.params;
  const double mu = p.sun_dir_water[1];
  const double cos_theta = -p.sun_dir_water[2];  // s_w · (0, 0, -1)
  const double phase = seasim::kmath_d::hg_phase(cos_theta, p.g);
  double exact[3] = {0, 0, 0};
  for (const UwBand& b : setup.bands) {
    const double l = b.b * phase * b.e_beam0 * std::exp(-b.c * 5.0 / mu) * -std::expm1(-b.c * 200.0) / b.c;
    exact[0] += l * b.w_r;
    exact[1] += l * b.w_g;
    exact[2] += l * b.w_b;
  }
  for (int nz : {1, 256}) {
    seasim::FroxelConfig config = seasim::froxelConfigFromScene(s);
    config.nx = config.ny = 1;
    config.nz = nz;
    const KernelRun k = runKernel(setup, config);
    for (int c = 0; c < 3; ++c) {
      ASSERT_GT(exact[c], 0);
      // float: the 256 slices' sum rounds at ~1e-6 relative each.
      EXPECT_NEAR(k.rgb[c] / exact[c], 1.0, 2e-5) << "nz = " << nz << " channel " << c;
    }
  }
}

TEST(FroxelKernelError, ShrinksWithSliceCountAgainstBruteForce) {
  // Froxel columns = pixels (32×18), so the error is the depth discretisation (and the 256² shadow
  // map's PCF), measured against the brute-force integral through the pixel centres (2000 midpoint
  // steps in 1 - e^{-c_min z} per pixel, exact shadow rays).
  const seasim::Scene s = scene();
  const seasim::UnderwaterSetup setup = setupOf(s);
  const std::vector<double> ref = seasim::froxelBruteForcePixelArea(setup, 2000, 1);
  ASSERT_GT(mean(ref), 0.0);
  std::printf("froxel L_SS vs brute force, 32x18 px, grid 32x18xnz, near 0.05 m, far 200 m, 8 bands:\n");
  std::printf("   nz   rel.L2 (spectral)   max rel   rel.L2 (rgb injection)\n");
  std::vector<double> errors;
  double rgb_last = 0;
  for (int nz : {8, 16, 32, 64, 128}) {
    seasim::FroxelConfig config = seasim::froxelConfigFromScene(s);
    config.nz = nz;
    const KernelRun k = runKernel(setup, config);
    expectFiniteNonNegative(k.rgb, "rgb");
    config.rgb_injection = true;
    const KernelRun r = runKernel(setup, config);
    errors.push_back(relativeL2(k.rgb, ref));
    rgb_last = relativeL2(r.rgb, ref);
    std::printf("  %3d   %.3e           %.3e   %.3e\n", nz, errors.back(), maxRelative(k.rgb, ref), rgb_last);
  }
  for (size_t i = 1; i < errors.size(); ++i) EXPECT_LT(errors[i], 1.1 * errors[i - 1]) << "step " << i;
  EXPECT_LT(errors.back(), 0.5 * errors.front());
  EXPECT_LT(errors.back(), 5e-3);  // measured: see the report
  // RGB injection's error does not vanish with nz: it is the averaged coefficients' (002 eq. 5.3–5.4).
  EXPECT_GT(rgb_last, errors.back());
}

TEST(FroxelKernelError, ShadowingSphereReducesSingleScattering) {
  // A sphere above and behind the camera, out of view, whose shadow along the refracted beam (which
  // travels towards -z) falls over the camera and the first metres of the view rays, where most of
  // L_SS comes from: the same pixels and distances, less light. The froxel image and the brute force
  // agree on the loss. (The scene's own sphere at y = -1.5 is in view and is taken out here.)
  seasim::test::SeabedObjectsScene without = froxelScene();
  without.shadow_sphere = false;
  seasim::test::SeabedObjectsScene with = without;
  with.more_objects = "[[objects]]\ntype = \"sphere\"\ncenter = [1.2, -1, 0.5]\nradius = 0.8\nalbedo = 0.5\n";
  const seasim::Scene with_s = scene({}, seasim::test::seabedObjectsScene(with)),
                      without_s = scene({}, seasim::test::seabedObjectsScene(without));
  const seasim::UnderwaterSetup a = setupOf(with_s), b = setupOf(without_s);
  const KernelRun ka = runKernel(a, seasim::froxelConfigFromScene(with_s));
  const KernelRun kb = runKernel(b, seasim::froxelConfigFromScene(without_s));
  const std::vector<double> ra = seasim::froxelBruteForcePixelArea(a, 1000, 1),
                            rb = seasim::froxelBruteForcePixelArea(b, 1000, 1);
  const double froxel_loss = 1 - mean(ka.rgb) / mean(kb.rgb), exact_loss = 1 - mean(ra) / mean(rb);
  std::printf("shadow of the sphere: mean L_SS loss froxel %.4f, brute force %.4f\n", froxel_loss, exact_loss);
  EXPECT_GT(exact_loss, 0.01);
  EXPECT_NEAR(froxel_loss, exact_loss, 0.1 * exact_loss);
  // Per pixel, never more light with the sphere.
  size_t darker = 0;
  for (size_t i = 0; i < ka.rgb.size(); ++i) {
    EXPECT_LE(ka.rgb[i], kb.rgb[i] * 1.01 + 1e-12);  // 1 %: the map frame moves with the bounding box
    if (ka.rgb[i] < 0.97 * kb.rgb[i]) ++darker;
  }
  EXPECT_GT(darker, ka.rgb.size() / 20);
}

TEST(FroxelKernelError, TurbidWaterLongRangeAndDeepCamera) {
  // 9C-like water (b = 10/m, c = 11/m, all bands) looking 1 km: the light comes from the first metre.
  const seasim::Scene turbid =
      scene({set("water", "{ wavelengths_nm = [400, 700], a = [1, 1], b = [10, 10] }"),
             set("underwater.froxel_far_m", "1000"), set("camera.look_at", "[0, -4.2, -8]")});
  const seasim::UnderwaterSetup setup = setupOf(turbid);
  ASSERT_NEAR(setup.bands[0].c, 11.0f, 1e-5f);
  const KernelRun k = runKernel(setup, seasim::froxelConfigFromScene(turbid));
  expectFiniteNonNegative(k.rgb, "turbid rgb");
  expectVolumeValid(k.volume, "turbid volume");
  const std::vector<double> ref = seasim::froxelBruteForcePixelArea(setup, 2000, 1);
  const double err = relativeL2(k.rgb, ref);
  std::printf("turbid 9C-like, far 1000 m, 64 slices: rel.L2 vs brute force %.3e\n", err);
  EXPECT_LT(err, 0.02);
  // The camera at 1000 m (Jerlov II, looking slightly up): E_beam is e^{-c 996/μ} of the scene's at
  // 4 m (c >= 0.07/m: < 1e-30), underflowing towards 0 in float, nowhere NaN.
  const seasim::Scene shallow = scene();
  const seasim::Scene deep = scene({set("camera.position", "[0, -1000, 0]"), set("camera.look_at", "[0, -999, -8]"),
                                    set("bottom.depth", "1005")});
  const KernelRun ks = runKernel(setupOf(shallow), seasim::froxelConfigFromScene(shallow));
  const KernelRun kd = runKernel(setupOf(deep), seasim::froxelConfigFromScene(deep));
  expectFiniteNonNegative(kd.rgb, "deep rgb");
  expectVolumeValid(kd.volume, "deep volume");
  EXPECT_GT(mean(ks.rgb), 0.0);
  EXPECT_LT(mean(kd.rgb), 1e-20 * mean(ks.rgb));
}

TEST(FroxelKernelError, CausticsMoveLightButKeepTheMean) {
  const seasim::Scene off = scene(), on = scene({set("underwater.caustics", "\"texture\"")});
  const KernelRun a = runKernel(setupOf(off), seasim::froxelConfigFromScene(off));
  const KernelRun b = runKernel(setupOf(on), seasim::froxelConfigFromScene(on));
  expectFiniteNonNegative(b.rgb, "caustics rgb");
  double biggest = 0;
  for (size_t i = 0; i < a.rgb.size(); ++i)
    biggest = std::max(biggest, std::fabs(double(b.rgb[i]) / std::max(double(a.rgb[i]), 1e-30) - 1));
  const double ratio = mean(b.rgb) / mean(a.rgb);
  // The brute force with the same texture: what the froxels' point samples of it should average to.
  const std::vector<double> ref_on = seasim::froxelBruteForcePixelArea(setupOf(on), 1000, 1);
  std::printf("caustics: largest pixel change %.3f, image mean on/off %.4f, rel.L2 vs brute force %.3e\n", biggest,
              ratio, relativeL2(b.rgb, ref_on));
  EXPECT_GT(biggest, 0.05);           // the image changes
  EXPECT_NEAR(ratio, 1.0, 0.03);      // its mean does not (modulation mean 1)
  EXPECT_NEAR(mean(b.rgb) / mean(ref_on), 1.0, 0.03);
}

// The shipped seabed at 96×54 with the default grid (80×45 columns, 32 slices), its
// surfaces black and the sky dark so the image is the froxel term alone, against the quadrature over
// each pixel's area (3×3 rays, exact shadows and caustic texture): with caustics the froxels' point
// samples of the texture, kept by the footprint filter, stand for the mean the pixel integrates.
TEST(FroxelKernelError, SeabedAgainstThePixelAreaQuadrature) {
  for (const char* caustics : {"\"none\"", "\"texture\""}) {
    const seasim::Scene s = seasim::loadScene(
        SEASIM_SOURCE_DIR "/scenes/seabed.toml",
        {set("camera.width", "96"), set("camera.height", "54"), set("underwater.multiple_scattering", "false"),
         set("sky.radiance", "0"), set("bottom.albedo", "0"), set("objects[0].albedo", "0"),
         set("objects[1].albedo", "0"), set("objects[2].albedo", "0"), set("underwater.caustics", caustics)});
    const seasim::FroxelConfig config = seasim::froxelConfigFromScene(s);
    EXPECT_EQ(config.nx, 80);
    EXPECT_EQ(config.ny, 45);
    const seasim::UnderwaterSetup setup = setupOf(s);
    const KernelRun k = runKernel(setup, config);
    const std::vector<double> ref = seasim::froxelBruteForcePixelArea(setup, 400, 3);
    const double err = relativeL2(k.rgb, ref);
    std::printf("seabed 96x54, caustics %s, grid %dx%dx%d: rel.L2 vs the pixel-area quadrature %.4f, mean ratio %.4f\n",
                caustics, config.nx, config.ny, config.nz, err, mean(k.rgb) / mean(ref));
    // Measured: 0.0129 and 0.0200, means 0.9992 and 0.9986. The grid of 160×90×64 with point-sampled
    // caustics this replaced erred by 6.1 % with caustics at 320×180 (results/BENCHMARKS.md).
    EXPECT_NEAR(mean(k.rgb) / mean(ref), 1.0, 0.005);
    EXPECT_LT(err, std::string(caustics) == "\"none\"" ? 0.02 : 0.03);
  }
}

TEST(FroxelKernelCulling, UnreadFroxelsAreSkippedAndTheImageIsBitIdentical) {
  // Given the G-buffer, froxel_inject leaves 0 the froxels past the last slice any pixel's read needs
  // in their column (froxel_column_extent): every froxel a read uses is the same float, so the image is
  // the same bit for bit, and the froxels behind the bottom and the rocks are not evaluated.
  // The test scene (a column per pixel) looking down and up, and the shipped seabed at 320×180 looking up
  // with its "auto" grid (4 pixels per column, the border columns clamped): rays rising to the surface
  // read their columns whole, and froxel_column_extent must have marked them so.
  const char* kSeabedUp = "seabed 320x180 [0, 4, -8]";
  for (const char* look_at : {"[0, -4.5, -8]", "[0, 4, -8]", kSeabedUp}) {
    const bool seabed = look_at == kSeabedUp;
    const seasim::Scene s =
        seabed ? seasim::loadScene(SEASIM_SOURCE_DIR "/scenes/seabed.toml", {set("camera.look_at", "[0, 4, -8]")})
               : scene({set("underwater.caustics", "\"texture\""), set("camera.look_at", look_at)});
    const seasim::UnderwaterSetup setup = setupOf(s);
    seasim::Device& device = seasim::test::testDevice();
    const int w = setup.params.width, h = setup.params.height;
    const std::vector<double> S = seasim::froxelPixelDistances(setup);
    std::vector<float> geom(4 * S.size(), 0.0f);
    for (size_t i = 0; i < S.size(); ++i) geom[4 * i] = static_cast<float>(std::min(S[i], 1e30));
    cl::Buffer geom_buf(device.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(float) * geom.size(),
                        geom.data());
    cl::Buffer rgb_buf(device.context(), CL_MEM_WRITE_ONLY, sizeof(float) * 3 * S.size());
    std::vector<float> light[2], rgb[2];
    seasim::FroxelPass pass(device, setup, seasim::froxelConfigFromScene(s), {});
    for (int culled = 0; culled < 2; ++culled) {
      pass.run(nullptr, culled ? &geom_buf : nullptr, w, h);
      pass.resolve(geom_buf, w, h, rgb_buf);
      rgb[culled].resize(3 * S.size());
      device.queue().enqueueReadBuffer(rgb_buf, CL_TRUE, 0, sizeof(float) * rgb[culled].size(), rgb[culled].data());
      pass.readLight(light[culled]);
    }
    ASSERT_EQ(rgb[0].size(), rgb[1].size());
    for (size_t i = 0; i < rgb[0].size(); ++i) ASSERT_EQ(rgb[1][i], rgb[0][i]) << look_at << " value " << i;
    // Skipped froxels are 0; every other one is unchanged; every froxel a pixel reads is unchanged.
    const FroxelParams fp = pass.params();
    size_t skipped = 0, lit = 0;
    for (size_t i = 0; i < light[0].size(); ++i) {
      if (light[0][i] > 0) ++lit;
      if (light[1][i] == light[0][i]) continue;
      ASSERT_EQ(light[1][i], 0.0f) << i;
      ++skipped;
    }
    for (int y = 0; y < h && !seabed; ++y) {  // (the test scene: no ray reads its columns whole)
      for (int x = 0; x < w; ++x) {
        const int k = kf::froxel_read_slice(&fp, geom[4 * (size_t(y) * w + x)]);
        const int i0 = int(kf::froxel_pixel_column(x, w, fp.nx)), j0 = int(kf::froxel_pixel_column(y, h, fp.ny));
        for (int j : {j0, std::min(j0 + 1, fp.ny - 1)})
          for (int i : {i0, std::min(i0 + 1, fp.nx - 1)})
            for (int kk = 0; kk <= k; ++kk) {
              const size_t idx = (size_t(kk) * fp.ny + j) * fp.nx + i;
              ASSERT_EQ(light[1][idx], light[0][idx]) << "pixel " << x << "," << y << " slice " << kk;
            }
      }
    }
    std::printf("culling, look_at %s: %zu of %zu lit froxels skipped (%.0f %%)\n", look_at, skipped, lit,
                100.0 * skipped / std::max<size_t>(lit, 1));
    // Looking down, the froxels behind the bottom and the rocks (measured 20 %); looking up at the
    // surface, next to none (the froxels above it are 0 already).
    if (look_at[4] == '-') EXPECT_GT(skipped, lit / 10) << look_at;
    if (seabed) EXPECT_EQ(fp.nx, 80);
  }
}

TEST(FroxelKernelError, ContradictoryDefinesAreAnError) {
  const seasim::Scene s = scene();
  EXPECT_THROW(seasim::FroxelPass(seasim::test::testDevice(), s, setupOf(s), {"SEASIM_SPECTRAL_INJECTION=0"}),
               seasim::RuntimeError);
  seasim::FroxelConfig bad = seasim::froxelConfigFromScene(s);
  bad.nz = 0;
  EXPECT_THROW(seasim::makeFroxelParams(setupOf(s), bad), seasim::RuntimeError);
}

}  // namespace
