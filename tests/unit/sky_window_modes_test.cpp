// sky_window_modes_test.cpp — a sky that is not uniform at the discrete-ordinates solver's surface
// (host/underwater/sky_window_modes.*, DiscreteOrdinatesLayer::sky_shape):
//   * the uniform sky is S_0 = 1 and no azimuth modes, exactly, and leaves the solver's field bit for
//     bit as it was without a shape;
//   * a Preetham sky's modes against a brute-force azimuth integral of the host sky module's radiance
//     (SkyLight::radiance) along directions found by Snell's law written out here;
//   * the solver's surface radiance in black water is (1 − R) times that shape in modes 0 and 1, and
//     the sky's share of E_d just below the surface stays e_sky0.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "math/kernel_math.h"
#include "scene/scene_parser.h"
#include "sky/sky_light.h"
#include "spectral/wavelength_grid.h"
#include "underwater/discrete_ordinates.h"
#include "underwater/sky_window_modes.h"

namespace {

using seasim::DiscreteOrdinates;
using seasim::DiscreteOrdinatesLayer;
using seasim::SkyLight;
using seasim::SkyWindowModes;

constexpr double kIor = 1.34;

SkyLight skyOf(const std::string& model, double sun_zenith_deg) {
  const seasim::Scene scene = seasim::parseScene("[sun]\nzenith_deg = " + std::to_string(sun_zenith_deg) +
                                                     "\nazimuth_deg = 60.0\n[sky]\nmodel = \"" + model +
                                                     "\"\nradiance = 0.05\n",
                                                 "sky.toml");
  return seasim::makeSkyLight(scene, seasim::makeGrid(4, 400.0, 700.0));
}

std::array<double, 3> weights(const SkyLight& sky, int band) {
  return {sky.shape.band_weights[band][0], sky.shape.band_weights[band][1], sky.shape.band_weights[band][2]};
}

// Mode m of band `band`'s sky radiance along light travelling down at cosine mu in water, φ from the
// refracted sun's direction of travel, by brute force: Snell's law for the direction in air (towards
// the sky, horizontally at φ from the sun's azimuth), the sky module's radiance, 4096 azimuths.
double bruteMode(const SkyLight& sky, int band, double mu, int m) {
  const double sin_air = kIor * std::sqrt(1 - mu * mu);
  if (sin_air >= 1) return 0.0;
  const double cos_air = std::sqrt(1 - sin_air * sin_air);
  const double sun_az = std::atan2(sky.sun_dir[2], sky.sun_dir[0]);
  const int n = 4096;
  double sum = 0;
  for (int j = 0; j < n; ++j) {
    const double phi = 2 * M_PI * (j + 0.5) / n, az = sun_az + phi;
    const std::array<double, 3> a{sin_air * std::cos(az), cos_air, sin_air * std::sin(az)};
    sum += sky.radiance(band, a) * std::cos(m * phi);
  }
  return (m == 0 ? 1.0 : 2.0) * sum / n;
}

TEST(SkyWindowModes, UniformSkyIsOneAverageAndNoAzimuthExactly) {
  const SkyWindowModes modes = seasim::makeSkyWindowModes(skyOf("uniform", 30), kIor);
  for (double mu : {modes.mu_min, 0.8, 0.95, 1.0}) {
    const std::array<double, 3> s = modes.at(mu, {0.3, 0.3, 0.3});
    EXPECT_EQ(s[0], 1.0);
    EXPECT_EQ(s[1], 0.0);
    EXPECT_EQ(s[2], 0.0);
  }
  EXPECT_EQ(modes.at(0.5 * modes.mu_min, {1, 1, 1})[0], 0.0);  // outside the window: no sky
}

TEST(SkyWindowModes, PreethamModesAreTheAzimuthIntegralsOfTheSkyThroughSnellsWindow) {
  for (double sun : {30.0, 60.0}) {
    const SkyLight sky = skyOf("preetham", sun);
    const SkyWindowModes modes = seasim::makeSkyWindowModes(sky, kIor);
    for (int band : {0, 3}) {
      for (double mu : {0.70, 0.80, 0.90, 0.99}) {
        const std::array<double, 3> s = modes.at(mu, weights(sky, band));
        const double s0 = bruteMode(sky, band, mu, 0) / sky.level[band];
        for (int m = 0; m < 3; ++m) {
          const double brute = bruteMode(sky, band, mu, m) / sky.level[band];
          // Linear in μ between 64 samples, 256 azimuths: within 0.5 % of S_0.
          EXPECT_NEAR(s[m], brute, 5e-3 * s0) << "sun " << sun << " band " << band << " mu " << mu << " mode " << m;
        }
      }
    }
    // The sky is brighter towards the sun: its light in water travels with the beam (S_1 > 0).
    EXPECT_GT(modes.at(0.8, weights(sky, 1))[1], 0.05 * modes.at(0.8, weights(sky, 1))[0]) << sun;
  }
}

DiscreteOrdinatesLayer blackWater(double e_sky0) {
  DiscreteOrdinatesLayer l;
  l.a = 50.0;  // nothing comes back up: the surface's downward radiance is the sky's alone
  l.b = 0.01;
  l.g = 0.9;
  l.ior = kIor;
  l.mu_sun = 0.9;
  l.e_sun0 = 0.0;
  l.e_sky0 = e_sky0;
  return l;
}

TEST(SkyWindowModes, UniformShapeLeavesTheSolverBitForBit) {
  DiscreteOrdinatesLayer plain = blackWater(0.146);
  plain.a = 0.1, plain.b = 0.3, plain.e_sun0 = 0.85, plain.bottom_depth = 5, plain.bottom_albedo = 0.35;
  DiscreteOrdinatesLayer shaped = plain;
  const SkyWindowModes uniform = seasim::makeSkyWindowModes(skyOf("uniform", 30), kIor);
  shaped.sky_shape = [&](double mu) { return uniform.at(mu, {1, 1, 1}); };
  for (int mode = 0; mode < 3; ++mode) {
    const DiscreteOrdinates a(plain, 16, mode), b(shaped, 16, mode);
    std::vector<double> da, ua, db, ub;
    for (double y : {0.0, 1.0, 4.0}) {
      a.radiances(y, da, ua);
      b.radiances(y, db, ub);
      EXPECT_EQ(da, db) << mode;
      EXPECT_EQ(ua, ub) << mode;
    }
  }
}

TEST(SkyWindowModes, SolverSurfaceRadianceIsOneMinusRTimesTheSkysShape) {
  const SkyLight sky = skyOf("preetham", 50);
  const SkyWindowModes modes = seasim::makeSkyWindowModes(sky, kIor);
  const std::array<double, 3> w = weights(sky, 2);
  DiscreteOrdinatesLayer layer = blackWater(0.146);
  layer.sky_shape = [&](double mu) { return modes.at(mu, w); };
  const DiscreteOrdinates avg(layer, 16, 0), cos1(layer, 16, 1);
  // The sky's share of E_d just below the surface is e_sky0 whatever its shape.
  EXPECT_NEAR(avg.at(0.0).down, layer.e_sky0, 1e-5 * layer.e_sky0);  // + R E_u, 1e-6 of it here
  std::vector<double> d0, u0, d1, u1;
  avg.radiances(0.0, d0, u0);
  cos1.radiances(0.0, d1, u1);
  const std::vector<double>& mu = avg.cosines();
  double scale = -1;  // (1 − R) S_0(μ) times one scale for every stream
  int inside = 0;
  for (size_t i = 0; i < mu.size(); ++i) {
    if (mu[i] < modes.mu_min + 1e-3) continue;  // total reflection: no sky
    ++inside;
    const double t = 1 - seasim::kmath_d::fresnel_reflectance(mu[i], kIor, 1.0);
    const std::array<double, 3> s = modes.at(mu[i], w);
    if (scale < 0) scale = d0[i] / (t * s[0]);
    EXPECT_NEAR(d0[i], scale * t * s[0], 1e-6 * d0[i]) << mu[i];
    EXPECT_NEAR(d1[i], scale * t * s[1], 1e-6 * d0[i]) << mu[i];  // mode 1 by mode 0's scale
  }
  EXPECT_GE(inside, 6);  // the streams inside the window (the quadrature splits at its edge)
}

}  // namespace
