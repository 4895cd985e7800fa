// discrete_ordinates_test.cpp — the plane-parallel discrete-ordinates solver behind the discrete-ordinates
// underwater model's diffuse field (host/underwater/discrete_ordinates.*): against an
// independent solution (tests/perf/plane_parallel_dom.py: the exact HG phase averaged over azimuth
// numerically, no delta-M, 100 streams per hemisphere, numpy's general eigen-solver), the isotropic
// K∞ of the characteristic equation, energy conservation without absorption, the cos φ mode, the
// bottom's limits and bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <utility>
#include <algorithm>
#include <vector>
#include <stdexcept>

#include "underwater/discrete_ordinates.h"
#include "underwater/underwater_ordinates_setup.h"

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
  // sits at the quadrature's edge, not at κ. At ω = 0.5, 1/κ = 1.044 is near it: the window's 8 nodes of
  // the split quadrature, the largest at 0.9934, give κ within 1.6e-6.)
  for (double omega : {0.5, 0.75, 0.95, 0.99}) {
    DiscreteOrdinatesLayer l = studyLayer(1 - omega, omega, 0.0, 0);
    const DiscreteOrdinates d(l, 16);
    EXPECT_NEAR(d.asymptoticK(), seasim::isotropicAsymptoticKappa(omega), omega > 0.5 ? 1e-6 : 2e-6) << omega;
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
  bad([](DiscreteOrdinatesLayer&) {}, 16, 3);
  EXPECT_THROW(DiscreteOrdinates(studyLayer(0.1, 0.3, 0.9, 5), 16, 0, 33), std::invalid_argument);
  EXPECT_THROW(DiscreteOrdinates(studyLayer(0.1, 0.3, 0.9, 5), 16, 0, -1), std::invalid_argument);
}

// The beam's own scattering towards a cosine ν of this azimuth mode: fourier b̂ p^m(ν, μ_sun) F0 e^{-m y}
// from the delta-M phase's first `kept` moments (written here from Legendre's recurrences, not the solver's).
double beamSource(const DiscreteOrdinatesLayer& l, int mode, int kept, double nu, double y, double m) {
  const double f = std::pow(l.g, kept), b_hat = l.b * (1 - f);
  // P_l^m(x) √((l - m)! / (l + m)!), l = 0..n-1, by the recurrence in l from P_m^m = (2m - 1)!! (1 - x²)^{m/2}
  // (the Condon-Shortley sign left out: it cancels in the products).
  auto legendre = [&](double x, int n) {
    std::vector<double> raw(n + 1, 0.0), p(n, 0.0);
    double pmm = 1;
    for (int k = 1; k <= mode; ++k) pmm *= (2 * k - 1) * std::sqrt(1 - x * x);
    if (mode < n) raw[mode] = pmm;
    if (mode + 1 < n) raw[mode + 1] = (2 * mode + 1) * x * pmm;
    for (int k = mode + 2; k < n; ++k) raw[k] = ((2 * k - 1) * x * raw[k - 1] - (k + mode - 1) * raw[k - 2]) / (k - mode);
    for (int k = mode; k < n; ++k) {
      double ratio = 1;  // (l - m)! / (l + m)!
      for (int i = k - mode + 1; i <= k + mode; ++i) ratio /= i;
      p[k] = raw[k] * std::sqrt(ratio);
    }
    return p;
  };
  const std::vector<double> pn = legendre(nu, kept), ps = legendre(l.mu_sun, kept);
  double s = 0;
  for (int k = 0; k < kept; ++k) s += (2 * k + 1) * (std::pow(l.g, k) - f) / (1 - f) * pn[k] * ps[k];
  return (mode == 0 ? 1.0 : 2.0) * b_hat * s / (4 * M_PI) * l.e_sun0 / l.mu_sun * std::exp(-m * y);
}

