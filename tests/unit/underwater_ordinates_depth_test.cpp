// underwater_ordinates_depth_test.cpp — the discrete-ordinates model's k over the depths a frame sees
// (host/underwater/underwater_ordinates_setup.*): the mean log-slope of a two-mode field over
// [0, D] (depthMeanDiffuseK) is the two-stream's k at D = 0 and tends to K∞ deep down, is continuous
// and monotone, finite at the extremes; the band built with it keeps its boundary conditions, never
// NaN at a = 0, H = 0 or without a bottom; the set-up takes D from the camera's depth, and the scene
// key sets w with file:line:key errors.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "math/kernel_math.h"
#include "scene/scene_parser.h"
#include "spectral/sensor.h"
#include "spectral/wavelength_grid.h"
#include "underwater/underwater_ordinates_setup.h"
#include "underwater/underwater_setup.h"

#include "underwater_ordinates_fixtures.h"

namespace {

namespace kd = seasim::kmath_d;
using seasim::depthMeanDiffuseK;
using seasim::DiffuseDepth;
using seasim::makeUwiBand;
using seasim::TwoStreamClosure;

using seasim::testing::uwTestBand;

// The two-mode field's mean log-slope computed the plain way, for moderate D.
double twoModeSlope(double k, double k_inf, double depth, double w) {
  const double k_fast = (k - w * k_inf) / (1 - w);
  return -std::log((1 - w) * std::exp(-k_fast * depth) + w * std::exp(-k_inf * depth)) / depth;
}

TEST(UnderwaterOrdinatesDepth, MeanSlopeOfTwoModes) {
  const double k = 0.35, k_inf = 0.3;
  for (double w : {0.05, 0.2, 0.5, 0.9}) {
    // D = 0 (and D < 0): the two-stream's k exactly; deep: K∞ + ln(1/w)/D, so within 1e-4 at D = 1e5.
    EXPECT_EQ(depthMeanDiffuseK(k, k_inf, 0.0, w), k);
    EXPECT_EQ(depthMeanDiffuseK(k, k_inf, -3.0, w), k);
    EXPECT_NEAR(depthMeanDiffuseK(k, k_inf, 1e5, w), k_inf, std::log(1 / w) / 1e5 + 1e-12) << w;
    EXPECT_GT(depthMeanDiffuseK(k, k_inf, 1e5, w), k_inf) << w;
    // The closed form is the slope of E(D)/E(0) of the field it names.
    for (double depth : {0.5, 3.0, 18.8, 60.0})
      EXPECT_NEAR(depthMeanDiffuseK(k, k_inf, depth, w), twoModeSlope(k, k_inf, depth, w), 1e-12) << w << " " << depth;
    // Near the surface k - D w (k - K∞)² / (2 (1 - w)) + O(D²): no cancellation at tiny D (log1p/expm1).
    for (double depth : {1e-3, 1e-8, 1e-200}) {
      const double expected = k - depth * w * (k - k_inf) * (k - k_inf) / (2 * (1 - w));
      EXPECT_NEAR(depthMeanDiffuseK(k, k_inf, depth, w), expected, 2e-2 * depth * depth + 1e-15) << w << " " << depth;
    }
    // Monotone from k down to K∞, and continuous: steps of 1 mm move it by at most 1e-3 (k - K∞) per m.
    double prev = k;
    for (int i = 1; i <= 100000; ++i) {
      const double depth = i * 1e-3;
      const double kd_ = depthMeanDiffuseK(k, k_inf, depth, w);
      ASSERT_LE(kd_, prev + 1e-15) << w << " " << depth;
      ASSERT_GE(kd_, k_inf) << w << " " << depth;
      ASSERT_LE(prev - kd_, 1e-3 * (k - k_inf)) << w << " " << depth;
      prev = kd_;
    }
  }
  // w = 0: the two-stream's k at any depth; w = 1: all asymptotic; no gap (k <= K∞): k.
  EXPECT_EQ(depthMeanDiffuseK(k, k_inf, 20.0, 0.0), k);
  EXPECT_EQ(depthMeanDiffuseK(k, k_inf, 20.0, 1.0), k_inf);
  EXPECT_EQ(depthMeanDiffuseK(k_inf, k, 20.0, 0.3), k_inf);
  // Continuous in w at both ends.
  EXPECT_NEAR(depthMeanDiffuseK(k, k_inf, 20.0, 1e-9), k, 1e-9);
  EXPECT_NEAR(depthMeanDiffuseK(k, k_inf, 20.0, 1 - 1e-9), k_inf, 1e-9);
  // Finite where e^{-q} underflows (w > 0 keeps the log at ln w).
  EXPECT_NEAR(depthMeanDiffuseK(100.0, 1.0, 1e4, 0.2), 1.0 + std::log(5.0) / 1e4, 1e-12);
}

TEST(UnderwaterOrdinatesDepth, AsymptoticK) {
  // The similarity medium's K∞ = c_s κ(ω_s); isotropic ω = 0.75 (a = 0.1, 2 b_back = 0.3): 0.77552 c.
  EXPECT_NEAR(seasim::asymptoticDiffuseK(0.1, 0.15), 0.4 * 0.77552, 1e-4);
  EXPECT_NEAR(seasim::asymptoticDiffuseK(0.2, 0.0), 0.2, 1e-12);  // no scattering: the absorption
  EXPECT_EQ(seasim::asymptoticDiffuseK(0.0, 0.3), 0.0);           // nothing absorbed: no decay
  EXPECT_EQ(seasim::asymptoticDiffuseK(0.0, 0.0), 0.0);
  // Always below the two-stream's diffusion k √3 √(a (a + 2 b_back)).
  for (double a : {0.01, 0.1, 0.4, 2.0})
    for (double bb : {0.001, 0.05, 0.3, 1.0})
      EXPECT_LT(seasim::asymptoticDiffuseK(a, bb), std::sqrt(3.0 * a * (a + 2 * bb))) << a << " " << bb;
}

// E_d(0) = e_sky0 + r_s E_u(0) and E_u(H) = ρ (E_d(H) + e_sun0 e^{-m H}) hold for the band built
// with the depth's k, as for the two-stream's.
void expectBoundaries(const UwiBand& ib, const UwBand& bd, double H, double ior) {
  double ed0, eu0;
  kd::uwi_irradiance(&ib, H, 0.0, &ed0, &eu0);
  const double rs = seasim::internalDiffuseReflectance(ior);
  EXPECT_NEAR(ed0, bd.e_sky0 + rs * eu0, 2e-5 * (1 + std::abs(ed0)));
  if (H > 0) {
    double edh, euh;
    kd::uwi_irradiance(&ib, H, H, &edh, &euh);
    EXPECT_NEAR(euh, bd.bottom_albedo * (edh + bd.e_sun0 * std::exp(-double(ib.m) * H)), 2e-5 * (1 + std::abs(euh)));
  }
}

bool finite(const UwiBand& ib) {
  const float* f = &ib.c_dm;
  for (int i = 0; i < 15; ++i)
    if (!std::isfinite(f[i])) return false;
  return true;
}

TEST(UnderwaterOrdinatesDepth, BandTakesTheDepthsK) {
  const double mu = 0.8, ior = 1.34;
  for (double g : {0.0, 0.5, 0.9}) {
    for (double H : {0.0, 5.0, 20.0}) {
      const UwBand bd = uwTestBand(0.1, 0.3, 0.3, 1.0, mu, 0.35);
      const seasim::DiffuseMeanCosines mean = seasim::diffuseMeanCosines(g);
      const UwiBand surface = makeUwiBand(bd, g, mu, H, ior, mean, TwoStreamClosure::Quadrature);
      // D = 0 or w = 0: the two-stream's band, every value.
      for (DiffuseDepth off : {DiffuseDepth{0.0, 0.3}, DiffuseDepth{10.0, 0.0}}) {
        const UwiBand same = makeUwiBand(bd, g, mu, H, ior, mean, TwoStreamClosure::Quadrature, off);
        EXPECT_EQ(same.k, surface.k);
        EXPECT_EQ(same.d1, surface.d1);
        EXPECT_EQ(same.u2, surface.u2);
        EXPECT_EQ(same.dp, surface.dp);
      }
      // At depth: the mean slope, smaller; the two-stream's reflectance r = u1/d1 kept; boundaries hold.
      const double bb = surface.b_dm * (1 - surface.g_dm) / 2;
      const double k_inf = seasim::asymptoticDiffuseK(0.1, bb);
      const UwiBand deep = makeUwiBand(bd, g, mu, H, ior, mean, TwoStreamClosure::Quadrature, {18.8, 0.3});
      EXPECT_NEAR(deep.k, depthMeanDiffuseK(surface.k, k_inf, 18.8, 0.3), 1e-6 * surface.k) << g << " " << H;
      EXPECT_LT(deep.k, surface.k);
      EXPECT_GT(deep.k, k_inf);
      EXPECT_NEAR(deep.u1 / deep.d1, surface.u1 / surface.d1, 1e-5) << g << " " << H;
      expectBoundaries(deep, bd, H, ior);
      // Very deep: K∞.
      const UwiBand far = makeUwiBand(bd, g, mu, H, ior, mean, TwoStreamClosure::Quadrature, {1e6, 0.3});
      EXPECT_NEAR(far.k, k_inf, 1e-5 * k_inf) << g << " " << H;
      EXPECT_TRUE(finite(far));
    }
  }
  // No absorption (a = 0: K∞ = 0, k at its floor), no scattering, an empty medium, a deep camera with
  // no bottom: finite everywhere.
  for (auto [a, b] : {std::pair{0.0, 0.3}, std::pair{0.1, 0.0}, std::pair{0.0, 0.0}}) {
    for (double H : {0.0, 5.0}) {
      const UwiBand ib = makeUwiBand(uwTestBand(a, b, 0.3, 1.0, mu, 0.35), 0.9, mu, H, ior, seasim::diffuseMeanCosines(0.9),
                                     TwoStreamClosure::Quadrature, {1e3, 0.5});
      EXPECT_TRUE(finite(ib)) << a << " " << b << " " << H;
      double ed, eu;
      kd::uwi_irradiance(&ib, H, 3.0, &ed, &eu);
      EXPECT_TRUE(std::isfinite(ed) && std::isfinite(eu)) << a << " " << b << " " << H;
    }
  }
}

TEST(UnderwaterOrdinatesDepth, ViewDepthIsTheCamerasWithinTheWater) {
  UwParams p{};
  p.cam_pos[1] = -3.8f;
  EXPECT_FLOAT_EQ(float(seasim::diffuseViewDepth(p)), 3.8f);  // no bottom
  p.bottom_depth = 2.0f;
  EXPECT_FLOAT_EQ(float(seasim::diffuseViewDepth(p)), 2.0f);  // below the bottom: clamped to it
  p.cam_pos[1] = 0.5f;
  EXPECT_EQ(seasim::diffuseViewDepth(p), 0.0);  // above the surface
}

using seasim::testing::kOrdinatesScene;

// With the two-stream's diffuse field (diffuse = "two_stream"), the set-up takes D from the
// camera (so a camera moved in depth changes k: the renderer builds the set-up again and the band table
// follows, tests/kernels/renderer_test.cpp), w from the key or, by default, from the fitted share.
TEST(UnderwaterOrdinatesDepth, SetUpTakesTheCamerasDepthAndTheKey) {
  using namespace seasim;
  const WavelengthGrid grid = makeGrid(4, 400, 700);
  const Sensor sensor = makeSensor("cie1931", grid, true, "");
  const std::string share = "asymptotic_share = 0.4\n";
  Scene shallow = parseScene(seasim::testing::twoStreamScene() + share, "uw.toml");
  Scene deep = shallow;
  deep.camera.position.y = -20;
  const UnderwaterSetup s = makeUnderwaterSetup(shallow, grid, sensor);
  const UnderwaterSetup d = makeUnderwaterSetup(deep, grid, sensor);
  EXPECT_LT(d.ordinates[1].k, s.ordinates[1].k * 0.999f);
  Scene off = parseScene(seasim::testing::twoStreamScene() + "asymptotic_share = 0\n", "uw.toml");
  const UnderwaterSetup o = makeUnderwaterSetup(off, grid, sensor);
  EXPECT_GT(o.ordinates[1].k, s.ordinates[1].k);
  off.camera.position.y = -20;
  EXPECT_EQ(makeUnderwaterSetup(off, grid, sensor).ordinates[1].k, o.ordinates[1].k);  // w = 0: no depth
  // Default (-1): the fitted share at the water's g.
  const Scene plain = parseScene(seasim::testing::twoStreamScene(), "uw.toml");
  EXPECT_EQ(plain.underwater.asymptotic_share, -1.0);
  const UnderwaterSetup p = makeUnderwaterSetup(plain, grid, sensor);
  const UwiBand expected = makeUwiBand(p.bands[1], p.params.g, p.params.sun_dir_water[1], p.params.bottom_depth,
                                       p.params.ior, diffuseMeanCosines(p.params.g), twoStreamClosure(),
                                       {3.0, diffuseAsymptoticShare(p.params.g)});
  EXPECT_EQ(p.ordinates[1].k, expected.k);
  for (const char* bad : {"asymptotic_share = 1.5", "asymptotic_share = -0.5"}) {
    seasim::testing::expectOrdinatesSceneRejects(bad, "underwater.asymptotic_share");
  }
}

}  // namespace
