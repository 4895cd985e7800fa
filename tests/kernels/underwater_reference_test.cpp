// underwater_reference_test.cpp — the underwater path tracer (kernels/reference.cl) on PoCL against
// closed forms and double-precision CPU quadrature, on tiny images with hand-built scenes
// (UnderwaterSetup filled directly, so every coefficient is known exactly):
//   * no scattering (b = 0): Lambertian sphere, box shadow and bottom lit by the sun beam alone,
//     e^{-c S} ρ/π E_beam(y) max(n·s_w, 0) V;
//   * single-scattering mode (max_bounces = 1) against the L_SS quadrature, without objects (also
//     against its closed form) and with an occluding sphere (exact shadow rays in double);
//   * a height-field floor (the sea's, common/sea_bottom.h): a sloping plane lit by the sun without
//     scattering against its closed form, and a floor of one depth as the flat bottom at that depth;
//   * Snell's window with b = 0: n² (1 - F) L_sky e^{-c S}, zero under total internal reflection;
//     under a Preetham sky L_sky(a) towards the refracted direction a in air, and the camera above
//     seeing that sky directly and mirrored by R, against the host's sky module (host/sky) in double;
//   * the ocean's white furnace: a = 0, no sun, albedo-1 objects and bottom under a uniform sky give
//     n² L_sky everywhere, whatever b and g (uniform radiance solves the RTE and every boundary);
//   * more bounces never lower a pixel (same seed), the same seed gives the same image whatever the
//     batch size, and no NaN/Inf in turbid water at 1000 m or with a = 0 (roulette only).
// Statistics: z = (path tracer - reference) / (its own standard error) per pixel and channel; the
// tests ask for the image means to agree within 4 standard errors of the image mean, the RMS of z to
// be near 1 (the error estimate is honest) and no |z| beyond 6. Seeds are fixed, so all is deterministic.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "math/kernel_math.h"
#include "passes/froxel_pass.h"
#include "reference/froxel_reference.h"
#include "reference/underwater_reference.h"
#include "scene/scene_parser.h"
#include "sky/sky_light.h"
#include "spectral/wavelength_grid.h"
#include "test_device.h"
#include "util/error.h"

namespace {

namespace kd = seasim::kmath_d;
using seasim::Image;
using seasim::UnderwaterReferenceResult;
using seasim::UnderwaterReferenceSettings;
using seasim::UnderwaterSetup;
using seasim::Vec3;

seasim::Device& device() { return seasim::test::testDevice(); }

struct BandSpec {
  double a, b;
  double e_beam0;        // W m^-2 nm^-1, normal to the refracted beam just below the surface
  double sky_radiance;   // in air
  double bottom_albedo;
  double w[3];           // sensor weights
};

struct ObjectSpec {
  UwObject object;
  std::vector<float> albedo;  // per band
};

UwObject sphere(Vec3 c, double r) {
  UwObject o{};
  o.type = UW_SPHERE;
  o.a[0] = float(c.x), o.a[1] = float(c.y), o.a[2] = float(c.z), o.a[3] = float(r);
  return o;
}
UwObject box(Vec3 lo, Vec3 hi) {
  UwObject o{};
  o.type = UW_BOX;
  o.a[0] = float(lo.x), o.a[1] = float(lo.y), o.a[2] = float(lo.z);
  o.b[0] = float(hi.x), o.b[1] = float(hi.y), o.b[2] = float(hi.z);
  return o;
}

struct SceneSpec {
  int width = 16, height = 12;
  Vec3 eye{0, -5, 0};
  Vec3 forward{0, 0, -1};
  Vec3 up_hint{0, 1, 0};
  double fov_y_deg = 60;
  Vec3 sun_water = seasim::normalize(Vec3{0.3, 0.9, -0.25});
  double ior = 1.333, g = 0.0, bottom_depth = 0.0;
  std::vector<BandSpec> bands;
  std::vector<ObjectSpec> objects;
};

void set4(float out[4], Vec3 v) {
  out[0] = float(v.x), out[1] = float(v.y), out[2] = float(v.z), out[3] = 0.0f;
}

UnderwaterSetup build(const SceneSpec& s) {
  UnderwaterSetup u;
  UwParams& p = u.params;
  const Vec3 f = seasim::normalize(s.forward);
  const Vec3 r = seasim::normalize(seasim::cross(f, s.up_hint));
  set4(p.cam_pos, s.eye);
  set4(p.cam_forward, f);
  set4(p.cam_right, r);
  set4(p.cam_up, seasim::cross(r, f));
  const Vec3 sw = seasim::normalize(s.sun_water);
  set4(p.sun_dir_water, sw);
  set4(p.sun_dir_air, Vec3{0, 1, 0});  // not read by the reference
  u.sun_water = sw;
  p.tan_half_fov_y = float(std::tan(s.fov_y_deg * M_PI / 360));
  p.aspect = float(s.width) / float(s.height);
  p.ior = float(s.ior);
  p.g = float(s.g);
  p.bottom_depth = float(s.bottom_depth);
  p.width = s.width;
  p.height = s.height;
  p.band_count = int(s.bands.size());
  p.object_count = int(s.objects.size());
  for (const BandSpec& b : s.bands) {
    UwBand band{};
    band.a = float(b.a), band.b = float(b.b), band.c = float(b.a + b.b);
    band.kd = band.c;
    band.e_beam0 = float(b.e_beam0);
    band.e_sun0 = float(b.e_beam0 * sw.y);
    band.sky_radiance = float(b.sky_radiance);
    band.bottom_albedo = float(b.bottom_albedo);
    band.w_r = float(b.w[0]), band.w_g = float(b.w[1]), band.w_b = float(b.w[2]);
    u.bands.push_back(band);
  }
  for (const ObjectSpec& o : s.objects) {
    u.objects.push_back(o.object);
    u.albedo.insert(u.albedo.end(), o.albedo.begin(), o.albedo.end());
  }
  if (u.objects.empty()) u.objects.push_back(UwObject{});
  if (u.albedo.empty()) u.albedo.push_back(0.0f);
  return u;
}

// Sensor RGB of per-band radiances L(i) through every pixel centre, in double.
template <typename F>
Image perPixel(const UnderwaterSetup& s, F radiance) {
  const UwParams& p = s.params;
  Image img;
  img.resize(p.width, p.height, 3);
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x) {
      const Vec3 d = seasim::underwaterPixelDirection(p, x + 0.5, y + 0.5);
      double rgb[3] = {0, 0, 0};
      for (int i = 0; i < p.band_count; ++i) {
        const double L = radiance(i, kd::real3{d.x, d.y, d.z});
        const UwBand& b = s.bands[i];
        rgb[0] += L * b.w_r, rgb[1] += L * b.w_g, rgb[2] += L * b.w_b;
      }
      for (int c = 0; c < 3; ++c) img.at(x, y, c) = float(rgb[c]);
    }
  return img;
}

