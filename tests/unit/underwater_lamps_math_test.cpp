// underwater_lamps_math_test.cpp — the math of spotlights in water (kernels/common/underwater_lamps.h):
// the sampling-plane estimate of one lamp's single scattering per band against brute-force quadrature
// of the integral it approximates (no planes, no cone clipping, no far-field closed form: a fine
// midpoint rule over the whole ray, the profile evaluated at every step), float against double, and
// the stiff cases: a cone of 0.1°, turbid water, a ray through the lamp, g -> 1.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "math/kernel_math.h"
#include "underwater/lamps_setup.h"

namespace {

namespace kd = seasim::kmath_d;
namespace kf = seasim::kmath_f;

struct Case {
  kd::real3 o, d, lamp, axis;
  double cone_deg, falloff_deg, sigma_s, sigma_t, g, t_end;
};

double cosDeg(double deg) { return std::cos(deg * M_PI / 180); }

// I_s per unit I: ∫_0^{t_end} P(t) σ_s p_HG(cos α) e^{-σ_t (s + t)} / max(s, s_min)² dt by the midpoint rule
// in the angle the lamp sees (dt / s² is smooth in it), `steps` steps, over the whole ray.
double bruteForce(const Case& c, double s_min, int steps) {
  const double ci = cosDeg(c.cone_deg), cin = cosDeg(c.cone_deg - c.falloff_deg);
  double a, h;
  kd::shafts_closest_approach(c.o, c.d, c.lamp, &a, &h);
  const double r = std::max(h, s_min);
  const double t_max = std::isinf(c.t_end) ? a + 1e6 : c.t_end;
  const double phi0 = std::atan((0 - a) / r), phi1 = std::atan((t_max - a) / r);
  double sum = 0;
  for (int k = 0; k < steps; ++k) {
    const double phi = phi0 + (phi1 - phi0) * (k + 0.5) / steps;
    const double t = a + r * std::tan(phi);
    const double dt_dphi = r / (std::cos(phi) * std::cos(phi));
    const kd::real3 p = c.o + t * c.d;
    const double P = kd::uw_lamp_profile(p, c.lamp, c.axis, ci, cin);
    if (P <= 0) continue;
    double s, cos_alpha;
    kd::uw_lamp_at(c.o, c.d, c.lamp, t, &s, &cos_alpha);
    sum += P * kd::uw_lamp_plane_g(c.sigma_s, c.sigma_t, c.g, s, t, cos_alpha, s_min) * dt_dphi;
  }
  return sum * (phi1 - phi0) / steps;
}

double planesD(const Case& c, int n, int m) {
  return kd::uw_lamp_inscatter(c.o, c.d, c.lamp, c.axis, cosDeg(c.cone_deg), cosDeg(c.cone_deg - c.falloff_deg), 1e-3,
                               c.t_end, c.sigma_s, c.sigma_t, c.g, n, m);
}

float planesF(const Case& c, int n, int m) {
  auto v = [](kd::real3 x) { return kf::real3{float(x.x), float(x.y), float(x.z)}; };
  const float t_end = std::isinf(c.t_end) ? 1e30f : float(c.t_end);
  return kf::uw_lamp_inscatter(v(c.o), v(c.d), v(c.lamp), v(c.axis), float(cosDeg(c.cone_deg)),
                               float(cosDeg(c.cone_deg - c.falloff_deg)), 1e-3f, t_end, float(c.sigma_s),
                               float(c.sigma_t), float(c.g), n, m);
}

// A diver's torch 1 m to the side of the view ray, beam crossing it; coastal water (3C-like at 550 nm).
Case crossing() {
  Case c;
  c.o = {0, -5, 0};
  c.d = kd::normalize(kd::real3{0, -0.1, -1});
  c.lamp = {1, -5, -3};
  c.axis = kd::normalize(kd::real3{-1, -0.2, -0.6});
  c.cone_deg = 25;
  c.falloff_deg = 8;
  c.sigma_s = 0.6;
  c.sigma_t = 0.8;
  c.g = 0.9;
  c.t_end = INFINITY;
  return c;
}

}  // namespace

