// underwater_ordinates_test.cpp — underwater.model = "discrete_ordinates" (kernels/common/underwater_ordinates.h,
// host/underwater/underwater_ordinates_setup.*) in float and double: the two-stream coefficients solve
// their differential equations and boundary conditions (finite differences), net flux is conserved
// without absorption, the view-ray closed form matches quadrature of its source along the ray, the
// resonance k = m and the extremes stay finite, and b = 0 leaves only the attenuated beam.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "math/kernel_math.h"
#include "underwater/underwater_ordinates_setup.h"

#include "underwater_ordinates_fixtures.h"

namespace {

namespace kd = seasim::kmath_d;
namespace kf = seasim::kmath_f;
using seasim::makeUwiBand;
using seasim::TwoStreamClosure;

using seasim::testing::uwTestBand;

struct Case {
  double a, b, g, mu_w, H, rho;
};

std::vector<Case> cases() {
  std::vector<Case> out;
  for (double g : {0.0, 0.5, 0.9, 0.95})
    for (auto ab : {std::pair{0.03, 0.05}, std::pair{0.1, 0.3}, std::pair{0.4, 1.2}, std::pair{1.0, 0.1}})
      for (double H : {0.0, 2.0, 5.0, 20.0}) out.push_back({ab.first, ab.second, g, 0.9, H, 0.35});
  return out;
}

// The two-stream coefficients as underwater_ordinates_setup.cpp documents them (the closure's streams
// at ±μ1 on the delta-M medium; the beam's b' split by Eddington's γ3).
struct TwoStream {
  double a1, a2, s_up, s_down, m;
};
TwoStream twoStream(const Case& c, const UwiBand& ib, TwoStreamClosure closure = seasim::twoStreamClosure()) {
  const double w = ib.b_dm / ib.c_dm, gp = ib.g_dm;
  TwoStream t;
  // Quadrature: μ1 = 1/√3; asymptotic: that of the similarity albedo b'(1 - g')/(a + b'(1 - g')).
  const double bb = ib.b_dm * (1 - gp) / 2, a = ib.c_dm - ib.b_dm;
  const double mu1 = closure == TwoStreamClosure::Asymptotic ? seasim::asymptoticStreamCosine(2 * bb / (a + 2 * bb))
                                                             : 1 / std::sqrt(3.0);
  t.a1 = ib.c_dm * (2 - w * (1 + gp)) / 2 / mu1;
  t.a2 = ib.c_dm * w * (1 - gp) / 2 / mu1;
  t.s_up = ib.b_dm * (2 - 3 * gp * c.mu_w) / 4;
  t.s_down = ib.b_dm - t.s_up;
  t.m = ib.c_dm / c.mu_w;
  return t;
}

TEST(UnderwaterOrdinates, TwoStreamSolvesItsEquationsAndBoundaries) {
  const double ior = 1.34, rs = seasim::internalDiffuseReflectance(ior);
  for (TwoStreamClosure closure : {TwoStreamClosure::Quadrature, TwoStreamClosure::Asymptotic})
  for (const Case& c : cases()) {
    const UwBand bd = uwTestBand(c.a, c.b, 0.3, 1.0, c.mu_w, c.rho);
    const UwiBand ib = makeUwiBand(bd, c.g, c.mu_w, c.H, ior, seasim::diffuseMeanCosines(c.g), closure);
    const TwoStream t = twoStream(c, ib, closure);
    auto E = [&](double y, double* ed, double* eu) { kd::uwi_irradiance(&ib, c.H, y, ed, eu); };
    const double y_max = c.H > 0 ? c.H : 30.0;
    double scale = 0;
    for (int i = 0; i <= 10; ++i) {
      double ed, eu;
      E(y_max * i / 10, &ed, &eu);
      scale = std::max(scale, std::abs(ed) + std::abs(eu));
    }
    for (int i = 1; i < 10; ++i) {
      const double y = y_max * i / 10, h = 1e-4;
      double ed0, eu0, edp, eup, edm, eum;
      E(y, &ed0, &eu0);
      E(y + h, &edp, &eup);
      E(y - h, &edm, &eum);
      const double beam = bd.e_beam0 * std::exp(-t.m * y);
      // float coefficients: residuals relative to the field's size and its rate
      const double tol = 2e-5 * scale * (t.a1 + t.m + 1);
      EXPECT_NEAR((eup - eum) / (2 * h), t.a1 * eu0 - t.a2 * ed0 - t.s_up * beam, tol) << c.a << " " << c.b << " " << c.g << " " << c.H;
      EXPECT_NEAR((edp - edm) / (2 * h), t.a2 * eu0 - t.a1 * ed0 + t.s_down * beam, tol) << c.a << " " << c.b << " " << c.g << " " << c.H;
      EXPECT_GT(ed0, 0);
      EXPECT_GE(eu0, 0);
    }
    double ed, eu;
    E(0, &ed, &eu);
    EXPECT_NEAR(ed, bd.e_sky0 + rs * eu, 1e-5 * scale);  // top: sky plus the surface's internal reflection
    if (c.H > 0) {
      E(c.H, &ed, &eu);
      EXPECT_NEAR(eu, c.rho * (ed + bd.e_sun0 * std::exp(-t.m * c.H)), 1e-5 * scale);  // Lambertian bottom
    }
  }
}

TEST(UnderwaterOrdinates, NoAbsorptionConservesNetFlux) {
  // a = 0: nothing is absorbed, so the net downward flux E_d - E_u + e_sun0 e^{-m y} is the same at
  // every depth (here the bottom reflects all of it: 0 net flux with ρ = 1 would be degenerate, so ρ = 0.5
  // and no bottom are checked; k is held at >= 1e-3 c', a 1e-3-sized departure).
  for (double H : {0.0, 10.0})
    for (double g : {0.0, 0.9}) {
      const double mu = 0.85;
      const UwBand bd = uwTestBand(0.0, 0.2, 0.3, 1.0, mu, 0.5);
      const UwiBand ib = makeUwiBand(bd, g, mu, H, 1.34);
      auto net = [&](double y) {
        double ed, eu;
        kd::uwi_irradiance(&ib, H, y, &ed, &eu);
        return ed - eu + bd.e_sun0 * std::exp(-double(ib.m) * y);
      };
      const double n0 = net(0.1);
      for (double y : {1.0, 3.0, 8.0}) EXPECT_NEAR(net(y) / n0, 1.0, 2e-2) << H << " " << g << " " << y;
    }
}

// The view-ray in-scatter by quadrature of its source J(y(z)) e^{-c' z} (Simpson, long double), the
// froxel's single scattering taken off the same way.
long double multipleQuadrature(const UwiBand& ib, const UwBand& bd, double g, double H, double S, double d_y,
                               double o_d, double cos_s, double mu_w, int single) {
  const int n = 20000;
  const double S_end = S >= 1e29 ? 60.0 / ib.c_dm : S;
  const long double h = S_end / n;
  const seasim::DiffuseMeanCosines mean = seasim::diffuseMeanCosines(g);
  // The source's table holds the first-order form at its nodes; the ray reads the one nearest its ν.
  const double nu_node = kd::uwi_source_node_cosine(kd::uwi_source_node(d_y));
  auto f = [&](long double z) -> long double {
    const double y = o_d - double(z) * d_y;
    double ed, eu;
    kd::uwi_irradiance(&ib, H, y, &ed, &eu);
    // The beam's offspring (dp, up) by its own mean cosines, the rest by the two-stream modes'.
    const double ep = std::exp(-double(ib.m) * y), bd_ = ib.dp * ep, bu_ = ib.up * ep;
    const double J = ib.b_dm * ((ed - bd_) / mean.down + (eu - bu_) / mean.up + bd_ / mean.beam_down +
                                bu_ / mean.beam_up + 3 * ib.g_flux * nu_node * (ed - eu)) / (4 * M_PI) +
                     bd.b * kd::hg_phase(cos_s, g) * bd.e_beam0 * std::exp(-double(ib.m) * y);
    const double ss = single ? bd.b * kd::hg_phase(cos_s, g) * bd.e_beam0 * std::exp(-bd.c * y / mu_w - bd.c * double(z)) : 0;
    return J * std::exp(-double(ib.c_dm) * double(z)) - ss;
  };
  long double sum = f(0) + f(S_end);
  for (int i = 1; i < n; ++i) sum += (i % 2 ? 4.0L : 2.0L) * f(i * h);
  return sum * h / 3.0L;
}

TEST(UnderwaterOrdinates, ViewRayClosedFormMatchesQuadrature) {
  int checked = 0;
  for (const Case& c : cases()) {
    const UwBand bd = uwTestBand(c.a, c.b, 0.3, 1.0, c.mu_w, c.rho);
    const UwiBand ib = makeUwiBand(bd, c.g, c.mu_w, c.H, 1.34);
    for (double d_y : {-1.0, -0.5, -0.05, 0.0, 0.3, 0.9}) {
      const double o_d = c.H > 0 ? 0.6 * c.H : 4.0;
      double S = 1e30;
      if (d_y > 0) S = o_d / d_y;
      else if (d_y < 0 && c.H > 0) S = (c.H - o_d) / -d_y;
      const double cos_s = 0.3;
      for (int single : {0, 1}) {
        const long double ref = multipleQuadrature(ib, bd, c.g, c.H, S, d_y, o_d, cos_s, c.mu_w, single);
        const double dv = kd::uwi_multiple(&ib, &bd, c.g, c.H, S, d_y, o_d, cos_s, c.mu_w, single, 1);
        const float fv = kf::uwi_multiple(&ib, &bd, float(c.g), float(c.H), float(S), float(d_y), float(o_d),
                                          float(cos_s), float(c.mu_w), single, 1);
        const double r = std::max(double(ref), 0.0);  // the closed form clamps at 0
        const double scale = std::max(r, 1e-12);
        // The quadrature stops 60 optical depths out (e^{-60}); the float side rounds its inputs.
        EXPECT_NEAR(dv, r, 1e-6 * scale + 1e-12) << c.a << " " << c.b << " " << c.g << " " << c.H << " " << d_y << " " << single;
        EXPECT_NEAR(fv, r, 5e-4 * scale + 1e-9) << c.a << " " << c.b << " " << c.g << " " << c.H << " " << d_y << " " << single;
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 700);
}

TEST(UnderwaterOrdinates, ResonanceAndExtremesStayFiniteAndContinuous) {
  // k = m: c'√3 √((1 - ω')(1 - ω' g')) = c'/μ_w. With g = 0, a = 1, b = 0.2 (ω' = 1/6):
  // k = √3 √1.2 = 1.897 and c' = 1.2, so μ_w = 0.6325 resonates. E_d at 3 m across it must be smooth.
  std::vector<double> e;
  const double mu_res = 1.0 / (std::sqrt(3.0) * std::sqrt(5.0 / 6.0));
  for (double dm : {-0.01, -0.0011, -0.0009, -0.0001, 0.0, 0.0001, 0.0009, 0.0011, 0.01}) {
    const double mu = mu_res * (1 + dm);
    const UwiBand ib = makeUwiBand(uwTestBand(1.0, 0.2, 0.3, 1.0, mu, 0.35), 0.0, mu, 5.0, 1.34);
    double ed, eu;
    kd::uwi_irradiance(&ib, 5.0, 3.0, &ed, &eu);
    ASSERT_TRUE(std::isfinite(ed) && std::isfinite(eu));
    e.push_back(ed);
  }
  // Near the resonance A1 ≈ -P ≈ ±87 while E_d(3 m) ≈ 0.0027: a cancellation of 3e4, so the float
  // rounding of k and m (1e-7 of k y ≈ 5.7) shows as up to 2.5 % (measured; the 1e-3 move of k itself
  // as 0.5 %). A known limit of this representation, in low-albedo water with the sun near μ_w = k/c'.
  for (size_t i = 1; i < e.size(); ++i) EXPECT_NEAR(e[i] / e[i - 1], 1.0, 0.03) << i;
  // Extremes: no water, no scattering, g -> 1, grazing sun, a camera 1000 m down looking up.
  for (auto [a, b, g, mu] : {std::tuple{0.0, 0.0, 0.9, 0.9}, std::tuple{0.5, 0.0, 0.0, 0.9},
                             std::tuple{0.05, 2.0, 0.999, 0.6}, std::tuple{0.1, 0.3, 0.9, 1e-3}}) {
    const UwBand bd = uwTestBand(a, b, 0.3, 1.0, mu, 0.35);
    for (double H : {0.0, 5.0}) {
      const UwiBand ib = makeUwiBand(bd, g, mu, H, 1.34);
      for (float d_y : {-1.0f, 0.0f, 1.0f}) {
        const float S = d_y > 0 ? 1000.0f : (H > 0 && d_y < 0 ? 1.0f : 1e30f);
        const float v = kf::uwi_multiple(&ib, &bd, float(g), float(H), S, d_y, d_y > 0 ? 1000.0f : 1.0f, 0.5f,
                                         float(mu), 1, 1);
        EXPECT_TRUE(std::isfinite(v) && v >= 0) << a << " " << b << " " << g << " " << mu << " " << H << " " << d_y;
      }
      const kf::real3 n = {0.0f, 1.0f, 0.0f}, s_w = {0.0f, float(mu), std::sqrt(1.0f - float(mu * mu))};
      const float l = kf::uwi_lambert(&ib, &bd, float(H), 1.0f, n, s_w, 0.35f, 1.0f, 1.0f);
      EXPECT_TRUE(std::isfinite(l) && l >= 0);
    }
  }
}

TEST(UnderwaterOrdinates, NoScatteringLeavesTheBeamAndSkyAttenuatedByAbsorption) {
  // b = 0: no in-scatter; a horizontal Lambertian point at depth y sees ρ/π (E_d + e_sun0 e^{-a y/μ_w}),
  // E_d the sky's light decaying as e^{-√3·... } (two-stream diffusivity 2·(√3/2) = √3) without a bottom.
  const double a = 0.2, mu = 0.8, y = 4.0;
  const UwBand bd = uwTestBand(a, 0.0, 0.3, 1.0, mu, 0.0);
  const UwiBand ib = makeUwiBand(bd, 0.9, mu, 0.0, 1.34);
  EXPECT_EQ(kd::uwi_multiple(&ib, &bd, 0.9, 0.0, 5.0, -1.0, 1.0, 0.2, mu, 1, 1), 0.0);
  const kd::real3 n = {0, 1, 0}, s_w = {0, mu, std::sqrt(1 - mu * mu)};
  const double l = kd::uwi_lambert(&ib, &bd, 0.0, y, n, s_w, 0.5, 1.0, 1.0);
  const double expect = 0.5 / M_PI * (0.3 * std::exp(-std::sqrt(3.0) * a * y) + 1.0 * std::exp(-a * y / mu));
  EXPECT_NEAR(l / expect, 1.0, 1e-5);
}

TEST(UnderwaterOrdinates, DiffuseMeanCosinesFollowTheirTableAndReachTheKernel) {
  // The fitted table (underwater_ordinates_setup.cpp): the up stream at 0.52 for every g; the down stream
  // at the quadrature's 1/√3 up to g = 0.5, linear to 0.72 at g = 0.9, held above it (and below g = 0).
  const double q = 1.0 / std::sqrt(3.0);
  for (double g : {-0.3, 0.0, 0.3, 0.5}) {
    EXPECT_DOUBLE_EQ(seasim::diffuseMeanCosines(g).down, q) << g;
    EXPECT_DOUBLE_EQ(seasim::diffuseMeanCosines(g).up, 0.52) << g;
  }
  EXPECT_NEAR(seasim::diffuseMeanCosines(0.7).down, 0.5 * (q + 0.72), 1e-12);
  for (double g : {0.9, 0.95, 0.999, 1.0}) EXPECT_NEAR(seasim::diffuseMeanCosines(g).down, 0.72, 1e-12) << g;
  // Continuous at the knots, and within (0, 1] (a cosine) everywhere.
  for (double knot : {0.5, 0.9}) {
    EXPECT_NEAR(seasim::diffuseMeanCosines(knot - 1e-9).down, seasim::diffuseMeanCosines(knot + 1e-9).down, 1e-8);
  }
  for (int i = 0; i <= 100; ++i) {
    const seasim::DiffuseMeanCosines m = seasim::diffuseMeanCosines(i / 100.0);
    EXPECT_GT(m.down, 0.0);
    EXPECT_LE(m.down, 1.0);
  }
  // The two-stream's scalar irradiance is its plane irradiances over the mean cosines, mode by mode, and
  // the in-scatter source weighs it isotropically: a level view (ν = 0) sees b' E_0/(4π); the two streams
  // carry no horizontal flux.
  const UwiBand ib = makeUwiBand(uwTestBand(0.1, 0.3, 0.3, 1.0, 0.9, 0.35), 0.9, 0.9, 5.0, 1.34);
  EXPECT_NEAR(ib.o1, ib.d1 / 0.72 + ib.u1 / 0.52, 1e-6 * std::fabs(ib.o1));
  EXPECT_NEAR(ib.o2, ib.d2 / 0.72 + ib.u2 / 0.52, 1e-6 * std::fabs(ib.o2));
  EXPECT_NEAR(ib.op, ib.dp / 0.72 + ib.up / 0.52, 1e-6 * std::fabs(ib.op));
  EXPECT_EQ(ib.h1, 0.0f);
  EXPECT_EQ(ib.h2, 0.0f);
  EXPECT_EQ(ib.hp, 0.0f);
  // The two-stream's source table is the first-order form b' [E_0 + 3 g_f ν (E_d - E_u)]/(4π) per
  // exponential at its nodes (ν = -1 + 2 j / 128), which a ray reads nearest to its own ν: within half a
  // node's step between them; the same in float.
  for (double nu : {-1.0, -0.37, 0.0, 0.5, 0.996, 1.0}) {
    const int node = kd::uwi_source_node(nu);
    const double nu_node = kd::uwi_source_node_cosine(node);
    EXPECT_LE(std::fabs(nu_node - nu), 1.0 / (UWI_SOURCE_NODES - 1) + 1e-12) << nu;
    const double w = kd::uwi_source_weight(&ib, node, 0.4, 0);
    const double expect = ib.b_dm * (ib.o1 + 3 * ib.g_flux * nu_node * (ib.d1 - ib.u1)) / (4 * M_PI);
    EXPECT_NEAR(w, expect, 1e-6 * std::fabs(expect)) << nu;
    const int node_f = kf::uwi_source_node(float(nu));
    EXPECT_EQ(node_f, node);
    EXPECT_NEAR(kf::uwi_source_weight(&ib, node_f, 0.4f, 0), w, 1e-6 * std::fabs(w));
  }
  EXPECT_EQ(kd::uwi_source_node(-2.0), 0);  // clamped
  EXPECT_EQ(kd::uwi_source_node(2.0), UWI_SOURCE_NODES - 1);
}

TEST(UnderwaterOrdinates, AsymptoticClosureDecaysAtTheIsotropicEigenvalue) {
  // κ = K∞/c of isotropic scattering, the root of ω atanh(κ) = κ: Case & Zweifel's tabulated
  // 1/ν0 (ω = 0.5: ν0 = 1.04438; 0.9: 1.90320; 0.99: 5.79672), and its ends (at ω = 1e-6, 1 - κ =
  // 2 e^{-2/ω} is below the double spacing).
  EXPECT_NEAR(seasim::isotropicAsymptoticKappa(0.5), 1 / 1.04438, 1e-5);
  EXPECT_EQ(seasim::isotropicAsymptoticKappa(1e-6), 1.0);
  EXPECT_NEAR(seasim::isotropicAsymptoticKappa(0.9), 1 / 1.90320, 1e-5);
  EXPECT_NEAR(seasim::isotropicAsymptoticKappa(0.99), 1 / 5.79672, 1e-5);
  EXPECT_EQ(seasim::isotropicAsymptoticKappa(0.0), 1.0);
  EXPECT_EQ(seasim::isotropicAsymptoticKappa(1.0), 0.0);
  for (double w : {0.2, 0.3, 0.6, 0.99, 1 - 1e-5}) {
    const double k = seasim::isotropicAsymptoticKappa(w);
    EXPECT_NEAR(w * std::atanh(k), k, 1e-9 * (1 + k)) << w;
  }
  // μ1 = √(1 - ω)/κ: 1 with no scattering, the diffusion limit 1/√3 at ω -> 1, continuous at the
  // 1 - 1e-6 switch to the limit, monotone between, always a cosine.
  EXPECT_EQ(seasim::asymptoticStreamCosine(0.0), 1.0);
  EXPECT_NEAR(seasim::asymptoticStreamCosine(1.0), 1 / std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(seasim::asymptoticStreamCosine(1 - 1.01e-6), seasim::asymptoticStreamCosine(1 - 0.99e-6), 1e-6);
  double prev = 1.0;
  for (int i = 1; i <= 1000; ++i) {
    const double mu = seasim::asymptoticStreamCosine(i / 1000.0);
    EXPECT_LE(mu, prev + 1e-12) << i;
    EXPECT_GE(mu, 1 / std::sqrt(3.0) - 1e-9) << i;
    prev = mu;
  }
  // The band's k is then the similarity medium's K∞ = (a + b'(1 - g')) κ, where the quadrature's is
  // larger (isotropic ω = 0.75: 0.866 c against 0.776 c); deep in a bottomless layer E_d decays at it.
  for (double g : {0.0, 0.5, 0.9}) {
    const UwBand bd = uwTestBand(0.1, 0.3, 0.3, 1.0, 0.9, 0.35);
    const UwiBand ia = makeUwiBand(bd, g, 0.9, 0.0, 1.34, seasim::diffuseMeanCosines(g), TwoStreamClosure::Asymptotic);
    const UwiBand iq = makeUwiBand(bd, g, 0.9, 0.0, 1.34, seasim::diffuseMeanCosines(g), TwoStreamClosure::Quadrature);
    const double bb = ia.b_dm * (1 - ia.g_dm), cs = 0.1 + bb;
    EXPECT_NEAR(ia.k, cs * seasim::isotropicAsymptoticKappa(bb / cs), 1e-6) << g;
    EXPECT_LT(ia.k, 0.95 * iq.k) << g;
    if (g == 0.0) EXPECT_NEAR(ia.k / 0.4, 0.77552, 1e-4);
    if (ia.k < ia.m) {  // the beam's offspring decays faster: far down only e^{-k y} is left
      double e1, u1, e2, u2;
      kd::uwi_irradiance(&ia, 0.0, 200.0, &e1, &u1);
      kd::uwi_irradiance(&ia, 0.0, 201.0, &e2, &u2);
      EXPECT_NEAR(std::log(e1 / e2), ia.k, 2e-3 * ia.k) << g;
    }
  }
}

TEST(UnderwaterOrdinates, InternalDiffuseReflectance) {
  // 2 ∫ F μ dμ from below: 1 - (1 - r_ext)/n² by reciprocity (r_ext the external hemispherical
  // reflectance of a uniform sky, integrated here independently in double).
  for (double n : {1.33, 1.34, 1.5}) {
    double ext = 0;
    const int N = 200000;
    for (int i = 0; i < N; ++i) {
      const double mu = (i + 0.5) / N;
      ext += kd::fresnel_reflectance(mu, 1.0, n) * mu;
    }
    ext *= 2.0 / N;
    EXPECT_NEAR(seasim::internalDiffuseReflectance(n), 1 - (1 - ext) / (n * n), 2e-4) << n;
  }
  EXPECT_NEAR(seasim::internalDiffuseReflectance(1.34), 0.47, 0.02);
}

// The rays' azimuths k × the golden angle π(3 − √5), advanced by rotation, against cos and sin of the
// angle itself for every ray of uwi_bottom_visibility and uwi_sand_seen_lit.
TEST(UnderwaterOrdinates, GoldenAngleRotationGivesEachRaysAzimuth) {
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  double cd = 1.0, sd = 0.0;
  float cf = 1.0f, sf = 0.0f;
  for (int k = 0; k < 2 * UWI_BOTTOM_RAYS; ++k) {
    EXPECT_NEAR(cd, std::cos(golden * k), 1e-14) << k;
    EXPECT_NEAR(sd, std::sin(golden * k), 1e-14) << k;
    EXPECT_NEAR(cf, std::cos(golden * k), 2e-6) << k;
    EXPECT_NEAR(sf, std::sin(golden * k), 2e-6) << k;
    kd::uwi_golden_advance(&cd, &sd);
    kf::uwi_golden_advance(&cf, &sf);
  }
}

}  // namespace
