// underwater_reference_error_bars_test.cpp — are the path tracer's error bars honest where its samples
// are heavy-tailed? A dim, absorbing case: the camera 12 m down looking 15° up, absorbing and strongly
// forward-scattering water (a 0.4, b 0.2, g 0.95), a low sun (75° in air) and a dim sky (0.005 of the
// beam). Many seeds of the same image: the spread of their means is the true standard error; each run's
// reported error (from its independent blocks of paths, reference/batch_error.h) must match it within
// 20 %, for the image mean and pixel by pixel (pooled: Σ reported² against Σ spread² over pixels).
// The per-sample estimate is printed beside it: measured here (64 seeds, 256 paths in 16 blocks),
// image mean spread 2.54e-5, from blocks 2.48e-5 (0.98), per-sample 1.64e-5 (0.65: it took R, G and B
// as independent, and they are one path's light); 5 m down 0.85 and 0.56. About 7 s on PoCL, 2 cores.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "reference/underwater_reference.h"
#include "test_device.h"

namespace {

using seasim::UnderwaterReferenceResult;
using seasim::UnderwaterReferenceSettings;
using seasim::UnderwaterSetup;
using seasim::Vec3;

void set4(float out[4], Vec3 v) {
  out[0] = float(v.x), out[1] = float(v.y), out[2] = float(v.z), out[3] = 0.0f;
}

// The dim absorbing case (see the top), one band, 16x9 pixels, no bottom, no objects.
UnderwaterSetup dimAbsorbingCase() {
  UnderwaterSetup u;
  UwParams& p = u.params;
  const double ior = 1.333, zenith_air = 75.0 * M_PI / 180.0;
  const double sin_w = std::sin(zenith_air) / ior;
  const Vec3 sun_w = Vec3{sin_w * 0.5, std::sqrt(1 - sin_w * sin_w), -sin_w * std::sqrt(0.75)};
  const Vec3 f = seasim::normalize(Vec3{0, std::tan(15.0 * M_PI / 180.0), -1});
  const Vec3 r = seasim::normalize(seasim::cross(f, Vec3{0, 1, 0}));
  set4(p.cam_pos, Vec3{0, -12, 0});
  set4(p.cam_forward, f);
  set4(p.cam_right, r);
  set4(p.cam_up, seasim::cross(r, f));
  set4(p.sun_dir_water, sun_w);
  set4(p.sun_dir_air, Vec3{0, 1, 0});  // not read by the reference
  u.sun_water = sun_w;
  p.tan_half_fov_y = float(std::tan(30.0 * M_PI / 180.0));
  p.width = 16;
  p.height = 9;
  p.aspect = float(p.width) / float(p.height);
  p.ior = float(ior);
  p.g = 0.95f;
  p.bottom_depth = 0.0f;  // none
  p.band_count = 1;
  p.object_count = 0;
  UwBand band{};
  band.a = 0.4f, band.b = 0.2f, band.c = 0.6f, band.kd = 0.6f;
  band.e_beam0 = 1.0f;
  band.e_sun0 = float(sun_w.y);
  band.sky_radiance = 0.005f;
  band.w_r = 1.0f, band.w_g = 0.5f, band.w_b = 0.25f;
  u.bands.push_back(band);
  u.objects.push_back(UwObject{});
  u.albedo.push_back(0.0f);
  return u;
}

TEST(UnderwaterReferenceErrorBars, SpreadOverSeedsMatchesTheReportedErrorInDimAbsorbingWater) {
  const UnderwaterSetup setup = dimAbsorbingCase();
  const int seeds = 64;
  UnderwaterReferenceSettings settings;
  settings.samples_per_pixel = 256;
  settings.batch = 64;
  settings.blocks = 16;
  std::vector<UnderwaterReferenceResult> runs;
  for (int s = 0; s < seeds; ++s) {
    settings.seed = 1000u + unsigned(s);
    runs.push_back(seasim::renderUnderwaterReference(seasim::test::testDevice(), setup, settings));
  }
  // The image mean: the spread over seeds against the RMS reported error.
  double m = 0, m2 = 0, rep2 = 0, rep_sample2 = 0, neff = 0, ms = 0;
  for (const auto& r : runs) m += r.image_mean / seeds;
  for (const auto& r : runs) {
    m2 += (r.image_mean - m) * (r.image_mean - m) / (seeds - 1);
    rep2 += r.image_mean_std_error * r.image_mean_std_error / seeds;
    rep_sample2 += r.image_mean_sample_std_error * r.image_mean_sample_std_error / seeds;
    neff += r.effective_samples / seeds;
    ms += r.ms;
  }
  const double spread = std::sqrt(m2), reported = std::sqrt(rep2), reported_sample = std::sqrt(rep_sample2);
  // Pixel by pixel: the same, pooled over pixels and channels (Σ spread² against Σ reported²).
  const size_t values = runs[0].rgb.pixels.size();
  double pix_spread2 = 0, pix_rep2 = 0;
  for (size_t i = 0; i < values; ++i) {
    double pm = 0, pv = 0, pr = 0;
    for (const auto& r : runs) pm += r.rgb.pixels[i] / seeds;
    for (const auto& r : runs) {
      pv += (r.rgb.pixels[i] - pm) * (r.rgb.pixels[i] - pm) / (seeds - 1);
      pr += double(r.std_error.pixels[i]) * r.std_error.pixels[i] / seeds;
    }
    pix_spread2 += pv;
    pix_rep2 += pr;
  }
  const double pixel_ratio = std::sqrt(pix_rep2 / pix_spread2);
  std::printf("image mean %.4g: spread over %d seeds %.4g; reported from blocks %.4g (ratio %.3f), per-sample %.4g "
              "(ratio %.3f); effective samples %.0f of %d; pixels: reported/spread %.3f; %.0f ms of kernels\n",
              m, seeds, spread, reported, reported / spread, reported_sample, reported_sample / spread, neff,
              settings.samples_per_pixel, pixel_ratio, ms);
  EXPECT_NEAR(reported / spread, 1.0, 0.2);
  EXPECT_NEAR(pixel_ratio, 1.0, 0.2);
}

}  // namespace