// The in-scatter towards the quadrature's own cosines closes the transfer equation of the solver's
// radiance: ±μ dL/dy + ĉ L - J = the beam's scattering, per node and depth (dL/dy by central differences),
// in azimuth modes 0, 1 and 2, for the full delta-M order and a low one (phase_moments 4). Its integral
// over directions is b̂ E_0 (mode 0), its first moment b̂ χ_1 (E_d - E_u). Would fail with a wrong phase
// sum, a wrong weight, the hemispheres swapped or the user cosines' Legendre functions off.
TEST(DiscreteOrdinates, InscatterClosesTheTransferEquation) {
  for (double bottom : {0.0, 5.0})
    for (int kept : {0, 4})
      for (int mode : {0, 1, 2}) {
        const DiscreteOrdinatesLayer l = studyLayer(0.1, 0.3, 0.9, bottom);
        const DiscreteOrdinates d(l, 16, mode, kept);
        const std::vector<double>& mu = d.cosines();
        std::vector<double> nus;
        for (double m : mu) nus.push_back(m);
        for (double m : mu) nus.push_back(-m);
        const double y = 2.0, h = 1e-4, c = d.extinction();
        // inscatterProfile's samples y = 0, 1, 2, 3, 4: y is sample 2.
        const std::vector<double> j = d.inscatterProfile(nus, 4.0, 5);
        std::vector<double> dn, up, dn_p, up_p, dn_m, up_m;
        d.radiances(y, dn, up);
        d.radiances(y + h, dn_p, up_p);
        d.radiances(y - h, dn_m, up_m);
        const int n = static_cast<int>(mu.size());
        double largest = 0;
        for (int i = 0; i < n; ++i) largest = std::max({largest, c * dn[i], c * up[i]});
        for (int i = 0; i < n; ++i) {
          const double j_down = j[2 * nus.size() + i], j_up = j[2 * nus.size() + n + i];
          const double res_down = mu[i] * (dn_p[i] - dn_m[i]) / (2 * h) + c * dn[i] - j_down;
          const double res_up = -mu[i] * (up_p[i] - up_m[i]) / (2 * h) + c * up[i] - j_up;
          const int order = kept > 0 ? kept : 32;
          EXPECT_NEAR(res_down, beamSource(l, mode, order, mu[i], y, d.beamK()), 1e-6 * largest)
              << "bottom " << bottom << " kept " << kept << " mode " << mode << " mu " << mu[i];
          EXPECT_NEAR(res_up, beamSource(l, mode, order, -mu[i], y, d.beamK()), 1e-6 * largest)
              << "bottom " << bottom << " kept " << kept << " mode " << mode << " mu " << -mu[i];
        }
        if (mode > 0) continue;
        // Simpson's rule in ν over [-1, 1] (J is a polynomial of degree < 32 in ν): 2π ∫ J dν and 2π ∫ ν J dν.
        const int count = 2001;
        std::vector<double> grid(count);
        for (int i = 0; i < count; ++i) grid[i] = -1.0 + 2.0 * i / (count - 1);
        const std::vector<double> jg = d.inscatterProfile(grid, 4.0, 5);
        double zeroth = 0, first = 0;
        for (int i = 0; i < count; ++i) {
          const double w = (i == 0 || i == count - 1 ? 1.0 : i % 2 ? 4.0 : 2.0) * (2.0 / (count - 1)) / 3.0;
          zeroth += 2 * M_PI * w * jg[2 * count + i];
          first += 2 * M_PI * w * grid[i] * jg[2 * count + i];
        }
        const int order = kept > 0 ? kept : 32;
        const double f = std::pow(l.g, order), b_hat = l.b * (1 - f), chi1 = (l.g - f) / (1 - f);
        const auto e = d.at(y);
        EXPECT_NEAR(zeroth, b_hat * e.scalar, 1e-8 * b_hat * e.scalar) << bottom << " " << kept;
        EXPECT_NEAR(first, b_hat * chi1 * (e.down - e.up), 1e-8 * b_hat * e.scalar) << bottom << " " << kept;
      }
}

}  // namespace

// At the kernel's delta-M order (3 moments) the quadrature is split at the edge of Snell's window, half
// the nodes each side: the cosines fall on either side of μ_c and the weights integrate [0, 1]. With the
// split the field converges in the streams (one Gauss rule over (0, 1) moved the regions' ratios by
// several % between 8, 12, 16 and 32 streams, docs/journal/underwater_regions_4_*.md): the irradiances and the in-scatter
// towards near-horizontal and vertical directions at 8–24 streams against 48.
TEST(DiscreteOrdinates, SplitQuadratureConvergesInTheStreams) {
  const double mu_c = std::sqrt(1 - 1 / (1.34 * 1.34));
  struct Case { double a, b, g, bottom; };
  const std::vector<double> nus = {-1.0, -0.6, -0.1, 0.0, 0.1, 0.6, 1.0};
  double worst_e = 0, worst_j = 0;
  for (const Case c : {Case{0.03, 0.05, 0.9, 0}, Case{0.1, 0.3, 0.95, 5}, Case{0.4, 1.2, 0.5, 2},
                       Case{0.4, 1.2, 0.95, 0}}) {
    const DiscreteOrdinatesLayer l = studyLayer(c.a, c.b, c.g, c.bottom);
    const double depth_end = c.bottom > 0 ? c.bottom : 8.0;
    const DiscreteOrdinates ref(l, 48, 0, 3);
    const auto e_ref = ref.profile(depth_end, 5);
    const auto j_ref = ref.inscatterProfile(nus, depth_end, 5);
    for (int streams : {8, 12, 16, 24}) {
      const DiscreteOrdinates d(l, streams, 0, 3);
      const std::vector<double>& mu = d.cosines();
      EXPECT_LT(mu[streams / 2 - 1], mu_c);
      EXPECT_GT(mu[streams / 2], mu_c);
      const auto e = d.profile(depth_end, 5);
      const auto j = d.inscatterProfile(nus, depth_end, 5);
      for (int s = 0; s < 5; ++s) {
        for (auto [x, r] : {std::pair{e[s].down, e_ref[s].down}, std::pair{e[s].up, e_ref[s].up},
                            std::pair{e[s].scalar, e_ref[s].scalar}})
          worst_e = std::max(worst_e, std::abs(x / r - 1));
        for (size_t u = 0; u < nus.size(); ++u)
          worst_j = std::max(worst_j, std::abs(j[s * nus.size() + u] / j_ref[s * nus.size() + u] - 1));
      }
    }
  }
  std::printf("split quadrature, 8-24 streams against 48: irradiances within %.2e, in-scatter within %.2e\n",
              worst_e, worst_j);
  EXPECT_LT(worst_e, 1e-2);
  EXPECT_LT(worst_j, 1e-2);
}
