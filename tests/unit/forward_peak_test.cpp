// The forward peak of the discrete-ordinates underwater model (host/underwater/forward_peak.h and
// common/underwater_ordinates.h's uwi_tms_phase, uwi_aureole, uwi_aureole_share, uwi_forward_peak): the
// ceiling takes exactly delta-M's f off the phase, the peak's Legendre moments are its own, and the aureole
// at the camera holds the delta-M beam's surplus over the unscattered beam, in
// float and double, at and near the singular inputs (no peak, g -> 1, n -> 0, a camera at the surface); the
// twice-scattered light is the peak convolved with itself.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <algorithm>

#include "math/kernel_math.h"
#include "underwater/forward_peak.h"
#include "underwater_ordinates_fixtures.h"

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

// The peak's Legendre moments: χ_0 = 1, χ_1 its mean cosine, and χ_l against quadrature on a uniform grid in
// μ (a different rule from forwardPeak's); they fall below 1e-7 before the cap below g = 0.99.
TEST(ForwardPeak, MomentsAgainstQuadrature) {
  for (double g : {0.3, 0.5, 0.9, 0.95, 0.99}) {
    const seasim::ForwardPeak peak = seasim::forwardPeak(g, g * g * g);
    ASSERT_GT(peak.p_clip, 0) << g;
    ASSERT_GT(peak.moments.size(), 3u);
    EXPECT_EQ(peak.moments[0], 1.0);
    if (g < 0.99) EXPECT_LT(peak.moments.size(), 4001u) << g;
    // The midpoint rule on μ: 200000 steps over [μ_c, 1] (the peak vanishes below).
    const double mu_c = (1 + g * g - std::pow((1 - g * g) / (4 * kPi * peak.p_clip), 2.0 / 3.0)) / (2 * g);
    for (int l : {1, 2, 5, 20, 60}) {
      if (size_t(l) >= peak.moments.size()) continue;
      double num = 0, den = 0;
      const int steps = 200000;
      for (int i = 0; i < steps; ++i) {
        const double mu = mu_c + (1 - mu_c) * (i + 0.5) / steps;
        const double w = std::max(hg(mu, g) - peak.p_clip, 0.0);
        // P_l by the recurrence
        double p0 = 1, p1 = mu;
        for (int k = 1; k < l; ++k) {
          const double p2 = ((2 * k + 1) * mu * p1 - k * p0) / (k + 1);
          p0 = p1;
          p1 = p2;
        }
        num += w * (l == 0 ? 1.0 : p1);
        den += w;
      }
      EXPECT_NEAR(peak.moments[l], num / den, 2e-5) << "g " << g << " l " << l;
    }
  }
  // Measured: the peak at g = 0.9 holds 73 % of the light within 28.5°, its mean angle about 10°.
  EXPECT_NEAR(std::acos(seasim::forwardPeak(0.9, 0.729).moments[1]) * 180 / kPi, 9.9, 0.6);
  EXPECT_TRUE(seasim::forwardPeak(0.0, 0.0).moments.empty());
  EXPECT_EQ(seasim::forwardPeak(0.0, 0.0).p_clip, 0.0);
}

