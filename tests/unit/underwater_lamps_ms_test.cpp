// underwater_lamps_ms_test.cpp — the "orders" model of spotlights under water
// (kernels/common/underwater_lamps_ms.h, host/underwater/lamps_ms_table.h): the orders' weights
// conserve the light they share out, the Poisson tail and HG's forward share against direct sums and
// quadrature, the blurred profiles conserve the lamp's power, the view-ray quadrature converges and
// float agrees with double; the stiff cases σ_s -> 0, g -> 1, a ray through the lamp, S -> ∞.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "math/kernel_math.h"
#include "underwater/lamps_ms_table.h"

namespace {

namespace kd = seasim::kmath_d;
namespace kf = seasim::kmath_f;

double cosDeg(double deg) { return std::cos(deg * M_PI / 180); }

TEST(UnderwaterLampsMs, OrderWeightsShareOutTheScatteredLight) {
  // κ = 0: paths as long as s, so the unscattered part and orders 1..N (the last taking the rest)
  // add up to the light absorption leaves, e^{-σ_a s}, in both precisions.
  for (double s : {0.01, 1.0, 5.0, 30.0})
    for (double b : {0.05, 0.3, 0.8, 3.0}) {
      const double a = 0.1;
      double sum = std::exp(-(a + b) * s);
      float sum_f = std::exp(-float(a + b) * float(s));
      for (int n = 1; n <= 8; ++n) {
        sum += kd::uw_ms_weight(a, b, s, 1.0, n, 8);
        sum_f += kf::uw_ms_weight(float(a), float(b), float(s), 1.0f, n, 8);
      }
      EXPECT_NEAR(sum, std::exp(-a * s), 2e-9) << "s " << s << " b " << b;
      EXPECT_NEAR(sum_f, std::exp(-a * s), 2e-6) << "s " << s << " b " << b;
    }
}

TEST(UnderwaterLampsMs, PoissonTailMatchesTheDirectSumOnBothBranches) {
  for (int n : {1, 3, 8, 12})
    for (double x : {1e-6, 0.01, 0.5, 2.0, double(n), n + 0.999, n + 1.0, n + 1.001, 20.0, 80.0}) {
      double lower = 0, term = std::exp(-x);
      for (int k = 0; k < n; ++k) {
        lower += term;
        term *= x / (k + 1);
      }
      double upper = 0;  // the tail summed directly (the reference on both branches)
      term = std::exp(-x);
      for (int k = 0; k < 400; ++k) {
        if (k >= n) upper += term;
        term *= x / (k + 1);
      }
      const double got = kd::uw_ms_poisson_at_least(n, x);
      EXPECT_NEAR(got, upper, 1e-12 + 2e-9 * upper) << "n " << n << " x " << x;
      EXPECT_NEAR(kf::uw_ms_poisson_at_least(n, float(x)), upper, 2e-6 + 1e-4 * upper) << "n " << n << " x " << x;
      EXPECT_NEAR(got + lower, 1.0, 2e-9);  // the upward sum stops at terms below 1e-9 of it
    }
  EXPECT_EQ(kd::uw_ms_poisson_at_least(3, 0.0), 0.0);
}

TEST(UnderwaterLampsMs, ForwardShareOfHgAgainstQuadrature) {
  for (double G : {-0.5, 0.0, 1e-4, 1e-3, 0.3, 0.9}) {  // (g -> 1: a peak no midpoint grid resolves)
    double q = 0;
    const int steps = 200000;
    for (int i = 0; i < steps; ++i) q += 2 * M_PI * kd::hg_phase((i + 0.5) / steps, G) / steps;
    EXPECT_NEAR(kd::uw_ms_forward_share(G), q, 2e-6) << "G " << G;
    EXPECT_NEAR(kf::uw_ms_forward_share(float(G)), q, 2e-6) << "G " << G;
  }
  EXPECT_NEAR(kd::uw_ms_forward_share(1.0), 1.0, 1e-15);
  EXPECT_NEAR(kf::uw_ms_forward_share(1.0f), 1.0f, 1e-7);
  EXPECT_GT(kd::uw_ms_forward_share(0.999), 0.9995);
}

TEST(UnderwaterLampsMs, ViewTransmissionBetweenItsLimits) {
  for (double S : {0.0, 0.5, 3.0, 20.0, 1e4}) {
    // No scattering, or scattering straight on (g = 1): only absorption.
    EXPECT_NEAR(kd::uw_ms_view_transmission(0.1, 0.0, 0.9, S, 8), std::exp(-0.1 * S), 1e-15);
    EXPECT_NEAR(kd::uw_ms_view_transmission(0.1, 0.5, 1.0, S, 8), std::exp(-0.1 * S), 1e-12);
    for (double g : {0.0, 0.5, 0.9, 0.95}) {
      const double T = kd::uw_ms_view_transmission(0.1, 0.5, g, S, 8);
      EXPECT_GE(T, std::exp(-0.6 * S) * (1 - 1e-12));
      EXPECT_LE(T, std::exp(-0.1 * S) * (1 + 1e-12));
      const float Tf = kf::uw_ms_view_transmission(0.1f, 0.5f, float(g), float(S), 8);
      EXPECT_TRUE(std::isfinite(Tf));
      EXPECT_NEAR(Tf, T, 1e-5 * std::max(T, 1e-30) + 1e-30);
    }
  }
}

TEST(UnderwaterLampsMs, BlurredProfilesConserveTheLampsPower) {
  // ∫ P_n dΩ = ∫ P dΩ = 2π (1 - cos θ_c) for a hard cone, every order; values in [0, 1].
  for (double cone : {10.0, 30.0, 60.0})
    for (double g : {0.5, 0.9, 0.95}) {
      const std::vector<float> rows = seasim::lampMsProfiles(cosDeg(cone), cosDeg(cone), g, 0.6, 4, 128, 32);
      for (int n = 1; n <= 4; ++n) {
        double power = 0;  // trapezoid over ψ in 1° steps
        for (int i = 0; i + 1 < UW_MS_TABLE; ++i) {
          const double p0 = rows[(n - 1) * UW_MS_ROW + i], p1 = rows[(n - 1) * UW_MS_ROW + i + 1];
          EXPECT_GE(p0, 0.0);
          EXPECT_LE(p0, 1.0 + 1e-6);
          power += 0.5 * (p0 * std::sin(i * M_PI / 180) + p1 * std::sin((i + 1) * M_PI / 180)) * 2 * M_PI * M_PI / 180;
        }
        const double cone_power = 2 * M_PI * (1 - cosDeg(cone));
        EXPECT_NEAR(power / cone_power, 1.0, 0.02) << "cone " << cone << " g " << g << " n " << n;
      }
    }
  // g -> 1: no spread, the profile itself (1 inside, 0 outside, away from the edge).
  const std::vector<float> sharp = seasim::lampMsProfiles(cosDeg(20), cosDeg(20), 0.99999, 0.6, 2);
  EXPECT_NEAR(sharp[10], 1.0, 1e-3);
  EXPECT_NEAR(sharp[30], 0.0, 1e-3);
}

struct Ray {
  kd::real3 o, d, lamp, axis;
  double t_end;
};

kf::real3 toF(kd::real3 x) { return kf::real3{float(x.x), float(x.y), float(x.z)}; }

// F(G, x) against its Legendre series: the clamped cosine max(μ, 0) = Σ c_l P_l(μ), c_l = (2l + 1)/2 ∫_0^1 μ P_l dμ
// (c_0 = 1/4, c_1 = 1/2, c_2 = 5/16, c_3 = 0, c_4 = -3/32), and an HG lobe's Legendre moments are G^l, so
// F = Σ_l G^l c_l P_l(x) — a route that shares nothing with the inverse-CDF quadrature but the definition.
TEST(UnderwaterLampsMs, IrradianceOfAnHgLobeMatchesItsLegendreSeries) {
  constexpr int kL = 400, kMu = 40000;
  std::vector<double> c(kL + 1, 0.0);
  for (int k = 0; k < kMu; ++k) {  // midpoints in μ over [0, 1], P_l by the three-term recurrence
    const double mu = (k + 0.5) / kMu;
    double p0 = 1.0, p1 = mu;
    c[0] += mu * p0;
    c[1] += mu * p1;
    for (int l = 2; l <= kL; ++l) {
      const double p2 = ((2 * l - 1) * mu * p1 - (l - 1) * p0) / l;
      c[l] += mu * p2;
      p0 = p1;
      p1 = p2;
    }
  }
  for (int l = 0; l <= kL; ++l) c[l] *= (2 * l + 1) / 2.0 / kMu;
  EXPECT_NEAR(c[0], 0.25, 1e-8);
  EXPECT_NEAR(c[1], 0.5, 1e-8);
  EXPECT_NEAR(c[2], 5.0 / 16.0, 1e-8);
  EXPECT_NEAR(c[3], 0.0, 1e-8);
  EXPECT_NEAR(c[4], -3.0 / 32.0, 1e-8);
  const auto series = [&](double G, double x) {
    double sum = c[0] + c[1] * G * x, p0 = 1.0, p1 = x, gl = G;
    for (int l = 2; l <= kL; ++l) {
      const double p2 = ((2 * l - 1) * x * p1 - (l - 1) * p0) / l;
      gl *= G;
      sum += c[l] * gl * p2;
      p0 = p1;
      p1 = p2;
    }
    return sum;
  };
  double worst = 0.0;
  for (double G : {0.0, 0.25, 0.5, 0.7, 0.81, 0.9})
    for (double x : {-1.0, -0.6, -0.2, 0.0, 0.3, 0.7, 0.95, 1.0}) {
      const double exact = kd::uw_ms_irradiance_exact(G, x, 4096);
      worst = std::max(worst, std::fabs(exact - series(G, x)));
      EXPECT_NEAR(exact, series(G, x), 2e-4) << "G " << G << " x " << x;
      EXPECT_NEAR(kf::uw_ms_irradiance_exact(float(G), float(x), 256), exact, 2e-3) << "G " << G << " x " << x;
    }
  std::printf("F(G, x): inverse-CDF quadrature against the Legendre series, max |difference| %.2e\n", worst);
  // The limits: isotropic light gives a quarter of its fluence to any surface, collimated light its cosine.
  for (double x : {-1.0, -0.3, 0.0, 0.5, 1.0}) {
    EXPECT_NEAR(kd::uw_ms_irradiance_exact(0.0, x, 4096), 0.25, 1e-6) << x;
    EXPECT_NEAR(kd::uw_ms_irradiance_exact(1.0, x, 64), std::fmax(x, 0.0), 1e-12) << x;
    // A backward lobe (g < 0, which the lamps' waters do not have) is taken as isotropic, not extrapolated.
    EXPECT_EQ(kd::uw_ms_irradiance_exact(-0.4, x, 4096), kd::uw_ms_irradiance_exact(0.0, x, 4096)) << x;
    EXPECT_TRUE(std::isfinite(kf::uw_ms_irradiance_exact(0.999999f, float(x), 64))) << x;
  }
  // Facing the lamp, the mixture G + (1 - G)/4 the model used before is 9 % high at G = 0.5.
  EXPECT_NEAR(kd::uw_ms_irradiance_exact(0.5, 1.0, 4096), 0.5729, 5e-4);
  // The lamp's table holds F(g^n, x) per order, read linearly between its cosines.
  const double g = 0.85;
  const std::vector<float> rows = seasim::lampMsProfiles(cosDeg(20), cosDeg(15), g, 0.6, 3, 64, 16);
  ASSERT_EQ(rows.size(), size_t(3 * UW_MS_ROW));
  double worst_table = 0.0;
  for (int n = 1; n <= 3; ++n)
    for (int k = 0; k <= 997; ++k) {
      const double x = -1.0 + 2.0 * k / 997.0;
      const double got = kd::uw_ms_irradiance_factor(rows.data() + (n - 1) * UW_MS_ROW, x);
      worst_table = std::max(worst_table, std::fabs(got - kd::uw_ms_irradiance_exact(std::pow(g, n), x, 4096)));
    }
  std::printf("the table of F between its %d cosines: max |difference| %.2e\n", UW_MS_IRRADIANCE, worst_table);
  EXPECT_LT(worst_table, 1e-3);
}

TEST(UnderwaterLampsMs, InscatterConvergesAndFloatAgreesWithDouble) {
  const std::vector<float> table = seasim::lampMsProfiles(cosDeg(20), cosDeg(20), 0.9, 0.6, 8);
  const kd::real3 axis = kd::normalize(kd::real3{-0.05, -0.5, -1.0});
  const Ray rays[] = {
      {{0, -4, 0}, kd::normalize(kd::real3{0, -0.45, -1}), {0.4, -4, -0.3}, axis, 7.0},    // along the beam to the bottom
      {{0, -4, 0}, kd::normalize(kd::real3{0.6, 0.2, -1}), {0.4, -4, -0.3}, axis, 1e30},   // beside it, to infinity
      {{0.4, -4, 2}, kd::real3{0, 0, -1}, {0.4, -4, -0.3}, axis, 1e30},                   // through the lamp
  };
  for (const Ray& r : rays)
    for (double kappa : {0.0, 0.5}) {
      const double fine = kd::uw_ms_inscatter(r.o, r.d, r.lamp, r.axis, cosDeg(20), 1e-3, r.t_end, 75.0, 0.1, 0.3, 0.9,
                                              kappa, 0.4, table.data(), 8, 4096);
      const double coarse = kd::uw_ms_inscatter(r.o, r.d, r.lamp, r.axis, cosDeg(20), 1e-3, r.t_end, 75.0, 0.1, 0.3,
                                                0.9, kappa, 0.4, table.data(), 8, 24);
      const float coarse_f = kf::uw_ms_inscatter(toF(r.o), toF(r.d), toF(r.lamp), toF(r.axis), float(cosDeg(20)), 1e-3f,
                                                 float(std::min(r.t_end, 1e30)), 75.0f, 0.1f, 0.3f, 0.9f, float(kappa),
                                                 0.4f, table.data(), 8, 24);
      ASSERT_GT(fine, 0.0);
      EXPECT_NEAR(coarse / fine, 1.0, 0.05) << "ray o.x " << r.o.x << " kappa " << kappa;
      EXPECT_NEAR(coarse_f / coarse, 1.0, 1e-3);
    }
}

// Order 1's phase outside the cone (uw_ms_order1_phase): its edge-line integral against the same
// integral by 20,000 midpoints in the deflection (the quadrature's own error: 12 nodes measured within
// 1.5 % but for an eye in the plane where HG(0.9)'s peak is narrowest, 9 % at 40° off the axis; 24 nodes
// within 4 %, at 1.4x the lamp passes' time on rov_lights, the same study results), in float and double;
// g = 0 gives 1/4π exactly; inside the cone, on the axis and with the edge line through the point it is
// HG(g²) about the radial direction; near the edge, far off the axis and at g -> 1 it stays finite and
// non-negative, and the light comes in from the beam's side (towards an eye on the far side of x from
// the beam the phase is larger than towards the beam).
double edgeLineReference(kd::real3 x, kd::real3 lamp, kd::real3 axis, double cos_cone, double g, double c, kd::real3 eye) {
  const kd::real3 w = x - lamp;
  const double s = std::sqrt(kd::dot(w, w));
  const kd::real3 rad = w * (1.0 / s);
  const double cp = kd::dot(rad, axis);
  kd::real3 perp = rad - cp * axis;
  perp = perp * (1.0 / std::sqrt(kd::dot(perp, perp)));
  const kd::real3 e = cos_cone * axis + std::sqrt(1 - cos_cone * cos_cone) * perp;
  const double ce = kd::dot(rad, e), dmin = std::acos(ce), h = s * std::sin(dmin), u0 = s * ce;
  kd::real3 n = rad - ce * e;
  n = n * (1.0 / std::sqrt(kd::dot(n, n)));
  const int N = 20000;
  double num = 0, den = 0;
  for (int k = 0; k < N; ++k) {
    const double delta = dmin + (M_PI - dmin) * (k + 0.5) / N;
    const double r = h / std::sin(delta), u = std::max(u0 - h / std::tan(delta), 0.0);
    const double wgt = kd::hg_phase(std::cos(delta), g) * std::exp(-c * (u + r - s));
    num += wgt * kd::hg_phase(kd::dot(std::cos(delta) * e + std::sin(delta) * n, eye), g);
    den += wgt;
  }
  return num / den;
}

TEST(UnderwaterLampsMs, OrderOnePhaseFromTheConesEdgeLine) {
  const kd::real3 lamp{0, 0, 0}, axis{0, 0, -1};
  const double cone = cosDeg(20);
  const auto at = [](double psi_deg, double s) {
    const double p = psi_deg * M_PI / 180;
    return kd::real3{s * std::sin(p), 0, -s * std::cos(p)};
  };
  for (double g : {0.5, 0.9})
    for (double psi : {25.0, 40.0, 90.0})
      for (const kd::real3 eye : {kd::real3{1, 0, 0}, kd::real3{-1, 0, 0}, kd::normalize(kd::real3{0.3, 0.8, 0.5})}) {
        const kd::real3 x = at(psi, 3.0);
        const double ref = edgeLineReference(x, lamp, axis, cone, g, 0.4, eye);
        const double d = kd::uw_ms_order1_phase(x, lamp, axis, cone, g, 0.4, eye);
        const float f = kf::uw_ms_order1_phase(toF(x), toF(lamp), toF(axis), float(cone), float(g), 0.4f, toF(eye));
        std::printf("[ measured ] g %.1f psi %.0f eye (%.1f, %.1f, %.1f): %d nodes / 20000 = %.4f\n", g, psi, eye.x, eye.y, eye.z, UW_MS_EDGE_NODES, d / ref);
        EXPECT_NEAR(d / ref, 1.0, 0.1) << "g " << g << " psi " << psi;
        EXPECT_NEAR(f / d, 1.0, 1e-4) << "g " << g << " psi " << psi;
      }
  // g = 0: isotropic.
  EXPECT_NEAR(kd::uw_ms_order1_phase(at(40, 3), lamp, axis, cone, 0.0, 0.4, kd::real3{1, 0, 0}), 1 / (4 * M_PI), 1e-12);
  // Inside the cone, on the axis: HG(g²) about the radial direction.
  for (const kd::real3 x : {at(10, 3), at(0, 3)})
    EXPECT_DOUBLE_EQ(kd::uw_ms_order1_phase(x, lamp, axis, cone, 0.9, 0.4, kd::real3{0, 1, 0}),
                     kd::hg_phase(kd::dot(kd::normalize(x - lamp), kd::real3{0, 1, 0}), 0.81));
  // Light from the beam: at x beside the beam (+x side) it travels away from the axis, so an eye further
  // out (+x) sees more of it than one back towards the beam.
  EXPECT_GT(kd::uw_ms_order1_phase(at(40, 3), lamp, axis, cone, 0.9, 0.4, kd::real3{1, 0, 0}),
            kd::uw_ms_order1_phase(at(40, 3), lamp, axis, cone, 0.9, 0.4, kd::real3{-1, 0, 0}));
  // Stiff: just outside the edge, far off the axis, behind the lamp, g -> 1, the lamp itself.
  for (double psi : {20.0001, 179.9})
    for (double g : {0.0, 0.9, 0.999999}) {
      const float f = kf::uw_ms_order1_phase(toF(at(psi, 2.0)), toF(lamp), toF(axis), float(cone), float(g), 0.4f,
                                             kf::real3{1, 0, 0});
      EXPECT_TRUE(std::isfinite(f) && f >= 0.0f) << psi << " " << g;
    }
  const float at_lamp = kf::uw_ms_order1_phase(toF(lamp), toF(lamp), toF(axis), float(cone), 0.9f, 0.4f, kf::real3{1, 0, 0});
  EXPECT_TRUE(std::isfinite(at_lamp) && at_lamp >= 0.0f);
}

TEST(UnderwaterLampsMs, StiffCasesStayFinite) {
  const kd::real3 lamp{0.4, -4, -0.3}, axis = kd::normalize(kd::real3{-0.05, -0.5, -1.0});
  for (double g : {0.0, 0.5, 0.999999})
    for (double b : {0.0, 1e-9, 0.3, 50.0}) {
      const std::vector<float> table = seasim::lampMsProfiles(cosDeg(0.1), cosDeg(0.1), g, 0.6, 8, 64, 16);
      for (float kappa : {0.0f, 1.0f}) {
        const float L = kf::uw_ms_inscatter(kf::real3{0.4f, -4, 2}, kf::real3{0, 0, -1}, toF(lamp), toF(axis),
                                            float(cosDeg(0.1)), 1e-3f, 1e30f, kf::uw_ms_ray_cap(0.1f + float(b)), 0.1f,
                                            float(b), float(g), kappa, 0.1f + float(b), table.data(), 8, 24);
        EXPECT_TRUE(std::isfinite(L)) << "g " << g << " b " << b;
        EXPECT_GE(L, 0.0f);
        // A surface point at the lamp itself (s = 0) and one just beside it.
        for (float dx : {0.0f, 1e-6f}) {
          const float E = kf::uw_ms_surface(kf::real3{0.4f + dx, -4, -0.3f}, kf::real3{0, 1, 0}, toF(lamp), toF(axis),
                                            1e-3f, 0.1f, float(b), float(g), kappa, table.data(), 8);
          EXPECT_TRUE(std::isfinite(E));
          EXPECT_GE(E, 0.0f);
        }
        if (b == 0.0) EXPECT_EQ(L, 0.0f);
      }
    }
}

}  // namespace
