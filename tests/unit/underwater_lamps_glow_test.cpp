// underwater_lamps_glow_test.cpp — the bottom's glow under a spotlight in the "orders" model
// (kernels/common/underwater_lamps_ms.h "The bottom's glow", host/underwater/lamps_bottom_glow.h): the
// lit patch's strength, centre and radius against closed forms in clear water, its strength against an
// independent area integral in scattering water, no glow without a bottom, the glow's phase function
// without its forward peak, and the glow along a view ray and on a surface in float and double, finite
// at its stiff points (a ray through the centre, σ_s -> 0, G -> 1); the lit bottom blurred on its way to
// the eye (T_view's terms against the Poisson law, the blur between its limits).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "math/kernel_math.h"
#include "underwater/lamps_bottom_glow.h"
#include "underwater/lamps_ms_table.h"

namespace {

namespace kd = seasim::kmath_d;
namespace kf = seasim::kmath_f;

double cosDeg(double deg) { return std::cos(deg * M_PI / 180); }

UwLamp lampAt(double x, double y, double z, kd::real3 dir, double cone_deg) {
  UwLamp L{};
  L.position[0] = float(x);
  L.position[1] = float(y);
  L.position[2] = float(z);
  const kd::real3 d = kd::normalize(dir);
  L.direction[0] = float(d.x);
  L.direction[1] = float(d.y);
  L.direction[2] = float(d.z);
  L.cos_cone = float(cosDeg(cone_deg));
  L.cos_inner = L.cos_cone;
  return L;
}

UwBand band(double a, double b, double albedo) {
  UwBand B{};
  B.a = float(a);
  B.b = float(b);
  B.c = float(a + b);
  B.bottom_albedo = float(albedo);
  return B;
}

UwParams bottomAt(double depth, double g) {
  UwParams p{};
  p.bottom_depth = float(depth);
  p.g = float(g);
  return p;
}

TEST(UnderwaterLampsGlow, ClearWaterPatchAgainstClosedForms) {
  // A lamp straight down, a hard cone θc, h above the bottom, no scattering, absorption a: the patch's
  // strength is ρ/π ∫_cone e^{-a h / cos θ} dω; without absorption ρ 2 (1 - cos θc), its centre the foot
  // point and its RMS radius² h² (1/cos θc + cos θc - 2)/(1 - cos θc) (E ∝ cos³θ, r = h tan θ).
  for (double cone : {10.0, 30.0, 60.0})
    for (double h : {1.0, 4.0}) {
      const UwLamp L = lampAt(0.3, -2.0, -1.0, {0.0, -1.0, 0.0}, cone);
      const std::vector<UwBand> bands = {band(0.0, 0.0, 0.5), band(0.2, 0.0, 0.25)};
      // The centre and radius from the clear band alone (the absorbing one weights the patch otherwise).
      const std::vector<float> g = seasim::lampBottomGlow(L, bottomAt(2.0 + h, 0.9), {bands[0]}, 0.02);
      const std::vector<float> both = seasim::lampBottomGlow(L, bottomAt(2.0 + h, 0.9), bands, 0.02);
      ASSERT_EQ(both.size(), size_t(seasim::lampGlowStride(2)));
      const double c = cosDeg(cone);
      EXPECT_NEAR(g[0], 0.3, 1e-4);
      EXPECT_NEAR(g[1], -(2.0 + h), 1e-6);
      EXPECT_NEAR(g[2], -1.0, 1e-4);
      EXPECT_NEAR(g[3], h * std::sqrt((1.0 / c + c - 2.0) / (1.0 - c)), 1e-3 * h) << "cone " << cone;
      EXPECT_NEAR(both[4], 0.5 * 2.0 * (1.0 - c), 1e-5) << "clear";
      // With absorption: ∫_c^1 e^{-a h/μ} dμ by Simpson's rule on 2000 intervals.
      double acc = 0.0;
      const int n = 2000;
      for (int k = 0; k <= n; ++k) {
        const double mu = c + (1.0 - c) * k / n;
        acc += (k == 0 || k == n ? 1 : (k % 2 ? 4 : 2)) * std::exp(-0.2 * h / mu);
      }
      acc *= (1.0 - c) / (3.0 * n);
      EXPECT_NEAR(both[5], 0.25 * 2.0 * acc, 2e-5 * 0.5) << "cone " << cone << " h " << h;
    }
}

TEST(UnderwaterLampsGlow, TiltedLampStrengthAndCentreAgainstACartesianAreaIntegral) {
  // A tilted soft-edged lamp in scattering water: the direct light summed on a plain Cartesian grid over
  // the bottom (another quadrature than the pass's over the lamp's solid angle) gives the same strength
  // within 0.5 % and the same centre within 2 cm.
  UwLamp L = lampAt(0.0, -3.0, 0.0, {0.3, -1.0, 0.2}, 25.0);
  L.cos_inner = float(cosDeg(18.0));
  const double depth = 5.0, s_min = 0.02;
  const UwBand B = band(0.1, 0.4, 0.5);
  const std::vector<float> g = seasim::lampBottomGlow(L, bottomAt(depth, 0.8), {B}, s_min);
  const kd::real3 lamp{L.position[0], L.position[1], L.position[2]}, axis{L.direction[0], L.direction[1], L.direction[2]};
  const kd::real3 up{0.0, 1.0, 0.0};
  double total = 0.0, mx = 0.0, mz = 0.0;
  const double half = 4.0, dx = 0.005;  // the 25° cone from 2 m lands within 2 m of the foot
  for (double x = -half + dx / 2; x < half; x += dx)
    for (double z = -half + dx / 2; z < half; z += dx) {
      const double e = dx * dx * B.bottom_albedo *
                       kd::uw_lamp_surface(kd::real3{x, -depth, z}, up, 0.0, lamp, axis, L.cos_cone, L.cos_inner, s_min, B.c, 1.0);
      total += e;
      mx += e * x;
      mz += e * z;
    }
  EXPECT_NEAR(g[4], total, 0.005 * total);
  EXPECT_NEAR(g[0], mx / total, 0.02);
  EXPECT_NEAR(g[2], mz / total, 0.02);
}

TEST(UnderwaterLampsGlow, NoGlowWithoutDirectLightOnTheBottom) {
  const UwLamp L = lampAt(0.0, -3.0, 0.0, {0.0, -1.0, 0.0}, 20.0);
  for (double depth : {0.0, -1.0, 2.0, 3.0}) {  // no bottom, deep water, the lamp under or on the bottom
    const std::vector<float> g = seasim::lampBottomGlow(L, bottomAt(depth, 0.9), {band(0.1, 0.3, 0.5)}, 0.02);
    EXPECT_EQ(g[3], 0.0f) << "depth " << depth;
    EXPECT_EQ(g[4], 0.0f) << "depth " << depth;
  }
  // A lamp pointing up lights the bottom only through its orders: the halo's, not the glow's.
  const UwLamp up = lampAt(0.0, -3.0, 0.0, {0.0, 1.0, 0.0}, 20.0);
  const std::vector<float> g = seasim::lampBottomGlow(up, bottomAt(5.0, 0.9), {band(0.1, 0.3, 0.5)}, 0.02);
  EXPECT_EQ(g[3], 0.0f);
  EXPECT_EQ(g[4], 0.0f);
}

TEST(UnderwaterLampsGlow, PhaseWithoutItsForwardPeak) {
  // ∫ 4π... over the sphere: 2π ∫ p dμ = 1 - G² (the peak's share G² left out), finite as G -> 1.
  for (double G : {0.0, 0.5, 0.9, 0.99, 1.0}) {
    double acc = 0.0;
    const int n = 20000;
    for (int k = 0; k < n; ++k) acc += 2.0 * M_PI * kd::uw_ms_glow_phase(-1.0 + (k + 0.5) * 2.0 / n, G) * 2.0 / n;
    EXPECT_NEAR(acc, 1.0 - G * G, 1e-4) << "G " << G;
    EXPECT_TRUE(std::isfinite(kf::uw_ms_glow_phase(1.0f, float(G))));
    EXPECT_NEAR(kf::uw_ms_glow_phase(0.3f, float(G)), kd::uw_ms_glow_phase(0.3, G), 1e-6);
  }
}

TEST(UnderwaterLampsGlow, AlongAViewRayFloatAgreesWithDoubleAndStiffPointsStayFinite) {
  const kd::real3 c{0.2, -6.0, -3.0}, up{0.0, 1.0, 0.0};
  const kd::real3 o{0.0, -3.0, 0.0};
  const kf::real3 cf{0.2f, -6.0f, -3.0f}, upf{0.0f, 1.0f, 0.0f}, of{0.0f, -3.0f, 0.0f};
  for (const kd::real3 aim : {kd::real3{0.2, -6.0, -3.0}, kd::real3{1.0, -6.0, -5.0}, kd::real3{0.0, -4.0, -8.0}}) {
    const kd::real3 d = kd::normalize(aim - o);
    const kf::real3 df{float(d.x), float(d.y), float(d.z)};
    const double t_end = 1e30;
    double first_d;
    float first_f;
    const double v = kd::uw_ms_glow_inscatter(o, d, c, up, 0.5, t_end, kd::uw_ms_ray_cap(0.4), 0.1, 0.3, 0.9, 8, 24, &first_d);
    const float vf = kf::uw_ms_glow_inscatter(of, df, cf, upf, 0.5f, 1e30f, kf::uw_ms_ray_cap(0.4f), 0.1f, 0.3f, 0.9f, 8,
                                              24, &first_f);
    EXPECT_TRUE(std::isfinite(vf));
    EXPECT_GE(v, first_d);
    EXPECT_GE(first_d, 0.0);
    EXPECT_NEAR(vf, v, 1e-4 * v + 1e-12);
    EXPECT_NEAR(first_f, first_d, 1e-4 * first_d + 1e-12);
    // The quadrature converges: the kernel's 12 steps (uw_ms_glow_steps of the default lamps_ms_steps 12
    // and of 24) and 24 against 256; a ray aimed at the centre is the hardest.
    const double fine = kd::uw_ms_glow_inscatter(o, d, c, up, 0.5, t_end, kd::uw_ms_ray_cap(0.4), 0.1, 0.3, 0.9, 8, 256, nullptr);
    const double coarse = kd::uw_ms_glow_inscatter(o, d, c, up, 0.5, t_end, kd::uw_ms_ray_cap(0.4), 0.1, 0.3, 0.9, 8,
                                                   kd::uw_ms_glow_steps(12), nullptr);
    EXPECT_EQ(kd::uw_ms_glow_steps(12), 12);
    EXPECT_EQ(kd::uw_ms_glow_steps(24), 12);
    EXPECT_EQ(kd::uw_ms_glow_steps(64), 32);
    EXPECT_EQ(kd::uw_ms_glow_steps(4), 4);
    std::printf("glow along a ray: 12 steps %.4f, 24 steps %.4f of 256\n", coarse / fine, v / fine);
    EXPECT_NEAR(v, fine, 0.02 * fine);
    EXPECT_NEAR(coarse, fine, 0.025 * fine);
  }
  // No scattering: no glow in the water; a ray ending before it starts; the radius at its floor.
  const kd::real3 d = kd::normalize(kd::real3{0.2, -3.0, -3.0});
  EXPECT_EQ(kd::uw_ms_glow_inscatter(o, d, c, up, 0.5, 1e30, 100.0, 0.1, 0.0, 0.9, 8, 24, nullptr), 0.0);
  EXPECT_EQ(kd::uw_ms_glow_inscatter(o, d, c, up, 0.5, 0.0, 100.0, 0.1, 0.3, 0.9, 8, 24, nullptr), 0.0);
  EXPECT_TRUE(std::isfinite(kf::uw_ms_glow_inscatter(of, kf::real3{0.0f, -1.0f, 0.0f}, kf::real3{0.0f, -6.0f, 0.0f}, upf, 1e-3f,
                                                     3.0f, 100.0f, 0.1f, 0.3f, 1.0f, 12, 64, nullptr)));
}

TEST(UnderwaterLampsGlow, OnASurfaceItsUnscatteredPartIsTheSoftenedLambertianSource) {
  // σ_s = 0: J cos ψ cos θ_i e^{-σ_a s} / (π (s² + R²)) exactly; below the bottom's plane nothing; with
  // scattering the orders add light.
  const kd::real3 c{0.0, -5.0, 0.0}, up{0.0, 1.0, 0.0};
  const kd::real3 p{1.0, -3.0, 0.5}, n = kd::normalize(kd::real3{-0.2, -1.0, 0.1});
  const kd::real3 w = p - c;
  const double s = kd::length(w), R = 0.7;
  const double expect = (kd::dot(w, up) / s) * (-kd::dot(w, n) / s) * std::exp(-0.1 * s) / (M_PI * (s * s + R * R));
  const std::vector<float> rows = seasim::lampMsProfiles(std::cos(20 * M_PI / 180), std::cos(20 * M_PI / 180), 0.9, 0.6, 8);
  double first;
  EXPECT_NEAR(kd::uw_ms_glow_surface(p, n, c, up, R, 0.1, 0.0, rows.data(), 8, &first), expect, 1e-12);
  EXPECT_NEAR(first, expect, 1e-12);
  EXPECT_GT(kd::uw_ms_glow_surface(p, n, c, up, R, 0.1, 0.3, rows.data(), 8, nullptr), 0.0);
  EXPECT_EQ(kd::uw_ms_glow_surface(kd::real3{1.0, -5.0, 0.0}, up, c, up, R, 0.1, 0.3, rows.data(), 8, nullptr), 0.0);
  EXPECT_EQ(kd::uw_ms_glow_surface(c, up, c, up, R, 0.1, 0.3, rows.data(), 8, nullptr), 0.0);
  EXPECT_NEAR(kf::uw_ms_glow_surface(kf::real3{1.0f, -3.0f, 0.5f}, kf::real3{float(n.x), float(n.y), float(n.z)},
                                     kf::real3{0.0f, -5.0f, 0.0f}, kf::real3{0.0f, 1.0f, 0.0f}, 0.7f, 0.1f, 0.3f, rows.data(), 8,
                                     nullptr),
              kd::uw_ms_glow_surface(p, n, c, up, R, 0.1, 0.3, rows.data(), 8, nullptr), 1e-5 * expect * 10);
}

}  // namespace