kd::real3 eyeOf(const UnderwaterSetup& s) { return kd::real3{s.params.cam_pos[0], s.params.cam_pos[1], s.params.cam_pos[2]}; }

// The sun beam reflected once by a Lambertian hit, with no scattering on the way (b = 0).
Image directSunImage(const UnderwaterSetup& s) {
  const UwParams& p = s.params;
  const kd::real3 sw{p.sun_dir_water[0], p.sun_dir_water[1], p.sun_dir_water[2]};
  return perPixel(s, [&](int i, kd::real3 d) {
    kd::real3 n{};
    int mat = 0;
    const double S = kd::uw_scene_hit(s.objects.data(), p.object_count, p.bottom_depth, eyeOf(s), d, 0.0, &n, &mat);
    if (mat < 0 && mat != UW_MAT_BOTTOM) return 0.0;
    const UwBand& b = s.bands[i];
    const double rho = mat >= 0 ? s.albedo[mat * p.band_count + i] : b.bottom_albedo;
    const kd::real3 x = eyeOf(s) + S * d;
    kd::real3 sn{};
    int smat = 0;
    kd::uw_scene_hit(s.objects.data(), p.object_count, 0.0, x + 1e-6 * n, sw, 0.0, &sn, &smat);
    const double vis = smat >= 0 ? 0.0 : 1.0;
    return std::exp(-b.c * S) * rho / M_PI * kd::uw_beam_irradiance(b.e_beam0, b.c, sw.y, -x.y) *
           std::max(kd::dot(n, sw), 0.0) * vis;
  });
}

struct Agreement {
  double mean_mc = 0, mean_ref = 0, mean_se = 0;  // image means and the standard error of the first
  double rms_z = 0, max_z = 0;                     // over values with a standard error
  int with_se = 0;
  double worst_exact = 0;  // largest |Δ| / (|ref| + floor) where the standard error is 0
};

Agreement agreement(const UnderwaterReferenceResult& r, const Image& ref) {
  Agreement a;
  double peak = 0, z2 = 0;
  for (float v : ref.pixels) peak = std::max(peak, double(std::fabs(v)));
  for (size_t i = 0; i < ref.pixels.size(); ++i) {
    const double mc = r.rgb.pixels[i], rf = ref.pixels[i], se = r.std_error.pixels[i];
    a.mean_mc += mc;
    a.mean_ref += rf;
    // Float (kernel) against double (reference): 5e-5 of the value, or of 1e-3 of the image's peak.
    const double rounding = 5e-5 * (std::fabs(rf) + 1e-3 * peak);
    const double z = (mc - rf) / std::hypot(se, rounding);
    a.max_z = std::max(a.max_z, std::fabs(z));
    if (se > rounding) {
      z2 += z * z;
      ++a.with_se;
    } else {
      a.worst_exact = std::max(a.worst_exact, std::fabs(mc - rf) / (std::fabs(rf) + 1e-3 * peak + 1e-30));
    }
  }
  a.mean_mc /= ref.pixels.size();
  a.mean_ref /= ref.pixels.size();
  a.mean_se = r.image_mean_std_error;
  a.rms_z = a.with_se ? std::sqrt(z2 / a.with_se) : 0.0;
  return a;
}

// The statistical verdict shared by the Monte Carlo tests (see the top of the file).
void expectAgrees(const UnderwaterReferenceResult& r, const Image& ref, const char* what) {
  const Agreement a = agreement(r, ref);
  std::printf("[%s] image mean %.6g vs %.6g (se %.3g), rms z %.3f, max |z| %.2f over %d values, %d spp, %.1f ms\n",
              what, a.mean_mc, a.mean_ref, a.mean_se, a.rms_z, a.max_z, a.with_se, r.samples, r.ms);
  EXPECT_NEAR(a.mean_mc, a.mean_ref, 4 * a.mean_se + 1e-5 * std::fabs(a.mean_ref)) << what;
  EXPECT_LT(a.max_z, 6.0) << what;
  if (a.with_se > 50) {
    EXPECT_GT(a.rms_z, 0.7) << what;  // the standard error is not overstated...
    EXPECT_LT(a.rms_z, 1.4) << what;  // ...nor understated
  }
  EXPECT_LT(a.worst_exact, 2e-4) << what;  // float against double where every sample is the same
}

void expectFiniteNonNegative(const UnderwaterReferenceResult& r) {
  for (float v : r.rgb.pixels) {
    ASSERT_TRUE(std::isfinite(v));
    ASSERT_GE(v, 0.0f);
  }
  for (float v : r.std_error.pixels) ASSERT_TRUE(std::isfinite(v));
  EXPECT_TRUE(std::isfinite(r.mean_std_error));
  EXPECT_TRUE(std::isfinite(r.image_mean_std_error));
}

const double kW1[3] = {1.0, 0.4, 0.1}, kW2[3] = {0.2, 0.8, 0.3}, kW3[3] = {0.0, 0.3, 1.2};

