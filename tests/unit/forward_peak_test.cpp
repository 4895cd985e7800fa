// The forward peak of the improved underwater model (s13, host/underwater/forward_peak.h and
// common/underwater_improved.h's uwi_tms_phase, uwi_aureole, uwi_aureole_share, uwi_forward_peak): the
// ceiling takes exactly delta-M's f off the phase, the von Mises-Fisher pieces are normalised and hold their
// mean cosine, and the aureole at the camera holds the delta-M beam's surplus over the unscattered beam, in
// float and double, at and near the singular inputs (no peak, g -> 1, n -> 0, a camera at the surface).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "math/kernel_math.h"
#include "underwater/forward_peak.h"

namespace {

namespace kd = seasim::kmath_d;
namespace kf = seasim::kmath_f;
constexpr double kPi = std::numbers::pi;

double hg(double mu, double g) { return (1 - g * g) / (4 * kPi * std::pow(1 + g * g - 2 * g * mu, 1.5)); }

// ∫ F(θ) dΩ by the midpoint rule in θ = π s² (steps crowd at the forward direction, where HG is sharpest).
template <class F>
double sphere(F f, int steps = 200000) {
  double sum = 0;
  for (int i = 0; i < steps; ++i) {
    const double s = (i + 0.5) / steps, theta = kPi * s * s;
    sum += f(std::cos(theta)) * 2 * kPi * std::sin(theta) * 2 * kPi * s / steps;
  }
  return sum;
}

TEST(ForwardPeak, CeilingTakesOffExactlyF) {
  for (double g : {1e-3, 0.1, 0.3, 0.5, 0.7, 0.9, 0.95, 0.99, 0.999})
    for (int power : {2, 3}) {
      const double f = std::pow(g, power);
      if (f < 1e-9) continue;
      const double p_clip = seasim::hgPeakCeiling(g, f);
      ASSERT_GT(p_clip, 0) << g;
      ASSERT_LT(p_clip, hg(1.0, g)) << g;
      const double peak = sphere([&](double mu) { return std::max(hg(mu, g) - p_clip, 0.0); });
      EXPECT_NEAR(peak, f, 2e-6 * std::max(f, 1e-3)) << "g " << g << " power " << power;
      // What the TMS term keeps: the phase but its peak.
      const double kept = sphere([&](double mu) { return kd::uwi_tms_phase(hg(mu, g), p_clip); });
      EXPECT_NEAR(kept, 1 - f, 2e-5) << g;
    }
}

TEST(ForwardPeak, NoPeakNoCeilingAndTheTmsPhaseIsTheWholePhase) {
  EXPECT_EQ(seasim::hgPeakCeiling(0.0, 0.0), 0.0);
  EXPECT_EQ(seasim::hgPeakCeiling(9.99e-4, 9.97e-10), 0.0);  // f below 1e-9 of the light: no peak
  EXPECT_EQ(seasim::hgPeakCeiling(-0.5, 0.0), 0.0);
  EXPECT_EQ(seasim::hgPeakCeiling(0.9, 0.0), 0.0);
  for (double phase : {0.0, 0.08, 15.0}) {
    EXPECT_EQ(kd::uwi_tms_phase(phase, 0.0), phase);
    EXPECT_EQ(kf::uwi_tms_phase(float(phase), 0.0f), float(phase));
  }
  // Just above the threshold the peak's light is f: the TMS phase changes by no more than that.
  const double p_clip = seasim::hgPeakCeiling(1e-3, 1e-9);
  ASSERT_GT(p_clip, 0);
  EXPECT_NEAR(sphere([&](double mu) { return kd::uwi_tms_phase(hg(mu, 1e-3), p_clip); }), 1.0, 1e-8);
}

TEST(ForwardPeak, PeakMeanCosineAgainstQuadrature) {
  for (double g : {0.3, 0.5, 0.9, 0.95, 0.99}) {
    const double f = g * g * g, p_clip = seasim::hgPeakCeiling(g, f);
    const double light = sphere([&](double mu) { return std::max(hg(mu, g) - p_clip, 0.0); });
    const double moment = sphere([&](double mu) { return mu * std::max(hg(mu, g) - p_clip, 0.0); });
    EXPECT_NEAR(seasim::hgPeakMeanCosine(g, p_clip), moment / light, 1e-6) << g;
  }
  EXPECT_EQ(seasim::hgPeakMeanCosine(0.9, 0.0), 1.0);
  // Measured: the peak at g = 0.9 holds 73 % of the light within 28.5° (its rms angle 10°).
  EXPECT_NEAR(std::acos(seasim::hgPeakMeanCosine(0.9, seasim::hgPeakCeiling(0.9, 0.729))) * 180 / kPi, 9.9, 0.6);
}

TEST(ForwardPeak, VonMisesFisherIsNormalisedAndHoldsItsMeanCosine) {
  for (double kappa : {0.0, 1e-12, 1e-4, 0.5, 3.0, 40.0, 2000.0, 1e5}) {
    EXPECT_NEAR(sphere([&](double mu) { return seasim::vonMisesFisher(mu, kappa); }), 1.0, 1e-6) << kappa;
    EXPECT_TRUE(std::isfinite(seasim::vonMisesFisher(-1.0, kappa)));
    EXPECT_TRUE(std::isfinite(seasim::vonMisesFisher(1.0, kappa)));
  }
  for (double mean : {1e-12, 1e-6, 1e-3, 0.2, 0.5, 0.9, 0.99, 0.99999}) {
    const double kappa = seasim::vonMisesFisherKappa(mean);
    const double m = sphere([&](double mu) { return mu * seasim::vonMisesFisher(mu, kappa); });
    EXPECT_NEAR(m, mean, 1e-6 * std::max(mean, 1e-3) + 1e-12) << mean;
  }
  EXPECT_EQ(seasim::vonMisesFisherKappa(0.0), 0.0);
}

TEST(ForwardPeak, ShareOfTheAureoleAtAndNearItsLimits) {
  for (double q : {0.0, 1e-12, 1e-7, 0.22, 3.0, 300.0}) {
    EXPECT_NEAR(kd::uwi_aureole_share(q, 4.0, 0.0), 1.0, 1e-12) << q;
    EXPECT_NEAR(kd::uwi_aureole_share(q, 4.0, 4.0), 0.0, 1e-12) << q;
    EXPECT_NEAR(kf::uwi_aureole_share(float(q), 4.0f, 0.0f), 1.0f, 1e-6f) << q;
    EXPECT_NEAR(kf::uwi_aureole_share(float(q), 4.0f, 4.0f), 0.0f, 1e-6f) << q;
    for (double y1 : {1e-6, 1.0, 3.999999}) {
      const double s = kd::uwi_aureole_share(q, 4.0, y1);
      // (e^{-q y1} - e^{-q y_c}) / (1 - e^{-q y_c}) written with sinh, which keeps its digits at small q.
      const double exact =
          q == 0 ? (4 - y1) / 4 : std::exp(-q * y1 / 2) * std::sinh(q * (4 - y1) / 2) / std::sinh(q * 4 / 2);
      EXPECT_NEAR(s, exact, 1e-6 * exact + 1e-12) << q << " " << y1;
      EXPECT_NEAR(kf::uwi_aureole_share(float(q), 4.0f, float(y1)), exact, 2e-5 * exact + 1e-6) << q << " " << y1;
    }
  }
  // On either side of the series' switch (q y_c = 1e-6), continuous.
  EXPECT_NEAR(kd::uwi_aureole_share(0.99e-6 / 4, 4.0, 1.0), kd::uwi_aureole_share(1.01e-6 / 4, 4.0, 1.0), 1e-6);
  EXPECT_EQ(kd::uwi_aureole_share(0.2, 0.0, 0.0), 0.0);  // a camera at the surface sees none
}

// One band block with the peak of (g, f) for a camera at y_c, the beam's irradiance 3 and c - c' = b f.
struct Band {
  UwBand band{};
  UwiBand ib{};
};
Band peakBand(double a, double b, double g, double f, double mu_w, double y_c) {
  Band o;
  o.band.a = float(a);
  o.band.b = float(b);
  o.band.c = float(a + b);
  o.band.e_beam0 = 3.0f;
  o.ib.c_dm = float(a + b * (1 - f));
  o.ib.m = float(double(o.ib.c_dm) / mu_w);
  seasim::setForwardPeak(o.ib, o.band, g, f, mu_w, y_c);
  return o;
}

TEST(ForwardPeak, AureoleHoldsTheBeamsSurplusInFloatAndDouble) {
  struct Case {
    double a, b, g, y_c;
  };
  // n = b f y_c / μ_w from 0.004 to about 40.
  const Case cases[] = {{0.1, 0.3, 0.9, 3.8}, {0.4, 1.2, 0.9, 3.8}, {0.03, 0.05, 0.95, 0.1}, {0.1, 0.3, 0.5, 10.0},
                        {0.4, 1.2, 0.95, 40.0}, {0.1, 0.3, 0.99, 2.0}};
  const double mu_w = 0.927;
  for (const Case& c : cases) {
    const double f = c.g * c.g * c.g;
    const Band p = peakBand(c.a, c.b, c.g, f, mu_w, c.y_c);
    ASSERT_GT(p.ib.p_clip, 0);
    const double cp = double(p.ib.c_dm), cc = double(p.band.c);
    const double surplus = 3.0 * (std::exp(-cp * c.y_c / mu_w) - std::exp(-cc * c.y_c / mu_w));
    // Over the whole sphere of directions (d_y = 1 passed for all: the kernel draws it only looking up),
    // the table with its once-scattered part: the surplus, to the table's interpolation.
    const double total = sphere([&](double mu) {
      return kd::uwi_aureole(&p.ib, &p.band, hg(mu, c.g), mu, 1.0, c.y_c, 0.0, mu_w);
    });
    EXPECT_NEAR(total / surplus, 1.0, 5e-3) << c.a << ":" << c.b << " g " << c.g << " y " << c.y_c;
    // Float and double read the same table.
    for (double theta_deg : {0.0, 0.3, 2.0, 7.0, 20.0, 60.0}) {
      const double mu = std::cos(theta_deg * kPi / 180);
      const double d = kd::uwi_aureole(&p.ib, &p.band, hg(mu, c.g), mu, mu, c.y_c, 0.0, 1.0);
      const float fl = kf::uwi_aureole(&p.ib, &p.band, float(hg(mu, c.g)), float(mu), float(mu), float(c.y_c), 0.0f, 1.0f);
      ASSERT_TRUE(std::isfinite(d) && std::isfinite(fl) && d >= 0 && fl >= 0);
      EXPECT_NEAR(fl, d, 1e-4 * d + 1e-12) << theta_deg;
    }
  }
}

}  // namespace
