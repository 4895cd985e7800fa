// sea_slab_mc_test.cpp — host/reference/sea_slab_mc (a per-order Monte Carlo of the flat sea of paper
// 000) against the model's closed forms and references: order 1 = the exact single-scattering
// integral, order 2 = the direct integration of L^(2) (host/reference/sea_second_reference), the
// bottom's direct term = eq. 9, and the energy check: single + second order <= all orders
// for an albedo-0.9 medium, with the share of orders >= 3 reported. Stiff: b -> 0, grazing sun and view.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "reference/sea_second_reference.h"
#include "reference/sea_slab_mc.h"
#include "scene/scene_parser.h"
#include "spectral/sensor.h"
#include "spectral/wavelength_grid.h"
#include "util/error.h"

namespace {

using seasim::SlabMcSetup;

constexpr double kDeg = M_PI / 180;

// The geometry of the sea scenes: camera 10 m up looking at (0, 0, -60), sun 40 deg from the zenith.
SlabMcSetup baseSetup() {
  SlabMcSetup s;
  s.sun_zenith = 40 * kDeg;
  s.sun_azimuth = 90 * kDeg;
  s.view = seasim::normalize(seasim::Vec3{0, -10, -60});
  s.a = 0.05;
  s.b = 0.2;
  s.g = 0.9;
  return s;
}

// A one-pixel, one-band scene with the water, bottom and sun of `s` (view: the camera looks along
// (0, y, -1) so the single pixel's direction is the camera's forward axis).
seasim::Scene sceneOf(const SlabMcSetup& s) {
  char text[2048];
  std::snprintf(text, sizeof text, R"(
[scene]
name = "slab_mc"
[camera]
position = [0, 10, 0]
look_at = [%.17g, %.17g, %.17g]
fov_deg = 30
width = 1
height = 1
[sun]
zenith_deg = %.17g
azimuth_deg = %.17g
[water]
wavelengths_nm = [400, 700]
a = [%.17g, %.17g]
b = [%.17g, %.17g]
g = %.17g
ior = %.17g
%s
[spectral]
count = 1
range_nm = [540, 560]
white_balance = false
[sea]
second_order = true
)",
                s.view.x, 10 + s.view.y, s.view.z, s.sun_zenith / kDeg, s.sun_azimuth / kDeg, s.a, s.a, s.b, s.b, s.g,
                s.ior,
                s.bottom_depth >= 0 ? ("[bottom]\ntype = \"flat\"\ndepth = " + std::to_string(s.bottom_depth) +
                                       "\nalbedo = " + std::to_string(s.bottom_albedo))
                                          .c_str()
                                    : "");
  return seasim::parseScene(text, "slab_mc.toml", {});
}

// L^(2) of the one-pixel scene from the reference, in radiance of the single band (G / its weight).
double referenceSecond(const seasim::Scene& scene, seasim::SeaSecondReferenceSettings settings) {
  const seasim::WavelengthGrid grid =
      seasim::makeGrid(scene.spectral.count, scene.spectral.min_nm, scene.spectral.max_nm);
  const seasim::Sensor sensor = seasim::makeSensor(scene.spectral.sensor, grid, scene.spectral.white_balance, scene.spectral.camera_dir);
  const seasim::Image img = seasim::renderSeaSecondReference(scene, settings);
  return img.pixels[1] / sensor.to_g[0];
}

TEST(SeaSlabMc, SetupFromSceneReproducesTheScene) {
  SlabMcSetup s = baseSetup();
  s.bottom_depth = 8;
  s.bottom_albedo = 0.25;
  const SlabMcSetup t = seasim::slabSetupFromScene(sceneOf(s), 0, 0, 0);
  EXPECT_NEAR(t.view.x, s.view.x, 1e-12);
  EXPECT_NEAR(t.view.y, s.view.y, 1e-12);
  EXPECT_NEAR(t.view.z, s.view.z, 1e-12);
  EXPECT_NEAR(t.sun_zenith, s.sun_zenith, 1e-12);
  EXPECT_NEAR(t.a, s.a, 1e-12);
  EXPECT_NEAR(t.b, s.b, 1e-12);
  EXPECT_NEAR(t.bottom_depth, 8, 1e-12);
  EXPECT_NEAR(t.bottom_albedo, 0.25, 1e-6);
  EXPECT_GT(t.sun_irradiance, 0.5);  // D65 near 550 nm, scale 1
}