TEST(UnderwaterReference, NoScatteringShowsTheSunOnLambertianSurfaces) {
  // b = 0, no sky. The analytic value is the first hit's direct sun alone, so nothing may reflect
  // twice: one Lambertian surface is white at a time, the others black (they still cast shadows),
  // and the scene sits 100 m down, where the light the surface mirrors back down has crossed 200 m:
  // e^{-c 200 m} ρ ≲ 2e-5 of the value, far below the noise. Free-flight sampling estimates the view
  // ray's transmittance (a path reaches the surface with probability e^{-c S}, else it is absorbed), so
  // even one band is a Monte Carlo estimate; three bands add the band choice.
  const Vec3 sun = seasim::normalize(Vec3{0.3, 0.9, -0.25});
  const Vec3 ball{0.5, -100.5, -6};
  for (int variant = 0; variant < 2; ++variant) {
    const bool lit_sphere = variant == 0;  // else the lit bottom with the shadows of sphere and box
    SceneSpec spec;
    spec.eye = {0, lit_sphere ? -97.5 : -100, 0};  // a little above the sphere: more of its lit side
    // The sphere ahead, or the bottom seen steeply: every view ray's transmittance is above ~0.3, so
    // 64 paths never all fail to reach the surface they look at.
    spec.forward = lit_sphere ? ball - spec.eye : Vec3{0, -1.2, -1};
    spec.fov_y_deg = lit_sphere ? 45 : 60;
    spec.sun_water = sun;
    spec.bottom_depth = 107;
    const double bottom = lit_sphere ? 0.0 : 0.5;
    spec.objects = {{sphere(ball, 1.5), {}},
                    {sphere(ball + sun * 2.6, 0.6), {}},  // shades part of the lit sphere
                    {box({-4, -104, -9}, {-1.5, -102, -7}), {}}};
    UnderwaterReferenceSettings set;
    set.samples_per_pixel = 64;
    set.jitter = false;
    for (int bands : {1, 3}) {
      if (bands == 1) {
        spec.bands = {{0.06, 0.0, 1e4, 0.0, bottom, {1, 0.5, 0.2}}};
        spec.objects[0].albedo = {lit_sphere ? 0.7f : 0.0f};
      } else {
        spec.bands = {{0.05, 0.0, 1e4, 0.0, bottom, {kW1[0], kW1[1], kW1[2]}},
                      {0.06, 0.0, 2e4, 0.0, bottom * 0.6, {kW2[0], kW2[1], kW2[2]}},
                      {0.08, 0.0, 4e4, 0.0, bottom * 1.8, {kW3[0], kW3[1], kW3[2]}}};
        spec.objects[0].albedo = lit_sphere ? std::vector<float>{0.2f, 0.6f, 0.9f} : std::vector<float>{0, 0, 0};
      }
      spec.objects[1].albedo = spec.objects[2].albedo = std::vector<float>(bands, 0.0f);
      const UnderwaterSetup s = build(spec);
      const UnderwaterReferenceResult r = seasim::renderUnderwaterReference(device(), s, set);
      expectFiniteNonNegative(r);
      const Image ref = directSunImage(s);
      const std::string what = std::string(lit_sphere ? "no scattering, sphere, " : "no scattering, bottom, ") +
                               std::to_string(bands) + " band(s)";
      expectAgrees(r, ref, what.c_str());
      int lit = 0, dark = 0;
      for (size_t i = 0; i < ref.pixelCount(); ++i) (ref.pixels[3 * i + 1] > 0 ? lit : dark) += 1;
      EXPECT_GT(lit, 8) << what;  // the scene is not trivially black...
      EXPECT_GT(dark, 8) << what; // ...nor all lit: shadows, black objects, the sphere's far side
    }
  }
}

SceneSpec singleScatteringScene() {
  SceneSpec spec;
  spec.eye = {0, -4, 0};
  spec.forward = {0, 0.1, -1};
  spec.fov_y_deg = 90;  // rays up to the surface, horizontal, and down into deep water
  spec.g = 0.8;
  spec.bands = {{0.05, 0.3, 2.0, 0.3, 0.0, {kW1[0], kW1[1], kW1[2]}}, {0.3, 0.6, 1.0, 0.3, 0.0, {kW3[0], kW3[1], kW3[2]}}};
  return spec;
}

// A floor of 21 x 21 nodes over 40 m whose depth is depth0 + slope z (a plane: bilinear patches of a
// linear function are exact).
seasim::HeightField rampFloor(double depth0, double slope) {
  std::vector<float> depth(21 * 21);
  for (int j = 0; j < 21; ++j)
    for (int i = 0; i < 21; ++i) depth[j * 21 + i] = float(depth0 + slope * (-20.0 + 2.0 * j));
  return seasim::makeHeightField(21, 21, 40.0, depth);
}

TEST(UnderwaterReference, HeightFieldFloorIsLitByTheSunAsItsPlane) {
  // b = 0, no sky: the sloping floor's direct sun, e^{-c S} ρ/π E_beam(y) max(n·s_w, 0), n ∝ (0, 1, slope)
  // (depth grows along +z: the floor y = -(5 + 0.2 z) rises towards -z, where the camera looks).
  SceneSpec spec;
  spec.eye = {0, -2, 0};
  spec.forward = {0, -0.5, -1};
  spec.fov_y_deg = 40;
  spec.sun_water = seasim::normalize(Vec3{0.2, 0.9, 0.3});
  spec.bands = {{0.08, 0.0, 2.0, 0.0, 0.5, {kW1[0], kW1[1], kW1[2]}}};
  const UnderwaterSetup s = build(spec);
  const seasim::HeightField floor = rampFloor(5.0, 0.2);
  const UwParams& p = s.params;
  const kd::real3 sw{p.sun_dir_water[0], p.sun_dir_water[1], p.sun_dir_water[2]};
  const kd::real3 n = kd::normalize(kd::real3{0.0, 1.0, 0.2});
  const Image ref = perPixel(s, [&](int i, kd::real3 d) {
    const kd::real3 o = eyeOf(s);
    const double t = -(5.0 + 0.2 * o.z + o.y) / (d.y + 0.2 * d.z);  // o + t d on y = -(5 + 0.2 z)
    const kd::real3 x = o + t * d;
    const UwBand& b = s.bands[i];
    return std::exp(-b.c * t) * b.bottom_albedo / M_PI * kd::uw_beam_irradiance(b.e_beam0, b.c, sw.y, -x.y) *
           std::max(kd::dot(n, sw), 0.0);
  });
  UnderwaterReferenceSettings set;
  set.samples_per_pixel = 64;
  set.jitter = false;
  set.max_bounces = 2;  // the floor's first hit: its light mirrored back down by the surface is not in ref
  set.height_field = &floor;
  const UnderwaterReferenceResult r = seasim::renderUnderwaterReference(device(), s, set);
  expectFiniteNonNegative(r);
  expectAgrees(r, ref, "height-field ramp, direct sun");
}

TEST(UnderwaterReference, HeightFieldShelfShadowsTheSunBeam) {
  // Single scattering along a level view 10 m down, the sun beam travelling down towards -z at 45°: a
  // shelf 1 m deep over z >= 0 shades the first 3 m of the view ray (from z = -6 to -9), so the image is
  // e^{-3c} of the one over a floor 30 m deep everywhere (L_SS = ∫ e^{-c t} b p E_beam V dt, E_beam the
  // same all along a level ray).
  SceneSpec spec;
  spec.width = 4, spec.height = 4;
  spec.eye = {0, -10, -6};
  spec.forward = {0, 0, -1};
  spec.fov_y_deg = 0.5;
  spec.sun_water = seasim::normalize(Vec3{0, 1, 1});
  spec.g = 0.5;
  const double c = 0.2;
  spec.bands = {{0.1, 0.1, 1.0, 0.0, 0.3, {1, 1, 1}}};
  const UnderwaterSetup s = build(spec);
  std::vector<float> shelf(21 * 21), deep(21 * 21, 30.0f);
  for (int j = 0; j < 21; ++j)
    for (int i = 0; i < 21; ++i) shelf[j * 21 + i] = -20.0 + 2.0 * j >= 0 ? 1.0f : 30.0f;
  const seasim::HeightField with_shelf = seasim::makeHeightField(21, 21, 40.0, shelf);
  const seasim::HeightField without = seasim::makeHeightField(21, 21, 40.0, deep);
  UnderwaterReferenceSettings set;
  set.samples_per_pixel = 8192;
  set.batch = 1024;
  set.max_bounces = 1;
  set.jitter = false;
  set.height_field = &with_shelf;
  const UnderwaterReferenceResult shaded = seasim::renderUnderwaterReference(device(), s, set);
  set.height_field = &without;
  const UnderwaterReferenceResult open = seasim::renderUnderwaterReference(device(), s, set);
  const double ratio = shaded.image_mean / open.image_mean;
  std::printf("[height-field shelf] shaded / open %.4f, e^{-3c} %.4f\n", ratio, std::exp(-3 * c));
  EXPECT_NEAR(ratio, std::exp(-3 * c), 0.02);
}

