// shafts_render_test.cpp — shafts.cl's per-pixel terms (kernels/common/shafts_render.h) in float and
// double: the first hit of the analytic objects, the lamp's cone emission, the shadow term, the F
// table, and one lamp's I_s over sampling planes with exact g against a fine midpoint sum of 001 eq. 2
// along the same ray (no objects: H = 1). tests/kernels/shafts_test.cpp runs the kernel against the
// double CPU reference.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "math/kernel_math.h"

namespace {

namespace kd = seasim::kmath_d;
namespace kf = seasim::kmath_f;

ShaftsLight downLamp() {
  ShaftsLight L{};
  L.position[1] = 4.0f;  // 4 m up, pointing down, 30° cone, no inner cone
  L.direction[1] = -1.0f;
  L.right[0] = 1.0f;
  L.up[2] = 1.0f;
  L.color[0] = L.color[1] = L.color[2] = 10.0f;
  L.cos_cone = static_cast<float>(std::cos(30.0 * M_PI / 180.0));
  L.cos_inner = L.cos_cone;
  L.tan_cone = static_cast<float>(std::tan(30.0 * M_PI / 180.0));
  L.light_map_offset = -1;
  return L;
}

ShaftsParams airParams() {
  ShaftsParams p{};
  p.light_count = 1;
  p.rho = 0.05f;
  p.sigma_t = 0.08f;
  p.s_min = 0.01f;
  p.planes = 400;
  p.subplanes = 2;
  return p;
}

TEST(ShaftsRender, SceneHitFindsTheNearestObjectAndFacesTheNormal) {
  std::vector<ShaftsObject> objects(2);
  objects[0].type = SHAFTS_SPHERE;  // sphere of radius 1 at z = 5
  objects[0].a[2] = 5.0f;
  objects[0].a[3] = 1.0f;
  objects[1].type = SHAFTS_PLANE;  // plane z = 10 facing +z (away from the ray)
  objects[1].a[2] = 10.0f;
  objects[1].b[2] = 1.0f;
  kd::real3 n{};
  int which = -2;
  const double t = kd::shafts_scene_hit(objects.data(), 2, kd::real3{0, 0, 0}, kd::real3{0, 0, 1}, 0.0, 1e30, &n, &which);
  EXPECT_NEAR(t, 4.0, 1e-12);
  EXPECT_EQ(which, 0);
  EXPECT_NEAR(n.z, -1.0, 1e-12);
  // Missing the sphere, the plane is hit from behind: its normal is turned towards the ray.
  const double t2 = kd::shafts_scene_hit(objects.data(), 2, kd::real3{3, 0, 0}, kd::real3{0, 0, 1}, 0.0, 1e30, &n, &which);
  EXPECT_NEAR(t2, 10.0, 1e-12);
  EXPECT_EQ(which, 1);
  EXPECT_NEAR(n.z, -1.0, 1e-12);
  EXPECT_EQ(kd::shafts_scene_hit(objects.data(), 2, kd::real3{3, 0, 0}, kd::real3{0, 0, -1}, 0.0, 1e30, nullptr, nullptr),
            -1.0);
}

TEST(ShaftsRender, EmissionIsTheColourInsideTheConeAndZeroOutside) {
  const ShaftsLight L = downLamp();
  const kd::real3 inside = kd::shafts_to_light(&L, kd::real3{0.5, 0.0, 0.0});
  EXPECT_NEAR(inside.z, 4.0, 1e-12);
  const kd::real3 e = kd::shafts_lamp_emission(0, &L, nullptr, inside, std::sqrt(16.25));
  EXPECT_NEAR(e.x, 10.0, 1e-9);
  const kd::real3 outside = kd::shafts_to_light(&L, kd::real3{4.0, 0.0, 0.0});
  EXPECT_EQ(kd::shafts_lamp_emission(0, &L, nullptr, outside, std::sqrt(32.0)).x, 0.0);
  EXPECT_EQ(kd::shafts_lamp_emission(0, &L, nullptr, kd::real3{0, 0, 0}, 0.0).x, 0.0);  // at the lamp
  EXPECT_EQ(kd::shafts_shadow_term(0, &L, nullptr, 8, inside, 4.0), 1.0);               // no objects: lit
}

TEST(ShaftsRender, PhaseTableInterpolatesLinearlyOverTheAngle) {
  const std::vector<float> F = {1.0f, 3.0f, 5.0f};  // F(α) = 1 + 4 α / π
  EXPECT_NEAR(kd::shafts_phase_table(F.data(), 3, 1.0), 1.0, 1e-12);
  EXPECT_NEAR(kd::shafts_phase_table(F.data(), 3, 0.0), 3.0, 1e-12);
  EXPECT_NEAR(kd::shafts_phase_table(F.data(), 3, -1.0), 5.0, 1e-12);
  EXPECT_NEAR(kf::shafts_phase_table(F.data(), 3, 0.5f), 1.0 + 4.0 / 3.0, 2e-6);
}

template <typename Real3, typename Lamp>
double planesAirlight(const ShaftsParams& p, const Lamp& L, Real3 eye, Real3 d, bool use_float) {
  if (use_float)
    return kf::shafts_lamp_planes(0, 0, 1, 0, &p, &L, nullptr, nullptr, nullptr, nullptr,
                                  kf::real3{float(eye.x), float(eye.y), float(eye.z)},
                                  kf::real3{float(d.x), float(d.y), float(d.z)}, 1e30f)
        .x;
  return kd::shafts_lamp_planes(0, 0, 1, 0, &p, &L, nullptr, nullptr, nullptr, nullptr, eye, d, 1e30).x;
}

TEST(ShaftsRender, PlanesAirlightMatchesAFineSumOfEq2) {
  const ShaftsParams p = airParams();
  const ShaftsLight L = downLamp();
  const kd::real3 eye{-6.0, 1.0, 0.0}, d{1.0, 0.0, 0.0};  // a horizontal ray through the cone, 3 m below the lamp
  // 001 eq. 2 with H = 1: ∫ I_l F(α) ρ exp(-σ (s + t)) / s² dt over the lit stretch, midpoint rule.
  double expected = 0.0;
  const int steps = 200000;
  const double t0 = 0.0, t1 = 12.0, dt = (t1 - t0) / steps;
  for (int i = 0; i < steps; ++i) {
    const double t = t0 + (i + 0.5) * dt;
    const kd::real3 P{eye.x + t * d.x, eye.y, eye.z};
    const kd::real3 w{P.x - 0.0, P.y - 4.0, P.z - 0.0};
    const double s = std::sqrt(w.x * w.x + w.y * w.y + w.z * w.z);
    const double e = kd::shafts_lamp_emission(0, &L, nullptr, kd::shafts_to_light(&L, P), s).x;
    if (e <= 0.0) continue;
    const double cos_alpha = -(w.x * d.x) / s;
    expected += e * kd::shafts_phase_fn(cos_alpha, 0, 0.0) * kd::shafts_h(s, t, p.rho, p.sigma_t, p.s_min) * dt;
  }
  ASSERT_GT(expected, 0.0);
  EXPECT_NEAR(planesAirlight(p, L, eye, d, false), expected, 2e-3 * expected);
  EXPECT_NEAR(planesAirlight(p, L, eye, d, true), expected, 2e-3 * expected);
}

}  // namespace
