// sky_test.cpp — the sky models of kernels/common/sky.h in float and double: the analytic (CIE clear)
// sky's normalisation (its cosine-weighted mean over the hemisphere is the configured radiance),
// finiteness at the horizon, the zenith and with the sun below the horizon; the latitude–longitude
// image reader (texel centres, azimuth wrap, poles) and its luminance normalisation; the per-band
// RGB weights.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "io/image_io.h"
#include "io/tonemap.h"
#include "math/kernel_math.h"
#include "passes/sea_sky.h"
#include "spectral/wavelength_grid.h"

namespace {

namespace kd = seasim::kmath_d;
namespace kf = seasim::kmath_f;

// The unqualified calls below find the kmath_f or kmath_d function through the real3 argument (ADL);
// scalar-only functions get an overload per precision here.
double sky_cie_gradation(double c) { return kd::sky_cie_gradation(c); }
float sky_cie_gradation(float c) { return kf::sky_cie_gradation(c); }
template <class V>
V dir(double theta, double phi) {
  using T = decltype(V{}.x);
  return V{T(std::sin(theta) * std::cos(phi)), T(std::cos(theta)), T(std::sin(theta) * std::sin(phi))};
}

// (1/π) ∫ f cos θ dω over the upper hemisphere in (θ, φ) by the midpoint rule in double: a different
// parameterisation and resolution from sky_cie_clear_cosine_mean's (s = cos²θ).
template <class V, class F>
double hemisphereCosineMean(F f, int n_theta, int n_phi) {
  double sum = 0;
  const double dt = M_PI / 2 / n_theta, dp = 2 * M_PI / n_phi;
  for (int i = 0; i < n_theta; ++i) {
    const double th = (i + 0.5) * dt;
    double row = 0;
    for (int k = 0; k < n_phi; ++k) row += double(f(dir<V>(th, (k + 0.5) * dp)));
    sum += row * std::cos(th) * std::sin(th) * dt * dp;
  }
  return sum / M_PI;
}

// Sun positions: overhead, mid, grazing, just below and well below the horizon (zenith angles, deg).
const double kSunZenithDeg[] = {0.0, 30.0, 60.0, 89.9, 95.0, 150.0};

template <class V>
void checkAnalyticNormalisation(double tolerance, const char* precision) {
  using T = decltype(V{}.x);
  for (double zen : kSunZenithDeg) {
    const V sun = dir<V>(zen * M_PI / 180, 1.1);
    const T mean = sky_cie_clear_cosine_mean(sun, 128, 256);  // what the host uses for the scale
    ASSERT_TRUE(std::isfinite(double(mean)) && mean > 0) << precision << " " << zen;
    const double radiance = 0.05;  // the band's sky radiance
    const double got = hemisphereCosineMean<V>(
        [&](V d) { return radiance * double(sky_cie_clear_shape(d, sun)) / double(mean); }, 720, 1440);
    EXPECT_NEAR(got / radiance, 1.0, tolerance) << precision << " sun zenith " << zen;
  }
}

TEST(Sky, AnalyticSkyCosineWeightedMeanIsTheConfiguredRadiance) {
  // Requirement: within 1 %. Measured: the host's (s, φ) midpoint rule at 128 x 256 agrees with this
  // (θ, φ) rule at 720 x 1440 within 3.1e-4 in double and in float (worst with the sun overhead,
  // where the indicatrix's cusp e^{-3χ} sits on the boundary s = 1).
  checkAnalyticNormalisation<kd::real3>(1e-3, "double");
  checkAnalyticNormalisation<kf::real3>(1e-3, "float");
}

TEST(Sky, AnalyticMeanQuadratureHasConverged) {
  // The host's 128 x 256 rule against 1024 x 2048 (the claim in sky.h): measured <= 2.9e-4.
  for (double zen : kSunZenithDeg) {
    const kd::real3 sun = dir<kd::real3>(zen * M_PI / 180, -0.4);
    const double coarse = kd::sky_cie_clear_cosine_mean(sun, 128, 256);
    const double fine = kd::sky_cie_clear_cosine_mean(sun, 1024, 2048);
    EXPECT_NEAR(coarse / fine, 1.0, 5e-4) << zen;
  }
}

template <class V>
void checkAnalyticFinite(const char* precision) {
  using T = decltype(V{}.x);
  for (double zen : kSunZenithDeg) {
    const V sun = dir<V>(zen * M_PI / 180, 0.3);
    // Zenith, horizon (exactly 0 and within rounding of it), just below, the sun itself, its antipode.
    const V views[] = {V{0, 1, 0}, V{1, 0, 0}, V{0, T(1e-30), 1}, V{0.6f, T(-1e-7), 0.8f}, sun, V{-sun.x, -sun.y, -sun.z},
                       dir<V>(M_PI / 2 - 1e-6, 0.3)};
    for (const V& d : views) {
      const double s = double(sky_cie_clear_shape(d, sun));
      EXPECT_TRUE(std::isfinite(s)) << precision << " " << zen;
      EXPECT_GT(s, 0.0) << precision << " " << zen;
      EXPECT_LT(s, 20.0) << precision << " " << zen;  // φ <= 1, f <= 1 + 10 + 0.45
    }
  }
  // φ at the horizon is its limit 1, and at the zenith 1 - e^{-0.32}.
  EXPECT_NEAR(double(sky_cie_gradation(T(0))), 1.0, 1e-7);
  EXPECT_NEAR(double(sky_cie_gradation(T(1))), 1.0 - std::exp(-0.32), 1e-6);
}

TEST(Sky, AnalyticSkyFiniteAtHorizonZenithAndWithTheSunDown) {
  checkAnalyticFinite<kd::real3>("double");
  checkAnalyticFinite<kf::real3>("float");
}

TEST(Sky, AnalyticSkyIsBrightestTowardsTheSun) {
  const kd::real3 sun = dir<kd::real3>(40 * M_PI / 180, 0.0);
  const double towards = kd::sky_cie_clear_shape(sun, sun);
  const double away = kd::sky_cie_clear_shape(dir<kd::real3>(40 * M_PI / 180, M_PI), sun);
  EXPECT_GT(towards / away, 5.0);  // f(0)/f(80°) ≈ 11.3/1.4 for this geometry
}

// A smooth 16 x 8 test image: R, G, B vary with azimuth and zenith angle (periodic in azimuth).
template <class T>
std::vector<T> smoothImage(int w, int h) {
  std::vector<T> tex(4 * w * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double phi = 2 * M_PI * (x + 0.5) / w, th = M_PI * (y + 0.5) / h;
      T* t = &tex[4 * (y * w + x)];
      t[0] = T(1.0 + 0.5 * std::cos(phi) * std::sin(th));
      t[1] = T(2.0 + std::cos(th));
      t[2] = T(0.5 + 0.25 * std::sin(phi));
      t[3] = 0;
    }
  return tex;
}

template <class V>
void checkImageReader(const char* precision) {
  using T = decltype(V{}.x);
  const int w = 16, h = 8;
  const std::vector<T> tex = smoothImage<T>(w, h);
  // At a texel centre the bilinear read returns the texel.
  for (int y : {0, 3, 7})
    for (int x : {0, 5, 15}) {
      const V d = dir<V>(M_PI * (y + 0.5) / h, 2 * M_PI * (x + 0.5) / w);
      const V c = sky_latlong_rgb(tex.data(), w, h, d);
      const T* t = &tex[4 * (y * w + x)];
      EXPECT_NEAR(double(c.x), double(t[0]), 2e-5) << precision << " " << x << "," << y;
      EXPECT_NEAR(double(c.y), double(t[1]), 2e-5) << precision;
      EXPECT_NEAR(double(c.z), double(t[2]), 2e-5) << precision;
    }
  // Across the azimuth seam (φ = 0 = 2π) the read is continuous: halfway between the last and the
  // first column it is their average.
  const V seam = sky_latlong_rgb(tex.data(), w, h, dir<V>(M_PI * 2.5 / h, -1e-4));
  const V seam2 = sky_latlong_rgb(tex.data(), w, h, dir<V>(M_PI * 2.5 / h, 1e-4));
  EXPECT_NEAR(double(seam.x), double(seam2.x), 1e-3) << precision;
  EXPECT_NEAR(double(seam.x), 0.5 * double(tex[4 * (2 * w + 0)] + tex[4 * (2 * w + w - 1)]), 2e-3) << precision;
  // Poles: finite, clamped to the first and last rows.
  for (const V& d : {V{0, 1, 0}, V{0, -1, 0}, V{0, T(0.5), 0}}) {
    const V c = sky_latlong_rgb(tex.data(), w, h, d);
    EXPECT_TRUE(std::isfinite(double(c.x)) && std::isfinite(double(c.y)) && std::isfinite(double(c.z))) << precision;
  }
}

TEST(Sky, LatLongImageReadsTexelCentresWrapsAndClamps) {
  checkImageReader<kd::real3>("double");
  checkImageReader<kf::real3>("float");
}

TEST(Sky, ImageLuminanceNormalisation) {
  // A constant image: the piecewise-constant cosine mean is its luminance exactly.
  const int w = 8, h = 4;
  std::vector<double> grey(4 * w * h, 0.0);
  for (int i = 0; i < w * h; ++i) grey[4 * i] = grey[4 * i + 1] = grey[4 * i + 2] = 0.7;
  EXPECT_NEAR(kd::sky_latlong_cosine_mean_luminance(grey.data(), w, h), 0.7, 1e-12);
  // Odd height: the horizon cuts the middle row, which counts only above it.
  std::vector<double> odd(4 * 8 * 5, 0.0);
  for (int i = 0; i < 8 * 5; ++i) odd[4 * i] = odd[4 * i + 1] = odd[4 * i + 2] = 1.0;
  EXPECT_NEAR(kd::sky_latlong_cosine_mean_luminance(odd.data(), 8, 5), 1.0, 1e-12);
  // A smooth image: the normalised bilinear sky has cosine-weighted mean luminance 1 within 1 %
  // (the texels are coarse: 16 x 8, so the two readings differ by interpolation only).
  for (int precision = 0; precision < 2; ++precision) {
    double got;
    if (precision == 0) {
      const std::vector<double> tex = smoothImage<double>(16, 8);
      const double scale = 1 / kd::sky_latlong_cosine_mean_luminance(tex.data(), 16, 8);
      got = hemisphereCosineMean<kd::real3>(
          [&](kd::real3 d) { return scale * kd::sky_luminance(kd::sky_latlong_rgb(tex.data(), 16, 8, d)); }, 360, 720);
    } else {
      const std::vector<float> tex = smoothImage<float>(16, 8);
      const float scale = 1 / kf::sky_latlong_cosine_mean_luminance(tex.data(), 16, 8);
      got = hemisphereCosineMean<kf::real3>(
          [&](kf::real3 d) { return scale * kf::sky_luminance(kf::sky_latlong_rgb(tex.data(), 16, 8, d)); }, 360, 720);
    }
    EXPECT_NEAR(got, 1.0, 0.01) << (precision ? "float" : "double");
  }
}

TEST(Sky, BandWeightsArePartitionOfUnity) {
  for (double nm = 350; nm <= 800; nm += 5) {
    const kd::real3 d = kd::sky_image_band_weights(nm);
    const kf::real3 f = kf::sky_image_band_weights(float(nm));
    EXPECT_NEAR(d.x + d.y + d.z, 1.0, 1e-12) << nm;
    EXPECT_NEAR(f.x + f.y + f.z, 1.0, 1e-6) << nm;
    for (double v : {d.x, d.y, d.z}) EXPECT_TRUE(v >= 0 && v <= 1) << nm;
  }
  const kd::real3 blue = kd::sky_image_band_weights(440), green = kd::sky_image_band_weights(540),
                  red = kd::sky_image_band_weights(650);
  EXPECT_EQ(blue.z, 1.0);
  EXPECT_EQ(green.y, 1.0);
  EXPECT_EQ(red.x, 1.0);
}

TEST(SeaSky, HostSetUpOfEachModel) {
  const seasim::WavelengthGrid grid = seasim::makeGrid(4, 400, 700);
  const double sun[3] = {0.0, std::cos(0.7), -std::sin(0.7)};
  seasim::SkyDesc desc;
  seasim::SeaSky sky = seasim::makeSeaSky(desc, sun, grid);
  EXPECT_EQ(sky.model, 0);
  EXPECT_EQ(sky.scale, 1.0);
  ASSERT_EQ(sky.band_weights.size(), 4u);

  desc.model = seasim::SkyDesc::Model::Analytic;
  sky = seasim::makeSeaSky(desc, sun, grid);
  EXPECT_EQ(sky.model, 1);
  EXPECT_NEAR(sky.scale, 1 / kd::sky_cie_clear_cosine_mean(kd::real3{sun[0], sun[1], sun[2]}, 128, 256), 1e-12);

  // The shipped sample sky (EXR, linear): 64 x 32, and its scaled luminance has cosine mean 1.
  desc.model = seasim::SkyDesc::Model::Image;
  desc.image = std::string(SEASIM_SOURCE_DIR) + "/scenes/textures/sky_clear.exr";
  sky = seasim::makeSeaSky(desc, sun, grid);
  EXPECT_EQ(sky.model, 2);
  ASSERT_EQ(sky.width, 64);
  ASSERT_EQ(sky.height, 32);
  EXPECT_NEAR(sky.scale * kd::sky_latlong_cosine_mean_luminance(sky.texels.data(), 64, 32), 1.0, 1e-12);
  EXPECT_TRUE(std::isfinite(sky.scale) && sky.scale > 0);

  // An 8-bit image is sRGB-decoded: the texel is srgbDecode of the file's value.
  desc.image = std::string(SEASIM_SOURCE_DIR) + "/scenes/textures/polka_dot.png";
  if (seasim::imageIoAvailable()) {
    sky = seasim::makeSeaSky(desc, sun, grid);
    const seasim::Image raw = seasim::readImage(desc.image);
    const int x = raw.width / 3, y = raw.height / 4;
    EXPECT_NEAR(sky.texels[4 * (size_t(y) * raw.width + x)], seasim::srgbDecode(raw.at(x, y, 0)), 1e-12);
  }
}

}  // namespace