TEST(UnderwaterReference, HeightFieldFloorOfOneDepthIsTheFlatBottom) {
  // All orders in scattering water: a floor 6 m down everywhere traces the flat bottom at 6 m's image
  // (the same paths but for rounding in the hit distance).
  SceneSpec spec = singleScatteringScene();
  spec.forward = {0, -0.4, -1};
  spec.bottom_depth = 6.0;
  const UnderwaterSetup flat = build(spec);
  spec.bottom_depth = 0.0;
  const UnderwaterSetup none = build(spec);
  const seasim::HeightField floor = rampFloor(6.0, 0.0);
  UnderwaterReferenceSettings set;
  set.samples_per_pixel = 256;
  set.batch = 64;
  const UnderwaterReferenceResult a = seasim::renderUnderwaterReference(device(), flat, set);
  set.height_field = &floor;
  const UnderwaterReferenceResult b = seasim::renderUnderwaterReference(device(), none, set);
  expectFiniteNonNegative(b);
  std::printf("[height field of one depth] image mean %.6g against the flat bottom's %.6g (se %.3g)\n", b.image_mean,
              a.image_mean, a.image_mean_std_error);
  EXPECT_NEAR(b.image_mean, a.image_mean, 1e-3 * a.image_mean);
  set.height_field = nullptr;  // without the floor the image differs: the test sees the floor
  EXPECT_GT(std::fabs(seasim::renderUnderwaterReference(device(), none, set).image_mean / a.image_mean - 1), 0.1);
  set.height_field = &floor;  // a floor and a flat bottom at once is refused
  EXPECT_THROW(seasim::renderUnderwaterReference(device(), flat, set), seasim::RuntimeError);
}

TEST(UnderwaterReference, SingleScatteringModeMatchesQuadratureWithoutObjects) {
  const UnderwaterSetup s = build(singleScatteringScene());
  // The quadrature itself against the closed form e_beam0 b p(θ) kd_exp_integral(c/μ_w, c, d_y, o_d, S).
  const UwParams& p = s.params;
  const kd::real3 sw{p.sun_dir_water[0], p.sun_dir_water[1], p.sun_dir_water[2]};
  const Image closed = perPixel(s, [&](int i, kd::real3 d) {
    const UwBand& b = s.bands[i];
    const double S = d.y > 0 ? -p.cam_pos[1] / d.y : 1e30;
    return b.e_beam0 * b.b * kd::hg_phase(kd::dot(sw, d), p.g) *
           kd::kd_exp_integral(b.c / sw.y, b.c, d.y, -p.cam_pos[1], S);
  });
  const Image quad = seasim::renderUnderwaterSingleScatteringQuadrature(s, false, 2000);
  for (size_t i = 0; i < quad.pixels.size(); ++i) EXPECT_NEAR(quad.pixels[i], closed.pixels[i], 1e-5 * closed.pixels[i]);

  UnderwaterReferenceSettings set;
  set.samples_per_pixel = 128;
  set.batch = 32;
  set.max_bounces = 1;
  set.jitter = false;
  const UnderwaterReferenceResult r = seasim::renderUnderwaterReference(device(), s, set);
  expectFiniteNonNegative(r);
  expectAgrees(r, closed, "single scattering, no objects");
}

TEST(UnderwaterReference, SingleScatteringModeMatchesQuadratureWithAnOccluder) {
  SceneSpec spec = singleScatteringScene();
  // A sphere between the sun and the rays: its shadow crosses the view; some rays hit it.
  spec.objects = {{sphere({0.8, -2.2, -4}, 1.0), {0.5f, 0.5f}}};
  spec.g = 0.5;
  const UnderwaterSetup s = build(spec);
  const Image quad = seasim::renderUnderwaterSingleScatteringQuadrature(s, false, 4000);
  UnderwaterReferenceSettings set;
  set.samples_per_pixel = 128;
  set.batch = 32;
  set.max_bounces = 1;
  set.jitter = false;
  const UnderwaterReferenceResult r = seasim::renderUnderwaterReference(device(), s, set);
  expectFiniteNonNegative(r);
  expectAgrees(r, quad, "single scattering, occluding sphere");
  // The shadow is really there: no pixel brighter than without the sphere, a patch of them darker.
  SceneSpec open = singleScatteringScene();
  open.g = 0.5;
  const Image unshadowed = seasim::renderUnderwaterSingleScatteringQuadrature(build(open), false, 1000);
  int darker = 0;
  for (size_t i = 0; i < quad.pixels.size(); ++i) {
    EXPECT_LE(quad.pixels[i], unshadowed.pixels[i] * (1 + 1e-6));
    darker += quad.pixels[i] < 0.9 * unshadowed.pixels[i];
  }
  EXPECT_GT(darker, 3 * 15);

  // Isotropic phase (the define) against the quadrature with p = 1/(4π).
  set.isotropic = true;
  const UnderwaterReferenceResult iso = seasim::renderUnderwaterReference(device(), s, set);
  expectAgrees(iso, seasim::renderUnderwaterSingleScatteringQuadrature(s, true, 4000), "single scattering, isotropic");
}

