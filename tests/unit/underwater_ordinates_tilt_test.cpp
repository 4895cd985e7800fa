// underwater_ordinates_tilt_test.cpp — how the discrete-ordinates underwater model lights an object's face:
// the diffuse irradiance on a tilted plane from the discrete ordinates' radiance
// (DiscreteOrdinates::tiltedIrradianceProfile, its azimuth kernel in closed form), tabulated per band in
// the normal's vertical (UwiBand.tilt) and read by uwi_tilt_irradiance in float and double; the part of it
// the sunlit bottom brings (UwiBand.tilt_bottom, DiscreteOrdinatesLayer::bottom_sunlit) and whether a face
// sees that bottom sunlit (uwi_bottom_visibility); the two-stream's uniform hemispheres.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <vector>

#include "math/kernel_math.h"
#include "underwater/discrete_ordinates.h"
#include "underwater/underwater_ordinates_solver.h"
#include "underwater/underwater_ordinates_setup.h"

#include "underwater_ordinates_fixtures.h"

namespace {

namespace kd = seasim::kmath_d;
namespace kf = seasim::kmath_f;
using seasim::DiscreteOrdinates;
using seasim::DiscreteOrdinatesLayer;
using seasim::FieldPart;
using seasim::testing::uwTestBand;

constexpr double kMuW = seasim::testing::kUwTestMuW;

DiscreteOrdinatesLayer layerOf(const UwBand& b, double g, double H) { return seasim::testing::uwTestLayer(b, g, H); }

// The closed form of ∫ max(0, ν n_y + √((1 - ν²)(1 - n_y²)) cos ψ) cos(m ψ) dψ against the midpoint rule,
// at and near its corners (ν, n_y = ±1, 0; the plane edge-on to the direction).
TEST(UnderwaterOrdinatesTilt, AzimuthKernelIsTheIntegral) {
  const int steps = 200000;
  double worst = 0;
  for (int mode = 0; mode <= 2; ++mode)
    for (double nu : {-1.0, -0.999, -0.7, -0.2, 0.0, 0.3, 0.8, 0.999, 1.0})
      for (double n_y : {-1.0, -0.6, -0.1, 0.0, 0.4, 0.95, 1.0}) {
        const double a = nu * n_y, b = std::sqrt(std::max((1 - nu * nu) * (1 - n_y * n_y), 0.0));
        double sum = 0;
        for (int i = 0; i < steps; ++i) {
          const double psi = 2 * M_PI * (i + 0.5) / steps;
          sum += std::max(0.0, a + b * std::cos(psi)) * std::cos(mode * psi);
        }
        sum *= 2 * M_PI / steps;
        const double k = seasim::tiltedIrradianceKernel(mode, nu, n_y);
        worst = std::max(worst, std::fabs(k - sum));
        EXPECT_NEAR(k, sum, 1e-6) << "mode " << mode << " nu " << nu << " n_y " << n_y;
      }
  std::printf("azimuth kernel vs midpoint rule: largest difference %.2e\n", worst);
  // Mode 0 of a plane facing straight up: 2π ν for light going down, nothing from below.
  EXPECT_NEAR(seasim::tiltedIrradianceKernel(0, 0.5, 1.0), M_PI, 1e-12);
  EXPECT_EQ(seasim::tiltedIrradianceKernel(0, -0.5, 1.0), 0.0);
}

// The solver's tilted irradiance: facing straight up it is E_d, straight down E_u (mode 0); edge-on,
// its cos φ part is half the horizontal flux (mode 1); over 0–5 m of the water.
TEST(UnderwaterOrdinatesTilt, SolversTiltedIrradianceEndsAreItsPlaneIrradiances) {
  const UwBand band = uwTestBand(0.1, 0.3, 0.146, 0.85, kMuW, 0.35);
  const DiscreteOrdinatesLayer layer = layerOf(band, 0.9, 5.0);
  const DiscreteOrdinates m0(layer, 16, 0, 3), m1(layer, 16, 1, 3);
  const int samples = 6;
  const std::vector<double> e0 = m0.tiltedIrradianceProfile({1.0, -1.0}, 5.0, samples);
  const std::vector<double> e1 = m1.tiltedIrradianceProfile({0.0}, 5.0, samples);
  const auto f0 = m0.profile(5.0, samples), f1 = m1.profile(5.0, samples);
  for (int s = 0; s < samples; ++s) {
    EXPECT_NEAR(e0[size_t(s) * 2], f0[s].down, 1e-9 * f0[s].down) << s;
    EXPECT_NEAR(e0[size_t(s) * 2 + 1], f0[s].up, 1e-9 * f0[s].up) << s;
    EXPECT_NEAR(e1[s], 0.5 * f1[s].horizontal, 1e-9 * std::fabs(f1[s].horizontal) + 1e-15) << s;
  }
  EXPECT_GT(f1[2].horizontal, 0.0);  // a real flux towards the sun's azimuth, not 0 = 0
}

// The bottom reflects the share bottom_sunlit of the beam: E_u(H) = ρ (E_d(H) + s e_sun0 e^{-m H}), and
// the field is linear in s. Shares outside [0, 1] are rejected.
TEST(UnderwaterOrdinatesTilt, BottomSunlitShareScalesTheBeamTheBottomReflects) {
  const UwBand band = uwTestBand(0.1, 0.3, 0.146, 0.85, kMuW, 0.35);
  DiscreteOrdinatesLayer layer = layerOf(band, 0.9, 5.0);
  std::vector<seasim::DiscreteOrdinatesIrradiance> at_h(3);
  std::vector<std::vector<seasim::DiscreteOrdinatesIrradiance>> profiles;
  const double shares[3] = {0.0, 0.5, 1.0};
  for (int i = 0; i < 3; ++i) {
    layer.bottom_sunlit = shares[i];
    const DiscreteOrdinates field(layer, 16, 0, 3);
    at_h[i] = field.at(5.0);
    profiles.push_back(field.profile(5.0, 5));
    const double expect = 0.35 * (at_h[i].down + shares[i] * at_h[i].beam_down);
    EXPECT_NEAR(at_h[i].up, expect, 1e-7 * expect) << shares[i];
  }
  EXPECT_LT(at_h[0].up, 0.5 * at_h[2].up);  // the beam is most of what the sand sends up
  for (int s = 0; s < 5; ++s) {
    EXPECT_NEAR(profiles[1][s].down, 0.5 * (profiles[0][s].down + profiles[2][s].down), 1e-9 * profiles[2][s].down);
    EXPECT_NEAR(profiles[1][s].up, 0.5 * (profiles[0][s].up + profiles[2][s].up), 1e-9 * profiles[2][s].up);
  }
  // The bottom's reflection of the whole beam, as the solver gives it apart (its light per unit of what it
  // reflects first, times the beam's irradiance there), is the difference between the sunlit and the shaded
  // bottom, whatever the share it was built with.
  const std::vector<double> n_ys = {-1.0, -0.4, 0.0, 0.6, 1.0};
  std::vector<std::vector<double>> tilted;
  for (double share : {0.0, 1.0, 0.3}) {
    layer.bottom_sunlit = share;
    const DiscreteOrdinates field(layer, 16, 0, 3);
    tilted.push_back(field.tiltedIrradianceProfile(n_ys, 5.0, 4, share == 0.3 ? FieldPart::sand_unit : FieldPart::whole));
    if (share == 0.3)
      for (double& e : tilted.back()) e *= field.sandBeam();
  }
  for (size_t i = 0; i < tilted[0].size(); ++i)
    EXPECT_NEAR(tilted[2][i], tilted[1][i] - tilted[0][i], 1e-7 * tilted[1][i]) << i;
  EXPECT_GT(tilted[2][0], 0.1 * tilted[1][0]);  // facing down at the surface: a real part of its light
  for (double bad : {-0.1, 1.1}) {
    layer.bottom_sunlit = bad;
    EXPECT_THROW(DiscreteOrdinates(layer, 16, 0, 3), std::invalid_argument) << bad;
  }
}

// The field over a bottom of albedo ρ is the field over a black one plus the bottom's light per unit of what
// it reflects first (FieldPart::sand_unit) times what it reflects first: the share bottom_sunlit of the beam
// (sandBeam) and the black bottom's E_d (sandDiffuse). In the tilted irradiance and in the in-scatter, at
// every depth, in clear and turbid water, with the bottom partly sunlit. The bottom's light is positive (it
// only adds light); none without a bottom, none in mode 1.
TEST(UnderwaterOrdinatesTilt, FieldIsTheBlackBottomsPlusWhatTheSandReflects) {
  const std::vector<double> n_ys = {-1.0, -0.4, 0.0, 0.6, 1.0};
  const std::vector<double> nus = {-0.95, -0.5, -0.1, 0.2, 0.7, 1.0};
  for (const auto& [a, b] : {std::pair{0.1, 0.3}, std::pair{0.03, 0.05}, std::pair{0.2, 2.0}}) {
    const UwBand band = uwTestBand(a, b, 0.146, 0.85, kMuW, 0.35);
    DiscreteOrdinatesLayer layer = layerOf(band, 0.9, 5.0);
    layer.bottom_sunlit = 0.6;
    const DiscreteOrdinates whole(layer, 16, 0, 3);
    DiscreteOrdinatesLayer black = layer;
    black.bottom_albedo = 0.0;
    const DiscreteOrdinates dark(black, 16, 0, 3);
    EXPECT_NEAR(whole.sandDiffuse(), dark.at(5.0).down, 1e-12 * whole.sandDiffuse());
    EXPECT_NEAR(whole.sandBeam(), band.e_sun0 * std::exp(-whole.beamK() * 5.0), 1e-12 * whole.sandBeam());
    const double reflected = 0.6 * whole.sandBeam() + whole.sandDiffuse();
    const auto parts = [&](auto profile) {
      const std::vector<double> w = profile(whole, FieldPart::whole), k = profile(dark, FieldPart::whole);
      const std::vector<double> unit = profile(whole, FieldPart::sand_unit);
      for (size_t i = 0; i < w.size(); ++i) {
        EXPECT_NEAR(k[i] + reflected * unit[i], w[i], 1e-9 * std::fabs(w[i]) + 1e-15) << a << " " << b << " " << i;
        EXPECT_GT(unit[i], 0.0) << a << " " << b << " " << i;
      }
    };
    parts([&](const DiscreteOrdinates& f, FieldPart part) { return f.tiltedIrradianceProfile(n_ys, 5.0, 4, part); });
    parts([&](const DiscreteOrdinates& f, FieldPart part) { return f.inscatterProfile(nus, 5.0, 4, part); });
    // Modes 1 and 2 see no Lambertian bottom; nor does open water.
    for (const auto& p : DiscreteOrdinates(layer, 16, 1, 3).inscatterProfile(nus, 5.0, 4, FieldPart::sand_unit))
      EXPECT_EQ(p, 0.0);
    DiscreteOrdinatesLayer open = layer;
    open.bottom_depth = 0.0;
    for (const auto& p : DiscreteOrdinates(open, 16, 0, 3).inscatterProfile(nus, 5.0, 4, FieldPart::sand_unit))
      EXPECT_EQ(p, 0.0);
  }
}

// The solver's irradiance on a plane of normal n at depth y and its azimuth from the sun's (cos_phi):
// Σ_m cos(m φ) of each mode's, at the delta-M order the band is built at.
double solverTilted(const DiscreteOrdinatesLayer& layer, double n_y, double cos_phi, double y) {
  double sum = 0;
  for (int mode = 0; mode <= 2; ++mode) {
    const DiscreteOrdinates field(layer, 16, mode, seasim::kOrdinatesSourceMoments);
    const double c = mode == 0 ? 1.0 : mode == 1 ? cos_phi : 2 * cos_phi * cos_phi - 1;
    sum += c * field.tiltedIrradianceProfile({n_y}, y, 2).back();
  }
  return sum;
}

// The band's table read by the kernel (uwi_tilt_irradiance, double and float) against the solver's tilted
// irradiance at normals between the nodes, three azimuths and three depths, relative to the irradiance on
// a vertical face: within 3 % (the fit's and the interpolation's error), 5 % near the surface of a 20 m
// water and 8 % in turbid water 8 optical depths deep, where three exponentials in depth hold the field
// less well (as E_d's and E_u's, UnderwaterOrdinatesSolver.BandHoldsTheSolversIrradiance); its ends are
// E_d's and E_u's own fits; with
// vis_b = 0 it is the field over a bottom that reflects none of the beam; without a bottom there is no
// bottom part.
TEST(UnderwaterOrdinatesTilt, BandTableHoldsTheSolversTiltedIrradiance) {
  struct Case {
    double a, b, g, H, tolerance;
  };
  for (const Case c : {Case{0.1, 0.3, 0.9, 5, 0.03}, Case{0.03, 0.05, 0.5, 2, 0.03}, Case{0.4, 1.2, 0.95, 5, 0.08},
                       Case{0.1, 0.3, 0.0, 20, 0.05}}) {
    const UwBand band = uwTestBand(c.a, c.b, 0.146, 0.85, kMuW, 0.35);
    seasim::OrdinatesFitError fit;
    const UwiBand ib = seasim::makeUwiBandFromOrdinates(band, c.g, kMuW, c.H, 1.34, c.H - 1.2, 16, &fit);
    DiscreteOrdinatesLayer layer = layerOf(band, c.g, c.H);
    DiscreteOrdinatesLayer dark = layer;
    dark.bottom_sunlit = 0;
    // The ends: E_d's and E_u's coefficients, no azimuth.
    const float* top = ib.tilt + (UWI_TILT_NODES - 1) * UWI_SOURCE_TERMS;
    EXPECT_EQ(top[0], ib.d1);
    EXPECT_EQ(top[1], ib.d2);
    EXPECT_EQ(top[2], ib.dp);
    EXPECT_EQ(ib.tilt[0], ib.u1);
    EXPECT_EQ(ib.tilt[2], ib.up);
    for (int q = 3; q < UWI_SOURCE_TERMS; ++q) EXPECT_EQ(top[q], 0.0f);
    const kd::real3 s_w{std::sqrt(1 - kMuW * kMuW), kMuW, 0};
    double worst = 0, worst_dark = 0;
    for (double y : {0.3, 0.5 * c.H, c.H - 0.2}) {
      const double scale = solverTilted(layer, 0.0, 0.0, y);
      ASSERT_GT(scale, 0);
      for (double n_y : {-0.83, -0.31, 0.0, 0.22, 0.71})
        for (double cos_phi : {-1.0, 0.0, 1.0}) {
          // A normal of vertical n_y whose -n has the azimuth cos φ from the beam's: n = -(horizontal) ...
          const double h = std::sqrt(1 - n_y * n_y);
          const double sin_phi = std::sqrt(std::max(1 - cos_phi * cos_phi, 0.0));
          // -n's horizontal part along (cos φ, sin φ) of the beam's photon azimuth (the beam goes along -s_w).
          const kd::real3 n{h * cos_phi, n_y, -h * sin_phi};
          EXPECT_NEAR(kd::uwi_cos_azimuth(kd::dot(n, s_w), n.y, s_w.y), cos_phi, 1e-9);
          const double solver = solverTilted(layer, n_y, cos_phi, y);
          const double table = kd::uwi_tilt_irradiance(&ib, c.H, y, n, s_w, 1.0);
          const float table_f = kf::uwi_tilt_irradiance(&ib, float(c.H), float(y), kf::real3{float(n.x), float(n.y), float(n.z)},
                                                        kf::real3{float(s_w.x), float(s_w.y), float(s_w.z)}, 1.0f);
          worst = std::max(worst, std::fabs(table - solver) / scale);
          EXPECT_NEAR(table, solver, c.tolerance * scale) << c.a << ":" << c.b << " g " << c.g << " y " << y << " n_y " << n_y
                                                   << " cos_phi " << cos_phi;
          EXPECT_NEAR(table_f, table, 1e-4 * scale);
          const double solver_dark = solverTilted(dark, n_y, cos_phi, y);
          const double table_dark = kd::uwi_tilt_irradiance(&ib, c.H, y, n, s_w, 0.0);
          worst_dark = std::max(worst_dark, std::fabs(table_dark - solver_dark) / scale);
          EXPECT_NEAR(table_dark, solver_dark, c.tolerance * scale) << "dark " << c.a << ":" << c.b << " g " << c.g;
          if (n_y < 0) EXPECT_LT(table_dark, table);  // a face looking down loses the sunlit sand's light
        }
    }
    std::printf("a %.2f b %.2f g %.2f H %2.0f: tilted table vs solver %.4f, over shadow %.4f (of a vertical face's "
                "irradiance); fit %.4f\n",
                c.a, c.b, c.g, c.H, worst, worst_dark, fit.tilt);
  }
  const UwiBand deep = seasim::makeUwiBandFromOrdinates(uwTestBand(0.1, 0.3, 0.146, 0.85, kMuW, 0.35), 0.9, kMuW, 0.0,
                                                        1.34, 3.8);
  for (float v : deep.tilt_bottom) EXPECT_EQ(v, 0.0f);
}

// The two-stream's table is its uniform hemispheres, E_d (1 + n_y)/2 + E_u (1 - n_y)/2 (as the thesis's), and
// it has no bottom part.
TEST(UnderwaterOrdinatesTilt, TwoStreamTableIsUniformHemispheres) {
  const UwBand band = uwTestBand(0.1, 0.3, 0.146, 0.85, kMuW, 0.35);
  const UwiBand ib = seasim::makeUwiBand(band, 0.9, kMuW, 5.0, 1.34);
  for (float v : ib.tilt_bottom) EXPECT_EQ(v, 0.0f);
  const kd::real3 s_w{std::sqrt(1 - kMuW * kMuW), kMuW, 0};
  for (double y : {0.0, 2.0, 5.0})
    for (double n_y : {-1.0, -0.55, 0.0, 0.37, 1.0}) {
      const kd::real3 n{std::sqrt(1 - n_y * n_y), n_y, 0};
      double ed, eu;
      kd::uwi_irradiance(&ib, 5.0, y, &ed, &eu);
      const double expect = 0.5 * (1 + n_y) * ed + 0.5 * (1 - n_y) * eu;
      EXPECT_NEAR(kd::uwi_tilt_irradiance(&ib, 5.0, y, n, s_w, 1.0), expect, 1e-6 * std::fabs(expect)) << y << " " << n_y;
      EXPECT_NEAR(kf::uwi_tilt_irradiance(&ib, 5.0f, float(y), kf::real3{float(n.x), float(n.y), float(n.z)},
                                          kf::real3{float(s_w.x), float(s_w.y), float(s_w.z)}, 1.0f),
                  expect, 1e-5 * std::fabs(expect));
    }
}

using seasim::testing::uwTestBox;
using seasim::testing::uwTestSphere;

// The share of the sand a face sees that is sunlit, in float and double, under a sun straight above a 5 m
// bottom with a box on it and a sphere above the sand far away: all of it far from both, none just above the
// box's top or under the sphere, some where the box hides part of the sand, all of it beside the box, and 1
// for a face looking up (no sand in view) or without a bottom.
template <class M>
void checkBottomVisibility() {
  using V = typename M::real3;
  const std::vector<UwObject> objects = {uwTestBox(-1, -5, -1, 1, -4, 1), uwTestSphere(-20, -1, -20, 0.5f)};
  const V up{0, 1, 0}, down{0, -1, 0}, side{1, 0, 0}, s_w{0, 1, 0};
  auto vis = [&](V p, V n, float H = 5) { return M::uwi_bottom_visibility(objects.data(), 2, H, p, n, s_w); };
  EXPECT_EQ(vis(V{30, -2, 30}, down), 1);            // open sand, sunlit
  EXPECT_EQ(vis(V{-20, -4.9f, -20}, down), 0);       // 0.1 m above the sphere's shadow (its rays reach 0.4 m)
  EXPECT_EQ(vis(V{0, -3.9f, 0}, down), 0);           // just above the box's top: no sand in view
  const auto part = vis(V{2, -3, 0}, down);          // the box hides some of the sand
  EXPECT_GT(part, 0);
  EXPECT_LT(part, 1);
  EXPECT_EQ(vis(V{1, -4.5f, 0}, side), 1);           // the box's side looks at sunlit sand
  EXPECT_EQ(vis(V{30, -2, 30}, up), 1);              // looking up: no sand in view
  EXPECT_EQ(vis(V{30, -2, 30}, down, 0), 1);         // no bottom
}

struct Kd {
  using real3 = kd::real3;
  static double uwi_bottom_visibility(const UwObject* o, int n, double H, real3 p, real3 nrm, real3 s) {
    return kd::uwi_bottom_visibility(o, n, H, p, nrm, s);
  }
};
struct Kf {
  using real3 = kf::real3;
  static float uwi_bottom_visibility(const UwObject* o, int n, float H, real3 p, real3 nrm, real3 s) {
    return kf::uwi_bottom_visibility(o, n, H, p, nrm, s);
  }
};

TEST(UnderwaterOrdinatesTilt, BottomVisibilityFollowsTheShadowsOnTheSand) {
  checkBottomVisibility<Kd>();
  checkBottomVisibility<Kf>();
}

}  // namespace
