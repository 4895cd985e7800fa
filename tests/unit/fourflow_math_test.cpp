// fourflow_math_test.cpp — the four-flow model of paper 003 (kernels/common/fourflow.h) in float and
// double against the numerical boundary-value solve of its ODEs (host/reference/fourflow_reference),
// which shares no formula with the closed form: a grid over (k, S, X1, τ0, bottom reflectance) with
// two surfaces, the resonance λ0 -> λ, deep water (τ0 = 50, 200), the paper's own form where it is
// well conditioned, energy (Fresnel R + T = 1, k = 0 loses nothing) and the limits h -> 0, h -> ∞.
#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <vector>

#include "math/kernel_math.h"
#include "reference/fourflow_reference.h"

namespace {

namespace kd = seasim::kmath_d;
namespace kf = seasim::kmath_f;

struct Case {
  double k, S, S1, S2, tau0;
  kd::FfSurface srf;
  kd::FfBottom bot;
  double e_sun, e_sky;
};

// The constants of 003 eq. 4 with k, S and X1 chosen independently (the paper ties S to X1 through
// its approximations; the solution must hold for any S > 0): S1, S2 share the albedo 1 - k.
Case makeCase(double k, double S, double x1, double tau0, const kd::FfSurface& srf, const kd::FfBottom& bot) {
  Case c{};
  c.k = k;
  c.S = S;
  c.S1 = 0.5 * (1 - k) * (1 + x1);
  c.S2 = 0.5 * (1 - k) * (1 - x1);
  c.tau0 = tau0;
  c.srf = srf;
  c.bot = bot;
  c.e_sun = 0.8;
  c.e_sky = 0.3;
  return c;
}

seasim::FourFlowBvp toBvp(const Case& c) {
  seasim::FourFlowBvp p;
  p.k = c.k, p.S = c.S, p.S1 = c.S1, p.S2 = c.S2, p.tau0 = c.tau0;
  p.T_dd = c.srf.T_dd, p.T_df = c.srf.T_df, p.T_ff = c.srf.T_ff;
  p.Rw_dd = c.srf.Rw_dd, p.Rw_df = c.srf.Rw_df, p.Rw_ff = c.srf.Rw_ff;
  p.Rb_dd = c.bot.R_dd, p.Rb_df = c.bot.R_df, p.Rb_ff = c.bot.R_ff;
  p.e_sun = c.e_sun, p.e_sky = c.e_sky;
  return p;
}

// The same case with every input rounded to float, as the float path sees it.
Case roundedToFloat(Case c) {
  auto f = [](double& v) { v = double(float(v)); };
  f(c.k), f(c.S), f(c.S1), f(c.S2), f(c.tau0), f(c.e_sun), f(c.e_sky);
  f(c.srf.T_dd), f(c.srf.T_df), f(c.srf.T_ff), f(c.srf.Rw_dd), f(c.srf.Rw_df), f(c.srf.Rw_ff);
  f(c.bot.R_dd), f(c.bot.R_df), f(c.bot.R_ff);
  return c;
}

kd::FfSolution solveD(const Case& c) {
  kd::FfMedium m{c.k, c.S, c.S1, c.S2};
  return kd::ff_solve(m, c.srf, c.bot, c.tau0, c.e_sun, c.e_sky);
}

kf::FfSolution solveF(const Case& c) {
  kf::FfMedium m{float(c.k), float(c.S), float(c.S1), float(c.S2)};
  kf::FfSurface s{float(c.srf.T_dd), float(c.srf.T_df), float(c.srf.T_ff),
                  float(c.srf.Rw_dd), float(c.srf.Rw_df), float(c.srf.Rw_ff)};
  kf::FfBottom b{float(c.bot.R_dd), float(c.bot.R_df), float(c.bot.R_ff)};
  return kf::ff_solve(m, s, b, float(c.tau0), float(c.e_sun), float(c.e_sky));
}

// The five boundary values eq. 11–13 use: G+(τ0), F+(τ0), F-(τ0), F+(0), F-(0).
std::array<double, 5> boundaryValues(const kd::FfSolution& s) {
  return {s.C1 * std::exp(-kd::ff_lambda(s.m) * s.tau0), s.Fp_bot, s.Fm_bot, s.Fp_top, s.Fm_top};
}
std::array<double, 5> boundaryValues(const kf::FfSolution& s) {
  return {double(s.C1 * std::exp(-kf::ff_lambda(s.m) * s.tau0)), double(s.Fp_bot), double(s.Fm_bot),
          double(s.Fp_top), double(s.Fm_top)};
}
std::array<double, 5> boundaryValues(const seasim::FourFlowProfile& p) {
  const auto& top = p.flow.front();
  const auto& bot = p.flow.back();
  return {bot[0], bot[2], bot[3], top[2], top[3]};
}

// Error model: |got - want| <= rel |want| + abs, abs a fraction of the incoming light I = E_sun + E_sky.
// Double: rel = 1e-6 (the figure) and abs = 1e-11 I, the size of the closed form's τ0 clamp
// (FF_TAU0_MIN = 1e-12) and of the reference's round-off around exact zeros (a black bottom under
// τ0 = 0). Float: rel = 1e-6 and abs = 1e-10 I, the abs part only for values that underflow or sit
// at the clamp (G+(τ0) at τ0 = 200 is 1e-87 I). The outgoing flows F-(0), F+(τ0) are computed by
// adding the layer to its boundaries (fourflow.h ff_solve), sums of non-negative terms; an earlier
// form read F-(0) as (s(0) - src)/(1 + R~ff), a difference of O(I) flows, and reached 4e-5 relative
// on a small F-(0) (a black bottom under a thin layer: FourFlowMath.SmallFlowsInFloat).
double excess(double got, double want, double rel, double abs) {
  return std::fabs(got - want) / (rel * std::fabs(want) + abs);
}
double relErr(double got, double want) { return std::fabs(got - want) / std::max(std::fabs(want), 1e-300); }

// A realistic surface (flat water, sun 30° from the zenith) and one that exercises every term of
// eq. 7 (rough-surface-like df coefficients and an upward beam reflected under the surface).
kd::FfSurface flatSurface() { return kd::ff_flat_surface(std::cos(30.0 * M_PI / 180.0), 1.333); }
kd::FfSurface fullSurface() { return kd::FfSurface{0.88, 0.04, 0.91, 0.06, 0.05, 0.47}; }

// Runs the whole grid; returns the worst relative errors (double, float) over the boundary values and,
// in double, over the flows at interior nodes.
struct GridResult {
  double worst_d = 0, worst_f = 0, worst_interior = 0;  // relative, over values > 1e-9 I (float: > 1e-7 I)
  double worst_f_abs = 0;                                // float, absolute, in units of I
  int cases = 0;
};

void checkCase(const Case& c, GridResult& g, double tol_d, double tol_f) {
  const auto ref = seasim::solveFourFlowBvp(toBvp(c));
  const auto vd = boundaryValues(solveD(c));
  const auto vr = boundaryValues(ref);
  const double I = c.e_sun + c.e_sky;
  for (int i = 0; i < 5; ++i) {
    if (std::fabs(vr[i]) > 1e-9 * I) g.worst_d = std::max(g.worst_d, relErr(vd[i], vr[i]));
    EXPECT_LE(excess(vd[i], vr[i], tol_d, 1e-11 * I), 1.0) << "value " << i << " k=" << c.k << " S=" << c.S << " S1=" << c.S1 << " tau0=" << c.tau0
                        << " Rb=" << c.bot.R_ff << ": " << vd[i] << " vs " << vr[i];
  }
  // Interior flows of eq. 5 at a few nodes (ff_flows_at), where the flows are not vanishingly small.
  const kd::FfSolution sd = solveD(c);
  for (size_t n = 0; n < ref.tau.size(); n += std::max<size_t>(1, ref.tau.size() / 7)) {
    const kd::FfFlows f = kd::ff_flows_at(sd, ref.tau[n]);
    const double got[4] = {f.Gp, f.Gm, f.Fp, f.Fm};
    for (int j = 0; j < 4; ++j) {
      const double want = ref.flow[n][j];
      if (std::fabs(want) > 1e-9 * I) g.worst_interior = std::max(g.worst_interior, relErr(got[j], want));
      EXPECT_LE(excess(got[j], want, tol_d, 1e-11 * I), 1.0) << "interior tau=" << ref.tau[n] << " flow " << j << " k=" << c.k << " S=" << c.S
                          << " tau0=" << c.tau0;
    }
  }
  // Float: against the reference for the float-rounded inputs, so only the arithmetic is measured.
  const Case cf = roundedToFloat(c);
  const auto vf = boundaryValues(solveF(cf));
  const auto vrf = boundaryValues(seasim::solveFourFlowBvp(toBvp(cf)));
  for (int i = 0; i < 5; ++i) {
    EXPECT_TRUE(std::isfinite(vf[i]));
    if (std::fabs(vrf[i]) > 1e-7 * I) g.worst_f = std::max(g.worst_f, relErr(vf[i], vrf[i]));
    g.worst_f_abs = std::max(g.worst_f_abs, std::fabs(vf[i] - vrf[i]) / I);
    EXPECT_LE(excess(vf[i], vrf[i], tol_f, 1e-10 * I), 1.0) << "float value " << i << " k=" << c.k << " S=" << c.S << " S1=" << c.S1
                        << " tau0=" << c.tau0 << " Rb=" << c.bot.R_ff << ": " << vf[i] << " vs " << vrf[i];
  }
  ++g.cases;
}

constexpr double kTolDouble = 1e-6;
constexpr double kTolFloat = 1e-6;

TEST(FourFlowMath, ClosedFormMatchesNumericalSolveOverTheGrid) {
  GridResult g;
  for (const kd::FfSurface& srf : {flatSurface(), fullSurface()}) {
    for (double k : {0.0, 0.02, 0.3, 0.8, 1.0}) {
      for (double S : {0.05, 0.5, 1.5}) {
        for (double x1 : {-0.6, 0.0, 0.5, 0.95}) {
          for (double tau0 : {0.0, 0.01, 0.5, 3.0, 20.0}) {
            for (double rb : {0.0, 0.3, 1.0}) {
              kd::FfBottom bot = kd::ff_lambert_bottom(rb);
              if (srf.Rw_df > 0) bot.R_dd = 0.2 * rb;  // a partly specular bottom with the full surface
              checkCase(makeCase(k, S, x1, tau0, srf, bot), g, kTolDouble, kTolFloat);
            }
          }
        }
      }
    }
  }
  std::printf("four-flow grid: %d cases, worst relative error: double %.2e (interior %.2e), float %.2e (values > 1e-7 I), float absolute %.2e I\n",
              g.cases, g.worst_d, g.worst_interior, g.worst_f, g.worst_f_abs);
  EXPECT_EQ(g.cases, 1800);
}

TEST(FourFlowMath, ResonanceLambda0ToLambda) {
  // λ = 1; λ0² = k (k + 2S) = 1 at S* = (1 - k²)/(2k). At and around it A1, A2 of the paper divide by 0.
  GridResult g;
  for (double k : {0.2, 0.5, 0.9}) {
    const double s_star = (1 - k * k) / (2 * k);
    for (double rel : {0.0, 1e-12, -1e-12, 1e-9, -1e-9, 1e-6, -1e-6, 1e-3, -1e-3}) {
      for (double tau0 : {0.3, 4.0, 50.0}) {
        for (double x1 : {-0.5, 0.7}) {
          checkCase(makeCase(k, s_star * (1 + rel), x1, tau0, flatSurface(), kd::ff_lambert_bottom(0.4)), g,
                    kTolDouble, kTolFloat);
        }
      }
    }
  }
  std::printf("resonance: %d cases, worst relative error: double %.2e (interior %.2e), float %.2e (values > 1e-7 I), float absolute %.2e I\n",
              g.cases, g.worst_d, g.worst_interior, g.worst_f, g.worst_f_abs);
  // The paper's A1 really diverges there (so the test is at the singular point).
  const double k = 0.5, s_star = (1 - k * k) / (2 * k);
  EXPECT_GT(std::fabs(kd::ff_A1(kd::FfMedium{k, s_star * (1 + 1e-12), 0.25, 0.25})), 1e9);
}

TEST(FourFlowMath, DeepWaterTau50And200) {
  GridResult g;
  for (double tau0 : {50.0, 200.0}) {
    for (double k : {0.0, 0.01, 0.3, 0.9}) {
      for (double S : {0.1, 0.8}) {
        for (double rb : {0.0, 0.5, 1.0}) {
          checkCase(makeCase(k, S, 0.8, tau0, fullSurface(), kd::ff_lambert_bottom(rb)), g, kTolDouble, kTolFloat);
        }
      }
    }
  }
  std::printf("deep water: %d cases, worst relative error: double %.2e (interior %.2e), float %.2e (values > 1e-7 I), float absolute %.2e I\n",
              g.cases, g.worst_d, g.worst_interior, g.worst_f, g.worst_f_abs);
  // The naive form would need e^{λ τ0}: float overflows beyond 88.7, so τ0 = 200 is past it.
  EXPECT_TRUE(std::isinf(std::exp(200.0f)));
}

// The paper's eq. 5 basis, (A1, A2) e^{-λτ}, (1, A3) e^{-λ0τ}, (1, A4) e^{λ0τ}, (A2, A1) e^{λτ}, with
// the boundary conditions of eq. 7 solved directly (the typo-corrected eq. 8–9): well conditioned for
// moderate τ0, k > 0 and λ0 away from λ, where the rescaled form must give the same numbers.
std::array<double, 2> paperForm(const Case& c) {
  kd::FfMedium m{c.k, c.S, c.S1, c.S2};
  const double l = kd::ff_lambda(m), l0 = kd::ff_lambda0(m);
  const double A1 = kd::ff_A1(m), A2 = kd::ff_A2(m), A3 = kd::ff_A3(m), A4 = kd::ff_A4(m);
  const double t0 = c.tau0;
  // G+ = C1 e^{-λτ}, G- = C4 e^{λτ}: G+(0) = T E + R~ C4, C4 e^{λτ0} = R^ C1 e^{-λτ0}.
  const double C1 = c.srf.T_dd * c.e_sun / (1 - c.srf.Rw_dd * c.bot.R_dd * std::exp(-2 * l * t0));
  const double C4 = c.bot.R_dd * C1 * std::exp(-2 * l * t0);
  auto Fp = [&](double t, double C2, double C3) {
    return C1 * A1 * std::exp(-l * t) + C2 * std::exp(-l0 * t) + C3 * std::exp(l0 * t) + C4 * A2 * std::exp(l * t);
  };
  auto Fm = [&](double t, double C2, double C3) {
    return C1 * A2 * std::exp(-l * t) + C2 * A3 * std::exp(-l0 * t) + C3 * A4 * std::exp(l0 * t) + C4 * A1 * std::exp(l * t);
  };
  const double gm0 = C4, gp1 = C1 * std::exp(-l * t0);
  const double src_t = c.srf.T_df * c.e_sun + c.srf.T_ff * c.e_sky + c.srf.Rw_df * gm0;
  const double src_b = c.bot.R_df * gp1;
  // Linear in (C2, C3): rows r(C2, C3) = Fp - R~ Fm - src at 0 and Fm - R^ Fp - src at τ0.
  auto top = [&](double C2, double C3) { return Fp(0, C2, C3) - c.srf.Rw_ff * Fm(0, C2, C3) - src_t; };
  auto bot = [&](double C2, double C3) { return Fm(t0, C2, C3) - c.bot.R_ff * Fp(t0, C2, C3) - src_b; };
  const double t00 = top(0, 0), b00 = bot(0, 0);
  const double a11 = top(1, 0) - t00, a12 = top(0, 1) - t00, a21 = bot(1, 0) - b00, a22 = bot(0, 1) - b00;
  const double det = a11 * a22 - a12 * a21;
  const double C2 = (-t00 * a22 + a12 * b00) / det, C3 = (-a11 * b00 + a21 * t00) / det;
  return {Fm(0, C2, C3), Fp(t0, C2, C3)};
}

TEST(FourFlowMath, EqualsThePapersFormWhereThatIsWellConditioned) {
  int n = 0;
  for (double k : {0.05, 0.3, 0.7}) {
    for (double x1 : {0.0, 0.9}) {
      for (double tau0 : {0.2, 2.0, 6.0}) {
        for (double rb : {0.0, 0.5}) {
          Case c = makeCase(k, (1 - k) * (1 - 0.5 * x1), x1, tau0, fullSurface(), kd::ff_lambert_bottom(rb));
          c.bot.R_dd = 0.1;
          const auto paper = paperForm(c);
          const kd::FfSolution s = solveD(c);
          EXPECT_NEAR(s.Fm_top / paper[0], 1.0, 1e-10) << k << " " << x1 << " " << tau0;
          EXPECT_NEAR(s.Fp_bot / paper[1], 1.0, 1e-10) << k << " " << x1 << " " << tau0;
          ++n;
        }
      }
    }
  }
  EXPECT_EQ(n, 36);
}

TEST(FourFlowMath, MediumConstantsFromTheText) {
  // 003 eq. 4 text: k = χ/ε, S = σ/ε (1 - X1/2), S1,2 = σ/(2ε)(1 ± X1), so λ = k + S1 + S2 = 1.
  const kd::FfMedium m = kd::ff_medium(0.06, 0.24, 0.9);
  EXPECT_DOUBLE_EQ(m.k, 0.2);
  EXPECT_DOUBLE_EQ(m.S, 0.8 * 0.55);
  EXPECT_DOUBLE_EQ(m.S1, 0.4 * 1.9);
  EXPECT_NEAR(m.S2, 0.4 * 0.1, 1e-16);
  EXPECT_NEAR(kd::ff_lambda(m), 1.0, 1e-15);
  EXPECT_NEAR(kd::ff_lambda0(m), std::sqrt(0.2 * (0.2 + 2 * 0.44)), 1e-15);
  // A3 A4 = 1, and A3 is the eigenvector ratio (k + S - λ0)/S of the diffuse system.
  EXPECT_NEAR(kd::ff_A3(m) * kd::ff_A4(m), 1.0, 1e-15);
  EXPECT_NEAR(kd::ff_A3(m), (m.k + m.S - kd::ff_lambda0(m)) / m.S, 1e-15);
}

TEST(FourFlowMath, FresnelCoefficientsOfAFlatSurface) {
  const double n = 1.333;
  // The diffuse reflectance from air: ≈ 6.6 % for water; converged at the default interval count.
  const double r_air = kd::ff_diffuse_reflectance(1.0, n, FF_FRESNEL_INTERVALS);
  const double r_air_fine = kd::ff_diffuse_reflectance(1.0, n, 4096);
  EXPECT_NEAR(r_air, r_air_fine, 1e-9);
  EXPECT_NEAR(r_air, 0.066, 0.002);
  // From the water side, with total internal reflection beyond the critical angle.
  const double r_w = kd::ff_diffuse_reflectance(n, 1.0, FF_FRESNEL_INTERVALS);
  const double r_w_fine = kd::ff_diffuse_reflectance(n, 1.0, 4096);
  EXPECT_NEAR(r_w, r_w_fine, 1e-9);
  // The n² law for Lambertian light (Snell: n² μw dμw = μa dμa, same Fresnel term for the pair):
  // T~_ff = T_ff / n². An independent check of both quadratures and of the critical-angle split.
  EXPECT_NEAR(1 - r_w, (1 - r_air) / (n * n), 1e-9);
  EXPECT_NEAR(kd::ff_diffuse_reflectance(1.0, 1.0, 64), 0.0, 1e-15);
  // Float agrees to float precision.
  EXPECT_NEAR(kf::ff_diffuse_reflectance(float(n), 1.0f, FF_FRESNEL_INTERVALS), r_w, 2e-6);
  // 003 eq. 6: R + T = 1 for each kind of light, at every sun angle, in float and double.
  for (double deg : {0.0, 30.0, 60.0, 85.0, 89.9, 90.0}) {
    const double mu = std::cos(deg * M_PI / 180.0);
    const kd::FfSurface s = kd::ff_flat_surface(mu, n);
    const double R_dd = kd::fresnel_reflectance(mu, 1.0, n);
    EXPECT_NEAR(s.T_dd + s.T_df + R_dd, 1.0, 1e-15) << deg;
    EXPECT_NEAR(s.T_ff + r_air, 1.0, 1e-15) << deg;
    EXPECT_EQ(s.T_df, 0.0);
    EXPECT_EQ(s.Rw_df, 0.0);
    EXPECT_NEAR(s.Rw_dd, R_dd, 1e-15);  // same Fresnel term for the refracted pair
    const kf::FfSurface sf = kf::ff_flat_surface(float(mu), float(n));
    EXPECT_NEAR(double(sf.T_dd) + double(kf::fresnel_reflectance(float(mu), 1.0f, float(n))), 1.0, 1e-7);
  }
}

// Energy through the surface for the flat surface: in = E_sun + E_sky (on a horizontal plane); out =
// reflected (R_dd E_sun + R_ff E_sky) + transmitted up ((1 - R~_dd) G-(0) + (1 - R~_ff) F-(0)).
double energyOut(const kd::FfSolution& s, const kd::FfSurface& srf, double mu_sun, double n, double e_sun,
                 double e_sky) {
  const double r_dd = kd::fresnel_reflectance(mu_sun, 1.0, n);
  const double r_ff = 1 - srf.T_ff;
  const double gm0 = s.C4s * std::exp(-kd::ff_lambda(s.m) * s.tau0);
  return r_dd * e_sun + r_ff * e_sky + (1 - srf.Rw_dd) * gm0 + (1 - srf.Rw_ff) * s.Fm_top;
}

TEST(FourFlowMath, NoAbsorptionLosesNothing) {
  const double mu = std::cos(40.0 * M_PI / 180.0), n = 1.333;
  const kd::FfSurface srf = kd::ff_flat_surface(mu, n);
  for (double S : {0.05, 0.5, 2.0}) {
    for (double x1 : {-0.3, 0.0, 0.9}) {
      for (double tau0 : {0.0, 0.1, 2.0, 50.0, 200.0}) {
        for (double rb : {0.3, 1.0}) {
          Case c = makeCase(0.0, S, x1, tau0, srf, kd::ff_lambert_bottom(rb));
          c.bot.R_dd = 0.1 * rb;  // partly specular; R_dd + R_df = rb
          c.bot.R_df = 0.9 * rb;
          const kd::FfSolution s = solveD(c);
          // Net downward flux N = G+ - G- + F+ - F- is constant in τ when k = 0 (sum of eq. 4).
          const kd::FfFlows top = kd::ff_flows_at(s, 0), mid = kd::ff_flows_at(s, 0.5 * s.tau0);
          const double n_top = top.Gp - top.Gm + top.Fp - top.Fm, n_mid = mid.Gp - mid.Gm + mid.Fp - mid.Fm;
          // At the bottom G- = R^dd G+ (F-(τ0) already holds R^df G+).
          const double n_bot = s.C1 * std::exp(-s.tau0) * (1 - c.bot.R_dd) + s.Fp_bot - s.Fm_bot;
          EXPECT_NEAR(n_mid, n_top, 1e-9 * (c.e_sun + c.e_sky)) << S << " " << x1 << " " << tau0;
          EXPECT_NEAR(n_bot, n_top, 1e-9 * (c.e_sun + c.e_sky)) << S << " " << x1 << " " << tau0;
          // What the bottom absorbs plus what leaves = what came in.
          const double absorbed = n_bot;
          const double out = energyOut(s, srf, mu, n, c.e_sun, c.e_sky);
          EXPECT_NEAR(absorbed + out, c.e_sun + c.e_sky, 1e-9 * (c.e_sun + c.e_sky)) << S << " " << x1 << " " << tau0;
          EXPECT_GE(absorbed, -1e-12);
          // Float: same balance to float precision.
          const Case cf = roundedToFloat(c);
          const kf::FfSolution sf = solveF(cf);
          const kd::FfSolution sd = solveD(cf);
          EXPECT_NEAR(double(sf.Fm_top), sd.Fm_top, 2e-5 * (c.e_sun + c.e_sky)) << S << " " << x1 << " " << tau0;
        }
      }
    }
  }
  // A white Lambertian bottom and no absorption: everything comes back out.
  Case c = makeCase(0.0, 0.5, 0.8, 5.0, srf, kd::ff_lambert_bottom(1.0));
  const kd::FfSolution s = solveD(c);
  EXPECT_NEAR(energyOut(s, srf, mu, n, c.e_sun, c.e_sky), c.e_sun + c.e_sky, 1e-9);
}

TEST(FourFlowMath, ThinWaterShowsTheBottom) {
  // h -> 0: the layer vanishes and F-(0) = R^ (G+(0) + F+(0)) with F+(0) = src + R~ff F-(0):
  //   F-(0) = R^ (T_dd E_sun + T_ff E_sky) / (1 - R^ R~ff) for a Lambertian bottom, flat surface.
  const kd::FfSurface srf = flatSurface();
  for (double rb : {0.1, 0.5, 0.9}) {
    const double limit = rb * (srf.T_dd * 0.8 + srf.T_ff * 0.3) / (1 - rb * srf.Rw_ff);
    double prev_err = 1e300;
    for (double tau0 : {1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 0.0}) {
      Case c = makeCase(0.3, 0.5, 0.8, tau0, srf, kd::ff_lambert_bottom(rb));
      const double up = solveD(c).Fm_top;
      const double err = std::fabs(up / limit - 1);
      EXPECT_LE(err, 3 * std::max(tau0, 1e-6)) << rb << " " << tau0;  // first order in τ0
      EXPECT_LE(err, prev_err * 1.0000001) << rb << " " << tau0;
      prev_err = err;
      const double upf = solveF(roundedToFloat(c)).Fm_top;
      EXPECT_NEAR(upf / limit, 1.0, 3 * std::max(tau0, 1e-6) + 1e-5) << rb << " " << tau0;
    }
  }
}

TEST(FourFlowMath, SmallFlowsInFloat) {
  // At and near τ0 -> 0 over a black bottom F-(0) is small (~ S2 τ0 of the sun, S τ0 of the sky)
  // under O(1) incoming flows: the case where reading it as a difference lost digits in float. Here
  // float must match the double reference to 1e-6 relative down to τ0 = 1e-6, including k = 0 (the
  // diffuse modes coalesce) and λ0 = λ (resonance, S = (1 - k²)/(2k)).
  GridResult g;
  for (double k : {0.0, 0.3, 0.5, 0.9}) {
    for (double S : {0.05, 0.75, 1.5}) {
      for (double x1 : {-0.5, 0.9}) {
        for (double tau0 : {1e-6, 1e-5, 1e-4, 1e-3, 1e-2, 0.1}) {
          for (double rb : {0.0, 0.02}) {
            checkCase(makeCase(k, S, x1, tau0, flatSurface(), kd::ff_lambert_bottom(rb)), g, kTolDouble, kTolFloat);
            checkCase(makeCase(k, S, x1, tau0, fullSurface(), kd::ff_lambert_bottom(rb)), g, kTolDouble, kTolFloat);
          }
        }
      }
    }
  }
  std::printf("small flows: %d cases, worst relative error: double %.2e, float %.2e (values > 1e-7 I)\n", g.cases,
              g.worst_d, g.worst_f);
  EXPECT_LE(g.worst_f, kTolFloat);
  // F-(0) really is small there: a thin layer over a black bottom reflects ~τ0 of the light.
  const Case thin = makeCase(0.3, 0.5, 0.9, 1e-4, flatSurface(), kd::ff_lambert_bottom(0.0));
  EXPECT_LT(solveD(thin).Fm_top, 1e-3 * (thin.e_sun + thin.e_sky));
}

TEST(FourFlowMath, DeepWaterTendsToTheSemiInfiniteSolution) {
  // τ0 = ∞: no upward beam, no growing mode: F = C1 (A1, A2) e^{-λτ} + C2 (1, A3) e^{-λ0τ} with
  // F+(0) = T_ff E_sky + R~ff F-(0) (flat surface), C1 = T_dd E_sun.
  const kd::FfSurface srf = flatSurface();
  for (double k : {0.05, 0.3, 0.8}) {
    for (double x1 : {0.0, 0.9}) {
      Case c = makeCase(k, (1 - k) * (1 - 0.5 * x1), x1, 0, srf, kd::ff_lambert_bottom(0.7));
      kd::FfMedium m{c.k, c.S, c.S1, c.S2};
      const double A1 = kd::ff_A1(m), A2 = kd::ff_A2(m), A3 = kd::ff_A3(m);
      const double C1 = srf.T_dd * c.e_sun;
      const double C2 = (srf.T_ff * c.e_sky + C1 * (srf.Rw_ff * A2 - A1)) / (1 - srf.Rw_ff * A3);
      const double semi = C1 * A2 + C2 * A3;
      // The bottom's share decays like e^{-2 min(λ, λ0) τ0} (down and back up the slowest mode).
      const double slowest = std::min(kd::ff_lambda(m), kd::ff_lambda0(m));
      for (double tau0 : {1.0, 5.0, 20.0, 50.0, 200.0, 1e4}) {
        c.tau0 = tau0;
        const double err = std::fabs(solveD(c).Fm_top / semi - 1);
        EXPECT_LE(err, 100 * std::exp(-2 * slowest * tau0) + 1e-12) << k << " " << x1 << " " << tau0;
        if (tau0 >= 50) {
          EXPECT_NEAR(solveF(roundedToFloat(c)).Fm_top / semi, 1.0, 2e-5);
        }
      }
    }
  }
}

TEST(FourFlowMath, ExtremeInputsStayFinite) {
  int n = 0;
  for (float k : {0.0f, 1e-7f, 0.5f, 1.0f}) {
    for (float S : {1e-6f, 0.5f, 10.0f}) {
      for (float tau0 : {0.0f, 1e-30f, 1e-3f, 88.0f, 1e4f, 1e30f}) {
        for (float rb : {0.0f, 1.0f}) {
          kf::FfMedium m{k, S, 0.5f * (1 - k) * 1.9f, 0.5f * (1 - k) * 0.1f};
          const kf::FfSurface srf = kf::ff_flat_surface(0.0f, 1.333f);  // grazing sun too
          const kf::FfSolution s = kf::ff_solve(m, srf, kf::ff_lambert_bottom(rb), tau0, 1.0f, 1.0f);
          EXPECT_TRUE(std::isfinite(s.Fm_top) && std::isfinite(s.Fp_bot) && std::isfinite(kf::ff_bottom_irradiance(s)))
              << k << " " << S << " " << tau0 << " " << rb;
          const kf::FfFlows f = kf::ff_flows_at(s, 0.5f * s.tau0);
          EXPECT_TRUE(std::isfinite(f.Fp) && std::isfinite(f.Fm) && std::isfinite(f.Gp) && std::isfinite(f.Gm));
          EXPECT_GE(s.Fm_top, 0.0f);
          ++n;
        }
      }
    }
  }
  EXPECT_EQ(n, 144);
}

}  // namespace

namespace {

TEST(FourFlowReference, ConvergesWithItsStepAndSegmentLength) {
  // The reference's own error: RK4 at 32 steps per 0.25 optical depth against 4x finer steps and
  // shorter segments, on deep, resonant and conservative cases.
  for (double k : {0.0, 0.5, 0.95}) {
    for (double tau0 : {0.7, 30.0, 200.0}) {
      Case c = makeCase(k, k == 0.5 ? 0.75 : 0.4, 0.6, tau0, fullSurface(), kd::ff_lambert_bottom(0.5));
      const auto coarse = boundaryValues(seasim::solveFourFlowBvp(toBvp(c)));
      const auto fine = boundaryValues(seasim::solveFourFlowBvp(toBvp(c), 0.1, 64));
      for (int i = 0; i < 5; ++i) {
        EXPECT_LE(std::fabs(coarse[i] - fine[i]), 1e-8 * std::fabs(fine[i]) + 1e-300) << k << " " << tau0 << " " << i;
      }
    }
  }
}

}  // namespace