TEST(UnderwaterLampsMath, PlanesConvergeToBruteForceQuadrature) {
  const Case c = crossing();
  const double ref = bruteForce(c, 1e-3, 400000);
  ASSERT_GT(ref, 0);
  // The paper's setting is within a few per cent; many planes within 0.1 %.
  EXPECT_NEAR(planesD(c, 30, 6), ref, 0.03 * ref);
  EXPECT_NEAR(planesD(c, 400, 16), ref, 1e-3 * ref);
  // Errors fall as planes are added (the method converges to the integral).
  EXPECT_LT(std::fabs(planesD(c, 200, 8) - ref), std::fabs(planesD(c, 10, 2) - ref));
}

TEST(UnderwaterLampsMath, EndsAtTheFirstSurfaceAndFarFieldClosesTheRay) {
  Case c = crossing();
  c.t_end = 4.0;  // a rock at 4 m
  const double ref = bruteForce(c, 1e-3, 400000);
  EXPECT_NEAR(planesD(c, 400, 16), ref, 1e-3 * ref);
  // A ray along the beam that never leaves it: the far field's samples to infinity.
  Case along = crossing();
  along.o = {0, -5, 0};
  along.lamp = {0, -4.8, 0.5};
  along.d = kd::normalize(kd::real3{0, -0.1, -1});
  along.axis = along.d;
  const double ref_along = bruteForce(along, 1e-3, 400000);
  EXPECT_NEAR(planesD(along, 400, 16), ref_along, 2e-3 * ref_along);
}

// The far field's samples (uw_lamp_tail_weight: 8-point Gauss–Legendre in the lamp's angle) against air's
// closed form over the same span (shafts_tail_from: exponential integrals, another derivation), where the
// two integrands are the same: an isotropic phase (g = 0; the closed form freezes the phase) and no
// profile. Finite and infinite spans, clear to turbid water and none (σ_t = 0); judged against the whole
// ray's in-scatter (the planes' part before it as well), since where the far field is far off in relative
// terms it is a vanishing part of the ray. Float against double.
TEST(UnderwaterLampsMath, FarFieldSamplesMatchTheClosedFormUnderAConstantPhase) {
  Case along = crossing();
  along.lamp = {0, -4.8, 0.5};
  along.axis = along.d;
  auto v = [](kd::real3 x) { return kf::real3{float(x.x), float(x.y), float(x.z)}; };
  for (const Case& base : {crossing(), along})
    for (const double t_end : {4.0, 12.0, double(INFINITY)})
      for (const double sigma_t : {0.0, 0.05, 0.8, 5.0}) {
        kd::UwLampSpan sp;
        if (!kd::uw_lamp_span(base.o, base.d, base.lamp, base.axis, cosDeg(80), 1e-3, std::isinf(t_end) ? 1e30 : t_end,
                              30, &sp) ||
            !sp.tail)
          continue;
        double samples = 0;
        for (int j = 0; j < UW_LAMP_TAIL_SAMPLES; ++j) {
          double t, x;
          samples += kd::uw_lamp_tail_weight(&sp, j, 0.0, base.o, base.d, base.lamp, &t, &x) * std::exp(-sigma_t * x);
        }
        double closed = kd::shafts_tail_from(sp.tp - sp.a, sp.a, sp.h, 1.0, sigma_t);
        if (!sp.infinite) closed -= kd::shafts_tail_from(sp.tb - sp.a, sp.a, sp.h, 1.0, sigma_t);
        closed /= 4 * M_PI;
        ASSERT_GT(closed, 0);
        double planes = 0;  // the same integrand over [ta, tp] (30 planes), for the whole ray's scale
        for (int i = 0; i < 30; ++i) {
          double s, c;
          const double t = sp.ta + (i + 0.5) * sp.dt;
          kd::uw_lamp_at(base.o, base.d, base.lamp, t, &s, &c);
          planes += kd::uw_lamp_plane_g(1.0, sigma_t, 0.0, s, t, c, 1e-3) * sp.dt;
        }
        const double whole = planes + closed;
        std::printf("t_end %g, sigma_t %g: the far field %.2e of the ray; its samples off by %.2e of it, %.2e of the ray\n",
                    t_end, sigma_t, closed / whole, samples / closed - 1, (samples - closed) / whole);
        EXPECT_NEAR(samples, closed, 5e-4 * whole) << t_end << " " << sigma_t;
        if (closed > 0.01 * whole) EXPECT_NEAR(samples, closed, 1e-3 * closed) << t_end << " " << sigma_t;
        if (sigma_t > 0) continue;  // the weights and path lengths do not depend on the water
        kf::UwLampSpan spf;
        ASSERT_TRUE(kf::uw_lamp_span(v(base.o), v(base.d), v(base.lamp), v(base.axis), float(cosDeg(80)), 1e-3f,
                                     std::isinf(t_end) ? 1e30f : float(t_end), 30, &spf));
        // Float's tan near π/2 (the infinite ray's last nodes) loses digits as 1/(π/2 - φ): those samples
        // are the farthest and weigh least.
        double worst_w = 0, worst_x = 0;
        for (int j = 0; j < UW_LAMP_TAIL_SAMPLES; ++j) {
          float tf, xf;
          double td, xd;
          const float wf = kf::uw_lamp_tail_weight(&spf, j, 0.9f, v(base.o), v(base.d), v(base.lamp), &tf, &xf);
          const double wd = kd::uw_lamp_tail_weight(&sp, j, 0.9, base.o, base.d, base.lamp, &td, &xd);
          worst_w = std::max(worst_w, std::fabs(wf / wd - 1));
          worst_x = std::max(worst_x, std::fabs(xf / xd - 1));
        }
        std::printf("  float against double: weights %.2e, path lengths %.2e\n", worst_w, worst_x);
        EXPECT_LT(worst_w, 1e-4);
        EXPECT_LT(worst_x, 1e-4);
      }
}