TEST(SeaSlabMc, Order1IsTheExactSingleScatteringIntegral) {
  // The order-1 tally against eq. 5 with c_f = 0 (the exact integral): within 4 standard errors, with
  // the noise itself under 0.5 % so the check has teeth. Eq. 5 WITH c_f (sea_single.cl) is not the
  // single-scattering integral: its attenuation c (1 - w0 c_f) < c keeps forward-scattered light in
  // both beams, so it must exceed the exact value by far more than the noise.
  struct Case {
    double g, bottom, zenith_deg;
  };
  for (const Case& k : {Case{0.9, 8, 40}, Case{0.9, -1, 40}, Case{0.0, -1, 70}, Case{0.5, 3, 10}}) {
    SlabMcSetup s = baseSetup();
    s.g = k.g;
    s.bottom_depth = k.bottom;
    s.sun_zenith = k.zenith_deg * kDeg;
    const seasim::SlabMcResult mc = seasim::runSlabMc(s, {1 << 16, 7});
    const double exact = seasim::slabExactSingle(s), paper = seasim::slabPaperSingle(s);
    std::printf("order 1, g %.1f bottom %g sun %g deg: MC %.6g +- %.2g, exact %.6g (%+.2f se), eq. 5 with c_f %.6g\n",
                k.g, k.bottom, k.zenith_deg, mc.order1().mean, mc.order1().std_error, exact,
                (mc.order1().mean - exact) / mc.order1().std_error, paper);
    ASSERT_GT(exact, 0);
    EXPECT_LT(mc.order1().std_error, 5e-3 * exact) << k.g;
    EXPECT_NEAR(mc.order1().mean, exact, 4 * mc.order1().std_error) << "g " << k.g << " bottom " << k.bottom;
    if (k.g > 0) EXPECT_GT(paper, exact + 10 * mc.order1().std_error) << "c_f raises eq. 5 above order 1";
    // The bottom is excluded (albedo 0): nothing in the bottom tallies.
    EXPECT_EQ(mc.bottom_direct.mean, 0.0);
    EXPECT_EQ(mc.bottom_other.mean, 0.0);
  }
}

TEST(SeaSlabMc, BottomDirectIsEquation9) {
  SlabMcSetup s = baseSetup();
  s.bottom_depth = 4;
  s.bottom_albedo = 0.3;
  const seasim::SlabMcResult mc = seasim::runSlabMc(s, {1 << 16, 11});
  const double eq9 = seasim::slabBottomDirect(s);
  ASSERT_GT(eq9, 0);
  EXPECT_NEAR(mc.bottom_direct.mean, eq9, 4 * mc.bottom_direct.std_error);
  EXPECT_LT(mc.bottom_direct.std_error, 0.01 * eq9);
  // The orders are unchanged by the bottom's albedo (paths that touch it are tallied apart).
  SlabMcSetup black = s;
  black.bottom_albedo = 0;
  const seasim::SlabMcResult mc0 = seasim::runSlabMc(black, {1 << 16, 11});
  EXPECT_NEAR(mc.order1().mean, mc0.order1().mean, 1e-12 * mc0.order1().mean);
  EXPECT_GT(mc.bottom_other.mean, 0.0);
}