// The froxel integrator (002 §5.1–5.2, froxel.cl) at high resolution against the path tracer's
// single-scattering mode: two independent estimates of the same L_SS. The froxel grid is one column per
// pixel with 256 depth slices and a 2048² shadow map, so its own bias (measured against the quadrature
// in froxel_test.cpp) is far below the path tracer's noise at this sample count; a shadowing sphere
// crosses the view. Light beyond froxel_far (40 m) is dropped: e^{-c 40 m} <= e^{-14} here.
TEST(UnderwaterReference, FroxelIntegratorAgreesWithPathTracerSingleScattering) {
  SceneSpec spec = singleScatteringScene();
  spec.objects = {{sphere({0.8, -2.2, -4}, 1.0), {0.5f, 0.5f}}};
  spec.g = 0.5;
  const UnderwaterSetup s = build(spec);
  const int w = s.params.width, h = s.params.height;

  seasim::FroxelConfig config;
  config.nx = w;
  config.ny = h;
  config.nz = 256;
  config.z_near = 0.05;
  config.z_far = 40.0;
  config.shadow_map_size = 2048;
  seasim::FroxelPass froxels(device(), s, config,
                             {"SEASIM_HAS_OBJECTS=1", "SEASIM_CAUSTICS=0", "SEASIM_SPECTRAL_INJECTION=1"});
  froxels.run();
  // The G-buffer depth the shading would pass: the first hit (surface, sphere) or deep water.
  const std::vector<double> S = seasim::froxelPixelDistances(s);
  std::vector<cl_float4> geom(S.size());
  for (size_t i = 0; i < S.size(); ++i) geom[i] = {{float(std::min(S[i], 1e30)), 0.0f, 1.0f, 0.0f}};
  cl::Buffer geom_buffer(device().context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(cl_float4) * geom.size(),
                         geom.data());
  cl::Buffer rgb_buffer(device().context(), CL_MEM_READ_WRITE, sizeof(float) * 3 * S.size());
  froxels.resolve(geom_buffer, w, h, rgb_buffer);
  Image froxel_image;
  froxel_image.resize(w, h, 3);
  device().queue().enqueueReadBuffer(rgb_buffer, CL_TRUE, 0, sizeof(float) * froxel_image.pixels.size(),
                                     froxel_image.pixels.data());

  UnderwaterReferenceSettings set;
  set.samples_per_pixel = 256;
  set.batch = 64;
  set.max_bounces = 1;
  set.jitter = false;
  const UnderwaterReferenceResult r = seasim::renderUnderwaterReference(device(), s, set);
  expectFiniteNonNegative(r);
  const Agreement a = agreement(r, froxel_image);
  std::printf("[froxel vs path tracer] image mean %.6g vs %.6g (se %.3g), rms z %.3f, max |z| %.2f over %d values\n",
              a.mean_mc, a.mean_ref, a.mean_se, a.rms_z, a.max_z, a.with_se);
  EXPECT_GT(a.mean_ref, 0.0);
  EXPECT_NEAR(a.mean_mc, a.mean_ref, 4 * a.mean_se);  // the image means agree within the CI
  EXPECT_GT(a.with_se, 3 * w * h / 2);                // most values carry noise (not a black image)
  EXPECT_LT(a.rms_z, 1.3);                            // per value: the differences are the noise
  EXPECT_LT(a.max_z, 6.0);
}

TEST(UnderwaterReference, SnellsWindowWithoutScattering) {
  SceneSpec spec;
  spec.eye = {0, -3, 0};
  spec.forward = {0, 1, 0};
  spec.up_hint = {0, 0, -1};
  spec.fov_y_deg = 120;  // the corners lie outside the window (critical angle 48.6°)
  spec.bands = {{0.1, 0.0, 1.0, 0.5, 0.0, {kW1[0], kW1[1], kW1[2]}}, {0.6, 0.0, 1.0, 0.8, 0.0, {kW2[0], kW2[1], kW2[2]}}};
  const UnderwaterSetup s = build(spec);
  const Image ref = perPixel(s, [&](int i, kd::real3 d) {
    const UwBand& b = s.bands[i];
    return std::exp(-b.c * 3.0 / d.y) * kd::uw_window_radiance(d.y, s.params.ior, b.sky_radiance, 0.0);
  });
  int outside = 0;
  for (float v : ref.pixels) outside += v == 0.0f;
  EXPECT_GT(outside, 12);  // total internal reflection shows the (black) deep water
  UnderwaterReferenceSettings set;
  set.samples_per_pixel = 64;
  set.jitter = false;
  const UnderwaterReferenceResult r = seasim::renderUnderwaterReference(device(), s, set);
  expectFiniteNonNegative(r);
  expectAgrees(r, ref, "Snell's window");
}

// A Preetham sky (sun 50° from the zenith, azimuth 60°) on two bands of 400–700 nm, put into a hand-built
// set-up as makeUnderwaterSetup puts the scene's sky: level, band shares, kernel parameters and buffer.
seasim::SkyLight preethamSky() {
  const seasim::Scene scene = seasim::parseScene(
      "[sun]\nzenith_deg = 50.0\nazimuth_deg = 60.0\n[sky]\nmodel = \"preetham\"\nradiance = 0.05\n", "sky.toml");
  return seasim::makeSkyLight(scene, seasim::makeGrid(2, 400.0, 700.0));
}

void putSky(const seasim::SkyLight& sky, UnderwaterSetup& s) {
  s.sky_params = sky.params;
  s.sky_buffer = sky.kernelBuffer();
  for (size_t i = 0; i < s.bands.size(); ++i) {
    s.bands[i].sky_radiance = float(sky.level[i]);
    s.bands[i].sky_w_r = float(sky.shape.band_weights[i][0]);
    s.bands[i].sky_w_g = float(sky.shape.band_weights[i][1]);
    s.bands[i].sky_w_b = float(sky.shape.band_weights[i][2]);
  }
}

// Snell's law from below, in double and on its own: the direction in air of the upward unit d in
// water (the sky seen through the window), or false under total internal reflection.
bool airDirection(kd::real3 d, double ior, std::array<double, 3>& a) {
  const double h = std::sqrt(d.x * d.x + d.z * d.z), sin_air = ior * h;
  if (sin_air >= 1.0) return false;
  const double k = h > 0 ? sin_air / h : 0.0;
  a = {k * d.x, std::sqrt(1.0 - sin_air * sin_air), k * d.z};
  return true;
}

TEST(UnderwaterReference, SnellsWindowShowsAPreethamSkyTowardsTheRefractedDirection) {
  SceneSpec spec;
  spec.eye = {0, -3, 0};
  spec.forward = {0.3, 1, -0.2};
  spec.up_hint = {0, 0, -1};
  spec.fov_y_deg = 110;
  spec.bands = {{0.1, 0.0, 1.0, 0.0, 0.0, {kW1[0], kW1[1], kW1[2]}}, {0.6, 0.0, 1.0, 0.0, 0.0, {kW2[0], kW2[1], kW2[2]}}};
  UnderwaterSetup s = build(spec);
  const seasim::SkyLight sky = preethamSky();
  putSky(sky, s);
  const double n = s.params.ior;
  const Image ref = perPixel(s, [&](int i, kd::real3 d) {
    std::array<double, 3> a{};
    if (!airDirection(d, n, a)) return 0.0;
    return std::exp(-s.bands[i].c * 3.0 / d.y) * kd::uw_window_radiance(d.y, n, sky.radiance(i, a), 0.0);
  });
  // The sky is not uniform across the window: its brightest pixel at least 1.5× its dimmest lit one.
  double lo = 1e30, hi = 0;
  for (float v : ref.pixels)
    if (v > 0) lo = std::min(lo, double(v)), hi = std::max(hi, double(v));
  EXPECT_GT(hi, 1.5 * lo);
  UnderwaterReferenceSettings set;
  set.samples_per_pixel = 64;
  set.jitter = false;
  const UnderwaterReferenceResult r = seasim::renderUnderwaterReference(device(), s, set);
  expectFiniteNonNegative(r);
  expectAgrees(r, ref, "Snell's window, Preetham sky");
}

