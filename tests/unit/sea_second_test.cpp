// sea_second_test.cpp — kernels/common/sea_second.h (000 eq. 6–8) in float and double: the radiance map
// (eq. 7) against quadrature along the sampling ray, its continuity at theta -> pi/2 from both sides,
// the 0/0 at 1 - sec(theta_io) cos(theta) = 0, the sampling-plane depths and directions as quadratures.
#include <gtest/gtest.h>

#include <cmath>

#include "math/kernel_math.h"

namespace {

namespace kd = seasim::kmath_d;
namespace kf = seasim::kmath_f;

// L^(1) by midpoint quadrature along the sampling ray in optical path l (long double): the beam
// e_beam e^{-tau sec_io} at optical depth tau = tau_k - l cos_theta, scattered into -omega, attenuated
// by e^{-l}. l_max: to the surface, to the bottom, or far enough (60 optical depths) without one.
long double radianceQuadrature(double e_beam, double albedo, double phase, double cos_io, double cos_theta,
                               double tau_k, double tau_d, int steps) {
  long double l_max;
  if (cos_theta > 0) l_max = tau_k / cos_theta;
  else if (cos_theta < 0 && tau_d >= 0) l_max = (tau_d - tau_k) / -cos_theta;
  else l_max = 60.0L;
  l_max = std::min(l_max, 60.0L / (1.0L - cos_theta / cos_io > 0 ? 1.0L - cos_theta / cos_io : 1.0L));
  const long double dl = l_max / steps;
  long double sum = 0;
  for (int i = 0; i < steps; ++i) {
    const long double l = (i + 0.5L) * dl;
    sum += std::exp(-(tau_k - l * cos_theta) / cos_io - l);
  }
  return e_beam * albedo * phase * sum * dl;
}

TEST(SeaSecond, RadianceMapMatchesQuadratureAlongTheSamplingRay) {
  const double e = 1.7, albedo = 0.8, phase = 0.3;
  for (double cos_io : {1.0, 0.9, 0.67}) {
    for (double cos_theta : {0.95, 0.5, 0.1, -0.1, -0.5, -1.0}) {
      for (double tau_k : {0.01, 0.5, 3.0}) {
        for (double tau_d : {-1.0, 4.0}) {
          const double closed = kd::sea_radiance_map(e, albedo, phase, cos_io, cos_theta, tau_k, tau_d);
          const long double quad = radianceQuadrature(e, albedo, phase, cos_io, cos_theta, tau_k, tau_d, 200000);
          EXPECT_NEAR(closed, double(quad), 1e-7 * double(quad) + 1e-15)
              << "cos_io " << cos_io << " cos_theta " << cos_theta << " tau_k " << tau_k << " tau_d " << tau_d;
        }
      }
    }
  }
}

TEST(SeaSecond, RadianceMapIsEquation7InBothBranches) {
  // The paper's own form, L* [e^{-c z sec_io} - e^{...}], away from its 0/0 (c = 1: tau = z).
  const double e = 2.0, albedo = 0.6, phase = 0.2, cos_io = 0.8, z_k = 1.3, z_d = 5.0;
  for (double cos_theta : {0.9, 0.4, -0.3, -0.9}) {
    const double l_star = e * albedo * phase / (1 - cos_theta / cos_io);  // L*/c in optical units
    const double far = cos_theta > 0 ? std::exp(-z_k / cos_theta)
                                     : std::exp(-(z_d / cos_io - (z_d - z_k) / cos_theta));
    const double eq7 = l_star * (std::exp(-z_k / cos_io) - far);
    EXPECT_NEAR(kd::sea_radiance_map(e, albedo, phase, cos_io, cos_theta, z_k, z_d), eq7, 1e-12 * std::fabs(eq7));
  }
}

TEST(SeaSecond, RadianceMapIsContinuousAtTheHorizontalFromBothSides) {
  // theta -> pi/2: both branches tend to L* e^{-tau sec_io} with L* = e albedo phase (kappa = 1).
  for (double tau_d : {-1.0, 6.0}) {
    const double e = 1.0, albedo = 0.7, phase = 0.25, cos_io = 0.75, tau_k = 2.0;
    const double limit = e * albedo * phase * std::exp(-tau_k / cos_io);
    EXPECT_NEAR(kd::sea_radiance_map(e, albedo, phase, cos_io, 0.0, tau_k, tau_d), limit, 1e-15);
    for (double eps : {1e-2, 1e-4, 1e-6, 1e-9}) {
      const double up = kd::sea_radiance_map(e, albedo, phase, cos_io, eps, tau_k, tau_d);
      const double down = kd::sea_radiance_map(e, albedo, phase, cos_io, -eps, tau_k, tau_d);
      // Departure from the limit is O(eps) on both sides (the far-end term vanishes like e^{-1/eps}).
      EXPECT_NEAR(up, limit, 2 * eps * limit) << eps;
      EXPECT_NEAR(down, limit, 2 * eps * limit) << eps;
      const float upf = kf::sea_radiance_map(1.0f, 0.7f, 0.25f, 0.75f, float(eps), 2.0f, float(tau_d));
      const float downf = kf::sea_radiance_map(1.0f, 0.7f, 0.25f, 0.75f, float(-eps), 2.0f, float(tau_d));
      EXPECT_NEAR(upf, limit, 2 * eps * limit + 1e-6 * limit) << eps;
      EXPECT_NEAR(downf, limit, 2 * eps * limit + 1e-6 * limit) << eps;
    }
  }
}

TEST(SeaSecond, RadianceMapAtAndNearTheSunBeamDirection) {
  // cos_theta = cos_io: 1 - sec_io cos_theta = 0, L* of eq. 7 is 0/0; the limit is
  // e albedo phase e^{-tau sec_io} * l_max with l_max = tau sec_theta (uniform attenuation along the ray).
  const double e = 1.0, albedo = 0.9, phase = 3.0, tau_k = 1.5;
  for (double cos_io : {1.0, 0.8, 0.67}) {
    const double exact = e * albedo * phase * std::exp(-tau_k / cos_io) * tau_k / cos_io;
    EXPECT_NEAR(kd::sea_radiance_map(e, albedo, phase, cos_io, cos_io, tau_k, -1.0), exact, 1e-14 * exact);
    const float f_at = kf::sea_radiance_map(1.0f, 0.9f, 3.0f, float(cos_io), float(cos_io), 1.5f, -1.0f);
    EXPECT_NEAR(f_at, exact, 1e-6 * exact);
    for (double rel : {1e-12, 1e-9, 1e-7, 1e-5, 1e-3, 1e-2}) {
      for (double sign : {-1.0, 1.0}) {
        const double ct = std::min(1.0, cos_io * (1 + sign * rel));
        const double d = kd::sea_radiance_map(e, albedo, phase, cos_io, ct, tau_k, -1.0);
        const double q = double(radianceQuadrature(e, albedo, phase, cos_io, ct, tau_k, -1.0, 100000));
        EXPECT_NEAR(d, q, 1e-8 * q) << "cos_io " << cos_io << " rel " << sign * rel;
        const float f = kf::sea_radiance_map(1.0f, 0.9f, 3.0f, float(cos_io), float(ct), 1.5f, -1.0f);
        EXPECT_TRUE(std::isfinite(f));
        EXPECT_NEAR(f, q, 3e-6 * q) << "float, cos_io " << cos_io << " rel " << sign * rel;
      }
    }
  }
}

TEST(SeaSecond, RadianceMapExtremes) {
  // No sun, no scattering, zero depth, huge optical depths: finite and right.
  EXPECT_EQ(kd::sea_radiance_map(0.0, 0.8, 0.3, 1.0, 0.5, 1.0, -1.0), 0.0);
  EXPECT_EQ(kd::sea_radiance_map(1.0, 0.0, 0.3, 1.0, 0.5, 1.0, -1.0), 0.0);
  EXPECT_EQ(kd::sea_radiance_map(1.0, 0.8, 0.3, 0.9, 0.5, 0.0, -1.0), 0.0);  // at the surface, looking up
  for (double tau : {50.0, 500.0, 1e4}) {
    const float f = kf::sea_radiance_map(1.0f, 0.8f, 0.3f, 0.67f, 0.99f, float(tau), -1.0f);
    EXPECT_TRUE(std::isfinite(f) && f >= 0.0f) << tau;
    const float g = kf::sea_radiance_map(1.0f, 0.8f, 0.3f, 0.67f, -0.99f, float(tau), float(2 * tau));
    EXPECT_TRUE(std::isfinite(g) && g >= 0.0f) << tau;
  }
  // Bottom at the plane itself: no path downwards.
  EXPECT_EQ(kd::sea_radiance_map(1.0, 0.8, 0.3, 0.9, -0.5, 2.0, 2.0), 0.0);
}

TEST(SeaSecond, SamplingPlanesIntegrateTheViewRayIntegrand) {
  // int_0^tau_d e^{-q tau} dtau with q = sec_ji + sec_io (the shape of G J) converges with n_z.
  for (double tau_d : {-1.0, 0.2, 3.0}) {
    const double cos_io = 0.8, q = 1.2 + 1 / cos_io;
    const double exact = tau_d < 0 ? 1 / q : -std::expm1(-q * tau_d) / q;
    double previous_error = 1e300;
    for (int n_z : {2, 4, 8, 16, 32}) {
      double sum = 0, weights = 0;
      for (int k = 0; k < n_z; ++k) {
        double w = 0;
        const double tau = kd::sea_plane_depth(k, n_z, cos_io, tau_d, &w);
        EXPECT_GT(tau, 0.0);
        if (tau_d >= 0) EXPECT_LT(tau, tau_d);
        sum += w * std::exp(-q * tau);
        weights += w;
      }
      const double err = std::fabs(sum - exact) / exact;
      EXPECT_LT(err, previous_error) << n_z;
      previous_error = err;
      if (n_z == 32) EXPECT_LT(err, 2e-3) << tau_d;
      // int dtau (unweighted) only where the transmittance is near 1: the planes follow the attenuation.
      if (tau_d > 0 && tau_d < 0.5 && n_z == 32) EXPECT_NEAR(weights, tau_d, 0.01 * tau_d);
    }
  }
  float w = 0;  // float, very thin water: planes inside (0, tau_d)
  const float t = kf::sea_plane_depth(0, 12, 0.7f, 1e-6f, &w);
  EXPECT_GT(t, 0.0f);
  EXPECT_LT(t, 1e-6f);
  EXPECT_NEAR(w, 1e-6f / 12, 1e-9f);
}

TEST(SeaSecond, SamplingDirectionsCoverTheSphere) {
  for (int n_theta : {2, 8, 32}) {
    const int n_phi = 2 * n_theta;
    double total = 0;
    kd::real3 mean{0, 0, 0};
    for (int m = 0; m < n_theta * n_phi; ++m) {
      kd::real3 w{};
      const double weight = kd::sea_direction(m, n_theta, n_phi, &w);
      EXPECT_NEAR(kd::length(w), 1.0, 1e-12);
      total += weight;
      mean = mean + w * weight;
    }
    EXPECT_NEAR(total, 4 * M_PI, 4 * M_PI * 2.0 / (n_theta * n_theta));  // midpoint rule in theta
    EXPECT_NEAR(kd::length(mean), 0.0, 1e-12);
  }
}

TEST(SeaSecond, VsfMapParameterRoundTrips) {
  for (double alpha : {0.0, 1e-3, 0.1, 1.0, 2.0, M_PI}) {
    const double t = kd::sea_vsf_param(std::cos(alpha));
    EXPECT_NEAR(t, std::sin(alpha / 2), 1e-9);
    EXPECT_NEAR(kd::sea_vsf_value(t, 0.9), kd::hg_phase(std::cos(alpha), 0.9), 1e-9 * kd::hg_phase(std::cos(alpha), 0.9));
  }
}

TEST(SeaSecond, AttenuationMap) {
  EXPECT_DOUBLE_EQ(kd::sea_attenuation(0.0, 0.7), 1.0);
  EXPECT_NEAR(kd::sea_attenuation(1.4, 0.7), std::exp(-2.0), 1e-15);
  EXPECT_EQ(kf::sea_attenuation(1e4f, 0.7f), 0.0f);
}

}  // namespace