TEST(SeaSlabMc, Order2IsTheSecondOrderReference) {
  // The order-2 tally against the direct integration of 000 eq. 6 (host/reference/
  // sea_second_reference.cpp, eq. 7 inside) on the same one-pixel scene. The reference's quadrature
  // error is estimated as |L(96, 48) - L(192, 96)| (depth steps, angle steps per lobe) and added.
  struct Case {
    double g, bottom, zenith_deg;
  };
  for (const Case& k : {Case{0.9, 8, 40}, Case{0.5, -1, 20}, Case{0.0, 5, 60}}) {
    SlabMcSetup s = baseSetup();
    s.g = k.g;
    s.bottom_depth = k.bottom;
    s.sun_zenith = k.zenith_deg * kDeg;
    const seasim::Scene scene = sceneOf(s);
    const SlabMcSetup t = seasim::slabSetupFromScene(scene, 0, 0, 0);
    const double coarse = referenceSecond(scene, {96, 48}), fine = referenceSecond(scene, {192, 96});
    const double quad_error = std::fabs(fine - coarse);
    const seasim::SlabMcResult mc = seasim::runSlabMc(t, {1 << 17, 3});
    std::printf("order 2, g %.1f bottom %g sun %g deg: MC %.6g +- %.2g, reference %.6g (%+.2f se, quadrature %.2g)\n",
                k.g, k.bottom, k.zenith_deg, mc.order2().mean, mc.order2().std_error, fine,
                (mc.order2().mean - fine) / mc.order2().std_error, quad_error);
    ASSERT_GT(fine, 0);
    EXPECT_LT(mc.order2().std_error, 0.01 * fine);
    EXPECT_LT(quad_error, 0.01 * fine);
    EXPECT_NEAR(mc.order2().mean, fine, 4 * mc.order2().std_error + quad_error)
        << "g " << k.g << " bottom " << k.bottom << " mc " << mc.order2().mean << " +- " << mc.order2().std_error
        << " reference " << fine << " (quadrature " << quad_error << ")";
  }
}

TEST(SeaSlabMc, EnergyAlbedo09SingleAndSecondBelowAllOrders) {
  // Energy: single + second order <= the full multiple-scattering answer, albedo 0.9, deep water.
  SlabMcSetup s = baseSetup();
  s.a = 0.02;
  s.b = 0.18;
  const seasim::Scene scene = sceneOf(s);
  const SlabMcSetup t = seasim::slabSetupFromScene(scene, 0, 0, 0);
  ASSERT_NEAR(t.b / (t.a + t.b), 0.9, 1e-12);
  const double l2 = referenceSecond(scene, {192, 96});
  const double l1_exact = seasim::slabExactSingle(t), l1_paper = seasim::slabPaperSingle(t);
  const seasim::SlabMcResult mc = seasim::runSlabMc(t, {1 << 19, 5});
  const double all = mc.all_orders.mean, se = mc.all_orders.std_error;
  const double share3 = mc.orders_3plus.mean / all;
  std::printf("albedo 0.9, g 0.9, deep: L1 exact %.5g, L1 eq.5 (c_f) %.5g, L2 %.5g; MC order1 %.5g order2 %.5g "
              "all %.5g +- %.2g; orders >= 3 carry %.1f %% of all; (L1 exact + L2)/all = %.3f, "
              "(L1 eq.5 + L2)/all = %.3f\n",
              l1_exact, l1_paper, l2, mc.order1().mean, mc.order2().mean, all, se, 100 * share3,
              (l1_exact + l2) / all, (l1_paper + l2) / all);
  ::testing::Test::RecordProperty("orders_3plus_share", std::to_string(share3));
  EXPECT_LT(se, 0.02 * all);  // orders >= 3 carry the variance (NEE of the g = 0.9 lobe at every vertex)
  // The exact single + second order is a partial sum of the Neumann series: below the total, and
  // short of it by the orders >= 3 (which the Monte Carlo measures independently).
  EXPECT_LE(l1_exact + l2, all + 4 * se);
  EXPECT_NEAR(all - (l1_exact + l2), mc.orders_3plus.mean, 4 * (se + mc.orders_3plus.std_error) + 0.01 * l2);
  EXPECT_GT(share3, 0.05);
  EXPECT_LT(share3, 0.95);
  // The model's own L1 (eq. 5 with c_f) + L2 also stays below the full answer here: the c_f term
  // adds back part of the forward-scattered orders >= 2, less than orders >= 3 carry (measured).
  EXPECT_LE(l1_paper + l2, all + 4 * se);
  // The surface reflecting light back down from below (left out by the model) only adds.
  SlabMcSetup reflecting = t;
  reflecting.internal_reflection = true;
  const seasim::SlabMcResult mc_r = seasim::runSlabMc(reflecting, {1 << 16, 5});
  EXPECT_GE(mc_r.all_orders.mean + 4 * mc_r.all_orders.std_error, all);
}