TEST(UnderwaterReference, CameraAboveSeesAPreethamSkyDirectlyAndMirroredByR) {
  SceneSpec spec;
  spec.eye = {0, 3, 0};
  spec.forward = {0.2, -0.1, -1};
  spec.fov_y_deg = 70;  // the horizon across the image: sky above it, the surface below
  // Black water (a = 1000/m): the surface shows R L_sky of the mirrored ray and nothing from below.
  spec.bands = {{1000, 0.0, 1.0, 0.0, 0.0, {kW1[0], kW1[1], kW1[2]}}, {1000, 0.0, 1.0, 0.0, 0.0, {kW3[0], kW3[1], kW3[2]}}};
  UnderwaterSetup s = build(spec);
  const seasim::SkyLight sky = preethamSky();
  putSky(sky, s);
  const double n = s.params.ior;
  const Image ref = perPixel(s, [&](int i, kd::real3 d) {
    if (d.y >= 0) return sky.radiance(i, {d.x, d.y, d.z});
    const double ci = -d.y, st = std::sqrt(1 - ci * ci) / n, ct = std::sqrt(1 - st * st);
    const double rs = (ci - n * ct) / (ci + n * ct), rp = (ct - n * ci) / (ct + n * ci);
    return 0.5 * (rs * rs + rp * rp) * sky.radiance(i, {d.x, -d.y, d.z});
  });
  UnderwaterReferenceSettings set;
  set.samples_per_pixel = 256;  // the band is drawn per path: its spread is the only noise
  set.jitter = false;
  set.camera_above = true;
  const UnderwaterReferenceResult r = seasim::renderUnderwaterReference(device(), s, set);
  expectFiniteNonNegative(r);
  expectAgrees(r, ref, "camera above, Preetham sky");
}

// A normal map of one normal everywhere (grid x grid texels over a 10 m patch), for the waves from above.
seasim::WaveNormalMap constantWaves(Vec3 n, int grid = 4) {
  seasim::WaveNormalMap w;
  w.grid = grid;
  w.patch = 10.0;
  const Vec3 u = seasim::normalize(n);
  for (int i = 0; i < grid * grid; ++i) w.normals.insert(w.normals.end(), {float(u.x), float(u.y), float(u.z), 0.0f});
  return w;
}

// The path tracer with the camera above, through `waves` (common/sea_waves.h), the sun's disk of angular
// radius `sun_radius` mirrored in its facets.
UnderwaterReferenceSettings aboveWaves(const seasim::WaveNormalMap& waves, int samples_per_pixel, double sun_radius,
                                       bool jitter) {
  UnderwaterReferenceSettings set;
  set.samples_per_pixel = samples_per_pixel;
  set.jitter = jitter;
  set.camera_above = true;
  set.waves = &waves;
  set.sun_angular_radius = sun_radius;
  return set;
}

// The camera above black water under a Preetham sky: the surface shows R L_sky of the mirrored ray.
UnderwaterSetup blackWaterFromAbove(const seasim::SkyLight& sky) {
  SceneSpec spec;
  spec.eye = {0, 3, 0};
  spec.forward = {0.2, -1, -1};
  spec.fov_y_deg = 40;  // every ray meets the surface, 20-70 degrees below the horizon
  spec.bands = {{1000, 0.0, 1.0, 0.0, 0.0, {kW1[0], kW1[1], kW1[2]}}, {1000, 0.0, 1.0, 0.0, 0.0, {kW3[0], kW3[1], kW3[2]}}};
  UnderwaterSetup s = build(spec);
  putSky(sky, s);
  return s;
}

TEST(UnderwaterReference, WavesOfTheFlatNormalAreTheFlatSurface) {
  const seasim::SkyLight sky = preethamSky();
  const UnderwaterSetup s = blackWaterFromAbove(sky);
  UnderwaterReferenceSettings set;
  set.samples_per_pixel = 64;
  set.camera_above = true;
  const UnderwaterReferenceResult flat = seasim::renderUnderwaterReference(device(), s, set);
  const seasim::WaveNormalMap waves = constantWaves({0, 1, 0});
  set.waves = &waves;
  set.sun_angular_radius = 0.0;  // no sun's disk in the mirror: the flat tracer draws none
  const UnderwaterReferenceResult wavy = seasim::renderUnderwaterReference(device(), s, set);
  EXPECT_EQ(wavy.rgb.pixels, flat.rgb.pixels);
  // A map that is not grid x grid texels is refused before anything is traced.
  seasim::WaveNormalMap torn = waves;
  torn.normals.pop_back();
  set.waves = &torn;
  EXPECT_THROW(seasim::renderUnderwaterReference(device(), s, set), seasim::RuntimeError);
}

TEST(UnderwaterReference, WavesTiltTheMirroredSkyAndTheFresnelSplit) {
  // Every facet tilted 8 degrees towards +x: R and the mirrored sky of that normal, written out here
  // (the reflected ray stays above the horizon for every pixel of this view).
  const seasim::SkyLight sky = preethamSky();
  const UnderwaterSetup s = blackWaterFromAbove(sky);
  const double tilt = 8.0 * M_PI / 180;
  const Vec3 n{std::sin(tilt), std::cos(tilt), 0.0};
  const double ior = s.params.ior;
  const Image ref = perPixel(s, [&](int i, kd::real3 d) {
    const double ci = -(d.x * n.x + d.y * n.y + d.z * n.z), st = std::sqrt(1 - ci * ci) / ior, ct = std::sqrt(1 - st * st);
    const double rs = (ci - ior * ct) / (ci + ior * ct), rp = (ct - ior * ci) / (ct + ior * ci);
    const Vec3 r{d.x + 2 * ci * n.x, d.y + 2 * ci * n.y, d.z + 2 * ci * n.z};
    EXPECT_GT(r.y, 0.0);
    return 0.5 * (rs * rs + rp * rp) * sky.radiance(i, {r.x, r.y, r.z});
  });
  const seasim::WaveNormalMap waves = constantWaves(n);
  const UnderwaterReferenceResult r =
      seasim::renderUnderwaterReference(device(), s, aboveWaves(waves, 256, 0.0, false));
  expectFiniteNonNegative(r);
  expectAgrees(r, ref, "camera above, tilted facets, Preetham sky");
}

