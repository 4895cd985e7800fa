// shafts_math_test.cpp — the CPU side of the shafts model (paper 001): the closed-form airlight of
// Sun et al. 2005 against direct quadrature of the single-scattering integral it solves, F(u, v)
// at its limits, the shared math of kernels/common/shafts.h in float and double at the stiff
// points (s -> 0, ρκ large), the ray-object intersections, and the sampling-plane depth range.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "math/kernel_math.h"
#include "reference/shafts_reference.h"
#include "scene/scene_parser.h"
#include "util/error.h"

namespace {

namespace kd = seasim::kmath_d;
namespace kf = seasim::kmath_f;

// ∫_0^T σs I0/(4π) exp(-σt (x + d(x))) / d(x)² dx, d² = D² + x² - 2 D x cos γ, by composite
// Gauss–Legendre (5 points) on many panels, denser near the closest approach x = D cos γ.
double airlightByQuadrature(double ss, double st, double I0, double D, double gamma, double T) {
  const double xg[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831, 0.9061798459386640};
  const double wg[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665,
                        0.2369268850561891};
  auto f = [&](double x) {
    const double d2 = D * D + x * x - 2 * D * x * std::cos(gamma);
    return ss * I0 / (4 * M_PI) * std::exp(-st * (x + std::sqrt(d2))) / d2;
  };
  // Panels uniform in the angle seen from the light (the substitution that makes 1/d² smooth).
  const double h = D * std::sin(gamma), x0 = D * std::cos(gamma);
  const double a0 = std::atan((0 - x0) / h), a1 = std::atan((T - x0) / h);
  const int panels = 4000;
  double sum = 0;
  for (int p = 0; p < panels; ++p) {
    const double lo = a0 + (a1 - a0) * p / panels, hi = a0 + (a1 - a0) * (p + 1) / panels;
    for (int k = 0; k < 5; ++k) {
      const double a = 0.5 * (lo + hi) + 0.5 * (hi - lo) * xg[k];
      const double x = x0 + h * std::tan(a), dxda = h / (std::cos(a) * std::cos(a));
      sum += 0.5 * (hi - lo) * wg[k] * f(x) * dxda;
    }
  }
  return sum;
}

TEST(ShaftsAirlight, SunClosedFormMatchesQuadrature) {
  // Tolerance 1e-9 relative: both are double quadratures of smooth integrands.
  for (double st : {0.0, 0.02, 0.3, 2.0})
    for (double gamma : {0.05, 0.4, 1.2, 2.0, 3.0})
      for (double T : {0.5, 4.0, 30.0}) {
        const double D = 5.0, ss = 0.1, I0 = 50;
        const double closed = seasim::sunAirlight(ss, st, I0, D, gamma, T);
        const double quad = airlightByQuadrature(ss, st, I0, D, gamma, T);
        EXPECT_NEAR(closed, quad, 1e-9 * quad + 1e-300) << "st=" << st << " gamma=" << gamma << " T=" << T;
      }
}

TEST(ShaftsAirlight, FAtItsLimits) {
  EXPECT_DOUBLE_EQ(seasim::sunF(0.0, 1.0), 1.0);          // u = 0: ∫ dξ = v
  EXPECT_DOUBLE_EQ(seasim::sunF(3.0, 0.0), 0.0);
  EXPECT_NEAR(seasim::sunF(1.0, M_PI / 2), seasim::sunF(1.0, M_PI / 2 - 1e-12), 1e-9);  // integrable end
  EXPECT_LT(seasim::sunF(50.0, 1.0), 1.0 / 50 * 1.01);    // ≈ 1/u for large u
  EXPECT_GT(seasim::sunF(50.0, 1.0), 1.0 / 50 * 0.95);
}

TEST(ShaftsMath, HIsFiniteAtTheLampAndUnderExtremeExtinction) {
  // s -> 0: clamped at s_min, finite in float and double; ρκ (s + t) huge: exactly 0, not NaN.
  EXPECT_TRUE(std::isfinite(kf::shafts_h(0.0f, 1.0f, 1.0f, 0.05f, 1e-3f)));
  EXPECT_FLOAT_EQ(kf::shafts_h(0.0f, 0.0f, 1.0f, 0.0f, 1e-3f), 1e6f);
  EXPECT_EQ(kf::shafts_h(1.0f, 1e3f, 1.0f, 1e3f, 1e-3f), 0.0f);
  EXPECT_EQ(kd::shafts_h(1.0, 1e308, 1.0, 1e3, 1e-3), 0.0);
  EXPECT_DOUBLE_EQ(kd::shafts_h(2.0, 3.0, 0.5, 0.0, 1e-3), 0.5 / 4);  // ρκ = 0: no attenuation
  // h = ĥ / s², the table's smooth factor.
  EXPECT_NEAR(kd::shafts_h(2.0, 3.0, 0.5, 0.1, 1e-3), kd::shafts_h_scaled(2.0, 3.0, 0.5, 0.1) / 4, 1e-15);
}

TEST(ShaftsMath, ConeProfileIsAMonotoneSmoothEdge) {
  const double cone = 0.4, inner = 0.3;
  double prev = 1.0;
  for (int i = 0; i <= 100; ++i) {
    const double a = 0.5 * i / 100;
    const double p = kd::shafts_cone_profile(std::cos(a), std::cos(cone), std::cos(inner));
    EXPECT_LE(p, prev + 1e-15);
    EXPECT_GE(p, 0.0);
    EXPECT_LE(p, 1.0);
    if (a <= inner) EXPECT_EQ(p, 1.0);
    if (a >= cone) EXPECT_EQ(p, 0.0);
    prev = p;
  }
  // Zero falloff: a hard edge.
  EXPECT_EQ(kd::shafts_cone_profile(std::cos(0.39), std::cos(0.4), std::cos(0.4)), 1.0);
  EXPECT_EQ(kd::shafts_cone_profile(std::cos(0.41), std::cos(0.4), std::cos(0.4)), 0.0);
}

TEST(ShaftsMath, RayIntersections) {
  const kd::real3 o{0, 0, 0}, d{0, 0, -1};
  EXPECT_NEAR(kd::ray_sphere(o, d, kd::real3{0, 0, -5}, 1.0, 0.0, 1e30), 4.0, 1e-12);
  EXPECT_NEAR(kd::ray_sphere(kd::real3{0, 0, -5}, d, kd::real3{0, 0, -5}, 1.0, 0.0, 1e30), 1.0, 1e-12);  // inside
  EXPECT_LT(kd::ray_sphere(o, d, kd::real3{0, 3, -5}, 1.0, 0.0, 1e30), 0.0);
  EXPECT_LT(kd::ray_sphere(o, d, kd::real3{0, 0, -5}, 1.0, 0.0, 3.5), 0.0);  // beyond t_max
  int axis = -1;
  EXPECT_NEAR(kd::ray_box(o, d, kd::real3{-1, -1, -4}, kd::real3{1, 1, -2}, 0.0, 1e30, &axis), 2.0, 1e-12);
  EXPECT_EQ(axis, 2);
  const kd::real3 n = kd::box_normal(kd::real3{0, 0, -2}, kd::real3{-1, -1, -4}, kd::real3{1, 1, -2}, 2);
  EXPECT_EQ(n.z, 1.0);
  EXPECT_NEAR(kd::ray_plane(o, d, kd::real3{0, 0, -7}, kd::real3{0, 0, 1}, 0.0, 1e30), 7.0, 1e-12);
  EXPECT_LT(kd::ray_plane(o, kd::real3{1, 0, 0}, kd::real3{0, 0, -7}, kd::real3{0, 0, 1}, 0.0, 1e30), 0.0);  // parallel
}

TEST(ShaftsMath, IntervalsTileTheDepthRangeAndClipAtTheSurface) {
  double za = 0, zb = 0, covered = 0;
  for (int i = 0; i < 7; ++i) {
    if (!kd::shafts_interval(i, 7, 0.5, 10.0, 4.2, &za, &zb)) break;
    covered += zb - za;
  }
  EXPECT_NEAR(covered, 4.2 - 0.5, 1e-12);
  EXPECT_EQ(kd::shafts_interval(0, 7, 0.5, 10.0, 0.3, &za, &zb), 0);  // surface before the first plane
}

TEST(ShaftsRange, FarPlaneReachesTheBackWallOfSpotSphere) {
  const seasim::Scene scene = seasim::loadScene(std::string(SEASIM_SOURCE_DIR) + "/scenes/spot_sphere.toml");
  const seasim::ShaftsRange r = seasim::shaftsRange(scene);
  // Camera at z = 9 looking down -z at a wall at z = -6: the deepest visible surface is the wall (15 m).
  EXPECT_GT(r.z_far, 15.0);
  EXPECT_LT(r.z_far, 15.0 * 1.03);
  EXPECT_GT(r.t_max, r.z_far);
  EXPECT_GT(r.s_max, r.t_max);
}

// shaftsClipToCones: every point of every cone inside the frustum lies within the clipped depth range
// (conservative), and the range is not much wider than those points' extent (the 8-sided pyramid is
// 8 % wider than the cone in tan θ). Points sampled uniformly in each cone's solid angle and distance.
void expectConservativeAndTight(const seasim::Scene& scene, double max_widening) {
  const seasim::ShaftsRange full = seasim::shaftsRange(scene);
  const seasim::ShaftsRange r = seasim::shaftsClipToCones(scene, full);
  const seasim::CameraDesc& cam = scene.camera;
  const seasim::Vec3 fwd = seasim::normalize(cam.look_at - cam.position);
  const seasim::Vec3 right = seasim::normalize(seasim::cross(fwd, cam.up)), up = seasim::cross(right, fwd);
  const double ty = std::tan(cam.fov_y / 2), tx = ty * cam.width / cam.height;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  double lo = 1e30, hi = -1e30;
  long inside = 0;
  for (const auto& l : scene.spotlights) {
    seasim::Vec3 lr, lu;
    seasim::shaftsLightBasis(l, lr, lu);
    const seasim::Vec3 a = seasim::normalize(l.direction);
    for (int i = 0; i < 200000; ++i) {
      const double cos_t = 1 - u01(rng) * (1 - std::cos(l.cone)), sin_t = std::sqrt(1 - cos_t * cos_t);
      const double phi = 2 * M_PI * u01(rng), dist = 40 * u01(rng);
      const seasim::Vec3 d = a * cos_t + lr * (sin_t * std::cos(phi)) + lu * (sin_t * std::sin(phi));
      const seasim::Vec3 q = l.position + d * dist - cam.position;
      const double z = seasim::dot(q, fwd);
      if (z < full.z_near || z > full.z_far || std::fabs(seasim::dot(q, right)) > tx * z ||
          std::fabs(seasim::dot(q, up)) > ty * z)
        continue;
      ++inside;
      lo = std::min(lo, z);
      hi = std::max(hi, z);
      ASSERT_GE(z, r.z_near - 1e-9);
      ASSERT_LE(z, r.z_far + 1e-9);
    }
  }
  ASSERT_GT(inside, 500);
  std::printf("[ measured ] %s: planes over [%.3f, %.3f] m (unclipped [%.3f, %.3f]); cone points seen over "
              "[%.3f, %.3f] m\n",
              scene.name.c_str(), r.z_near, r.z_far, full.z_near, full.z_far, lo, hi);
  EXPECT_LE(r.z_far - r.z_near, max_widening * (hi - lo));
  EXPECT_TRUE(std::isfinite(r.t_max) && r.t_max >= r.z_far && r.s_max >= r.t_max);
}

TEST(ShaftsRange, ClipToConesIsConservativeAndTight) {
  const std::string dir = std::string(SEASIM_SOURCE_DIR) + "/scenes/";
  expectConservativeAndTight(seasim::loadScene(dir + "spot_sphere.toml"), 1.1);
  expectConservativeAndTight(seasim::loadScene(dir + "stage.toml"), 1.1);
}

TEST(ShaftsRange, ClipToConesKeepsTheNearPlaneWithTheCameraInsideACone) {
  const seasim::Scene scene = seasim::loadScene(
      std::string(SEASIM_SOURCE_DIR) + "/scenes/spot_sphere.toml",
      {{"camera.position", "[0.3, 1.0, -1.5]", {"test", 1}}, {"camera.look_at", "[0, 0, -4]", {"test", 1}}});
  const seasim::ShaftsRange full = seasim::shaftsRange(scene);
  const seasim::ShaftsRange r = seasim::shaftsClipToCones(scene, full);
  EXPECT_NEAR(r.z_near, full.z_near, 1e-9);  // the frustum's near plane is the cone-polytope's vertex
  EXPECT_GT(r.z_far, r.z_near);
  EXPECT_LE(r.z_far, full.z_far);
  // Few samples reach the corner of the frustum next to the eye (757 of 200000): the seen extent
  // underestimates the true one there, hence the looser bound.
  expectConservativeAndTight(scene, 1.25);
}

TEST(ShaftsRange, HeightFieldObjectsWithSpotlightsAreAnErrorNamingFileLineAndKey) {
  const seasim::Scene scene = seasim::parseScene(R"([air]
density = 0.04
[[spotlights]]
position = [0, 5, -1]
[[objects]]
type = "sphere"
[[objects]]
type = "heightfield"
heightfield = "textures/polka_dot.png"
)",
                                                 std::string(SEASIM_SOURCE_DIR) + "/scenes/hf_spot.toml");
  for (int which = 0; which < 2; ++which) {
    try {
      if (which == 0) (void)seasim::shaftsRange(scene);
      else (void)seasim::renderShaftsReference(scene, 4);
      ADD_FAILURE() << "no error";
    } catch (const seasim::InputError& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find("hf_spot.toml:7: key 'objects[1].type': \"heightfield\" objects are not supported"),
                std::string::npos)
          << m;
    }
  }
}

}  // namespace
