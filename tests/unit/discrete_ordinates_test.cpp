// discrete_ordinates_test.cpp — the plane-parallel discrete-ordinates solver behind the improved
// underwater model's diffuse field (host/underwater/discrete_ordinates.*, issue 13 s9a): against an
// independent solution (tests/perf/plane_parallel_dom.py: the exact HG phase averaged over azimuth
// numerically, no delta-M, 100 streams per hemisphere, numpy's general eigen-solver), the isotropic
// K∞ of the characteristic equation, energy conservation without absorption, the cos φ mode, the
// bottom's limits and bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "underwater/discrete_ordinates.h"
#include "underwater/underwater_improved_setup.h"

namespace {

using seasim::DiscreteOrdinates;
using seasim::DiscreteOrdinatesLayer;

// The regions study's light: sun 30° from the zenith refracted into water of n = 1.34, e_sun0 = 0.85
// and a uniform sky of radiance 0.05 (transmitted irradiance 0.146135 through the flat surface).
DiscreteOrdinatesLayer studyLayer(double a, double b, double g, double bottom_depth) {
  DiscreteOrdinatesLayer l;
  l.a = a;
  l.b = b;
  l.g = g;
  l.bottom_depth = bottom_depth;
  l.bottom_albedo = 0.35;
  l.ior = 1.34;
  l.mu_sun = std::cos(std::asin(0.5 / 1.34));
  l.e_sun0 = 0.85;
  l.e_sky0 = 0.146135;
  return l;
}

double totalDown(const DiscreteOrdinates& d, double y) {
  const auto e = d.at(y);
  return e.down + e.beam_down;
}

// Values of tests/perf/plane_parallel_dom.py (exact HG phase, no delta-M): E_d with the beam, E_u, and
// E_0 with the beam.
TEST(DiscreteOrdinates, AgreesWithTheIndependentSolution) {
  struct Case {
    double a, b, g, bottom, y, e_d, e_u, e_0;
  };
  const Case cases[] = {
      // plane_parallel_dom.py 0.1 0.3 0.95 --depths 0,10,20; ... 0.1 0.3 0 --depths 10,20;
      // ... 0.1 0.3 0.95 --bottom 20 --depths 18.8 (100 streams)
      {0.1, 0.3, 0.95, 0, 0, 1.00357, 0.0114946, 1.14623},
      {0.1, 0.3, 0.95, 0, 10, 0.295783, 0.00395864, 0.370326},
      {0.1, 0.3, 0.95, 0, 20, 0.0812508, 0.00114509, 0.104984},
      {0.1, 0.3, 0.0, 0, 10, 0.0615539, 0.0171726, 0.136012},
      {0.1, 0.3, 0.0, 0, 20, 0.00281435, 0.000788701, 0.00627639},
      {0.1, 0.3, 0.95, 20, 18.8, 0.0955633, 0.0231175, 0.161197},
  };
  for (const Case& c : cases) {
    const DiscreteOrdinates d(studyLayer(c.a, c.b, c.g, c.bottom), 16);
    const auto e = d.at(c.y);
    // 0.5 %: the 16 streams' delta-M and the Snell window's edge between two cosines (0.3 % at g = 0).
    EXPECT_NEAR(e.down + e.beam_down, c.e_d, 5e-3 * c.e_d) << c.g << " " << c.bottom << " " << c.y;
    EXPECT_NEAR(e.up, c.e_u, 5e-3 * c.e_u) << c.g << " " << c.bottom << " " << c.y;
    EXPECT_NEAR(e.scalar + e.beam_scalar, c.e_0, 5e-3 * c.e_0) << c.g << " " << c.bottom << " " << c.y;
  }
}

// K∞ of isotropic scattering is c κ(ω) with ω atanh κ = κ (isotropicAsymptoticKappa, bisection); the
// solver's slowest mode must be it, and with HG the python solution's eigenvalue (0.1336 at g = 0.95).
TEST(DiscreteOrdinates, SlowestModeIsTheAsymptoticK) {
  // (Below ω ≈ 0.3 κ is within 1e-3 of 1, beyond the largest cosine's 1/μ: the discrete eigenvalue then
  // sits at the quadrature's edge, not at κ.)
  for (double omega : {0.5, 0.75, 0.95, 0.99}) {
    DiscreteOrdinatesLayer l = studyLayer(1 - omega, omega, 0.0, 0);
    const DiscreteOrdinates d(l, 16);
    EXPECT_NEAR(d.asymptoticK(), seasim::isotropicAsymptoticKappa(omega), 1e-6) << omega;
  }
  EXPECT_NEAR(DiscreteOrdinates(studyLayer(0.1, 0.3, 0.95, 0), 16).asymptoticK(), 0.13365, 2e-4);
  EXPECT_NEAR(DiscreteOrdinates(studyLayer(0.4, 1.2, 0.9, 0), 16).asymptoticK(), 0.6084, 6e-4);
}

// Without absorption (the solver keeps 1e-6 c of it) nothing is lost in the water: over a black bottom,
// the net downward flux E_d + beam - E_u is the same at every depth (what the bottom absorbs).
TEST(DiscreteOrdinates, ConservesTheFluxWithoutAbsorption) {
  DiscreteOrdinatesLayer l = studyLayer(0.0, 0.5, 0.8, 10);
  l.bottom_albedo = 0;
  const DiscreteOrdinates d(l, 16);
  auto net = [&](double y) {
    const auto e = d.at(y);
    return e.down + e.beam_down - e.up;
  };
  const double top = net(0);
  ASSERT_GT(top, 0.1);
  for (double y : {1.0, 5.0, 10.0}) EXPECT_NEAR(net(y), top, 2e-4 * top) << y;
}

// The cos φ mode: nothing at g = 0 (the beam's scattering has no azimuth then) or with the sun at the
// zenith; with HG and a slanted sun the light flows along the sun's azimuth (F_h > 0), and its beam part is
// the beam's scalar irradiance times sin θ_w.
TEST(DiscreteOrdinates, HorizontalFluxFollowsTheSunsAzimuth) {
  EXPECT_NEAR(DiscreteOrdinates(studyLayer(0.1, 0.3, 0.0, 0), 16, 1).at(2).horizontal, 0.0, 1e-15);
  DiscreteOrdinatesLayer zenith = studyLayer(0.1, 0.3, 0.9, 0);
  zenith.mu_sun = 1;
  EXPECT_NEAR(DiscreteOrdinates(zenith, 16, 1).at(2).horizontal, 0.0, 1e-12);
  const DiscreteOrdinatesLayer l = studyLayer(0.1, 0.3, 0.9, 0);
  const DiscreteOrdinates h(l, 16, 1);
  for (double y : {0.5, 2.0, 10.0}) {
    const auto e = h.at(y);
    EXPECT_GT(e.horizontal, 0.0) << y;
    EXPECT_NEAR(e.beam_horizontal, e.beam_scalar * std::sqrt(1 - l.mu_sun * l.mu_sun), 1e-12);
    // Less than the total scalar irradiance (|F_h| <= E_0).
    const auto s = DiscreteOrdinates(l, 16, 0).at(y);
    EXPECT_LT(e.horizontal + e.beam_horizontal, s.scalar + s.beam_scalar) << y;
  }
  // More streams, the same flux: 16 against 32 within 2 % (the delta-M beam carries a different share).
  const DiscreteOrdinates fine(l, 32, 1);
  for (double y : {1.0, 3.8}) {
    const auto a = h.at(y), b = fine.at(y);
    EXPECT_NEAR(a.horizontal + a.beam_horizontal, b.horizontal + b.beam_horizontal,
                0.02 * (b.horizontal + b.beam_horizontal)) << y;
  }
}

// A black bottom far below is no bottom; a white one sends light up; an empty band stays finite.
TEST(DiscreteOrdinates, BottomLimitsAndDegenerateLayers) {
  DiscreteOrdinatesLayer black = studyLayer(0.4, 1.2, 0.5, 60);
  black.bottom_albedo = 0;
  const DiscreteOrdinates deep(black, 16), none(studyLayer(0.4, 1.2, 0.5, 0), 16);
  for (double y : {0.0, 1.0, 3.0}) {
    EXPECT_NEAR(deep.at(y).down, none.at(y).down, 1e-9 * none.at(0).down) << y;
    EXPECT_NEAR(deep.at(y).up, none.at(y).up, 1e-9 * none.at(0).down) << y;
  }
  DiscreteOrdinatesLayer white = studyLayer(0.1, 0.3, 0.5, 5);
  white.bottom_albedo = 1;
  const DiscreteOrdinates w(white, 16);
  // At the bottom the upwelling light is the down-welling light reflected: E_u(H) = E_d(H) + beam.
  EXPECT_NEAR(w.at(5).up, totalDown(w, 5), 1e-9 * totalDown(w, 5));
  // Pure absorption: no upwelling light without a bottom, the sky's light attenuated along its slant paths.
  const DiscreteOrdinates absorbing(studyLayer(0.2, 0.0, 0.5, 0), 16);
  EXPECT_NEAR(absorbing.at(3).up, 0.0, 1e-12);
  EXPECT_LT(absorbing.at(3).down, 0.146135 * std::exp(-0.2 * 3));
  // No medium, a thin layer, no sun: finite.
  for (const DiscreteOrdinatesLayer& l :
       {studyLayer(0.0, 0.0, 0.0, 0), studyLayer(0.0, 0.0, 0.9, 2), studyLayer(0.1, 0.3, 0.9, 1e-3)}) {
    for (int mode : {0, 1}) {
      const auto e = DiscreteOrdinates(l, 16, mode).at(0.5e-3);
      for (double v : {e.down, e.up, e.scalar, e.horizontal}) EXPECT_TRUE(std::isfinite(v));
    }
  }
  DiscreteOrdinatesLayer night = studyLayer(0.1, 0.3, 0.9, 5);
  night.e_sun0 = 0;
  const auto e = DiscreteOrdinates(night, 16).at(2);
  EXPECT_GT(e.down, 0.0);
  EXPECT_EQ(e.beam_down, 0.0);
}

// profile() is at() at evenly spaced depths (its exponentials as geometric sequences), with a bottom
// (ending at it or above it) and without.
TEST(DiscreteOrdinates, ProfileIsAtEvenlySpacedDepths) {
  for (double bottom : {0.0, 5.0})
    for (int mode : {0, 1}) {
      const DiscreteOrdinates d(studyLayer(0.4, 1.2, 0.9, bottom), 16, mode);
      for (double end : {5.0, 3.0}) {
        const auto p = d.profile(end, 41);
        ASSERT_EQ(p.size(), 41u);
        for (int s = 0; s <= 40; ++s) {
          const auto e = d.at(end * s / 40);
          const double size = std::abs(e.down) + std::abs(e.up) + std::abs(e.scalar) + std::abs(e.horizontal) + 1e-30;
          EXPECT_NEAR(p[s].down, e.down, 1e-12 * size) << bottom << " " << mode << " " << end << " " << s;
          EXPECT_NEAR(p[s].up, e.up, 1e-12 * size);
          EXPECT_NEAR(p[s].scalar, e.scalar, 1e-12 * size);
          EXPECT_NEAR(p[s].horizontal, e.horizontal, 1e-12 * size);
          EXPECT_NEAR(p[s].beam_down, e.beam_down, 1e-12 * (e.beam_down + 1e-30));
        }
      }
    }
}

TEST(DiscreteOrdinates, RejectsBadInput) {
  auto bad = [](auto edit, int streams = 16, int mode = 0) {
    DiscreteOrdinatesLayer l = studyLayer(0.1, 0.3, 0.9, 5);
    edit(l);
    EXPECT_THROW(DiscreteOrdinates(l, streams, mode), std::invalid_argument);
  };
  bad([](DiscreteOrdinatesLayer& l) { l.g = 1.0; });
  bad([](DiscreteOrdinatesLayer& l) { l.a = -0.1; });
  bad([](DiscreteOrdinatesLayer& l) { l.b = std::nan(""); });
  bad([](DiscreteOrdinatesLayer& l) { l.mu_sun = 0; });
  bad([](DiscreteOrdinatesLayer& l) { l.bottom_albedo = 1.5; });
  bad([](DiscreteOrdinatesLayer& l) { l.e_sun0 = -1; });
  bad([](DiscreteOrdinatesLayer&) {}, 1);
  bad([](DiscreteOrdinatesLayer&) {}, 16, 2);
}

}  // namespace