TEST(UnderwaterReference, WavesMirrorASunOfNoSizeAsNothingFinite) {
  // A sun of angular radius 0 straight above a camera looking straight down at a flat map: the view's
  // mirror is the sun's direction exactly, and a disk of no solid angle adds nothing (not E/0).
  SceneSpec spec;
  spec.width = spec.height = 1;
  spec.eye = {0, 3, 0};
  spec.forward = {0, -1, 0};
  spec.up_hint = {0, 0, -1};
  spec.bands = {{1000, 0.0, 1.0, 0.0, 0.0, {kW1[0], kW1[1], kW1[2]}}};
  const UnderwaterSetup s = build(spec);  // the sun in air straight up
  const seasim::WaveNormalMap waves = constantWaves({0, 1, 0});
  const UnderwaterReferenceResult r = seasim::renderUnderwaterReference(device(), s, aboveWaves(waves, 4, 0.0, false));
  expectFiniteNonNegative(r);
  EXPECT_EQ(r.rgb.pixels[1], 0.0f);
}

TEST(UnderwaterReference, WavesMirrorTheSunsDiskWithItsIrradianceTimesR) {
  // A flat normal map, black water and a black sky: the image is the sun's disk (radius 1 degree) in
  // the mirror, radiance R E / Ω. Summed over the pixels' solid angles it is R E per sensor weight,
  // whatever the disk's size.
  SceneSpec spec;
  spec.width = spec.height = 48;
  const Vec3 sun = seasim::normalize(Vec3{0, 0.8, -0.6});
  spec.eye = {0, 3, 0};
  spec.forward = {0, -sun.y, sun.z};  // at the sun's mirror point
  spec.fov_y_deg = 4;
  spec.bands = {{1000, 0.0, 1.0, 0.0, 0.0, {kW1[0], kW1[1], kW1[2]}}};
  UnderwaterSetup s = build(spec);
  set4(s.params.sun_dir_air, sun);
  const double ior = s.params.ior;
  const double R_sun = kd::fresnel_reflectance(sun.y, 1.0, ior);
  const double E = 2.0;  // the sun's normal irradiance in air
  s.bands[0].e_sun0 = float(E * sun.y * (1 - R_sun));
  const seasim::WaveNormalMap waves = constantWaves({0, 1, 0});
  const UnderwaterReferenceResult r =
      seasim::renderUnderwaterReference(device(), s, aboveWaves(waves, 256, M_PI / 180, true));
  expectFiniteNonNegative(r);
  const double t = std::tan(spec.fov_y_deg * M_PI / 360);
  double flux[3] = {0, 0, 0};
  for (int y = 0; y < spec.height; ++y)
    for (int x = 0; x < spec.width; ++x) {
      const double u = (2.0 * (x + 0.5) / spec.width - 1) * t, v = (1 - 2.0 * (y + 0.5) / spec.height) * t;
      const double omega = (2 * t / spec.height) * (2 * t / spec.height) / std::pow(1 + u * u + v * v, 1.5);
      for (int c = 0; c < 3; ++c) flux[c] += r.rgb.at(x, y, c) * omega;
    }
  // The mirror's incidence is the sun's own angle (cos 0.8).
  const double R_view = kd::fresnel_reflectance(sun.y, 1.0, ior);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(flux[c], R_view * E * kW1[c], 0.02 * R_view * E * kW1[c]) << c;
  // The corners lie outside the disk: black.
  EXPECT_EQ(r.rgb.at(0, 0, 1), 0.0f);
}

TEST(UnderwaterReference, WhiteFurnaceIsUniformSkyRadianceTimesIorSquared) {
  // a = 0, no sun, white (albedo 1) sphere, box and bottom under a uniform sky: L = n² L_sky is the
  // solution (scattering conserves it, the surface sends n²(1-F) L_sky + F L_up = n² L_sky down inside
  // the window and L_up outside, a white Lambertian surface returns what it receives), so every pixel
  // is n² L_sky Σ w whatever b and the phase function.
  for (double g : {0.0, 0.9}) {
    SceneSpec spec;
    spec.eye = {0, -3, 0};
    spec.forward = {0.3, -0.2, -1};
    spec.g = g;
    spec.bottom_depth = 6;
    spec.bands = {{0.0, 0.15, 0.0, 0.4, 1.0, {kW1[0], kW1[1], kW1[2]}}, {0.0, 0.4, 0.0, 0.7, 1.0, {kW3[0], kW3[1], kW3[2]}}};
    spec.objects = {{sphere({1, -3.5, -5}, 1.2), {1.0f, 1.0f}}, {box({-3, -6, -8}, {-1, -4.5, -6}), {1.0f, 1.0f}}};
    const UnderwaterSetup s = build(spec);
    const Image ref = perPixel(s, [&](int i, kd::real3) {
      return double(s.params.ior) * s.params.ior * s.bands[i].sky_radiance;
    });
    UnderwaterReferenceSettings set;
    set.samples_per_pixel = 64;
    set.max_bounces = 1000;  // truncation far below the noise (a path escapes at ~half its surface visits)
    const UnderwaterReferenceResult r = seasim::renderUnderwaterReference(device(), s, set);
    expectFiniteNonNegative(r);
    expectAgrees(r, ref, g == 0 ? "white furnace, g = 0" : "white furnace, g = 0.9");
  }
}

SceneSpec fullScene() {
  SceneSpec spec;
  spec.eye = {0, -4, 0};
  spec.forward = {0.2, -0.15, -1};
  spec.g = 0.85;
  spec.bottom_depth = 10;
  spec.bands = {{0.1, 0.3, 2.0, 0.3, 0.4, {kW1[0], kW1[1], kW1[2]}}, {0.4, 0.5, 1.0, 0.2, 0.2, {kW3[0], kW3[1], kW3[2]}}};
  spec.objects = {{sphere({0.5, -4.5, -5}, 1.2), {0.6f, 0.3f}}, {box({-3, -10, -9}, {-1, -7, -7}), {0.4f, 0.4f}}};
  return spec;
}

