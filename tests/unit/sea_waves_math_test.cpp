// sea_waves_math_test.cpp — kernels/common/sea_waves.h in float and double: the periodic bilinear
// read of the ocean's normal map, the facing/folded-normal fixes, the horizon clamp of reflected
// rays, and the view/surface interaction (Fresnel, reflection, refraction by the local normal): flat
// normal = the flat sea's operations exactly; steep normals and grazing views never give NaN/Inf.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "math/kernel_math.h"

namespace {

namespace kd = seasim::kmath_d;
namespace kf = seasim::kmath_f;

template <class V>
using Real = decltype(V{}.x);

// Scalar-only functions are not found through the real3 argument (ADL): pick the precision here.
void sea_wrap_coord(double x, double p, int n, int* i0, int* i1, double* t) { kd::sea_wrap_coord(x, p, n, i0, i1, t); }
void sea_wrap_coord(float x, float p, int n, int* i0, int* i1, float* t) { kf::sea_wrap_coord(x, p, n, i0, i1, t); }
kd::real3 sea_wave_normal(const double* m, int n, double p, double x, double z) { return kd::sea_wave_normal(m, n, p, x, z); }
kf::real3 sea_wave_normal(const float* m, int n, float p, float x, float z) { return kf::sea_wave_normal(m, n, p, x, z); }
double fresnel_reflectance(double c, double n1, double n2) { return kd::fresnel_reflectance(c, n1, n2); }
float fresnel_reflectance(float c, float n1, float n2) { return kf::fresnel_reflectance(c, n1, n2); }

template <class V>
bool finite(V v) {
  return std::isfinite(double(v.x)) && std::isfinite(double(v.y)) && std::isfinite(double(v.z));
}

template <class V>
double len(V v) {
  return std::sqrt(double(v.x) * v.x + double(v.y) * v.y + double(v.z) * v.z);
}

// An n x n normal map of the surface h = A sin(2π x / L) (slope along x only), 4 reals per texel.
template <class T>
std::vector<T> sineNormalMap(int n, double L, double A) {
  std::vector<T> map(4 * n * n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double x = i * L / n, s = A * 2 * M_PI / L * std::cos(2 * M_PI * x / L);
      const double norm = std::sqrt(1 + s * s);
      T* t = &map[4 * (j * n + i)];
      t[0] = T(-s / norm), t[1] = T(1 / norm), t[2] = 0, t[3] = 0;
    }
  return map;
}

template <class V>
void checkWrapCoord(const char* precision) {
  using T = Real<V>;
  const int n = 8;
  const T L = 10;
  // x, expected i0, t: inside, on a texel, at the patch end, negative, many patches away.
  struct Case {
    double x;
    int i0;
    double t;
  } cases[] = {{1.5625, 1, 0.25}, {0.0, 0, 0.0},    {10.0, 0, 0.0}, {-1.25, 7, 0.0},
               {-0.625, 7, 0.5},  {1003.75, 3, 0.0}, {-1e-9, 0, 0.0}};
  for (const Case& c : cases) {
    int i0 = -1, i1 = -1;
    T t = -1;
    sea_wrap_coord(T(c.x), L, n, &i0, &i1, &t);
    EXPECT_TRUE(i0 >= 0 && i0 < n && i1 >= 0 && i1 < n) << precision << " x=" << c.x;
    EXPECT_EQ(i1, (i0 + 1) % n) << precision << " x=" << c.x;
    EXPECT_TRUE(t >= 0 && t <= 1) << precision << " x=" << c.x;
    // The texel position i0 + t equals x mod L in texels (up to the wrap of a value at the seam).
    const double pos = i0 + double(t), want = c.i0 + c.t;
    EXPECT_LT(std::min(std::fabs(pos - want), std::fabs(std::fabs(pos - want) - n)), 1e-4) << precision << " x=" << c.x;
  }
  // Huge and non-representable-fraction coordinates still give valid indices.
  for (double x : {1e7, -1e7, 3.3e9}) {
    int i0 = -1, i1 = -1;
    T t = -1;
    sea_wrap_coord(T(x), L, n, &i0, &i1, &t);
    EXPECT_TRUE(i0 >= 0 && i0 < n && i1 >= 0 && i1 < n && t >= 0 && t <= 1) << precision << " x=" << x;
  }
}

TEST(SeaWaves, WrapCoordinateIsPeriodicAndInRange) {
  checkWrapCoord<kd::real3>("double");
  checkWrapCoord<kf::real3>("float");
}

template <class V>
void checkNormalRead(const char* precision) {
  using T = Real<V>;
  const int n = 16;
  const double L = 8.0;
  // A flat map reads exactly (0, 1, 0) anywhere (a + t (b - a) with a = b).
  std::vector<T> flat(4 * n * n, T(0));
  for (int i = 0; i < n * n; ++i) flat[4 * i + 1] = 1;
  for (double x : {0.0, 0.3, 7.99, -3.7, 1234.5}) {
    const V nrm = sea_wave_normal(flat.data(), n, T(L), T(x), T(0.77 * x));
    EXPECT_EQ(nrm.x, T(0));
    EXPECT_EQ(nrm.y, T(1));
    EXPECT_EQ(nrm.z, T(0));
  }
  // A sine surface: at texel positions the texel, between them a unit vector close to the exact
  // normal, and periodic in x and z with period L.
  const std::vector<T> map = sineNormalMap<T>(n, L, 0.3);
  for (int i = 0; i < n; ++i) {
    const V at = sea_wave_normal(map.data(), n, T(L), T(i * L / n), T(2.0));
    EXPECT_NEAR(double(at.x), double(map[4 * i]), 1e-6) << precision;
    EXPECT_NEAR(double(at.y), double(map[4 * i + 1]), 1e-6) << precision;
  }
  for (double x : {0.1, 2.9, 5.55, 7.9}) {
    const V a = sea_wave_normal(map.data(), n, T(L), T(x), T(1.0));
    const V b = sea_wave_normal(map.data(), n, T(L), T(x + L), T(1.0 - 3 * L));
    EXPECT_NEAR(len(a), 1.0, 1e-6) << precision;
    EXPECT_NEAR(double(a.x), double(b.x), 2e-5) << precision << " x=" << x;
    EXPECT_NEAR(double(a.y), double(b.y), 2e-5) << precision << " x=" << x;
    const double s = 0.3 * 2 * M_PI / L * std::cos(2 * M_PI * x / L);
    EXPECT_NEAR(double(a.x), -s / std::sqrt(1 + s * s), 0.01) << precision << " x=" << x;  // texel 0.5 m, slope 0.24
  }
  // Opposite normals in neighbouring texels interpolate to ~zero length: (0, 1, 0), not NaN.
  std::vector<T> opposite(4 * 2 * 2, T(0));
  opposite[0] = 1, opposite[4] = -1, opposite[8] = 1, opposite[12] = -1;
  const V mid = sea_wave_normal(opposite.data(), 2, T(2), T(0.5), T(0.25));
  EXPECT_TRUE(finite(mid)) << precision;
  EXPECT_EQ(mid.y, T(1));
}

TEST(SeaWaves, NormalMapReadIsBilinearPeriodicAndExactWhenFlat) {
  checkNormalRead<kd::real3>("double");
  checkNormalRead<kf::real3>("float");
}

template <class V>
void checkFacing(const char* precision) {
  using T = Real<V>;
  const V d = normalize(V{T(0), T(-0.5), T(-1)});
  // Facing the eye: unchanged.
  const V up = normalize(V{T(0.1), T(1), T(0.2)});
  const V same = sea_facing_normal(d, up);
  EXPECT_EQ(same.x, up.x);
  EXPECT_EQ(same.y, up.y);
  // Facing away (tilted towards -z more than the view's depression): bent to grazing, unit.
  const V away = normalize(V{T(0), T(0.3), T(-1)});
  const V bent = sea_facing_normal(d, away);
  EXPECT_NEAR(double(dot(d, bent)), 0.0, 1e-6) << precision;
  EXPECT_NEAR(len(bent), 1.0, 1e-6) << precision;
  EXPECT_GT(double(bent.y), 0.0) << precision;
  // A folded facet's downward normal is turned up.
  const V folded = sea_facing_normal(d, V{T(0), T(-1), T(0)});
  EXPECT_EQ(folded.y, T(1));
  // A normal along the view itself (degenerate bend): (0, 1, 0).
  const V along = sea_facing_normal(V{T(0), T(-1), T(0)}, V{T(0), T(-1), T(0)});
  EXPECT_TRUE(finite(along)) << precision;
  EXPECT_LT(double(dot(V{T(0), T(-1), T(0)}, along)), 1e-6) << precision;
}

TEST(SeaWaves, BackFacingAndFoldedNormalsAreMadeVisible) {
  checkFacing<kd::real3>("double");
  checkFacing<kf::real3>("float");
}

template <class V>
void checkSkyDirection(const char* precision) {
  using T = Real<V>;
  const V upward{T(0.6), T(0.8), T(0)};
  const V kept = sea_sky_direction(upward);
  EXPECT_EQ(kept.y, upward.y);
  const V down = sea_sky_direction(normalize(V{T(0.3), T(-0.5), T(-0.4)}));
  EXPECT_EQ(down.y, T(0));
  EXPECT_NEAR(len(down), 1.0, 1e-6) << precision;
  EXPECT_NEAR(double(down.x) / double(down.z), 0.3 / -0.4, 1e-6) << precision;
  const V straight = sea_sky_direction(V{T(0), T(-1), T(0)});
  EXPECT_TRUE(finite(straight)) << precision;
  EXPECT_EQ(straight.y, T(0));
}

TEST(SeaWaves, ReflectionBelowTheHorizonSeesTheHorizon) {
  checkSkyDirection<kd::real3>("double");
  checkSkyDirection<kf::real3>("float");
}

template <class V>
void checkFlatInteraction(const char* precision) {
  using T = Real<V>;
  // With the flat normal the helper must do exactly what the flat sea did (kernels/sea_single.cl):
  // R(cos_jo = -d.y), refract_dir / reflect_dir about (0, 1, 0), cos_ji = max(-t.y, 1e-4).
  const T ior = T(1.333);
  const V n{T(0), T(1), T(0)};
  for (double elev : {-89.9, -60.0, -20.0, -3.0, -0.01}) {
    for (double az : {0.0, 1.0, 2.5}) {
      const double e = elev * M_PI / 180;
      const V d{T(std::cos(e) * std::cos(az)), T(std::sin(e)), T(std::cos(e) * std::sin(az))};
      T R = -1;
      V sky{}, t{};
      const T cos_ji = sea_view_interaction(d, n, ior, &R, &sky, &t);
      V t_flat{};
      refract_dir(d, n, T(1) / ior, &t_flat);
      const V r_flat = reflect_dir(d, n);
      EXPECT_EQ(R, fresnel_reflectance(-d.y, T(1), ior)) << precision << " " << elev;
      EXPECT_EQ(cos_ji, fmax(-t_flat.y, T(1e-4))) << precision;
      EXPECT_EQ(t.x, t_flat.x);
      EXPECT_EQ(t.y, t_flat.y);
      EXPECT_EQ(sky.x, r_flat.x);
      EXPECT_EQ(sky.y, r_flat.y);
      EXPECT_EQ(sky.z, r_flat.z);
    }
  }
}

TEST(SeaWaves, FlatNormalGivesTheFlatSeaExactly) {
  checkFlatInteraction<kd::real3>("double");
  checkFlatInteraction<kf::real3>("float");
}

template <class V>
void checkSteepAndGrazing(const char* precision) {
  using T = Real<V>;
  // Random normals over the whole sphere (folded, vertical, back-facing included) and views from
  // straight down to 1e-7 below the horizon: every output finite and in range.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  int count = 0;
  for (int k = 0; k < 20000; ++k) {
    const double elev = -std::pow(10.0, -7 + 7 * (0.5 + 0.5 * u(rng)));  // sin of depression, 1e-7 .. 1
    const double az = M_PI * u(rng);
    const double c = std::sqrt(std::max(0.0, 1 - elev * elev));
    const V d{T(c * std::cos(az)), T(elev), T(c * std::sin(az))};
    V raw{T(u(rng)), T(u(rng)), T(u(rng))};
    if (k % 5 == 0) raw = V{T(u(rng)), T(0), T(u(rng))};  // vertical facets
    if (len(raw) < 1e-3) continue;
    const V n = sea_facing_normal(d, normalize(raw));
    ASSERT_TRUE(finite(n)) << precision;
    // Facing the eye, or grazing to rounding: the bend cancels when n is nearly along d (float: up
    // to 2e-5 measured).
    EXPECT_LE(double(dot(d, n)), sizeof(T) == 4 ? 1e-4 : 1e-12) << precision;
    T R = -1;
    V sky{}, t{};
    const T cos_ji = sea_view_interaction(d, n, T(1.333), &R, &sky, &t);
    ASSERT_TRUE(std::isfinite(double(R)) && std::isfinite(double(cos_ji)) && finite(sky) && finite(t)) << precision;
    EXPECT_TRUE(R >= 0 && R <= 1) << precision;
    EXPECT_TRUE(cos_ji >= T(1e-4) && cos_ji <= T(1)) << precision;
    EXPECT_GE(double(sky.y), 0.0) << precision;
    EXPECT_NEAR(len(sky), 1.0, 1e-5) << precision;
    // A bent normal's float rounding (d·n up to 2e-5 past grazing, taken as grazing) shortens t by as much.
    EXPECT_NEAR(len(t), 1.0, sizeof(T) == 4 ? 2e-5 : 1e-12) << precision;
    // The refracted view goes into the water, also where the bent normal's rounding leaves it a hair
    // behind the view (refract_dir would turn the normal over and send the view up into the air).
    EXPECT_LT(double(t.y), 1e-6) << precision << ": d·n = " << double(dot(d, n));
    ++count;
  }
  EXPECT_GT(count, 19000);
}

TEST(SeaWaves, SteepNormalsAndGrazingViewsStayFinite) {
  checkSteepAndGrazing<kd::real3>("double");
  checkSteepAndGrazing<kf::real3>("float");
}

TEST(SeaWaves, TiltedNormalChangesFresnelAsTheLocalAngleSays) {
  // A view 10° below the horizon on a facet tilted 30° towards the eye meets it at 50° from its
  // normal (not 80°): R drops from the flat grazing value to the 50° value.
  const double e = -10 * M_PI / 180, tilt = 30 * M_PI / 180;
  const kd::real3 d{0, std::sin(e), -std::cos(e)};
  const kd::real3 n{0, std::cos(tilt), std::sin(tilt)};  // towards +z, the eye's side
  double R = 0;
  kd::real3 sky{}, t{};
  kd::sea_view_interaction(d, kd::sea_facing_normal(d, n), 1.333, &R, &sky, &t);
  EXPECT_NEAR(R, kd::fresnel_reflectance(std::cos(50 * M_PI / 180), 1.0, 1.333), 1e-12);
  EXPECT_LT(R, kd::fresnel_reflectance(std::sin(10 * M_PI / 180), 1.0, 1.333));
}

}  // namespace
