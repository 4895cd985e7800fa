// caustics_test.cpp — kernels/caustics.cl (CausticsPass) under the FFT ocean: a flat sea gives a
// uniform map equal to T(θ) e^{-c d / cos θt}; flux is conserved (the flux on the plane equals the
// flux through the surface times its Fresnel transmittance and Beer–Lambert attenuation, to 1 %,
// against a CPU double sum over the same rays); a wavy sea focuses light (contrast rises with depth);
// a sun below the horizon gives an empty map.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <vector>

#include "device/device.h"
#include "test_device.h"
#include "math/kernel_math.h"
#include "passes/caustics_pass.h"
#include "passes/ocean_pass.h"

namespace {

using seasim::CausticsConfig;
using seasim::CausticsPass;
using seasim::OceanConfig;
using seasim::OceanPass;
namespace km = seasim::kmath_d;

seasim::Device& device() { return seasim::test::testDevice(); }

OceanConfig sea() {
  OceanConfig c;
  c.grid = 64;
  c.patch_size = 40.0;
  c.wind_speed = 7.0;
  c.choppiness = 0.5;
  c.seed = 11;
  return c;
}

double mapFlux(const std::vector<float>& map, double patch, double sun_y) {
  const double texel = patch / std::sqrt(static_cast<double>(map.size()));
  double sum = 0;
  for (float v : map) sum += v;
  return sum * texel * texel * sun_y;
}

// The same rays in double from the ocean's fields (slot-major float pairs): returns the flux
// through the surface (sun-facing facets) and what arrives at depth d after T and attenuation.
void referenceFlux(const std::vector<float>& fields, const OceanConfig& oc, const CausticsConfig& cc,
                   double* through, double* arriving) {
  const int n = oc.grid, s = cc.supersample;
  const size_t nn = static_cast<size_t>(n) * n;
  auto field = [&](int c, int i, int j) {
    i &= n - 1;
    j &= n - 1;
    return static_cast<double>(fields[(c / 2) * 2 * nn + 2 * (static_cast<size_t>(j) * n + i) + (c % 2)]);
  };
  const km::real3 sun{std::sin(cc.sun_zenith) * std::cos(cc.sun_azimuth), std::cos(cc.sun_zenith),
                      std::sin(cc.sun_zenith) * std::sin(cc.sun_azimuth)};
  const double cell = oc.patch_size / n, lambda = oc.choppiness, dA = (cell / s) * (cell / s);
  *through = 0;
  *arriving = 0;
  for (int J = 0; J < n * s; ++J)
    for (int I = 0; I < n * s; ++I) {
      const double u = (I + 0.5) / s, v = (J + 0.5) / s;
      const int i0 = static_cast<int>(std::floor(u)), j0 = static_cast<int>(std::floor(v));
      const double wx = u - i0, wz = v - j0;
      double f[8];
      for (int c = 0; c < 8; ++c)
        f[c] = (1 - wz) * ((1 - wx) * field(c, i0, j0) + wx * field(c, i0 + 1, j0)) +
               wz * ((1 - wx) * field(c, i0, j0 + 1) + wx * field(c, i0 + 1, j0 + 1));
      const km::real3 tx{1 + lambda * f[5], f[1], lambda * f[7]};
      const km::real3 tz{lambda * f[7], f[2], 1 + lambda * f[6]};
      const km::real3 na = km::cross(tz, tx);
      const double projected = km::dot(sun, na);
      if (!(projected > 0)) continue;
      const km::real3 nrm = km::normalize(na);
      const double T = 1 - km::fresnel_reflectance(projected / km::length(na), 1.0, cc.ior);
      km::real3 t;
      km::refract_dir(-sun, nrm, 1.0 / cc.ior, &t);
      if (!(t.y < 0)) continue;
      const double path = std::max(f[0] + cc.plane_depth, 0.0) / -t.y;
      *through += projected * dA;
      *arriving += projected * dA * T * std::exp(-cc.attenuation * path);
    }
}

TEST(Caustics, FlatSurfaceGivesUniformMap) {
  OceanConfig oc = sea();
  oc.wind_speed = 0.0;
  OceanPass ocean(device(), oc);
  ocean.run(0.0);
  CausticsConfig cc;
  cc.sun_zenith = 30.0 * std::numbers::pi / 180;
  cc.sun_azimuth = 0.4;
  cc.attenuation = 0.1;
  cc.plane_depth = 5.0;
  CausticsPass caustics(device(), ocean.maps(), cc);
  caustics.run();
  const auto map = caustics.readMap();
  const double cos_i = std::cos(cc.sun_zenith);
  const double T = 1 - km::fresnel_reflectance(cos_i, 1.0, cc.ior);
  const double cos_t = std::sqrt(km::snell_cos_t2(cos_i, 1.0 / cc.ior));
  const double expect = T * std::exp(-cc.attenuation * cc.plane_depth / cos_t);
  for (float v : map) ASSERT_NEAR(v, expect, 1e-5 * expect);
}

TEST(Caustics, FluxIsConserved) {
  const OceanConfig oc = sea();
  OceanPass ocean(device(), oc);
  ocean.run(1.3);
  CausticsConfig cc;
  cc.sun_zenith = 25.0 * std::numbers::pi / 180;
  cc.sun_azimuth = 1.0;
  cc.attenuation = 0.08;
  const auto fields = ocean.readFields();
  for (double depth : {2.0, 10.0}) {
    cc.plane_depth = depth;
    CausticsPass caustics(device(), ocean.maps(), cc);
    caustics.run();
    const auto map = caustics.readMap();
    double through = 0, arriving = 0;
    referenceFlux(fields, oc, cc, &through, &arriving);
    const double sun_y = std::cos(cc.sun_zenith);
    // The periodic surface intercepts what a flat one would: ŝ_y L² (up to back-facing facets).
    EXPECT_NEAR(through / (sun_y * oc.patch_size * oc.patch_size), 1.0, 0.01);
    EXPECT_NEAR(mapFlux(map, oc.patch_size, sun_y) / arriving, 1.0, 0.01) << "depth " << depth;
    for (float v : map) ASSERT_TRUE(std::isfinite(v) && v >= 0);
  }
}

TEST(Caustics, WavesFocusLightMoreWithDepthAndPdfIsNormalised) {
  const OceanConfig oc = sea();
  OceanPass ocean(device(), oc);
  ocean.run(0.0);
  CausticsConfig cc;
  CausticsPass caustics(device(), ocean.maps(), cc);
  auto contrast = [&](double depth) {
    caustics.run(depth);
    const auto map = caustics.readMap();
    double mean = 0, m2 = 0;
    for (float v : map) mean += v;
    mean /= map.size();
    for (float v : map) m2 += (v - mean) * (v - mean);
    const auto pdf = seasim::causticIntensityPdf(map, 50, 5.0);
    double integral = 0;
    for (double d : pdf) integral += d * 0.1;
    EXPECT_NEAR(integral, 1.0, 1e-9);
    return std::sqrt(m2 / map.size()) / mean;
  };
  const double c_half = contrast(0.5), c2 = contrast(2.0), c10 = contrast(10.0);
  std::printf("caustic contrast (std/mean): 0.5 m %.3f, 2 m %.3f, 10 m %.3f\n", c_half, c2, c10);
  EXPECT_GT(c2, c_half);
  EXPECT_GT(c10, 0.05);
}

TEST(Caustics, SunBelowHorizonGivesNoLight) {
  OceanPass ocean(device(), sea());
  ocean.run(0.0);
  CausticsConfig cc;
  cc.sun_zenith = 95.0 * std::numbers::pi / 180;
  CausticsPass caustics(device(), ocean.maps(), cc);
  caustics.run();
  for (float v : caustics.readMap()) ASSERT_EQ(v, 0.0f);
}

}  // namespace
