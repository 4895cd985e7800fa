// caustics_floor_test.cpp — the caustic splat onto a height-field floor (caustics.cl
// caustics_splat_floor, 004 §5.2.1 onto 000 §5.4's floor): a level floor at depth d gives exactly the
// plane map at d (shifted to the floor's square); a calm sea over a sloping, bumpy floor gives
// T(θ) e^{-c l} times the slope's Lambert cosine at every texel; under waves a sloping floor's mean is
// the level plane's times that cosine (flux is conserved: the floor only moves where light lands);
// no NaN/Inf with steep waves, a grazing sun or a floor reaching the surface; no light at night.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "math/kernel_math.h"
#include "passes/caustics_pass.h"
#include "passes/ocean_pass.h"
#include "passes/sea_heightfield.h"
#include "test_device.h"
#include "util/error.h"

namespace {

using seasim::CausticsConfig;
using seasim::CausticsPass;
using seasim::OceanConfig;
using seasim::OceanPass;

seasim::Device& device() { return seasim::test::testDevice(); }

OceanConfig sea(double wind) {
  OceanConfig c;
  c.grid = 64;
  c.patch_size = 32.0;
  c.wind_speed = wind;
  c.choppiness = 0.5;
  c.seed = 5;
  return c;
}

CausticsConfig sun(double zenith_deg, double attenuation = 0.0) {
  CausticsConfig c;
  c.sun_zenith = zenith_deg * std::numbers::pi / 180;
  c.sun_azimuth = 0.4;
  c.attenuation = attenuation;
  c.map_size = 64;
  return c;
}

// A floor node grid over `extent` with depth f(x, z).
template <typename F>
seasim::HeightField floorOf(double extent, int nodes, F f) {
  std::vector<float> depth(size_t(nodes) * nodes);
  for (int j = 0; j < nodes; ++j)
    for (int i = 0; i < nodes; ++i) {
      const double x = -extent / 2 + i * extent / (nodes - 1), z = -extent / 2 + j * extent / (nodes - 1);
      depth[size_t(j) * nodes + i] = float(f(x, z));
    }
  return seasim::makeHeightField(nodes, nodes, extent, depth);
}

double mean(const std::vector<float>& v) {
  double s = 0;
  for (float x : v) s += x;
  return s / v.size();
}

TEST(CausticsFloor, LevelFloorEqualsThePlaneMap) {
  OceanPass ocean(device(), sea(7.0));
  ocean.run(1.5);
  CausticsPass splat(device(), ocean.maps(), sun(30));
  splat.run(6.0);
  const std::vector<float> plane = splat.readMap();
  // The floor spans exactly one patch, centred at the origin: floor texel i sits at plane texel i + M/2.
  splat.runFloor(floorOf(32.0, 9, [](double, double) { return 6.0; }));
  const std::vector<float> floor = splat.readFloorMap();
  const int m = 64;
  double worst = 0;
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < m; ++i) {
      const double a = floor[size_t(j) * m + i], b = plane[size_t((j + m / 2) % m) * m + (i + m / 2) % m];
      worst = std::max(worst, std::fabs(a - b) / std::max(b, 0.05));
    }
  // The same rays land at the same points; only float summation order and the walk's bisection
  // (≤ 1e-6 m) differ.
  EXPECT_LT(worst, 2e-3);
}

