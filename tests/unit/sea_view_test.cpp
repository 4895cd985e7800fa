// sea_view_test.cpp — sea_single.cl's per-pixel terms (kernels/common/sea_view.h) and band steps
// (kernels/common/sea_band_terms.h) in float and double: the pinhole ray, a flat sea's pixel (Fresnel,
// T_o, the sun's entry, the bottom's depth), and one band's radiance against the scalar eq. 5 and 9 of
// sea_surface.h plus the reflected uniform sky; the sun below the horizon and no bottom.
// tests/kernels/sea_single_test.cpp runs the kernel that calls these against the double reference.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <type_traits>
#include <vector>

#include "math/kernel_math.h"

namespace {

SeaParams flatSeaParams(double sun_zenith_deg) {
  SeaParams p{};
  p.cam_pos[1] = 5.0f;
  p.cam_right[0] = 1.0f;
  p.cam_up[1] = 0.8f;  // looking 36.87° below the horizon: up (0, 0.8, 0.6), forward (0, -0.6, 0.8)
  p.cam_up[2] = 0.6f;
  p.cam_forward[1] = -0.6f;
  p.cam_forward[2] = 0.8f;
  const double z = sun_zenith_deg * M_PI / 180.0;
  p.sun_dir[0] = static_cast<float>(std::sin(z));
  p.sun_dir[1] = static_cast<float>(std::cos(z));
  p.tan_half_fov_y = 0.5f;
  p.aspect = 1.0f;
  p.ior = 1.34f;
  p.g = 0.9f;
  p.bottom_depth = 6.0f;
  p.cos_sun_radius = 0.99999f;
  p.sun_solid_angle = 6.8e-5f;
  p.width = 3;
  p.height = 3;
  p.band_count = 1;
  return p;
}

template <typename T>
class SeaView : public ::testing::Test {};
struct F {
  using real = float;
};
struct D {
  using real = double;
};
using Precisions = ::testing::Types<F, D>;
class PrecisionName {
 public:
  template <typename T>
  static std::string GetName(int) {
    return std::is_same_v<T, F> ? "float" : "double";
  }
};
TYPED_TEST_SUITE(SeaView, Precisions, PrecisionName);

// Double is held to 2e-8: SeaParams carries floats (the sun's direction is a float rounding off unit
// length, and n² is a float product), so the double terms see the float inputs' rounding.
template <typename R>
double tolerance() {
  return std::is_same_v<R, float> ? 2e-6 : 2e-8;
}

template <typename NS>
void checkFlatPixel(double sun_zenith_deg, bool bottom, double tol) {
  using real = typename NS::real;
  const SeaParams p = flatSeaParams(sun_zenith_deg);
  // SeaParams holds floats: the expected values start from the same float inputs, in double.
  const double fy = p.cam_forward[1], fz = p.cam_forward[2], norm = std::sqrt(fy * fy + fz * fz);
  const double ior = p.ior, cos_sun = p.sun_dir[1], sin_sun = p.sun_dir[0];
  const auto d = NS::camera_ray(&p, 1, 1, 0, 1);  // the centre pixel: the forward direction
  EXPECT_NEAR(d.x, 0.0, tol);
  EXPECT_NEAR(d.y, fy / norm, tol);
  EXPECT_NEAR(d.z, fz / norm, tol);
  typename NS::Features f{1, 1, bottom ? 1 : 0, 1, 0, 0, 0, 0, 0, 0, 0};
  const auto px = NS::pixel(f, &p, d);
  const double R = NS::fresnel(-fy / norm, 1.0, ior);
  EXPECT_NEAR(px.R_view, R, tol);
  EXPECT_NEAR(px.t_out, (1.0 - R) / (ior * ior), tol);
  const bool sun_up = cos_sun > 1e-6;
  EXPECT_NEAR(px.t_in, sun_up ? 1.0 - NS::fresnel(cos_sun, 1.0, ior) : 0.0, tol);
  EXPECT_NEAR(px.sun_horizontal, sun_up ? cos_sun : 0.0, tol);
  const double sin_sun_in = sin_sun / ior;
  EXPECT_NEAR(px.cos_io, sun_up ? std::sqrt(1.0 - sin_sun_in * sin_sun_in) : 1.0, 10 * tol);  // steep near grazing
  EXPECT_NEAR(px.z_d, bottom ? 6.0 : -1.0, tol);
  EXPECT_EQ(px.focus, real(1));

  // One band: the reflected uniform sky plus 000 eq. 5 and 9 of sea_surface.h, term for term.
  std::vector<real> table(SEA_ROWS * SEA_BAND_STRIDE(1), real(0));
  const int stride = SEA_BAND_STRIDE(1);
  const real sun = 1.6, sky = 0.05, b = 0.2, c = 0.45, albedo = 0.3;
  table[SEA_ROW_SUN * stride] = sun;
  table[SEA_ROW_SKY * stride] = sky;
  table[SEA_ROW_B * stride] = b;
  table[SEA_ROW_C * stride] = c;
  table[SEA_ROW_BOTTOM_ALBEDO * stride] = albedo;
  const double e = double(sun) * px.sun_horizontal;
  double expected = px.R_view * double(sky);
  expected += NS::single_scattering(e, px.t_in, px.t_out, double(b) * px.phase, double(c), double(b) / double(c),
                                    px.c_f, px.cos_io, px.cos_ji, px.z_d);
  if (bottom)
    expected += NS::bottom_reflection(e, px.t_in, px.t_out, double(albedo), double(c), px.z_d, px.cos_io, px.cos_ji);
  const double L = NS::band(f, table.data(), stride, &px, p.sun_solid_angle);
  EXPECT_NEAR(L, expected, tol * (1.0 + std::fabs(expected)));
  EXPECT_TRUE(std::isfinite(L));
}

// Adapters onto kmath_f / kmath_d (the same header compiled twice).
#define SEA_VIEW_NS(NAME, K)                                                                                       \
  struct NAME {                                                                                                     \
    using real = K::real;                                                                                           \
    using Features = K::SeaFeatures;                                                                                  \
    static K::real3 camera_ray(const SeaParams* p, int x, int y, int sub, int n) {                                  \
      return K::sea_camera_ray(p, x, y, sub, n);                                                                    \
    }                                                                                                               \
    static K::SeaPixel pixel(K::SeaFeatures f, const SeaParams* p, K::real3 d) {                                       \
      K::SeaPixel px;                                                                                               \
      K::sea_pixel(f, p, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, d, &px);                             \
      return px;                                                                                                    \
    }                                                                                                               \
    static double fresnel(double c, double n1, double n2) {                                                         \
      return K::fresnel_reflectance(static_cast<real>(c), static_cast<real>(n1), static_cast<real>(n2));            \
    }                                                                                                               \
    static double single_scattering(double e, double ti, double to, double beta, double c, double alb, double cf,   \
                                    double cio, double cji, double zd) {                                            \
      return kd::sea_single_scattering(e, ti, to, beta, c, alb, cf, cio, cji, zd);                                  \
    }                                                                                                               \
    static double bottom_reflection(double e, double ti, double to, double alb, double c, double zd, double cio,     \
                                    double cji) {                                                                   \
      return kd::sea_bottom_reflection(e, ti, to, alb, c, zd, cio, cji);                                            \
    }                                                                                                               \
    static double band(K::SeaFeatures f, const real* table, int stride, const K::SeaPixel* px, real sun_solid_angle) { \
      return K::sea_band_lanes_b(f, table, stride, 0, px, sun_solid_angle);                                         \
    }                                                                                                               \
  };

namespace kd = seasim::kmath_d;
namespace kf = seasim::kmath_f;
SEA_VIEW_NS(NsF, kf)
SEA_VIEW_NS(NsD, kd)

template <typename T>
using Ns = std::conditional_t<std::is_same_v<T, F>, NsF, NsD>;

TYPED_TEST(SeaView, FlatSeaPixelAndBandMatchTheScalarTerms) {
  using NS = Ns<TypeParam>;
  const double tol = tolerance<typename NS::real>();
  checkFlatPixel<NS>(40.0, true, tol);   // ordinary
  checkFlatPixel<NS>(40.0, false, tol);  // no bottom: infinitely deep
  checkFlatPixel<NS>(89.9, true, tol);   // the sun grazing the surface
  checkFlatPixel<NS>(95.0, true, tol);   // the sun below the horizon: no light enters
}

TYPED_TEST(SeaView, CameraRayCoversThePixelGrid) {
  using NS = Ns<TypeParam>;
  const SeaParams p = flatSeaParams(40.0);
  // Sub-ray 0 of 2 x 2 in pixel (1, 1) lies a quarter pixel left of and above the centre ray.
  const auto centre = NS::camera_ray(&p, 1, 1, 0, 1);
  const auto sub = NS::camera_ray(&p, 1, 1, 0, 2);
  EXPECT_LT(sub.x, centre.x);
  EXPECT_GT(sub.y, centre.y);
  EXPECT_NEAR(sub.x * sub.x + sub.y * sub.y + sub.z * sub.z, 1.0, 10 * tolerance<typename NS::real>());
}

}  // namespace
