// underwater_lamps_halo_test.cpp — the bottom's halo in the "orders" model of the lamps under water
// (kernels/common/underwater_lamps_ms.h, "The bottom's halo"): E₂ against its integral, the plane's F
// against the closed form at g = 0 and against an area integral over the plane at g = 0.9, the kernel's
// table of F against F itself between its nodes, the view ray's quadrature against a fine one, float
// against double, and the stiff points (no scattering, no bottom, the ray on the bottom, the lamp on it,
// g -> 1, opaque water).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "math/kernel_math.h"
#include "underwater/lamps_ms_table.h"
#include "underwater/lamps_ms_weights.h"

namespace {

namespace kd = seasim::kmath_d;
namespace kf = seasim::kmath_f;

// E₂(x) = ∫_0^1 e^{-x/μ} dμ, independently of A&S's fits: for x < 2 from E₁'s convergent series
// (A&S 5.1.11, E₁ = −γ − ln x − Σ_{k>=1} (−x)^k/(k k!)) and E₂ = e^{-x} − x E₁; beyond, where the
// integrand is smooth on [0, 1], by Simpson's rule in μ.
double e2ByQuadrature(double x) {
  if (x < 2.0) {
    double sum = 0.0, term = 1.0;
    for (int k = 1; k < 60; ++k) {
      term *= -x / k;  // (−x)^k / k!
      sum += term / k;
    }
    const double e1 = -0.57721566490153286 - std::log(x) - sum;
    return std::exp(-x) - x * e1;
  }
  const int n = 20000;
  double acc = 0.0;
  for (int k = 1; k <= n; ++k) {  // the integrand is 0 at μ = 0
    const double mu = double(k) / n;
    acc += (k == n ? 1 : (k % 2 ? 4 : 2)) * std::exp(-x / mu);
  }
  return acc / (3.0 * n);
}

TEST(UnderwaterLampsHalo, ExponentialIntegralE2AgainstItsIntegral) {
  for (double x : {1e-8, 1e-3, 0.1, 0.5, 0.999, 1.0, 1.001, 2.0, 5.0, 10.0, 30.0, 80.0}) {
    const double want = e2ByQuadrature(x), got = kd::uw_ms_expint2(x);
    EXPECT_NEAR(got, want, std::max(3e-7, 2e-6 * want)) << "x " << x;
    EXPECT_NEAR(kf::uw_ms_expint2(float(x)), want, std::max(1e-6, 1e-5 * want)) << "x " << x << " (float)";
  }
  EXPECT_EQ(kd::uw_ms_expint2(0.0), 1.0);
  EXPECT_EQ(kf::uw_ms_expint2(0.0f), 1.0f);
  EXPECT_EQ(kd::uw_ms_expint2(-1.0), 1.0);
  // The two branches meet at x = 1 (A&S 5.1.53 and 5.1.56).
  EXPECT_NEAR(kd::uw_ms_expint2(std::nextafter(1.0, 0.0)), kd::uw_ms_expint2(1.0), 2e-7);
  // Far out: 0 or positive, never NaN/Inf, in float too (no x⁴ to overflow).
  for (float x : {1e3f, 1e6f, 1e30f, 3e38f}) {
    const float e = kf::uw_ms_expint2(x);
    EXPECT_TRUE(std::isfinite(e) && e >= 0.0f) << x;
  }
}

// F(z, μ_e) of one band, exactly (uw_ms_halo_azimuths then uw_ms_halo_plane_from).
double planeF(double z, double mu_e, double a, double b, double g, int orders) {
  std::vector<double> az(UW_MS_HALO_QUAD_MU * (orders + 1));
  kd::uw_ms_halo_azimuths(mu_e, g, orders, az.data());
  return kd::uw_ms_halo_plane_from(z, a, b, orders, az.data());
}

TEST(UnderwaterLampsHalo, PlaneAtIsotropicScatteringIsTheClosedForm) {
  // g = 0: every phase 1/(4π), the orders' weights sum to e^{-σ_a s}: F = σ_s E₂(σ_a z)/2.
  for (double z : {0.0, 0.1, 1.0, 5.0})
    for (double mu_e : {-1.0, 0.0, 0.5, 1.0}) {
      const double exact = 0.3 * (z > 0.0 ? e2ByQuadrature(0.1 * z) : 1.0) / 2.0;
      EXPECT_NEAR(planeF(z, mu_e, 0.1, 0.3, 0.0, 4), exact, 2e-3 * exact) << "z " << z << " mu_e " << mu_e;
    }
}

TEST(UnderwaterLampsHalo, PlaneAgainstAnAreaIntegralOverTheBottom) {
  // g = 0.9 (each order's phase without its forward peak): the same F summed over the plane in polar
  // coordinates about the foot, r = z sinh u (another variable and grid than the μ, φ midpoints).
  const double a = 0.1, b = 0.3, g = 0.9;
  const int orders = 4;
  for (double z : {0.5, 2.0})
    for (double mu_e : {-0.9, 0.0, 0.7}) {
      const kd::real3 e{std::sqrt(1.0 - mu_e * mu_e), mu_e, 0.0};  // the light's way to the eye
      const int nu = 4000, nphi = 720;
      const double u_max = std::asinh(600.0 / z), du = u_max / nu, dphi = 2.0 * M_PI / nphi;
      double acc = 0.0;
      std::vector<double> w(orders + 1);
      for (int iu = 0; iu < nu; ++iu) {
        const double u = (iu + 0.5) * du, r = z * std::sinh(u), dr = z * std::cosh(u) * du;
        const double s = std::hypot(r, z);
        kd::uw_ms_glow_weights(a, b, s, orders, w.data());
        for (int ip = 0; ip < nphi; ++ip) {
          const double phi = (ip + 0.5) * dphi;
          const kd::real3 omega{-r * std::cos(phi) / s, z / s, -r * std::sin(phi) / s};  // from the plane to x
          const double ca = kd::dot(omega, e);
          double sum = 0.0, G = g;
          for (int n = 0; n <= orders; ++n, G *= g) sum += w[n] * kd::uw_ms_glow_phase(ca, G);
          acc += sum * (z / s) / (s * s) * r * dr * dphi;
        }
      }
      const double want = b * acc, got = planeF(z, mu_e, a, b, g, orders);
      std::printf("F(z %.1f, mu_e %+.1f): %.6g (area integral %.6g)\n", z, mu_e, got, want);
      EXPECT_NEAR(got, want, 0.01 * want) << "z " << z << " mu_e " << mu_e;
    }
}

TEST(UnderwaterLampsHalo, KernelTableFollowsThePlaneBetweenItsNodes) {
  const std::vector<UwBand> bands = [] {
    std::vector<UwBand> v(3);
    const double ab[3][2] = {{0.05, 0.5}, {0.3, 0.05}, {0.02, 0.01}};
    for (int i = 0; i < 3; ++i) {
      v[i].a = float(ab[i][0]);
      v[i].b = float(ab[i][1]);
      v[i].c = float(ab[i][0] + ab[i][1]);
    }
    return v;
  }();
  const double g = 0.85;
  const int orders = 4;
  const std::vector<float> table = seasim::lampMsWeights(bands, g, 0.75, orders);
  ASSERT_EQ(table.size(), seasim::lampMsWeightsSize(bands.size(), orders));
  const float* rows = kd::uw_ms_halo_rows(table.data(), int(bands.size()), orders);
  for (size_t i = 0; i < bands.size(); ++i) {
    const double peak = planeF(0.0, 1.0, bands[i].a, bands[i].b, g, orders);
    double worst = 0.0;
    for (double z : {0.0, 0.013, 0.37, 1.9, 7.3, 41.0})
      for (double mu_e : {-0.97, -0.41, 0.03, 0.52, 0.99}) {
        int m, j;
        double fm, fz;
        kd::uw_ms_halo_dir_index(mu_e, &m, &fm);
        kd::uw_ms_halo_z_index(table.data(), z, &j, &fz);
        const double got = kd::uw_ms_halo_at_b(rows, int(bands.size()), int(i), m, fm, j, fz);
        worst = std::max(worst, std::fabs(got - planeF(z, mu_e, bands[i].a, bands[i].b, g, orders)));
      }
    std::printf("band %zu: the table within %.3g of a peak %.4g\n", i, worst, peak);
    EXPECT_LT(worst, 5e-3 * peak) << "band " << i;
  }
}

struct HaloRay {
  kd::real3 o, d;
  double t_end;
};

TEST(UnderwaterLampsHalo, ViewRayStepsAgainstAFineQuadrature) {
  // A lamp 2 m over the bottom, aimed down and ahead; rays along the bottom, down onto it, up past the lamp.
  const double depth = 6.0, a = 0.1, b = 0.3, g = 0.9, s_min = 0.02, kappa = 0.75;
  const int orders = 4;
  const std::vector<float> rows = seasim::lampMsProfiles(std::cos(25 * M_PI / 180), std::cos(20 * M_PI / 180), g, 0.6, orders);
  const kd::real3 lamp{0.0, -4.0, 0.0}, axis = kd::normalize(kd::real3{0.0, -1.0, 1.0});
  const HaloRay rays[] = {{{-3.0, -5.0, -2.0}, kd::normalize(kd::real3{0.2, 0.0, 1.0}), 1e30},
                          {{0.0, -3.0, -3.0}, kd::normalize(kd::real3{0.0, -0.5, 1.0}), 6.0 * std::sqrt(1.25)},
                          {{1.0, -5.5, -1.0}, kd::normalize(kd::real3{0.0, 1.0, 0.3}), 5.5 / (1.0 / std::sqrt(1.09))}};
  const int steps = kd::uw_ms_glow_steps(12);
  for (const HaloRay& r : rays) {
    const double cap = kd::uw_ms_ray_cap(a + b);
    const double coarse =
        kd::uw_ms_halo_inscatter(r.o, r.d, depth, 0.5, lamp, axis, s_min, r.t_end, cap, a, b, g, kappa, rows.data(), orders, steps);
    const double fine =
        kd::uw_ms_halo_inscatter(r.o, r.d, depth, 0.5, lamp, axis, s_min, r.t_end, cap, a, b, g, kappa, rows.data(), orders, 256);
    const float single = kf::uw_ms_halo_inscatter(
        kf::real3{float(r.o.x), float(r.o.y), float(r.o.z)}, kf::real3{float(r.d.x), float(r.d.y), float(r.d.z)}, float(depth),
        0.5f, kf::real3{float(lamp.x), float(lamp.y), float(lamp.z)}, kf::real3{float(axis.x), float(axis.y), float(axis.z)},
        float(s_min), float(std::min(r.t_end, 1e30)), float(cap), float(a), float(b), float(g), float(kappa), rows.data(), orders,
        steps);
    std::printf("halo along a ray: %d steps %.5g, 256 steps %.5g (%.1f %%)\n", steps, coarse, fine, 100 * (coarse / fine - 1));
    ASSERT_GT(fine, 0.0);
    EXPECT_NEAR(coarse, fine, 0.01 * fine);
    EXPECT_NEAR(single, coarse, 1e-4 * coarse);
  }
}

TEST(UnderwaterLampsHalo, StiffPointsStayFinite) {
  const int orders = 4;
  const std::vector<float> rows = seasim::lampMsProfiles(std::cos(30 * M_PI / 180), std::cos(30 * M_PI / 180), 0.9, 0.6, orders);
  const kd::real3 lamp{0.0, -4.0, 0.0}, down{0.0, -1.0, 0.0};
  const kd::real3 o{-2.0, -4.5, 0.0}, d = kd::normalize(kd::real3{1.0, -0.3, 0.0});
  // No scattering, no bottom, a black bottom: nothing.
  EXPECT_EQ(kd::uw_ms_halo_inscatter(o, d, 6.0, 0.5, lamp, down, 0.02, 1e30, 300.0, 0.1, 0.0, 0.9, 0.75, rows.data(), orders, 12), 0.0);
  EXPECT_EQ(kd::uw_ms_halo_inscatter(o, d, 0.0, 0.5, lamp, down, 0.02, 1e30, 300.0, 0.1, 0.3, 0.9, 0.75, rows.data(), orders, 12), 0.0);
  EXPECT_EQ(kd::uw_ms_halo_inscatter(o, d, 6.0, 0.0, lamp, down, 0.02, 1e30, 300.0, 0.1, 0.3, 0.9, 0.75, rows.data(), orders, 12), 0.0);
  // A ray along the bottom itself (z = 0), the lamp on the bottom, g -> 1, opaque water: finite, >= 0.
  const kf::real3 of{-2.0f, -6.0f, 0.0f}, df{1.0f, 0.0f, 0.0f}, lampf{0.0f, -4.0f, 0.0f}, downf{0.0f, -1.0f, 0.0f};
  const struct {
    kf::real3 lamp;
    float a, b, g;
  } cases[] = {{lampf, 0.1f, 0.3f, 0.9f}, {kf::real3{0.5f, -6.0f, 0.0f}, 0.1f, 0.3f, 0.9f}, {lampf, 0.1f, 0.3f, 1.0f},
               {lampf, 50.0f, 200.0f, 0.9f}};
  for (const auto& c : cases) {
    const float v = kf::uw_ms_halo_inscatter(of, df, 6.0f, 0.5f, c.lamp, downf, 0.02f, 1e30f, kf::uw_ms_ray_cap(c.a + c.b), c.a,
                                             c.b, c.g, 0.75f, rows.data(), orders, 12);
    EXPECT_TRUE(std::isfinite(v) && v >= 0.0f) << v;
  }
  // F itself at z = 0 and far up, every direction: finite, >= 0, and at z = 0 σ_s ∫ p over the upper half.
  for (double mu_e : {-1.0, 0.0, 1.0}) {
    EXPECT_TRUE(std::isfinite(planeF(0.0, mu_e, 0.1, 0.3, 1.0, orders)));
    EXPECT_GE(planeF(1e4, mu_e, 0.1, 0.3, 0.9, orders), 0.0);
  }
}

}  // namespace