TEST(SeaSlabMc, VanishingScatteringAndGrazingAngles) {
  // b -> 0: order k scales like b^k, every tally -> 0; b = 0 and a = b = 0 give exactly 0.
  SlabMcSetup s = baseSetup();
  s.bottom_depth = 6;
  s.bottom_albedo = 0;
  for (double b : {1e-3, 1e-6, 1e-9}) {
    s.b = b;
    const seasim::SlabMcResult mc = seasim::runSlabMc(s, {1 << 12, 1});
    const double exact = seasim::slabExactSingle(s);
    EXPECT_NEAR(mc.order1().mean, exact, 4 * mc.order1().std_error + 1e-12 * exact) << b;
    EXPECT_LT(mc.order2().mean, 50 * b * exact) << b;   // ~ b z exact
    EXPECT_LT(mc.all_orders.mean, 1.1 * exact + 1e-300) << b;
    EXPECT_LT(exact, 1e3 * b) << b;                       // order 1 itself ~ b
  }
  for (double a : {0.05, 0.0}) {
    s.a = a;
    s.b = 0;
    const seasim::SlabMcResult mc = seasim::runSlabMc(s, {256, 1});
    EXPECT_EQ(mc.all_orders.mean, 0.0);
    EXPECT_EQ(seasim::slabExactSingle(s), 0.0);
    EXPECT_EQ(seasim::slabPaperSingle(s), 0.0);
  }
  // Grazing and below-horizon sun, grazing and vertical views, with a bright bottom: finite, >= 0;
  // a sun at or below the horizon gives exactly 0.
  s = baseSetup();
  s.bottom_depth = 5;
  s.bottom_albedo = 0.5;
  for (double zen : {0.0, 89.99, 90.0, 100.0}) {
    for (seasim::Vec3 v : {seasim::Vec3{0, -1, 0}, seasim::Vec3{0, -1e-7, -1}, seasim::Vec3{1, -1e-12, 0},
                           seasim::Vec3{0, 0, -1}, seasim::Vec3{0, 0.2, -1}}) {
      s.sun_zenith = zen * kDeg;
      s.view = seasim::normalize(v);
      const seasim::SlabMcResult mc = seasim::runSlabMc(s, {2048, 2});
      for (const seasim::SlabMcEstimate& e : {mc.order1(), mc.order2(), mc.orders_3plus, mc.all_orders,
                                              mc.bottom_direct, mc.bottom_other}) {
        EXPECT_TRUE(std::isfinite(e.mean) && std::isfinite(e.std_error)) << zen << " " << v.y;
        EXPECT_GE(e.mean, 0.0);
        // cos(90 deg) = 6e-17 in double: a sun AT the horizon leaves ~1e-45, not exactly 0.
        if (zen > 90 || v.y >= 0) EXPECT_EQ(e.mean, 0.0) << zen << " " << v.y;
        if (zen == 90) EXPECT_LT(e.mean, 1e-30);
      }
      for (double L : {seasim::slabExactSingle(s), seasim::slabPaperSingle(s), seasim::slabBottomDirect(s)}) {
        EXPECT_TRUE(std::isfinite(L) && L >= 0) << zen << " " << v.y;
        if (zen > 90 || v.y >= 0) EXPECT_EQ(L, 0.0);
        if (zen == 90) EXPECT_LT(L, 1e-30);
      }
    }
  }
}

TEST(SeaSlabMc, DeterministicAndSeeded) {
  SlabMcSetup s = baseSetup();
  const seasim::SlabMcResult a = seasim::runSlabMc(s, {5000, 9}), b = seasim::runSlabMc(s, {5000, 9});
  const seasim::SlabMcResult c = seasim::runSlabMc(s, {5000, 10});
  EXPECT_EQ(a.all_orders.mean, b.all_orders.mean);  // bit for bit: fixed chunks summed in order
  EXPECT_EQ(a.order2().std_error, b.order2().std_error);
  EXPECT_NE(a.all_orders.mean, c.all_orders.mean);
  SlabMcSetup bad = s;
  bad.g = 1.0;
  EXPECT_THROW(seasim::runSlabMc(bad), seasim::RuntimeError);
}

}  // namespace