// The light scattered twice by the peak is the peak convolved with itself on the sphere: the table at small n
// (Poisson(2; n) of it, the rest negligible) against that convolution as a direct double integral.
TEST(ForwardPeak, TwiceScatteredLightIsThePeakConvolvedWithItself) {
  const double g = 0.9, f = g * g * g;
  const seasim::ForwardPeak peak = seasim::forwardPeak(g, f);
  const double theta_c = std::acos((1 + g * g - std::pow((1 - g * g) / (4 * kPi * peak.p_clip), 2.0 / 3.0)) / (2 * g));
  auto P = [&](double mu) { return std::max(hg(mu, g) - peak.p_clip, 0.0) / f; };
  UwBand band{};
  band.c = 0.4f;
  band.e_beam0 = 1.0f;
  UwiBand ib{};
  const double n = 1e-3, mu_w = 1.0, y_c = 1.0;
  ib.c_dm = float(0.4 - n);  // q = c - c' = n per metre, one metre down
  ib.m = 0.0f;
  seasim::setForwardPeak(ib, band, peak, mu_w, y_c);
  const double n_f = double(band.c) - double(ib.c_dm);  // the n the floats give
  const double twice = n_f * n_f / 2 * std::exp(-n_f);
  for (double theta_deg : {0.0, 2.0, 5.0, 10.0, 20.0, 35.0}) {
    const double theta = theta_deg * kPi / 180;
    // ∫ P(θ1) P(γ) dΩ1, cos γ = cos θ cos θ1 + sin θ sin θ1 cos φ1; θ1 = θ_c s² crowds the core.
    double conv = 0;
    const int ns = 1500, nphi = 720;
    for (int i = 0; i < ns; ++i) {
      const double s = (i + 0.5) / ns, t1 = theta_c * s * s, dt = 2 * theta_c * s / ns;
      const double p1 = P(std::cos(t1));
      if (p1 <= 0) continue;
      double ring = 0;
      for (int k = 0; k < nphi; ++k) {
        const double phi = kPi * (k + 0.5) / nphi;
        ring += P(std::cos(theta) * std::cos(t1) + std::sin(theta) * std::sin(t1) * std::cos(phi));
      }
      conv += p1 * std::sin(t1) * dt * 2 * kPi * ring / nphi;
    }
    const double table = kd::uwi_aureole_at_camera(&ib, 0.0, std::cos(theta), 1.0);  // phase 0: no once-scattered part
    EXPECT_NEAR(table / twice, conv, 0.01 * conv + 1e-3 * P(1.0)) << theta_deg << "°";
  }
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
Band peakBand(double a, double b, double g, double f, double mu_w, double y_c, double* scale = nullptr) {
  Band o;
  o.band.a = float(a);
  o.band.b = float(b);
  o.band.c = float(a + b);
  o.band.e_beam0 = 3.0f;
  o.ib.c_dm = float(a + b * (1 - f));
  o.ib.m = float(double(o.ib.c_dm) / mu_w);
  const double k = seasim::setForwardPeak(o.ib, o.band, seasim::forwardPeak(g, f), mu_w, y_c);
  if (scale) *scale = k;
  return o;
}

TEST(ForwardPeak, AureoleHoldsTheBeamsSurplusInFloatAndDouble) {
  struct Case {
    double a, b, g, y_c;
  };
  // n = b f y_c / μ_w from 0.004 to about 40.
  const Case cases[] = {{0.1, 0.3, 0.9, 3.8}, {0.4, 1.2, 0.9, 3.8}, {0.03, 0.05, 0.95, 0.1}, {0.1, 0.3, 0.5, 10.0},
                        {0.4, 1.2, 0.95, 40.0}, {0.1, 0.3, 0.99, 2.0}, {0.1, 0.3, 0.999, 2.0}};
  const double mu_w = 0.927;
  for (const Case& c : cases) {
    const double f = c.g * c.g * c.g;
    double scale = 0;
    const Band p = peakBand(c.a, c.b, c.g, f, mu_w, c.y_c, &scale);
    ASSERT_GT(p.ib.p_clip, 0);
    // The table's own sum before it is scaled to hold its light (measured 0.995-1.000 at g <= 0.95, 0.981 at
    // 0.99, 0.836 at 0.999, where the core, 0.06° wide, falls between the first two nodes).
    EXPECT_NEAR(scale, 1.0, c.g <= 0.95 ? 6e-3 : c.g <= 0.99 ? 2.5e-2 : 0.2) << "g " << c.g;
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

namespace {

// The sand the objects hide or shade (common/underwater_ordinates.h uwi_sand_seen, uwi_sand_shares): the shares
// of the sunlit and of the diffusely lit sand's light a water point gets, against objects whose answer is
// known, in float and double.
using seasim::testing::uwTestBox;
using seasim::testing::uwTestSphere;

TEST(SandShare, KnownAnswersInFloatAndDouble) {
  const double H = 5.0;
  const kd::real3 x{0, -2, 0}, sun_up{0, 1, 0};
  const kf::real3 xf{0, -2, 0}, sun_up_f{0, 1, 0};
  double open = -1;
  float open_f = -1;
  // A slab under the point, wider than every ray's reach to the sand: all the sand hidden.
  const UwObject slab[1] = {uwTestBox(-100, -4, -100, 100, -3, 100)};
  const float black[1] = {0.0f}, sand_like[1] = {0.3f};
  EXPECT_EQ(kd::uwi_sand_seen(slab, 1, H, x, sun_up, black, 1, 0.3, 0.1, &open), 0.0);
  EXPECT_EQ(open, 0.0);
  EXPECT_EQ(kf::uwi_sand_seen(slab, 1, float(H), xf, sun_up_f, black, 1, 0.3f, 0.1f, &open_f), 0.0f);
  EXPECT_EQ(open_f, 0.0f);
  // The same slab as bright as the sand, the sun overhead: its top sends what the sand would of the beam,
  // and of the diffuse light what its 2 m shallower top gets, e^{k 2} of the sand's.
  EXPECT_NEAR(kd::uwi_sand_seen(slab, 1, H, x, sun_up, sand_like, 1, 0.3, 0.1, &open), 1.0, 1e-6);  // 0.3f against 0.3
  EXPECT_NEAR(open, std::exp(0.2), 1e-6);
  EXPECT_NEAR(kf::uwi_sand_seen(slab, 1, float(H), xf, sun_up_f, sand_like, 1, 0.3f, 0.1f, &open_f), 1.0f, 1e-6f);
  EXPECT_NEAR(open_f, std::exp(0.2), 1e-6);
  // Nothing below the point (the slab above it): every ray reaches the sand, but the slab above shades it
  // from the sun overhead and hides the water above it from every up-ray: none of it lit either way.
  const UwObject roof[1] = {uwTestBox(-100, -1.5f, -100, 100, -1, 100)};
  EXPECT_EQ(kd::uwi_sand_seen(roof, 1, H, x, sun_up, black, 1, 0.3, 0.1, &open), 0.0);
  EXPECT_EQ(open, 0.0);
  // A small box far to the side: no ray meets it, no shadow falls under the point: 1.
  const UwObject aside[1] = {uwTestBox(50, -4, 50, 51, -3, 51)};
  EXPECT_EQ(kd::uwi_sand_seen(aside, 1, H, x, sun_up, black, 1, 0.3, 0.1, &open), 1.0);
  EXPECT_EQ(open, 1.0);
  // No objects, or no bottom: the plane-parallel model's own answer, 1.
  const kd::real3 d{0, 0, -1};
  for (const auto& [objects, count, depth, S] : {std::tuple{aside, 0, H, 10.0}, std::tuple{slab, 1, 0.0, 10.0},
                                                 std::tuple{slab, 1, H, 1e30}}) {  // the last: deep water
    EXPECT_EQ(kd::uwi_sand_shares(objects, count, depth, x, d, S, 0.1, 0.05, sun_up, black, 1, 0.3, &open), 1.0);
    EXPECT_EQ(open, 1.0);
  }
  // Along a level ray over the black slab: every point's sand hidden.
  EXPECT_EQ(kd::uwi_sand_shares(slab, 1, H, x, d, 10.0, 0.1, 0.05, sun_up, black, 1, 0.3, &open), 0.0);
  EXPECT_EQ(open, 0.0);
  // Over a slab that covers half the ray's points (x < 0 from z = -5): the weights of its points; the
  // diffusely lit sand beside the slab also loses the water the slab hides from it.
  const UwObject half[1] = {uwTestBox(-100, -4, -100, 100, -3, -5)};
  const double v = kd::uwi_sand_shares(half, 1, H, x, d, 10.0, 0.0, 0.0, sun_up, black, 1, 0.3, &open);
  EXPECT_GT(v, 0.3);
  EXPECT_LT(v, 0.7);
  EXPECT_GT(open, 0.2);
  EXPECT_LT(open, v);
  const float vf = kf::uwi_sand_shares(half, 1, float(H), xf, kf::real3{0, 0, -1}, 10.0f, 0.0f, 0.0f, sun_up_f, black,
                                       1, 0.3f, &open_f);
  EXPECT_NEAR(vf, v, 1e-6);
  EXPECT_NEAR(open_f, open, 1e-6);
}

// The in-scatter's quantiles along a view ray (uwi_inscatter_quantile): the weight e^{-r z} on [0, S] up to z
// is u of the whole, for light fading along the ray (r > 0, also to infinity), growing (r < 0: a ray looking
// up), and r = 0 and near it; finite and in [0, S] where e^{|r| S} overflows a float.
TEST(AboveShare, InscatterQuantileSplitsTheWeightAtAndNearItsLimits) {
  auto share = [](double r, double S, double z) {  // ∫_0^z e^{-r t} dt / ∫_0^S e^{-r t} dt
    if (r == 0) return z / S;
    return std::isinf(S) ? -std::expm1(-r * z) : std::expm1(-r * z) / std::expm1(-r * S);
  };
  for (const double r : {0.3, 1e-3, 1e-7, 0.0, -1e-7, -1e-3, -0.3})
    for (const double S : {0.5, 10.0, 200.0})
      for (const double u : {0.01, 0.25, 0.5, 0.75, 0.99}) {
        const double z = kd::uwi_inscatter_quantile(r, S, u);
        EXPECT_NEAR(share(r, S, z), u, 1e-6) << "r " << r << " S " << S << " u " << u;
        const float zf = kf::uwi_inscatter_quantile(float(r), float(S), float(u));
        EXPECT_NEAR(share(r, S, zf), u, 2e-4) << "float: r " << r << " S " << S << " u " << u;
      }
  for (const double u : {0.25, 0.75}) {
    EXPECT_NEAR(share(0.2, INFINITY, kd::uwi_inscatter_quantile(0.2, 1e30, u)), u, 1e-9);  // deep water
    EXPECT_NEAR(share(0.2, INFINITY, kf::uwi_inscatter_quantile(0.2f, 1e30f, float(u))), u, 1e-5);
    for (const double r : {-5.0, 5.0}) {  // e^{5 · 100} is no float
      const float zf = kf::uwi_inscatter_quantile(float(r), 100.0f, float(u));
      EXPECT_TRUE(std::isfinite(zf) && zf >= 0.0f && zf <= 100.0f) << r;
      EXPECT_NEAR(zf, kd::uwi_inscatter_quantile(r, 100.0, u), 1e-4) << r;
    }
  }
}

// The light from above that objects leave the in-scatter of a view ray (uwi_above_share), against objects
// whose answer is known, in float and double: none, one below the ray, a roof over all of it, a roof over
// its farther point alone, a small box over one point.
TEST(AboveShare, KnownAnswersInFloatAndDouble) {
  const double H = 5.0, c_dm = 0.1, k = 0.05;  // a level ray: r = c' = 0.1, points at 1.72 m and 6.42 m over S = 10
  const kd::real3 o{0, -2, 0}, d{0, 0, -1};
  const kf::real3 of{0, -2, 0}, df{0, 0, -1};
  const UwObject slab[1] = {uwTestBox(-100, -4, -100, 100, -3, 100)};
  const UwObject roof[1] = {uwTestBox(-100, -1.5f, -100, 100, -1, 100)};
  // The roof from z = -5 on: the near point is 3.3 m from its edge, 1 m under it, farther than the widest
  // of the four up-rays reaches (69° from the vertical: 2.6 m); the far point is under it.
  const UwObject half_roof[1] = {uwTestBox(-100, -1.5f, -100, 100, -1, -5)};
  for (const double S : {10.0, 1e30}) {  // a hit 10 m away, and deep water
    EXPECT_EQ(kd::uwi_above_share(slab, 0, H, o, d, S, c_dm, k), 1.0);
    EXPECT_EQ(kd::uwi_above_share(slab, 1, H, o, d, S, c_dm, k), 1.0);
    EXPECT_EQ(kd::uwi_above_share(roof, 1, H, o, d, S, c_dm, k), 0.0);
    EXPECT_EQ(kf::uwi_above_share(roof, 1, float(H), of, df, float(S), float(c_dm), float(k)), 0.0f);
    EXPECT_EQ(kd::uwi_above_share(slab, 1, 0.0, o, d, S, c_dm, k), 1.0);  // no bottom either
  }
  EXPECT_NEAR(kd::uwi_above_share(half_roof, 1, H, o, d, 10.0, c_dm, k), 0.5, 1e-12);
  EXPECT_NEAR(kf::uwi_above_share(half_roof, 1, float(H), of, df, 10.0f, float(c_dm), float(k)), 0.5f, 1e-6f);
  // A 1 m box 1 m over the far point: it holds off the steeper of the point's up-rays, not all of them.
  const UwObject box[1] = {uwTestBox(-0.5f, -1, -6.92f, 0.5f, 0, -5.92f)};
  const double v = kd::uwi_above_share(box, 1, H, o, d, 10.0, c_dm, k);
  EXPECT_GT(v, 0.5);
  EXPECT_LT(v, 1.0);
  EXPECT_NEAR(kf::uwi_above_share(box, 1, float(H), of, df, 10.0f, float(c_dm), float(k)), v, 1e-6);
  // Stiff: a camera inside a rock (every up-ray meets its inside: all the light from above held off), and water
  // that neither scatters nor absorbs (r = 0) looking into deep water: finite, in [0, 1].
  const UwObject rock[1] = {uwTestBox(-50, -4, -50, 50, -1, 50)};
  EXPECT_EQ(kd::uwi_above_share(rock, 1, H, o, d, 1e30, c_dm, k), 0.0);
  EXPECT_EQ(kf::uwi_above_share(rock, 1, float(H), of, df, 1e30f, float(c_dm), float(k)), 0.0f);
  for (const double S : {10.0, 1e30}) {
    const float vf0 = kf::uwi_above_share(box, 1, float(H), of, df, float(S), 0.0f, 0.0f);
    EXPECT_TRUE(std::isfinite(vf0) && vf0 >= 0.0f && vf0 <= 1.0f) << S;
  }
}


// The shares in pixel lanes (common/underwater_ordinates_lanes.h, one lane on the host; sand_share.cl runs 16)
// against the scalar uwi_sand_shares and uwi_above_share: the same values over random view rays among a sphere,
// two boxes (one a bright rock, one a black slab) over a bottom, with hits at the ray's own scene hit, short of
// it, inside a rock and in deep water; a sun high, low and below the horizon. Double to 1e-12; float, the
// kernel's, to 1e-5 but for rays that graze an edge and round to its other side (a step of a quarter at most).
TEST(SandShare, PixelLanesMatchTheScalarShares) {
  const UwObject objects[3] = {uwTestSphere(0.5f, -6.0f, -3.0f, 1.0f), uwTestBox(-2.5f, -8.0f, -5.0f, -1.0f, -6.5f, -3.5f),
                               uwTestBox(1.0f, -7.2f, -1.0f, 3.0f, -7.0f, 1.0f)};
  const float albedo[3] = {0.4f, 0.2f, 0.0f};
  const double H = 8.0;
  std::mt19937 rng(97531u);
  auto uniform = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); };
  int float_off = 0, partial = 0;
  const int rays = 3000;
  for (int i = 0; i < rays; ++i) {
    const kd::real3 o{uniform(-3, 3), uniform(-7.5, -1), uniform(-4, 3)};
    const kd::real3 d = kd::normalize(kd::real3{uniform(-1, 1), uniform(-1, 0.4), uniform(-1, 1)});
    const kd::real3 sun = kd::normalize(kd::real3{uniform(-1, 1), i % 5 == 0 ? -0.2 : uniform(0.05, 1), uniform(-1, 1)});
    kd::real3 n{};
    int mat = 0;
    double S = kd::uw_scene_hit(objects, 3, H, o, d, 0.0, &n, &mat);
    if (i % 7 == 0) S *= 0.5;  // a hit short of the scene's
    if (i % 11 == 0) S = 1e30;  // deep water
    const int count = i % 13 == 0 ? 0 : 3;
    const double c_dm = uniform(0.02, 0.5), k = uniform(0.01, 0.2), sand = i % 17 == 0 ? 0.0 : 0.3;
    double open = 0, open_b = 0;
    const double v = kd::uwi_sand_shares(objects, count, H, o, d, S, c_dm, k, sun, albedo, 1, sand, &open);
    const double v_b = kd::uwi_sand_shares_b(objects, count, H, o, kd::uw_splat3b(d), S, c_dm, k, sun, albedo, 1, sand,
                                             &open_b);
    EXPECT_NEAR(v_b, v, 1e-12) << i;
    EXPECT_NEAR(open_b, open, 1e-12) << i;
    const double a = kd::uwi_above_share(objects, count, H, o, d, S, c_dm, k);
    EXPECT_NEAR(kd::uwi_above_share_b(objects, count, H, o, kd::uw_splat3b(d), S, c_dm, k), a, 1e-12) << i;
    partial += (v > 0 && v < 1) || (a > 0 && a < 1);
    // Float.
    const kf::real3 of{float(o.x), float(o.y), float(o.z)}, df{float(d.x), float(d.y), float(d.z)};
    const kf::real3 sf{float(sun.x), float(sun.y), float(sun.z)};
    float open_f = 0, open_fb = 0;
    const float vf = kf::uwi_sand_shares(objects, count, float(H), of, df, float(S), float(c_dm), float(k), sf, albedo, 1,
                                         float(sand), &open_f);
    const float vf_b = kf::uwi_sand_shares_b(objects, count, float(H), of, kf::uw_splat3b(df), float(S), float(c_dm),
                                             float(k), sf, albedo, 1, float(sand), &open_fb);
    const float af = kf::uwi_above_share(objects, count, float(H), of, df, float(S), float(c_dm), float(k));
    const float af_b = kf::uwi_above_share_b(objects, count, float(H), of, kf::uw_splat3b(df), float(S), float(c_dm),
                                             float(k));
    const double worst = std::max({std::fabs(vf_b - vf), std::fabs(open_fb - open_f), std::fabs(af_b - af)});
    if (worst > 1e-5) {
      ++float_off;
      EXPECT_LE(worst, 0.25 + 1e-5) << i;
    }
  }
  std::printf("[ numbers  ] rays with a share strictly between 0 and 1: %d of %d; float lanes off by > 1e-5: %d\n",
              partial, rays, float_off);
  // The objects were in the way of a good part of the rays, so the comparison saw every branch.
  EXPECT_GT(partial, rays / 5);
  EXPECT_LE(float_off, rays / 500);
}

}  // namespace
