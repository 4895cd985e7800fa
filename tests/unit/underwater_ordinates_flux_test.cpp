// underwater_ordinates_flux_test.cpp — the discrete-ordinates model's flux term scale
// (host/underwater/underwater_ordinates_setup.*): the fitted table s(g), the band's g_flux = s g', the
// in-scatter source's flux term following g_flux (not the two-stream's g'), the set-up taking s from the
// table or from underwater.flux_scale, and the key's file:line:key errors.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "math/kernel_math.h"
#include "scene/scene_parser.h"
#include "spectral/sensor.h"
#include "spectral/wavelength_grid.h"
#include "underwater/underwater_ordinates_solver.h"
#include "underwater/underwater_ordinates_setup.h"
#include "underwater/underwater_setup.h"

#include "underwater_ordinates_fixtures.h"

namespace {

namespace kd = seasim::kmath_d;
using seasim::diffuseFluxScale;
using seasim::DiffuseDepth;
using seasim::makeUwiBand;

UwBand band(double a, double b) { return seasim::testing::uwTestBand(a, b, 0.3, 1.0, 0.8, 0.2); }

// The table at its knots, linear between, held outside; >= 1 and finite everywhere (the first-order
// expansion is the lower bound the fit never went under).
TEST(UnderwaterOrdinatesFlux, TableAtKnotsBetweenAndOutside) {
  EXPECT_DOUBLE_EQ(diffuseFluxScale(0.0), 1.0);
  EXPECT_DOUBLE_EQ(diffuseFluxScale(0.5), 1.3);
  EXPECT_DOUBLE_EQ(diffuseFluxScale(0.9), 1.6);
  EXPECT_DOUBLE_EQ(diffuseFluxScale(0.95), 1.3);
  EXPECT_NEAR(diffuseFluxScale(0.7), 1.45, 1e-12);
  EXPECT_NEAR(diffuseFluxScale(0.25), 1.15, 1e-12);
  EXPECT_DOUBLE_EQ(diffuseFluxScale(-0.5), 1.0);
  EXPECT_DOUBLE_EQ(diffuseFluxScale(0.99), 1.3);
  for (double g = -1; g <= 1.0001; g += 0.01) {
    const double s = diffuseFluxScale(g);
    EXPECT_TRUE(std::isfinite(s)) << g;
    EXPECT_GE(s, 1.0) << g;
  }
  EXPECT_DOUBLE_EQ(diffuseFluxScale(std::nan("")), 1.0);
}

// g_flux = s g'; g_dm (which the two-stream and the tests of it use) stays g / (1 + g); the two-stream's
// solution does not depend on s.
TEST(UnderwaterOrdinatesFlux, BandCarriesTheScaledAsymmetryOnly) {
  const UwBand b = band(0.1, 0.3);
  const auto mean = seasim::diffuseMeanCosines(0.9);
  const UwiBand one = makeUwiBand(b, 0.9, 0.8, 5.0, 1.34, mean, seasim::twoStreamClosure(), DiffuseDepth{3.0, 0.4, 1.0});
  const UwiBand two = makeUwiBand(b, 0.9, 0.8, 5.0, 1.34, mean, seasim::twoStreamClosure(), DiffuseDepth{3.0, 0.4, 1.6});
  EXPECT_FLOAT_EQ(one.g_dm, float(0.9 / 1.9));
  EXPECT_FLOAT_EQ(one.g_flux, one.g_dm);
  EXPECT_FLOAT_EQ(two.g_flux, float(1.6 * 0.9 / 1.9));
  EXPECT_EQ(two.g_dm, one.g_dm);
  EXPECT_EQ(two.k, one.k);
  EXPECT_EQ(two.d1, one.d1);
  EXPECT_EQ(two.u2, one.u2);
  EXPECT_EQ(two.dp, one.dp);
  // The plain form (no depth, no table) is the first-order expansion.
  EXPECT_EQ(makeUwiBand(b, 0.9, 0.8, 5.0, 1.34).g_flux, makeUwiBand(b, 0.9, 0.8, 5.0, 1.34).g_dm);
}

// The source's flux term, its odd part in ν, is 3 g_flux ν (D - U) b'/(4π): scaling s scales it, the
// even part (the scalar irradiance) is unchanged. Would fail if the kernel's formula kept g'.
TEST(UnderwaterOrdinatesFlux, SourceFluxTermFollowsTheScale) {
  const UwBand b = band(0.4, 1.2);
  const auto mean = seasim::diffuseMeanCosines(0.9);
  for (double s : {1.0, 1.6, 2.5}) {
    const UwiBand ib = makeUwiBand(b, 0.9, 0.8, 0.0, 1.34, mean, seasim::twoStreamClosure(), DiffuseDepth{2.0, 0.4, s});
    // The first exponential's source (the table holds the two-stream's first-order form) at ±ν on nodes.
    const double nu = 0.625, cos_dphi = -0.4;
    const int node_up = kd::uwi_source_node(nu), node_down = kd::uwi_source_node(-nu);
    const double up = kd::uwi_source_weight(&ib, node_up, cos_dphi, 0);
    const double down = kd::uwi_source_weight(&ib, node_down, cos_dphi, 0);
    const double odd = 0.5 * (up - down), even = 0.5 * (up + down);
    EXPECT_NEAR(odd, ib.b_dm * 3 * s * (0.9 / 1.9) * nu * (ib.d1 - ib.u1) / (4 * M_PI), 1e-6 * std::abs(odd)) << s;
    // The even part: the scalar irradiance (the two streams carry no horizontal flux).
    EXPECT_NEAR(even, ib.b_dm * ib.o1 / (4 * M_PI), 1e-6 * even) << s;
  }
}

using seasim::testing::kOrdinatesScene;

// The set-up takes s from the table at the water's g by default, or from the key; bad values name the
// file, line and key.
TEST(UnderwaterOrdinatesFlux, SetUpTakesTheTableOrTheKey) {
  using namespace seasim;
  const WavelengthGrid grid = makeGrid(4, 400, 700);
  const Sensor sensor = makeSensor("cie1931", grid, true, "");
  const Scene plain = parseScene(kOrdinatesScene, "uw.toml");
  EXPECT_EQ(plain.underwater.flux_scale, -1.0);
  const UnderwaterSetup p = makeUnderwaterSetup(plain, grid, sensor);
  ASSERT_GT(p.params.g, 0.0f);
  const double g_dm = p.params.g / (1.0 + p.params.g);
  // The two-stream's flux term takes its table's s(g), or the key's.
  const std::string two_stream = seasim::testing::twoStreamScene();
  const UnderwaterSetup t = makeUnderwaterSetup(parseScene(two_stream, "uw.toml"), grid, sensor);
  EXPECT_FLOAT_EQ(t.ordinates[1].g_flux, float(diffuseFluxScale(p.params.g) * g_dm));
  const UnderwaterSetup tk = makeUnderwaterSetup(parseScene(two_stream + "flux_scale = 2\n", "uw.toml"), grid, sensor);
  EXPECT_FLOAT_EQ(tk.ordinates[1].g_flux, float(2 * g_dm));
  EXPECT_EQ(tk.ordinates[1].k, t.ordinates[1].k);
  EXPECT_NE(tk.ordinates[1].src[0], t.ordinates[1].src[0]);
  // The discrete ordinates (the default) have no flux term to scale: their source is their own
  // in-scatter, the same with the key.
  const UnderwaterSetup dk =
      makeUnderwaterSetup(parseScene(std::string(kOrdinatesScene) + "flux_scale = 2\n", "uw.toml"), grid, sensor);
  for (int q = 0; q < UWI_SOURCE_NODES * UWI_SOURCE_TERMS; ++q) ASSERT_EQ(dk.ordinates[1].src[q], p.ordinates[1].src[q]) << q;
  for (const char* bad : {"flux_scale = 3.5", "flux_scale = -0.5"}) {
    seasim::testing::expectOrdinatesSceneRejects(bad, "underwater.flux_scale");
  }
}

}  // namespace
