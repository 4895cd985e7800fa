// underwater_ordinates_surface_test.cpp — the water surface seen from below in underwater.model =
// "discrete_ordinates" (kernels/common/underwater_ordinates.h uwi_surface): the froxel pass integrates the
// beam's single scattering along the camera's ray only, so the surface's reflected ray keeps its own
// (the TMS term) whether or not that pass runs. Turning the froxel term on must change a surface
// pixel by exactly the camera ray's closed-form single scattering, in float and double, inside Snell's
// window and under total internal reflection (where the reflected ray is the whole surface term); and an
// object in the mirror (uwi_mirror_hit) ends the reflected ray and is lit there.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "math/kernel_math.h"
#include "underwater/underwater_ordinates_setup.h"

#include "underwater_ordinates_fixtures.h"

namespace {

namespace kd = seasim::kmath_d;
namespace kf = seasim::kmath_f;

UwBand band(double a, double b, double mu_w) {
  UwBand o = seasim::testing::uwTestBand(a, b, 0.3, 1.0, mu_w, 0.35);
  o.sky_radiance = 0.05f;
  return o;
}

template <class M, class Real>
Real surfacePixel(const UwiBand& ib, const UwBand& bd, Real g, Real H, Real d_y, Real o_d, Real mu_w, int froxels) {
  using V = typename M::real3;
  const Real dx = std::sqrt(Real(1) - d_y * d_y);
  const V d{Real(0), d_y, -dx};
  const V s_w{Real(0.3) * std::sqrt(Real(1) - mu_w * mu_w), mu_w, Real(-0.95) * std::sqrt(Real(1) - mu_w * mu_w)};
  const Real S = o_d / d_y;
  return M::uwi_band_radiance(&ib, &bd, g, UW_MAT_SURFACE, S, V{0, -1, 0}, d, o_d, s_w, Real(0), Real(1),
                              Real(bd.sky_radiance), Real(1.34), H, froxels, 1);
}

struct Kd {
  using real3 = kd::real3;
  static double uwi_band_radiance(const UwiBand* ib, const UwBand* b, double g, int mat, double S, real3 n, real3 d,
                                  double o_d, real3 s_w, double albedo, double vis, double sky, double ior, double H,
                                  int ss, int ms) {
    return kd::uwi_band_radiance(ib, b, g, mat, S, n, d, o_d, s_w, albedo, vis, 1.0, sky, ior, H, ss, ms,
                                 kd::uwi_no_mirror_object());
  }
};
struct Kf {
  using real3 = kf::real3;
  static float uwi_band_radiance(const UwiBand* ib, const UwBand* b, float g, int mat, float S, real3 n, real3 d,
                                 float o_d, real3 s_w, float albedo, float vis, float sky, float ior, float H, int ss,
                                 int ms) {
    return kf::uwi_band_radiance(ib, b, g, mat, S, n, d, o_d, s_w, albedo, vis, 1.0f, sky, ior, H, ss, ms,
                                 kf::uwi_no_mirror_object());
  }
};

TEST(UnderwaterOrdinatesSurface, FroxelTermChangesOnlyTheCameraRaysSingleScattering) {
  const double mu_w = 0.93, o_d = 0.8;
  int tir = 0, window = 0, clamped = 0;
  for (double g : {0.0, 0.5, 0.9})
    for (auto [a, b] : {std::pair{0.03, 0.05}, std::pair{0.1, 0.3}})
      for (double H : {0.0, 2.0, 20.0})
        for (double d_y : {0.05, 0.3, 0.6, 0.9}) {
          const UwBand bd = band(a, b, mu_w);
          // The camera's depth given: the forward peak's aureole there holds the strict single
          // scattering's peak part, which the froxel term takes off with the rest.
          seasim::DiffuseDepth camera;
          camera.depth = o_d;
          const UwiBand ib = seasim::makeUwiBand(bd, g, mu_w, H, 1.34, seasim::diffuseMeanCosines(g),
                                                 seasim::twoStreamClosure(), camera);
          const double on = surfacePixel<Kd>(ib, bd, g, H, d_y, o_d, mu_w, 1);
          const double off = surfacePixel<Kd>(ib, bd, g, H, d_y, o_d, mu_w, 0);
          // The camera ray's strict single scattering, as uwi_multiple takes it off.
          const double dx = std::sqrt(1 - d_y * d_y);
          const double cos_s = d_y * mu_w - dx * (-0.95) * std::sqrt(1 - mu_w * mu_w);
          const double ss = double(bd.b) * kd::hg_phase(cos_s, g) * bd.e_beam0 *
                            kd::kd_exp_integral(bd.c / mu_w, bd.c, d_y, o_d, o_d / d_y);
          const kd::real3 d{0, d_y, -dx}, s_w{0.3 * std::sqrt(1 - mu_w * mu_w), mu_w, -0.95 * std::sqrt(1 - mu_w * mu_w)};
          ASSERT_NEAR(kd::dot(d, s_w), cos_s, 1e-12);
          // Where the in-scatter without it is below it (near the sun, the small-angle aureole's once-scattered
          // light is a little under the strict integral), the sum is clamped at 0: that much is taken off.
          const double inscatter = kd::uwi_multiple(&ib, &bd, g, H, o_d / d_y, d_y, o_d, cos_s, mu_w, 0, 1) +
                                   kd::uwi_forward_peak(&ib, &bd, g, o_d / d_y, d_y, o_d, 0.0, cos_s, mu_w, 0);
          ASSERT_GT(inscatter, 0.0);
          if (inscatter < ss) ++clamped;
          EXPECT_NEAR(off - on, std::min(ss, inscatter), 1e-12 + 1e-9 * off) << g << " " << a << " " << H << " " << d_y;
          const float on_f = surfacePixel<Kf>(ib, bd, float(g), float(H), float(d_y), float(o_d), float(mu_w), 1);
          const float off_f = surfacePixel<Kf>(ib, bd, float(g), float(H), float(d_y), float(o_d), float(mu_w), 0);
          EXPECT_NEAR(off_f - on_f, std::min(ss, inscatter), 2e-5 * off) << "float";
          (kd::fresnel_reflectance(d_y, 1.34, 1.0) == 1.0 ? tir : window)++;
        }
  EXPECT_GT(tir, 0);
  EXPECT_GT(window, 0);
  EXPECT_LE(clamped, 4) << "the in-scatter clamped at 0 in more than a few rays near the sun";
  std::printf("froxel term: %d of 72 rays clamped at 0\n", clamped);
}

TEST(UnderwaterOrdinatesSurface, ReflectedRayKeepsTheBeamsSingleScatteringUnderTotalInternalReflection) {
  // g = 0: delta-M leaves the beam as it is (m = c/μ_w), so the reflected ray's TMS term is exactly the
  // strict single scattering along it; under total internal reflection the surface term without the
  // sky is e^{-c S} (that ray's in-scatter), which must hold it: no bottom, clear water, a grazing ray.
  const double mu_w = 0.93, o_d = 0.8, d_y = 0.3;
  const UwBand bd = band(0.03, 0.05, mu_w);
  const UwiBand ib = seasim::makeUwiBand(bd, 0.0, mu_w, 0.0, 1.34);
  ASSERT_EQ(kd::fresnel_reflectance(d_y, 1.34, 1.0), 1.0);
  const double dx = std::sqrt(1 - d_y * d_y);
  const kd::real3 d{0, d_y, -dx}, s_w{0.3 * std::sqrt(1 - mu_w * mu_w), mu_w, -0.95 * std::sqrt(1 - mu_w * mu_w)};
  const double cos_r = kd::dot(d, s_w) - 2 * d.y * s_w.y;
  const double s_r = 1e30;
  const double reflected_ss =
      double(bd.b) * kd::hg_phase(cos_r, 0.0) * bd.e_beam0 * kd::kd_exp_integral(bd.c / mu_w, bd.c, -d_y, 0.0, s_r);
  const double with = kd::uwi_multiple(&ib, &bd, 0.0, 0.0, s_r, -d_y, 0.0, cos_r, mu_w, 0, 1);
  const double without = kd::uwi_multiple(&ib, &bd, 0.0, 0.0, s_r, -d_y, 0.0, cos_r, mu_w, 1, 1);
  EXPECT_NEAR(with - without, reflected_ss, 1e-12);
  EXPECT_GT(reflected_ss, 0.05 * with) << "a sizeable part in clear water at g = 0";
  // The surface term (froxels on for the camera's ray) holds the reflected ray's in-scatter with it.
  const double S = o_d / d_y;
  const double surface =
      kd::uwi_band_radiance(&ib, &bd, 0.0, UW_MAT_SURFACE, S, kd::real3{0, -1, 0}, d, o_d, s_w, 0, 1, 1, 0.0, 1.34, 0.0, 1, 1,
                             kd::uwi_no_mirror_object()) -
      kd::uwi_multiple(&ib, &bd, 0.0, 0.0, S, d_y, o_d, kd::dot(d, s_w), mu_w, 1, 1);
  EXPECT_NEAR(surface, std::exp(-double(ib.c_dm) * S) * with, 1e-12 + 1e-9 * surface);
}

}  // namespace