namespace {

TEST(UnderwaterLampsBlur, ViewTermsAreThePoissonOrdersSeenForward) {
  // Each term against the Poisson law summed directly (k < last: Pois(k; σ_s S) e^{-σ_a S} F(g^k); the
  // last: the tail from 400 direct terms), and the returned sum is theirs.
  for (double S : {0.0, 0.5, 3.0, 20.0})
    for (double g : {0.0, 0.5, 0.9, 1.0})
      for (int last : {1, 4, 8}) {
        const double a = 0.1, b = 0.4, x = b * S;
        double terms[UW_MS_MAX_ORDERS + 1];
        const double T = kd::uw_ms_view_terms(a, b, g, S, last, terms);
        double sum = 0.0, pois = std::exp(-x), tail = 0.0;
        for (int k = 0; k < 400; ++k) {
          if (k >= last) tail += pois;
          else
            EXPECT_NEAR(terms[k], std::exp(-a * S) * pois * (k == 0 ? 1.0 : kd::uw_ms_forward_share(std::pow(g, k))), 1e-13)
                << "S " << S << " g " << g << " k " << k;
          pois *= x / (k + 1);
        }
        EXPECT_NEAR(terms[last], last == 0 ? 0.0 : std::exp(-a * S) * tail * kd::uw_ms_forward_share(std::pow(g, last)),
                    1e-9 * std::exp(-a * S))
            << "S " << S << " g " << g << " last " << last;
        for (int k = 0; k <= last; ++k) sum += terms[k];
        EXPECT_NEAR(T, sum, 1e-14);
        EXPECT_EQ(T, kd::uw_ms_view_transmission(a, b, g, S, last));
      }
}

TEST(UnderwaterLampsBlur, ViewTermsInBandLanesAreTheScalarOnes) {
  // underwater_lamps.cl takes T_view's terms for its bands in lanes (uw_ms_view_terms_b, one lane here): the same
  // terms in the same order as uw_ms_view_terms, on both branches of the Poisson tail (x = σ_s S below and above
  // last + 1, and at it), without scattering (x = 0), and in float and double.
  for (double S : {0.0, 0.5, 3.0, 4.999, 5.0, 20.0, 200.0})
    for (double g : {0.0, 0.5, 0.9, 1.0})
      for (int last : {1, 4, 8})
        for (double b : {0.0, 1.0, 0.4}) {
          const double a = 0.1;
          double terms[UW_MS_MAX_ORDERS + 1], terms_b[UW_MS_MAX_ORDERS + 1];
          const double T = kd::uw_ms_view_terms(a, b, g, S, last, terms);
          EXPECT_EQ(kd::uw_ms_view_terms_b(a, b, g, S, last, terms_b), T)
              << "S " << S << " g " << g << " last " << last << " b " << b;
          for (int k = 0; k <= last; ++k) EXPECT_EQ(terms_b[k], terms[k]) << k;
          EXPECT_EQ(kd::uw_ms_poisson_at_least_b(last, b * S), kd::uw_ms_poisson_at_least(last, b * S));
          float terms_f[UW_MS_MAX_ORDERS + 1], terms_fb[UW_MS_MAX_ORDERS + 1];
          const float Tf = kf::uw_ms_view_terms(float(a), float(b), float(g), float(S), last, terms_f);
          EXPECT_EQ(kf::uw_ms_view_terms_b(float(a), float(b), float(g), float(S), last, terms_fb), Tf);
          for (int k = 0; k <= last; ++k) EXPECT_EQ(terms_fb[k], terms_f[k]) << k;
        }
}

TEST(UnderwaterLampsBlur, BlurredBottomBetweenItsLimits) {
  // A narrow spread (h -> 1) gives the light at the ray's end; under a lamp lighting the whole bottom
  // evenly near the ray's end a narrow spread keeps it within 5 %; a ray aimed up misses the bottom with
  // every narrow direction; float agrees with double; h = 0 (isotropic) stays finite.
  const UwLamp L = lampAt(0.0, -2.0, 0.0, {0.0, -1.0, 0.0}, 80.0);
  const kd::real3 lamp{0.0, -2.0, 0.0}, axis{0.0, -1.0, 0.0}, up{0.0, 1.0, 0.0};
  const kd::real3 o{0.5, -1.0, 0.3};
  const double depth = 5.0;
  const kd::real3 d = kd::normalize(kd::real3{0.6, -4.0, -0.5});
  const kd::real3 P = o + ((-depth - o.y) / d.y) * d;
  const double at_end = kd::uw_lamp_surface(P, up, 0.0, lamp, axis, L.cos_cone, L.cos_inner, 0.02, 0.0, 1.0);
  const kd::UwMsBlur sharp = kd::uw_ms_blurred_bottom(o, d, depth, lamp, axis, L.cos_cone, L.cos_inner, 0.02, 0.99999);
  EXPECT_NEAR(sharp.geometry, at_end, 1e-3 * at_end);
  EXPECT_NEAR(sharp.s_mean, kd::length(P - lamp), 1e-3);
  const kd::UwMsBlur wide = kd::uw_ms_blurred_bottom(o, d, depth, lamp, axis, L.cos_cone, L.cos_inner, 0.02, 0.99);
  EXPECT_NEAR(wide.geometry, at_end, 0.05 * at_end);
  const kd::UwMsBlur miss =
      kd::uw_ms_blurred_bottom(o, kd::real3{0.0, 1.0, 0.0}, depth, lamp, axis, L.cos_cone, L.cos_inner, 0.02, 0.999);
  EXPECT_EQ(miss.geometry, 0.0);
  const kf::UwMsBlur wide_f = kf::uw_ms_blurred_bottom(kf::real3{0.5f, -1.0f, 0.3f}, kf::real3{float(d.x), float(d.y), float(d.z)},
                                                       5.0f, kf::real3{0.0f, -2.0f, 0.0f}, kf::real3{0.0f, -1.0f, 0.0f},
                                                       L.cos_cone, L.cos_inner, 0.02f, 0.99f);
  EXPECT_NEAR(wide_f.geometry, wide.geometry, 1e-4 * wide.geometry);
  const kf::UwMsBlur iso = kf::uw_ms_blurred_bottom(kf::real3{0.5f, -1.0f, 0.3f}, kf::real3{float(d.x), float(d.y), float(d.z)},
                                                    5.0f, kf::real3{0.0f, -2.0f, 0.0f}, kf::real3{0.0f, -1.0f, 0.0f},
                                                    L.cos_cone, L.cos_inner, 0.02f, 0.0f);
  EXPECT_TRUE(std::isfinite(iso.geometry) && std::isfinite(iso.s_mean));
  // Beside a hard-edged patch the blur brings light where the ray's end has none (the halo).
  const UwLamp narrow = lampAt(0.0, -2.0, 0.0, {0.0, -1.0, 0.0}, 10.0);
  const kd::real3 beside_d = kd::normalize(kd::real3{1.2, -4.0, 0.0} - o);  // ends 1.2 m from the axis, outside 10° at 3 m
  EXPECT_EQ(kd::uw_lamp_surface(o + ((-depth - o.y) / beside_d.y) * beside_d, up, 0.0, lamp, axis, narrow.cos_cone,
                                narrow.cos_inner, 0.02, 0.0, 1.0),
            0.0);
  EXPECT_GT(kd::uw_ms_blurred_bottom(o, beside_d, depth, lamp, axis, narrow.cos_cone, narrow.cos_inner, 0.02, 0.9).geometry,
            0.0);
}

}  // namespace