TEST(CausticsFloor, CalmSeaOverASlopeIsUniform) {
  OceanPass ocean(device(), sea(0.0));
  ocean.run(0.0);
  const double c = 0.1, zenith = 40 * std::numbers::pi / 180, ior = 1.333;
  CausticsPass splat(device(), ocean.maps(), sun(40, c));
  // A floor sloping from 2 m to 20 m across 60 m, with a bump.
  splat.runFloor(floorOf(60.0, 31, [](double x, double z) {
    return 11.0 + 0.3 * x + 2.0 * std::exp(-(x * x + z * z) / 50.0);
  }));
  const std::vector<float> floor = splat.readFloorMap();
  const double T = 1 - seasim::kmath_d::fresnel_reflectance(std::cos(zenith), 1.0, ior);
  const double sin_t = std::sin(zenith) / ior, cos_t = std::sqrt(1 - sin_t * sin_t);
  const double az = 0.4;  // sun() azimuth: the rays travel along -(sin θt cos az, cos θt, sin θt sin az)
  // Every texel sees parallel rays: T e^{-c depth / cos θt} times the slope's Lambert cosine relative
  // to a level floor, (-t·n̂)/cos θt with n̂ ∝ (∂h/∂x, 1, ∂h/∂z) (the floor is y = -h).
  const int m = 64;
  double worst = 0;
  for (int j = 1; j < m - 1; ++j)
    for (int i = 1; i < m - 1; ++i) {
      const double x = -30 + (i + 0.5) * 60.0 / m, z = -30 + (j + 0.5) * 60.0 / m;
      const double bump = 2.0 * std::exp(-(x * x + z * z) / 50.0);
      const double d = 11.0 + 0.3 * x + bump;
      const double hx = 0.3 - bump * 2 * x / 50.0, hz = -bump * 2 * z / 50.0;
      const double lambert = (sin_t * std::cos(az) * hx + cos_t + sin_t * std::sin(az) * hz) /
                             std::sqrt(hx * hx + 1 + hz * hz) / cos_t;
      const double expected = T * std::exp(-c * d / cos_t) * lambert;
      worst = std::max(worst, std::fabs(floor[size_t(j) * m + i] - expected) / expected);
    }
  // Bilinear splats of a regular ray lattice onto a coarser map: a few % ripple at most; the
  // attenuation's depth dependence is resolved (it spans a factor 3.7 across the floor).
  EXPECT_LT(worst, 0.05);
}

TEST(CausticsFloor, WavesMoveLightButKeepTheMean) {
  OceanPass ocean(device(), sea(8.0));
  ocean.run(2.0);
  CausticsPass splat(device(), ocean.maps(), sun(25));
  splat.run(8.0);
  const double plane_mean = mean(splat.readMap());
  splat.runFloor(floorOf(64.0, 17, [](double x, double) { return 8.0 + 0.1 * x; }));  // 4.8 .. 11.2 m
  const std::vector<float> floor = splat.readFloorMap();
  double sd = 0;
  const double m = mean(floor);
  for (float v : floor) sd += (v - m) * (v - m);
  sd = std::sqrt(sd / floor.size());
  // No attenuation: what lands is what entered, so on a plane slope the mean is the level floor's
  // times the slope's Lambert cosine for the mean refracted direction, (-t·n̂)/cos θt (1.026 here).
  const double sin_t = std::sin(25 * std::numbers::pi / 180) / 1.333, cos_t = std::sqrt(1 - sin_t * sin_t);
  const double lambert = (sin_t * std::cos(0.4) * 0.1 + cos_t) / std::sqrt(1.01) / cos_t;
  std::printf("floor mean %.5f, plane mean %.5f x Lambert %.5f, sd %.4f\n", m, plane_mean, lambert, sd);
  EXPECT_NEAR(m, plane_mean * lambert, 0.01 * plane_mean);
  EXPECT_GT(sd, 0.1 * m);                         // and there is a pattern
}

TEST(CausticsFloor, SteepWavesGrazingSunAndShallowFloorStayFinite) {
  OceanConfig rough = sea(20.0);
  rough.choppiness = 2.5;
  OceanPass ocean(device(), rough);
  ocean.run(3.0);
  for (double zenith : {10.0, 89.0}) {
    CausticsPass splat(device(), ocean.maps(), sun(zenith, 0.2));
    splat.runFloor(floorOf(40.0, 11, [](double x, double) { return std::max(0.0, 0.5 + 0.2 * x); }));
    for (float v : splat.readFloorMap()) ASSERT_TRUE(std::isfinite(v) && v >= 0) << zenith;
  }
  CausticsPass below(device(), ocean.maps(), sun(95));
  below.runFloor(floorOf(40.0, 11, [](double, double) { return 5.0; }));
  for (float v : below.readFloorMap()) ASSERT_EQ(v, 0.0f);
}

TEST(CausticsFloor, AFloorTooLargeForTheSurfaceGridIsAClearError) {
  OceanPass ocean(device(), sea(7.0));
  ocean.run(0.0);
  CausticsPass splat(device(), ocean.maps(), sun(30));
  // 64 texels × 2 rays over a 32 m patch: a 20 km floor needs > 65536 rays per side.
  try {
    splat.runFloor(floorOf(20000.0, 3, [](double, double) { return 5.0; }));
    ADD_FAILURE() << "no error";
  } catch (const seasim::RuntimeError& e) {
    EXPECT_NE(std::string(e.what()).find("lower the ocean grid or supersample"), std::string::npos) << e.what();
  }
}

}  // namespace