TEST(UnderwaterReference, MoreBouncesNeverDarkenAndSeedsReproduce) {
  const UnderwaterSetup s = build(fullScene());
  UnderwaterReferenceSettings set;
  set.samples_per_pixel = 16;
  Image previous;
  double previous_mean = 0;
  for (int bounces : {2, 3, 4, 6, 10, 64}) {
    set.max_bounces = bounces;
    const UnderwaterReferenceResult r = seasim::renderUnderwaterReference(device(), s, set);
    expectFiniteNonNegative(r);
    if (!previous.pixels.empty()) {
      // The same paths, cut later: each sample only gains terms (float slack for the Welford sums).
      for (size_t i = 0; i < r.rgb.pixels.size(); ++i)
        ASSERT_GE(r.rgb.pixels[i], previous.pixels[i] * (1 - 1e-5f)) << "bounces " << bounces << " value " << i;
      EXPECT_GT(r.image_mean, previous_mean) << bounces;
    }
    previous = r.rgb;
    previous_mean = r.image_mean;
  }
  // Reproducible: same seed, same bits; another batch size or blocking, the same paths (float rounding
  // apart);
  // another seed, another image.
  set.max_bounces = 64;
  const UnderwaterReferenceResult a = seasim::renderUnderwaterReference(device(), s, set);
  const UnderwaterReferenceResult b = seasim::renderUnderwaterReference(device(), s, set);
  EXPECT_EQ(a.rgb.pixels, b.rgb.pixels);
  set.batch = 3;
  set.blocks = 2;  // launches never cross a block: 3+3+2 in each of two blocks of 8
  int progress_calls = 0, last_done = 0;
  set.progress = [&](int done, int total) {
    ++progress_calls;
    EXPECT_GT(done, last_done);
    EXPECT_EQ(total, 16);
    last_done = done;
  };
  const UnderwaterReferenceResult c = seasim::renderUnderwaterReference(device(), s, set);
  EXPECT_EQ(progress_calls, 6);
  EXPECT_EQ(last_done, 16);
  for (size_t i = 0; i < a.rgb.pixels.size(); ++i)
    EXPECT_NEAR(c.rgb.pixels[i], a.rgb.pixels[i], 1e-5 * std::fabs(a.rgb.pixels[i]) + 1e-12);
  set.seed = 2;
  set.progress = nullptr;
  const UnderwaterReferenceResult d = seasim::renderUnderwaterReference(device(), s, set);
  EXPECT_NE(d.rgb.pixels, a.rgb.pixels);
  // Different seeds agree within their noise (both are the same expectation).
  EXPECT_NEAR(d.image_mean, a.image_mean, 5 * std::hypot(a.image_mean_std_error, d.image_mean_std_error));
  // Multiple scattering adds light beyond single scattering + direct: the 64-bounce image is brighter
  // than the 2-bounce one (checked above) and its noise is quoted.
  std::printf("[full scene] 16x12, 16 spp: mean %.5g, mean std error %.3g, image-mean se %.3g, %.1f ms\n",
              a.image_mean, a.mean_std_error, a.image_mean_std_error, a.ms);
}

TEST(UnderwaterReference, NoNanInTurbidDeepWaterOrWithoutAbsorption) {
  // 9C-like turbid water (b = 10/m) at 1000 m: the sun beam underflows to 0, the sky is 10^4 optical
  // depths away; strongly forward scattering.
  SceneSpec turbid = fullScene();
  turbid.eye = {0, -1000, 0};
  turbid.bottom_depth = 1010;
  turbid.g = 0.95;
  turbid.objects = {{sphere({0.5, -1000.5, -5}, 1.2), {0.6f, 0.3f}}};
  turbid.bands = {{0.8, 10.0, 2.0, 0.3, 0.4, {kW1[0], kW1[1], kW1[2]}}, {2.0, 10.0, 1.0, 0.2, 0.2, {kW3[0], kW3[1], kW3[2]}}};
  UnderwaterReferenceSettings set;
  set.samples_per_pixel = 8;
  UnderwaterReferenceResult r = seasim::renderUnderwaterReference(device(), build(turbid), set);
  expectFiniteNonNegative(r);
  EXPECT_EQ(r.image_mean, 0.0);  // nothing reaches 1000 m through 10^4 optical depths

  // a = 0: only roulette and the cap end paths (albedo 1), near the surface with sun and sky.
  SceneSpec pure = fullScene();
  pure.bottom_depth = 0;  // semi-infinite: paths may wander down for ever
  for (BandSpec& b : pure.bands) b.a = 0.0;
  for (double g : {0.0, 0.99}) {
    pure.g = g;
    r = seasim::renderUnderwaterReference(device(), build(pure), set);
    expectFiniteNonNegative(r);
    EXPECT_GT(r.image_mean, 0.0);
  }
  // Sun below the horizon (e_beam0 = 0) and c = 0 (a = b = 0): the sky through the window only.
  SceneSpec empty = fullScene();
  for (BandSpec& b : empty.bands) b.a = b.b = b.e_beam0 = 0.0;
  r = seasim::renderUnderwaterReference(device(), build(empty), set);
  expectFiniteNonNegative(r);
}

// The camera above the surface (the sea seen from above): in single-scattering mode every
// pixel is (1 - R)/n² times the in-water single scattering along the refracted ray from the surface
// point, which the double quadrature gives independently; R and the refraction written out here.
TEST(UnderwaterReference, CameraAboveSeesTheWaterThroughTheSurfaceByOneMinusROverNSquared) {
  SceneSpec spec = singleScatteringScene();
  spec.eye = {0, 3, 0};
  spec.forward = {0, -1, -0.8};
  spec.fov_y_deg = 50;  // every ray meets the surface, at 25° to 64° from the nadir
  const UnderwaterSetup s = build(spec);
  const UwParams& p = s.params;
  const double n = p.ior;
  const Image expected = perPixel(s, [&](int i, kd::real3 d) {
    const double ci = -d.y, st = std::sqrt(1 - ci * ci) / n, ct = std::sqrt(1 - st * st);
    const double rs = (ci - n * ct) / (ci + n * ct), rp = (ct - n * ci) / (ct + n * ci);
    const double R = 0.5 * (rs * rs + rp * rp);
    const Vec3 o{p.cam_pos[0] + p.cam_pos[1] / ci * d.x, 0.0, p.cam_pos[2] + p.cam_pos[1] / ci * d.z};
    const Vec3 h = seasim::normalize(Vec3{d.x, 0, d.z});
    const Vec3 dw{h.x * st, -ct, h.z * st};  // Snell: the refracted ray, in the plane of incidence
    return (1 - R) / (n * n) * seasim::underwaterSingleScatteringRay(s, i, o, dw, false, 4000);
  });
  UnderwaterReferenceSettings set;
  set.samples_per_pixel = 128;
  set.batch = 32;
  set.max_bounces = 1;
  set.jitter = false;
  set.camera_above = true;
  const UnderwaterReferenceResult r = seasim::renderUnderwaterReference(device(), s, set);
  expectFiniteNonNegative(r);
  expectAgrees(r, expected, "camera above, single scattering");
  set.camera_above = false;  // the default still wants the camera below
  EXPECT_THROW(seasim::renderUnderwaterReference(device(), s, set), seasim::RuntimeError);
}

TEST(UnderwaterReference, RejectsWhatItCannotTrace) {
  SceneSpec spec = fullScene();
  UnderwaterReferenceSettings set;
  set.samples_per_pixel = 0;
  EXPECT_THROW(seasim::renderUnderwaterReference(device(), build(spec), set), seasim::RuntimeError);
  set.samples_per_pixel = 1;
  spec.eye = {0, 1, 0};  // above the surface
  EXPECT_THROW(seasim::renderUnderwaterReference(device(), build(spec), set), seasim::RuntimeError);
}

}  // namespace