namespace {

TEST(UnderwaterOrdinatesSurface, ObjectInTheMirrorEndsTheReflectedRayAndIsLitThere) {
  // A sphere below the surface point, on the reflected ray, nearer than the 5 m bottom: the surface
  // shows F times the in-scatter to the sphere plus the sphere's Lambertian radiance attenuated by c';
  // beyond the bottom (or with none in the way) the bottom as before.
  const double mu_w = 0.93, o_d = 1.0, d_y = 0.3, H = 5.0;
  const UwBand bd = band(0.03, 0.05, mu_w);
  const UwiBand ib = seasim::makeUwiBand(bd, 0.9, mu_w, H, 1.34);
  const double dx = std::sqrt(1 - d_y * d_y);
  const kd::real3 o{0, -o_d, 0}, d{0, d_y, -dx};
  const kd::real3 s_w{0.3 * std::sqrt(1 - mu_w * mu_w), mu_w, -0.95 * std::sqrt(1 - mu_w * mu_w)};
  const double S = o_d / d_y;
  const kd::real3 surface_point = o + S * d, d_r{0, -d_y, -dx};
  UwObject objects[1] = {};
  objects[0].type = UW_SPHERE;
  const kd::real3 centre = surface_point + 6.0 * d_r;  // 6 m along the reflected ray (bottom at 5/0.3 m)
  objects[0].a[0] = float(centre.x), objects[0].a[1] = float(centre.y), objects[0].a[2] = float(centre.z);
  objects[0].a[3] = 0.5f;
  int mat = UW_MAT_NONE;
  kd::UwiMirrorHit m = kd::uwi_mirror_hit(objects, 1, o, d, S, s_w, &mat);
  ASSERT_EQ(mat, 0);
  EXPECT_NEAR(m.s, 5.5, 1e-5) << "the sphere's near side";
  EXPECT_NEAR(m.n.y, d_y, 1e-5) << "facing the surface point";
  EXPECT_EQ(m.vis, 1.0) << "nothing between it and the sun";
  m.albedo = 0.3;
  const double cos_r = kd::dot(d, s_w) - 2 * d.y * s_w.y;
  const double f = kd::fresnel_reflectance(d_y, 1.34, 1.0);
  const double expect =
      1.34 * 1.34 * (1 - f) * bd.sky_radiance +
      f * (kd::uwi_multiple(&ib, &bd, 0.9, H, m.s, -d_y, 0.0, cos_r, mu_w, 0, 1) +
           std::exp(-double(ib.c_dm) * m.s) * kd::uwi_lambert(&ib, &bd, H, m.s * d_y, m.n, s_w, 0.3, 1.0, 1.0));
  const double with = kd::uwi_surface(&ib, &bd, 0.9, H, bd.sky_radiance, d, s_w, 1.34, 1, m);
  EXPECT_NEAR(with, expect, 1e-12 + 1e-9 * expect);
  const double none = kd::uwi_surface(&ib, &bd, 0.9, H, bd.sky_radiance, d, s_w, 1.34, 1, kd::uwi_no_mirror_object());
  EXPECT_GT(std::fabs(with / none - 1), 0.01) << "the sphere is not the bottom";
  // Beyond the bottom it is hidden: the same as no object.
  m.s = H / d_y + 0.1;
  EXPECT_EQ(kd::uwi_surface(&ib, &bd, 0.9, H, bd.sky_radiance, d, s_w, 1.34, 1, m), none);
  // The sphere moved off the ray: no hit.
  objects[0].a[0] += 2.0f;
  EXPECT_GE(kd::uwi_mirror_hit(objects, 1, o, d, S, s_w, &mat).s, 1e29);
  EXPECT_EQ(mat, UW_MAT_NONE);
}

}  // namespace