TEST(UnderwaterLampsMath, FloatMatchesDouble) {
  for (double g : {0.0, 0.9}) {
    Case c = crossing();
    c.g = g;
    const double d = planesD(c, 30, 6);
    EXPECT_NEAR(planesF(c, 30, 6), d, 1e-4 * d) << g;
  }
}

TEST(UnderwaterLampsMath, StiffCasesStayFiniteAndNonNegative) {
  // A cone of 0.1°: the beam is 7 mm wide where the ray crosses it; the planes fall inside it.
  Case narrow = crossing();
  narrow.cone_deg = 0.1;
  narrow.falloff_deg = 0.0;
  narrow.axis = kd::normalize(kd::real3{-1, 0, 1});  // through (0, -5, -2), on the ray's path below it
  narrow.d = kd::normalize(kd::real3{0, 0, -1});
  const double ref = bruteForce(narrow, 1e-3, 4000000);
  const double fast = planesD(narrow, 30, 6);
  ASSERT_GT(ref, 0);
  EXPECT_NEAR(fast, ref, 0.02 * ref);
  EXPECT_TRUE(std::isfinite(planesF(narrow, 30, 6)));
  // Turbid water (9C at 400 nm: c ≈ 3.5/m) and c = 100/m: exponentials underflow to 0, never NaN.
  for (double st : {3.5, 100.0}) {
    Case turbid = crossing();
    turbid.sigma_t = st;
    turbid.sigma_s = 0.8 * st;
    const double v = planesD(turbid, 30, 6);
    const float vf = planesF(turbid, 30, 6);
    EXPECT_TRUE(std::isfinite(v) && v >= 0) << st;
    EXPECT_TRUE(std::isfinite(vf) && vf >= 0) << st;
    if (st < 10) EXPECT_NEAR(v, bruteForce(turbid, 1e-3, 400000), 0.05 * v);
  }
  // A ray through the lamp (s -> 0 on the ray): 1/s² is clamped at the lamp radius.
  Case through = crossing();
  through.lamp = {0, -5, -3};
  through.axis = {0, 0, 1};  // shining back at the camera
  EXPECT_TRUE(std::isfinite(planesF(through, 30, 6)));
  EXPECT_GT(planesD(through, 30, 6), 0);
  // Henyey–Greenstein with g -> 1 (the forward spike) and g = -0.99.
  for (double g : {0.999, -0.99}) {
    Case spike = crossing();
    spike.g = g;
    EXPECT_TRUE(std::isfinite(planesF(spike, 30, 6))) << g;
    EXPECT_GE(planesD(spike, 30, 6), 0) << g;
  }
  // No scattering: nothing.
  Case clear = crossing();
  clear.sigma_s = 0;
  EXPECT_EQ(planesD(clear, 30, 6), 0.0);
}

