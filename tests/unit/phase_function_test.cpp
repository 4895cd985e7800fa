// phase_function_test.cpp — the water's phase functions (kernels/common/phase.h in float and double,
// host/radiometry/phase_function.*): normalisation by an independent quadrature, the moments against
// closed forms, Fournier–Forand's stiff points (the 0/0 at δ = 1, ψ -> 0, b_b/b from 0.001 to 0.5),
// Petzold's published g and b_b/b, the inverse-CDF sampler by χ² against the phase's own bin
// probabilities (Petzold and a phase with a 0.1° forward peak), and the table loader's errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "math/kernel_math.h"
#include "radiometry/phase_function.h"
#include "util/error.h"

namespace {

using seasim::PhaseFunction;
namespace kd = seasim::kmath_d;
namespace kf = seasim::kmath_f;
constexpr double kPi = 3.14159265358979323846;

// 2π ∫ f(ψ) sin ψ dψ over [psi0, psi1] by Simpson's rule in t = ln ψ (dψ = ψ dt: power laws ψ^m, m > -2,
// at the origin become smooth), from max(psi0, 1e-12); below 1e-12 (when psi0 = 0) the power law through
// f(1e-12) and f(2e-12) in closed form. A different rule, grid and head from the class's trapezoids.
template <class F>
double sphereIntegral(F f, double psi0 = 0, double psi1 = kPi, int n = 200000) {
  const double lo = std::max(psi0, 1e-12), t0 = std::log(lo), t1 = std::log(psi1), h = (t1 - t0) / n;
  double s = 0;
  for (int i = 0; i <= n; ++i) {
    const double psi = std::exp(t0 + i * h);
    const double w = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
    s += w * f(psi) * std::sin(psi) * psi;
  }
  double head = 0;
  if (psi0 <= 0) {
    const double m = std::log(f(2e-12) / f(1e-12)) / std::log(2.0);
    head = f(1e-12) * 1e-24 / (m + 2);
  }
  return 2 * kPi * (s * h / 3 + head);
}

std::string writeTemp(const std::string& name, const std::string& text) {
  const std::string path = (std::filesystem::temp_directory_path() / name).string();
  std::ofstream(path) << text;
  return path;
}

TEST(PhaseFunction, EveryKindIsNormalised) {
  std::vector<PhaseFunction> phases = {PhaseFunction::henyeyGreenstein(0.9), PhaseFunction::rayleighLike(),
                                       PhaseFunction::fournierForand(0.001), PhaseFunction::fournierForand(0.0183),
                                       PhaseFunction::fournierForand(0.3), PhaseFunction::fournierForand(0.5),
                                       PhaseFunction::petzold()};
  for (const PhaseFunction& p : phases) {
    const double total = sphereIntegral([&](double psi) { return p.evaluate(psi); });
    EXPECT_NEAR(total, 1.0, 2e-4) << p.name();
    EXPECT_NEAR(p.legendreMoments(1)[0], 1.0, 1e-12) << p.name();
  }
}

TEST(PhaseFunction, RayleighLikeMomentsAreClosedForm) {
  const PhaseFunction p = PhaseFunction::rayleighLike();
  const std::vector<double> chi = p.legendreMoments(6);
  const double a = 0.835;
  EXPECT_NEAR(chi[1], 0.0, 1e-6);
  EXPECT_NEAR(chi[2], 2 * a / (5 * (3 + a)), 1e-6);
  EXPECT_NEAR(chi[3], 0.0, 1e-6);
  EXPECT_NEAR(chi[4], 0.0, 1e-6);
  EXPECT_NEAR(p.backscatterRatio(), 0.5, 1e-6);
  // float and double agree with the closed form at the poles: (1 + a) / (4π (1 + a/3)).
  EXPECT_NEAR(kf::phase_rayleigh_like(1.0f), (1 + a) / (4 * kPi * (1 + a / 3)), 1e-7);
  EXPECT_NEAR(kd::phase_rayleigh_like(-1.0), (1 + a) / (4 * kPi * (1 + a / 3)), 1e-15);
}

// The quadrature's moments of a tabulated HG reproduce g^l: the table path (log-log interpolation,
// normalisation on load, moments by quadrature) against the closed form.
TEST(PhaseFunction, TabulatedHgMomentsMatchPowersOfG) {
  std::vector<double> ang, val;
  for (int i = 0; i <= 400; ++i) {
    const double deg = 0.01 * std::pow(18000.0, i / 400.0);  // 0.01° to 180°
    ang.push_back(deg);
    val.push_back(7.0 * kd::hg_phase(std::cos(deg * kPi / 180), 0.9));  // any scale: normalised on load
  }
  const PhaseFunction p = PhaseFunction::table(ang, val, "hg table");
  const std::vector<double> chi = p.legendreMoments(33);
  for (int l = 1; l < 33; ++l) EXPECT_NEAR(chi[l], std::pow(0.9, l), 2e-3) << "l = " << l;
  EXPECT_NEAR(p.evaluate(kPi / 3), kd::hg_phase(0.5, 0.9), 1e-3 * kd::hg_phase(0.5, 0.9));
}

// The series that replaces N / (1 - δ)² for |1 - δ| < 0.05 continues the direct formula across the
// switch (both in double: the direct one has lost ~20 eps there), and float stays within 1e-5 of double
// right at δ = 1 where the direct form is 0/0.
TEST(PhaseFunction, FournierForandSeriesJoinsTheDirectFormAtDeltaOne) {
  for (double bb : {0.001, 0.0183, 0.1, 0.5}) {
    const PhaseFunction p = PhaseFunction::fournierForand(bb);
    const double nu = p.ffNu(), k = p.ffK();
    for (double x : {0.0499999, 0.0500001, -0.0499999, -0.0500001}) {
      const double omc = 2 * (1 - x) / k;
      const double inside = kd::phase_fournier_forand(omc * (1 - 1e-9), nu, k);
      const double outside = kd::phase_fournier_forand(omc * (1 + 1e-9), nu, k);
      EXPECT_NEAR(inside, outside, 1e-6 * std::abs(outside)) << "bb " << bb << " x " << x;
    }
    const double at_one = kd::phase_fournier_forand(2 / k, nu, k);
    EXPECT_TRUE(std::isfinite(at_one) && at_one > 0);
    EXPECT_NEAR(kf::phase_fournier_forand(float(2 / k), float(nu), float(k)), at_one, 1e-5 * at_one) << bb;
  }
}

TEST(PhaseFunction, FournierForandIsFiniteAtZeroAngleInFloat) {
  for (double bb : {0.001, 0.01, 0.1, 0.5}) {
    const PhaseFunction p = PhaseFunction::fournierForand(bb);
    for (float omc : {0.0f, 1e-20f, 1e-12f, 1e-8f}) {
      const float v = kf::phase_fournier_forand(omc, float(p.ffNu()), float(p.ffK()));
      EXPECT_TRUE(std::isfinite(v) && v > 0) << bb << " " << omc;
    }
    EXPECT_TRUE(std::isfinite(p.evaluate(0.0)));
  }
}

// b_b/b: the parameter asked for, the closed form of phase.h, and the quadrature's backward half agree.
TEST(PhaseFunction, FournierForandReproducesItsBackscatterRatio) {
  for (double bb : {0.001, 0.005, 0.0183, 0.1, 0.3, 0.5}) {
    const PhaseFunction p = PhaseFunction::fournierForand(bb);
    EXPECT_NEAR(kd::phase_fournier_forand_bb(p.ffNu(), p.ffK()), bb, 1e-9 * bb);
    EXPECT_NEAR(p.backscatterRatio(), bb, 2e-3 * bb + 1e-6) << bb;
    const double back = sphereIntegral([&](double psi) { return p.evaluate(psi); }, kPi / 2, kPi, 20000);
    EXPECT_NEAR(back, bb, 2e-3 * bb) << bb;
  }
  EXPECT_THROW(PhaseFunction::fournierForand(0.0005), std::invalid_argument);
  EXPECT_THROW(PhaseFunction::fournierForand(0.6), std::invalid_argument);
}

// Petzold's average particle: g = 0.924 and b_b/b = 0.0183 (Mobley, Light and Water 1994, §3.8; Mobley
// et al. 2002 Table 1).
TEST(PhaseFunction, PetzoldHasItsPublishedAsymmetryAndBackscatter) {
  const PhaseFunction p = PhaseFunction::petzold();
  EXPECT_NEAR(p.asymmetry(), 0.924, 0.003);
  EXPECT_NEAR(p.backscatterRatio(), 0.0183, 0.0005);
  // Between nodes the table is log-log: at 0.1° it is the table's value times the normalisation.
  EXPECT_NEAR(p.evaluate(0.1 * kPi / 180) / p.evaluate(kPi), 1766.61 / 0.00315366, 1e-6 * 1766.61 / 0.00315366);
}

// χ² of n samples from the inverse-CDF table against the phase's own probabilities over `edges` (rad).
template <class Sample>
void expectChiSquare(const PhaseFunction& p, const std::vector<double>& edges, Sample sample, int n,
                     const char* what) {
  std::vector<double> count(edges.size() + 1, 0.0);
  for (int i = 0; i < n; ++i) {
    const double u = kd::pt_uniform(20261205u, static_cast<unsigned>(i));  // the path tracer's own generator
    const double omc = sample(u);
    const double psi = 2 * std::asin(std::sqrt(std::clamp(omc, 0.0, 2.0) / 2));  // no cancellation near 0
    const size_t bin = std::upper_bound(edges.begin(), edges.end(), psi) - edges.begin();
    count[bin] += 1;
  }
  double chi2 = 0;
  int dof = 0;
  for (size_t b = 0; b <= edges.size(); ++b) {
    const double lo = b == 0 ? 0.0 : edges[b - 1], hi = b == edges.size() ? kPi : edges[b];
    const double expected = n * p.probabilityBetween(lo, hi);
    if (expected < 5) continue;
    chi2 += (count[b] - expected) * (count[b] - expected) / expected;
    ++dof;
  }
  // χ² with dof bins at p ≈ 1e-6: below dof + 5 √(2 dof) (fixed seed: deterministic).
  EXPECT_LT(chi2, dof + 5 * std::sqrt(2.0 * dof)) << what << ": chi2 " << chi2 << " dof " << dof;
  std::printf("%s: chi2 %.1f over %d bins\n", what, chi2, dof);
}

std::vector<double> logEdges(double lo_deg, double hi_deg, int n) {
  std::vector<double> e;
  for (int i = 0; i <= n; ++i) e.push_back(lo_deg * std::pow(hi_deg / lo_deg, double(i) / n) * kPi / 180);
  return e;
}

TEST(PhaseFunction, TableSamplingMatchesPetzoldByChiSquare) {
  const PhaseFunction p = PhaseFunction::petzold();
  const std::vector<double> table = p.samplingTable(8192);
  std::vector<float> table_f(table.begin(), table.end());
  const std::vector<double> edges = logEdges(0.01, 179, 60);
  expectChiSquare(p, edges, [&](double u) { return kd::phase_table_sample_omc(table.data(), 8192, u); }, 400000,
                  "petzold double");
  expectChiSquare(p, edges, [&](double u) { return double(kf::phase_table_sample_omc(table_f.data(), 8192, float(u))); },
                  400000, "petzold float");
}

// A phase whose forward peak is 0.1° wide (1e7 times the rest within 0.1°, holding ~88 % of the
// scattering): the sampler puts that share inside 0.1° and follows the shape inside and outside it.
TEST(PhaseFunction, TableSamplingResolvesATenthOfADegreePeak) {
  const std::vector<double> ang = {0.01, 0.05, 0.1, 0.12, 1, 10, 180};
  const std::vector<double> val = {1e7, 1e7, 1e7, 1, 1, 1, 1};
  const PhaseFunction p = PhaseFunction::table(ang, val, "peak");
  const double peak = p.probabilityBetween(0, 0.1 * kPi / 180);
  EXPECT_GT(peak, 0.8);
  const double independent = sphereIntegral([&](double psi) { return p.evaluate(psi); }, 0, 0.1 * kPi / 180, 20000);
  EXPECT_NEAR(peak, independent, 1e-3 * independent);
  const std::vector<double> table = p.samplingTable(8192);
  std::vector<float> table_f(table.begin(), table.end());
  std::vector<double> edges = logEdges(0.001, 179, 80);
  expectChiSquare(p, edges, [&](double u) { return kd::phase_table_sample_omc(table.data(), 8192, u); }, 400000,
                  "peak double");
  expectChiSquare(p, edges, [&](double u) { return double(kf::phase_table_sample_omc(table_f.data(), 8192, float(u))); },
                  400000, "peak float");
  // The float sampler keeps ψ inside the peak: 1 - cos(0.05°) = 3.8e-7 is held as such, not rounded to 0.
  int inside = 0;
  for (int i = 0; i < 1000; ++i)
    if (kf::phase_table_sample_omc(table_f.data(), 8192, (i + 0.5f) / 1000) < float(1 - std::cos(0.1 * kPi / 180)))
      ++inside;
  EXPECT_NEAR(inside / 1000.0, peak, 0.01);
}

TEST(PhaseFunction, FournierForandSamplingByChiSquare) {
  for (double bb : {0.001, 0.0183, 0.5}) {
    const PhaseFunction p = PhaseFunction::fournierForand(bb);
    const std::vector<double> table = p.samplingTable(8192);
    expectChiSquare(p, logEdges(0.001, 179, 60), [&](double u) { return kd::phase_table_sample_omc(table.data(), 8192, u); },
                    200000, "fournier_forand");
  }
}

TEST(PhaseFunction, TableErrorsNameFileAndLine) {
  const std::string bad_order = writeTemp("seasim_phase_order.csv", "angle_deg,phase_per_sr\n1,5\n0.5,4\n");
  try {
    PhaseFunction::loadTable(bad_order);
    FAIL() << "expected an error";
  } catch (const seasim::RuntimeError& e) {
    EXPECT_NE(std::string(e.what()).find(bad_order + ":3:"), std::string::npos) << e.what();
  }
  const std::string negative = writeTemp("seasim_phase_negative.csv", "angle_deg,phase_per_sr\n1,5\n2,-4\n");
  try {
    PhaseFunction::loadTable(negative);
    FAIL() << "expected an error";
  } catch (const seasim::RuntimeError& e) {
    EXPECT_NE(std::string(e.what()).find(negative + ":3: phase value -4"), std::string::npos) << e.what();
  }
  EXPECT_THROW(PhaseFunction::loadTable("/nonexistent/phase.csv"), seasim::RuntimeError);
  EXPECT_THROW(PhaseFunction::henyeyGreenstein(1.0), std::invalid_argument);
}

// The path tracer's value table (phase_table_value) against the phase itself, float and double: within
// 0.5 % between nodes for every kind at 1024 entries (log-log interpolation of power laws and smooth tails).
TEST(PhaseFunction, ValueTableFollowsThePhase) {
  for (const PhaseFunction& p : {PhaseFunction::petzold(), PhaseFunction::fournierForand(0.001),
                                 PhaseFunction::fournierForand(0.1), PhaseFunction::rayleighLike(),
                                 PhaseFunction::henyeyGreenstein(0.95)}) {
    const std::vector<double> t = p.valueTable(1024);
    const std::vector<float> tf(t.begin(), t.end());
    for (double deg : {0.01, 0.1, 0.5, 1.0, 3.0, 10.0, 45.0, 90.0, 135.0, 179.0}) {
      const double psi = deg * kPi / 180, omc = 2 * std::sin(psi / 2) * std::sin(psi / 2);
      const double exact = p.evaluate(psi);
      EXPECT_NEAR(kd::phase_table_value(t.data(), 1024, omc), exact, 5e-3 * exact) << p.name() << " " << deg;
      EXPECT_NEAR(kf::phase_table_value(tf.data(), 1024, float(omc)), exact, 6e-3 * exact) << p.name() << " " << deg;
    }
  }
}

}  // namespace