TEST(UnderwaterLampsMath, DirectLightOnASurface) {
  // A floor point 2 m below the lamp, on its axis: cos = 1, P = 1, e^{-c (s + S)} / (π s²).
  const kd::real3 lamp{0, -3, 0}, axis{0, -1, 0}, p{0, -5, 0}, n{0, 1, 0};
  const double c = 0.4, S = 3;
  const double v = kd::uw_lamp_surface(p, n, S, lamp, axis, cosDeg(20), cosDeg(15), 1e-3, c, 1.0);
  EXPECT_NEAR(v, std::exp(-c * (2 + S)) / (M_PI * 4), 1e-15);
  EXPECT_EQ(kd::uw_lamp_surface(p, n, S, lamp, axis, cosDeg(20), cosDeg(15), 1e-3, c, 0.0), 0.0);  // shadowed
  EXPECT_EQ(kd::uw_lamp_surface(p, kd::real3{0, -1, 0}, S, lamp, axis, cosDeg(20), cosDeg(15), 1e-3, c, 1.0), 0.0);
  // Outside the cone: dark.
  EXPECT_EQ(kd::uw_lamp_surface(kd::real3{3, -5, 0}, n, S, lamp, axis, cosDeg(20), cosDeg(15), 1e-3, c, 1.0), 0.0);
  // The lamp on the surface (s = 0): finite.
  EXPECT_TRUE(std::isfinite(kf::uw_lamp_surface(kf::real3{0, -3, 0}, kf::real3{0, 1, 0}, 3.0f, kf::real3{0, -3, 0},
                                                kf::real3{0, -1, 0}, 0.9f, 0.95f, 1e-3f, 0.4f, 1.0f)));
}

TEST(UnderwaterLampsMath, DeltaMScalingOfTheWater) {
  UwParams p{};
  std::vector<UwBand> bands(2);
  bands[0].a = 0.1f, bands[0].b = 0.5f, bands[0].c = 0.6f;
  bands[1].a = 0.3f, bands[1].b = 0.0f, bands[1].c = 0.3f;
  p.g = 0.9f;
  seasim::deltaMScale(p, bands);
  EXPECT_NEAR(bands[0].b, 0.5 * 0.19, 1e-6);
  EXPECT_NEAR(bands[0].c, 0.1 + 0.5 * 0.19, 1e-6);
  EXPECT_NEAR(bands[1].c, 0.3, 1e-7);  // nothing to scale
  EXPECT_NEAR(p.g, 0.9 / 1.9, 1e-6);   // g' = (g - g²)/(1 - g²)
  // No forward peak (g <= 0): unchanged; g -> 1: finite.
  for (float g : {0.0f, -0.5f}) {
    UwParams q{};
    q.g = g;
    std::vector<UwBand> b(1);
    b[0].a = 0.1f, b[0].b = 0.5f, b[0].c = 0.6f;
    seasim::deltaMScale(q, b);
    EXPECT_EQ(b[0].b, 0.5f);
    EXPECT_EQ(q.g, g);
  }
  UwParams one{};
  one.g = 1.0f;
  std::vector<UwBand> b(1);
  b[0].a = 0.1f, b[0].b = 0.5f, b[0].c = 0.6f;
  seasim::deltaMScale(one, b);
  EXPECT_FLOAT_EQ(one.g, 0.5f);  // g/(1 + g): no 0/0 at g = 1
  EXPECT_EQ(b[0].b, 0.0f);       // all of the light in the forward peak: none scattered
  EXPECT_FLOAT_EQ(b[0].c, 0.1f);
}
