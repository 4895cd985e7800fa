// sea_lean_test.cpp — kernels/common/sea_lean.h (the filtered wave normals) in float and
// double, each against a brute-force evaluation that shares none of its approximations:
//  - the slope-moment mip chain and the footprint's statistics on synthetic slope fields, against
//    direct averages over the footprint's texels;
//  - the 3 × 3 Gauss–Hermite Fresnel mean against a fine 2-D quadrature of the Gaussian;
//  - the calm sea: the reflected sky is exactly the sky times the flat Fresnel reflectance;
//  - the glint against Monte Carlo: facets drawn from the Gaussian, mirror directions counted inside
//    the sun's disk;
//  - stiff cases: vertical and folded facets, zero variance, a sun of radius 0, the half vector at
//    the horizon: finite everywhere.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <type_traits>
#include <vector>

#include "math/kernel_math.h"

namespace {

namespace kd = seasim::kmath_d;
namespace kf = seasim::kmath_f;

// The header's functions in one precision (scalar arguments do not find them by ADL).
template <class T>
struct Lean;

#define SEASIM_LEAN_BIND(T, NS)                                                                                  \
  template <>                                                                                                    \
  struct Lean<T> {                                                                                               \
    using V = NS::real3;                                                                                         \
    static V vec(double x, double y, double z) { return V{T(x), T(y), T(z)}; }                                   \
    static void slope(V n, T* sx, T* sz) { NS::sea_lean_slope(n, sx, sz); }                                     \
    static V normal(T sx, T sz) { return NS::sea_lean_normal(sx, sz); }                                          \
    static int levels(int n) { return NS::sea_lean_levels(n); }                                                  \
    static int offset(int n, int l) { return NS::sea_lean_level_offset(n, l); }                                  \
    static void cell(T ax, T az, T bx, T bz, T cx, T cz, T ex, T ez, T* m) {                                     \
      NS::sea_lean_cell_moments(ax, az, bx, bz, cx, cz, ex, ez, m);                                              \
    }                                                                                                            \
    static void footprint(const T* mips, int n, T patch, T x, T z, T dx, T dz, T minor, T major, T* out) {       \
      NS::sea_lean_footprint(mips, n, patch, x, z, dx, dz, minor, major, out);                                   \
    }                                                                                                            \
    static void covariance(T vxx, T vzz, T vxz, T sun, T* cxx, T* czz, T* cxz, T* l11, T* l21, T* l22) {         \
      NS::sea_lean_covariance(vxx, vzz, vxz, sun, cxx, czz, cxz, l11, l21, l22);                                 \
    }                                                                                                            \
    /* E[F] over the facets by the header's rule; back-facing facets count F = 1 (bent to grazing). */        \
    static T fresnelMean(V d, T mx, T mz, T l11, T l21, T l22, T ior, bool* split) {                             \
      NS::SeaLeanRule r;                                                                                         \
      NS::sea_lean_rule(d, mx, mz, l11, l21, l22, &r);                                                           \
      *split = r.split != 0;                                                                                     \
      T sum = r.back;                                                                                            \
      for (int k = 0; k < NS::sea_lean_rule_nodes(&r); ++k) {                                                    \
        T sx, sz;                                                                                                \
        const T w = NS::sea_lean_rule_node(&r, k, &sx, &sz);                                                     \
        const V n = NS::sea_facing_normal(d, NS::sea_lean_normal(sx, sz));                                       \
        sum += w * NS::fresnel_reflectance(-NS::dot(d, n), T(1), ior);                                           \
      }                                                                                                          \
      return sum;                                                                                                \
    }                                                                                                            \
    static T glint(V d, V sun, T ior, T mx, T mz, T cxx, T czz, T cxz) {                                         \
      return NS::sea_lean_glint(d, sun, ior, mx, mz, cxx, czz, cxz);                                             \
    }                                                                                                            \
    static T pixelGlint(V d, V fwd, V du, V dv, V sun, T ior, T mx, T mz, T cxx, T czz, T cxz) {                 \
      return NS::sea_lean_pixel_glint(d, fwd, du, dv, sun, ior, mx, mz, cxx, czz, cxz);                          \
    }                                                                                                            \
    static V unit(V v) { return NS::normalize(v); }                                                              \
  };
SEASIM_LEAN_BIND(float, kf)
SEASIM_LEAN_BIND(double, kd)
#undef SEASIM_LEAN_BIND

template <class V>
double dotd(V a, V b) {
  return double(a.x) * b.x + double(a.y) * b.y + double(a.z) * b.z;
}

// The moment maps as the kernels build them, in T: the point map, level 0's cell moments (the
// header's closed form), then 2 x 2 box averages.
template <class T>
std::vector<T> buildMips(const std::vector<double>& sx, const std::vector<double>& sz, int n) {
  using L = Lean<T>;
  std::vector<T> mips(L::offset(n, L::levels(n)));
  for (int i = 0; i < n * n; ++i) {
    T* m = &mips[5 * i];
    m[0] = T(sx[i]), m[1] = T(sz[i]), m[2] = T(sx[i] * sx[i]), m[3] = T(sz[i] * sz[i]), m[4] = T(sx[i] * sz[i]);
  }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      auto at = [&](int ii, int jj) { return ((jj % n) * n + (ii % n)); };
      const int a = at(i, j), b = at(i + 1, j), c = at(i, j + 1), e = at(i + 1, j + 1);
      L::cell(T(sx[a]), T(sz[a]), T(sx[b]), T(sz[b]), T(sx[c]), T(sz[c]), T(sx[e]), T(sz[e]),
              &mips[L::offset(n, 0) + 5 * (j * n + i)]);
    }
  for (int l = 0; (n >> l) > 1; ++l) {
    const int src = n >> l, dst = src / 2;
    const T* s = &mips[L::offset(n, l)];
    T* t = &mips[L::offset(n, l + 1)];
    for (int j = 0; j < dst; ++j)
      for (int i = 0; i < dst; ++i)
        for (int k = 0; k < 5; ++k)
          t[5 * (j * dst + i) + k] = T(0.25) * ((s[5 * (2 * j * src + 2 * i) + k] + s[5 * (2 * j * src + 2 * i + 1) + k]) +
                                                (s[5 * ((2 * j + 1) * src + 2 * i) + k] + s[5 * ((2 * j + 1) * src + 2 * i + 1) + k]));
  }
  return mips;
}

// Brute force, independent of the closed form: the moments of the bilinear interpolation of the
// texel slopes (texel i at u = i) over [u0, u1) x [v0, v1) in whole cells, by 2-point Gauss–Legendre
// per cell and axis (exact for the biquadratic products).
std::vector<double> bilinearAverage(const std::vector<double>& sx, const std::vector<double>& sz, int n, int u0, int u1,
                                    int v0, int v1) {
  const double g[2] = {0.5 - 0.5 / std::sqrt(3.0), 0.5 + 0.5 / std::sqrt(3.0)};
  std::vector<double> m(5, 0.0);
  auto field = [&](const std::vector<double>& f, int i, int j, double u, double v) {
    auto at = [&](int ii, int jj) { return f[((jj % n + n) % n) * n + ((ii % n + n) % n)]; };
    return (1 - u) * (1 - v) * at(i, j) + u * (1 - v) * at(i + 1, j) + (1 - u) * v * at(i, j + 1) + u * v * at(i + 1, j + 1);
  };
  int count = 0;
  for (int j = v0; j < v1; ++j)
    for (int i = u0; i < u1; ++i)
      for (double u : g)
        for (double v : g) {
          const double a = field(sx, i, j, u, v), b = field(sz, i, j, u, v);
          m[0] += a, m[1] += b, m[2] += a * a, m[3] += b * b, m[4] += a * b, ++count;
        }
  for (double& x : m) x /= count;
  return m;
}

template <class T>
class SeaLean : public ::testing::Test {};
using Precisions = ::testing::Types<float, double>;
TYPED_TEST_SUITE(SeaLean, Precisions);

TYPED_TEST(SeaLean, LevelsAndOffsets) {
  using L = Lean<TypeParam>;
  EXPECT_EQ(L::levels(1), 1);
  EXPECT_EQ(L::levels(2), 2);
  EXPECT_EQ(L::levels(256), 9);
  EXPECT_EQ(L::offset(4, 0), 5 * 16);  // after the point map
  EXPECT_EQ(L::offset(4, 1), 5 * 32);
  EXPECT_EQ(L::offset(4, 2), 5 * 36);
  EXPECT_EQ(L::offset(4, 3), 5 * 37);  // the whole chain
}

// A level's read wraps periodically: at u and u ± whole periods (negative texel coordinates included)
// it reads the same bilinear moments, and at whole texels it reads that texel's stored values.
TYPED_TEST(SeaLean, LevelReadWrapsPeriodicallyInBothDirections) {
  using Real = TypeParam;
  constexpr int nl = 8;
  std::vector<Real> level(SEA_LEAN_STRIDE * nl * nl);
  for (size_t i = 0; i < level.size(); ++i) level[i] = Real(std::sin(0.37 * double(i)) + 0.1 * double(i % 7));
  auto read = [&](Real u, Real v) {
    std::vector<Real> m(SEA_LEAN_STRIDE);
    if constexpr (std::is_same_v<Real, float>) kf::sea_lean_read_level(level.data(), nl, u, v, m.data());
    else kd::sea_lean_read_level(level.data(), nl, u, v, m.data());
    return m;
  };
  for (double u : {0.0, 0.3, 3.75, 7.5, 7.99}) {
    for (double v : {0.0, 1.6, 6.25, 7.7}) {
      const std::vector<Real> base = read(Real(u), Real(v));
      for (int pu : {-3, -1, 1, 2})
        for (int pv : {-2, 0, 1}) {
          const std::vector<Real> m = read(Real(u + pu * nl), Real(v + pv * nl));
          for (int k = 0; k < SEA_LEAN_STRIDE; ++k)
            EXPECT_NEAR(m[k], base[k], 1e-5) << u << " " << v << " " << pu << " " << pv;
        }
    }
  }
  for (int i : {0, 5, 7})
    for (int j : {0, 3, 7}) {
      const std::vector<Real> m = read(Real(i - nl), Real(j - 2 * nl));
      for (int k = 0; k < SEA_LEAN_STRIDE; ++k) EXPECT_NEAR(m[k], level[SEA_LEAN_STRIDE * (j * nl + i) + k], 1e-6);
    }
}

TYPED_TEST(SeaLean, SlopeOfNormalRoundTripsAndCapsVerticalFacets) {
  using T = TypeParam;
  using L = Lean<T>;
  T sx, sz;
  L::slope(L::normal(T(0.3), T(-0.2)), &sx, &sz);
  EXPECT_NEAR(double(sx), 0.3, 1e-6);
  EXPECT_NEAR(double(sz), -0.2, 1e-6);
  L::slope(L::vec(1, 0, 0), &sx, &sz);  // a vertical facet
  EXPECT_TRUE(std::isfinite(double(sx)));
  EXPECT_NEAR(double(sx), -20.0, 1e-4);
  L::slope(L::vec(0, -1, 0), &sx, &sz);  // upside down (the kernel turns folded facets up first)
  EXPECT_TRUE(std::isfinite(double(sx)) && std::isfinite(double(sz)));
}

// Footprint statistics against direct averages of the bilinear slope field (what the unfiltered
// path's rays see) over the cells the footprint covers. The field is a random slope per texel; a
// square footprint aligned with a cell of level l must give the moments of the 2^l x 2^l level-0
// cells under it.
TYPED_TEST(SeaLean, FootprintMatchesDirectAveragesAtMipCells) {
  using T = TypeParam;
  using L = Lean<T>;
  const int n = 32;
  const double patch = 8.0, cell = patch / n;
  std::mt19937 rng(7);
  std::normal_distribution<double> gauss(0.0, 0.3);
  std::vector<double> sx(n * n), sz(n * n);
  for (int i = 0; i < n * n; ++i) sx[i] = gauss(rng), sz[i] = 0.5 * sx[i] + gauss(rng);
  const std::vector<T> mips = buildMips<T>(sx, sz, n);
  for (int level : {0, 1, 2, 3, 5}) {
    const int side = 1 << level;
    for (int ti : {0, 1, (n >> level) - 1}) {
      if (ti >= (n >> level)) continue;  // level 5 of 32 is one cell
      const int tj = (n >> level) / 2;
      const double cx = (ti + 0.5) * side * cell, cz = (tj + 0.5) * side * cell;
      const std::vector<double> m = bilinearAverage(sx, sz, n, side * ti, side * (ti + 1), side * tj, side * (tj + 1));
      T out[5];
      // A footprint read exactly at this level (the reads use SEA_LEAN_FOOTPRINT_SCALE of its size).
      const double size = side * cell / kd::sea_lean_footprint_scale();
      L::footprint(mips.data(), n, T(patch), T(cx), T(cz), T(1), T(0), T(size), T(size), out);
      const double tol = std::is_same_v<T, float> ? 2e-5 : 1e-12;
      EXPECT_NEAR(double(out[0]), m[0], tol) << "level " << level << " cell " << ti;
      EXPECT_NEAR(double(out[1]), m[1], tol);
      EXPECT_NEAR(double(out[2]), m[2] - m[0] * m[0], 4 * tol);
      EXPECT_NEAR(double(out[3]), m[3] - m[1] * m[1], 4 * tol);
      EXPECT_NEAR(double(out[4]), m[4] - m[0] * m[1], 4 * tol);
    }
  }
  // The interpolated surface has less slope variance than its texels (4/9 of it for uncorrelated
  // texels): the reason level 0 holds cell moments, not texel averages.
  double texel_var = 0;
  for (double v : sx) texel_var += v * v;
  texel_var /= n * n;
  const std::vector<double> all = bilinearAverage(sx, sz, n, 0, n, 0, n);
  EXPECT_LT(all[2], 0.6 * texel_var);
}

// A footprint as large as the patch sees every slope: its statistics are the field's, whatever the
// point; a tiny footprint sees (nearly) no variance and the bilinear slope at the point.
TYPED_TEST(SeaLean, FootprintLimits) {
  using T = TypeParam;
  using L = Lean<T>;
  const int n = 16;
  const double patch = 4.0;
  std::vector<double> sx(n * n), sz(n * n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      sx[j * n + i] = 0.2 * std::sin(2 * M_PI * i / n) + 0.05;
      sz[j * n + i] = 0.1 * std::cos(2 * M_PI * j / n);
    }
  const std::vector<double> all = bilinearAverage(sx, sz, n, 0, n, 0, n);
  const std::vector<T> mips = buildMips<T>(sx, sz, n);
  T out[5];
  L::footprint(mips.data(), n, T(patch), T(1.37), T(-2.9), T(0.6), T(0.8), T(8 * patch), T(8 * patch), out);
  EXPECT_NEAR(double(out[0]), all[0], 1e-5);
  EXPECT_NEAR(double(out[2]), all[2] - all[0] * all[0], 1e-5);
  // A footprint of 1e-4 cell at a texel: the texel's slope, variance ~0.
  L::footprint(mips.data(), n, T(patch), T(3 * patch / n), T(5 * patch / n), T(1), T(0), T(patch / n * 1e-4),
               T(patch / n * 1e-4), out);
  EXPECT_NEAR(double(out[0]), sx[5 * n + 3], 1e-4);
  EXPECT_NEAR(double(out[1]), sz[5 * n + 3], 1e-4);
  EXPECT_LT(double(out[2]), 1e-6);
  // An elongated footprint (taps along x) averages along x only: the mean of sx over a whole period
  // along x is the constant 0.05, while z keeps (nearly) its local value.
  L::footprint(mips.data(), n, T(patch), T(0.0), T(0.0), T(1), T(0), T(patch / n), T(patch), out);
  EXPECT_NEAR(double(out[0]), 0.05, 0.02);
  EXPECT_NEAR(double(out[1]), 0.1, 0.02);
}

// E[F] over the Gaussian of slopes (back-facing facets bent to grazing, F = 1, as the unfiltered
// path does): the header's rule against a 1401 x 1401 midpoint rule over ±7σ in the Cholesky frame,
// for views from high to 1° above the horizon and slope variances of calm to very rough seas
// (Cox–Munk: 0.003 + 0.00512 U per axis, ~0.05 at 10 m/s).
TYPED_TEST(SeaLean, FresnelMeanMatchesFineQuadrature) {
  using T = TypeParam;
  using L = Lean<T>;
  const double ior = 1.34;
  int split_cases = 0;
  for (double elevation_deg : {60.0, 20.0, 12.0, 8.0, 3.0, 1.0}) {
    for (double var : {0.003, 0.01, 0.05, 0.1}) {
      const double e = elevation_deg * M_PI / 180;
      const auto d = L::vec(0, -std::sin(e), -std::cos(e));
      T cxx, czz, cxz, l11, l21, l22;
      L::covariance(T(var), T(0.6 * var), T(0.2 * var), T(0), &cxx, &czz, &cxz, &l11, &l21, &l22);
      const double mx = 0.02, mz = -0.03;
      bool split = false;
      const double rule = double(L::fresnelMean(d, T(mx), T(mz), l11, l21, l22, T(ior), &split));
      split_cases += split;
      // Fine reference in double, independent of the rule's nodes.
      const int m = 1401;
      double fine = 0, wsum = 0;
      const kd::real3 dd{double(d.x), double(d.y), double(d.z)};
      for (int i = 0; i < m; ++i)
        for (int j = 0; j < m; ++j) {
          const double u1 = -7 + 14.0 * i / (m - 1), u2 = -7 + 14.0 * j / (m - 1);
          const double w = std::exp(-0.5 * (u1 * u1 + u2 * u2));
          const double sx = mx + double(l11) * u1, sz = mz + double(l21) * u1 + double(l22) * u2;
          const kd::real3 nk = kd::sea_facing_normal(dd, kd::sea_lean_normal(sx, sz));
          fine += w * kd::fresnel_reflectance(-kd::dot(dd, nk), 1.0, ior);
          wsum += w;
        }
      fine /= wsum;
      EXPECT_NEAR(rule, fine, 4e-3 * fine) << "elevation " << elevation_deg << " var " << var;
      if (std::is_same_v<T, double>)
        std::printf("[ numbers  ] elevation %4.0f deg, slope variance %.3f: E[F] rule %.5f (%s), fine %.5f (%+.3f %%)\n",
                    elevation_deg, var, rule, split ? "split 8x3" : "GH 3x3", fine, 100 * (rule / fine - 1));
    }
  }
  EXPECT_GT(split_cases, 8);  // both rules are exercised
}

// The calm sea, no water colour: the filtered reflection is the sky times the flat Fresnel
// reflectance (within 1e-3), down to 0.5° above the horizon.
TYPED_TEST(SeaLean, CalmSeaReflectsSkyTimesFresnel) {
  using T = TypeParam;
  using L = Lean<T>;
  for (double elevation_deg : {80.0, 30.0, 5.0, 0.5}) {
    const double e = elevation_deg * M_PI / 180;
    const auto d = L::vec(std::cos(e), -std::sin(e), 0);
    T cxx, czz, cxz, l11, l21, l22;
    L::covariance(T(0), T(0), T(0), T(0), &cxx, &czz, &cxz, &l11, &l21, &l22);
    bool split = false;
    const double mean_f = double(L::fresnelMean(d, T(0), T(0), l11, l21, l22, T(1.34), &split));
    const double flat = kd::fresnel_reflectance(std::sin(e), 1.0, 1.34);
    EXPECT_NEAR(mean_f, flat, 1e-3 * flat) << elevation_deg;
  }
}

// The glint against Monte Carlo (double): facets drawn from the Gaussian, each reflecting the view
// ray; a mirror direction inside the sun's disk (radius ρ) sees radiance E/Ω. The estimate of the
// pixel's mean radiance per unit irradiance is Σ F / (N Ω) over the hits. With the disk's own
// variance added (ρ²/16 per axis, the header's model) the glint is the Gaussian convolved with the
// disk; the counts use ρ = 1° so that enough facets hit.
TYPED_TEST(SeaLean, GlintMatchesMonteCarlo) {
  using T = TypeParam;
  using L = Lean<T>;
  const double rho = 1.0 * M_PI / 180, omega = 2 * M_PI * (1 - std::cos(rho)), ior = 1.34;
  std::mt19937_64 rng(11);
  std::normal_distribution<double> gauss(0.0, 1.0);
  struct Case {
    double view_elev_deg, sun_elev_deg, sun_az_offset_deg, var;
  };
  for (const Case& c : {Case{30, 40, 0, 0.01}, Case{10, 20, 5, 0.02}, Case{45, 45, -10, 0.05}}) {
    const double ve = c.view_elev_deg * M_PI / 180, se = c.sun_elev_deg * M_PI / 180;
    const double az = c.sun_az_offset_deg * M_PI / 180;
    const kd::real3 d{0, -std::sin(ve), -std::cos(ve)};
    const kd::real3 sun{std::cos(se) * std::sin(az), std::sin(se), -std::cos(se) * std::cos(az)};
    const double mx = 0.01, mz = 0.02, vxx = c.var, vzz = 0.7 * c.var, vxz = 0.1 * c.var;
    T cxx, czz, cxz, l11, l21, l22;
    L::covariance(T(vxx), T(vzz), T(vxz), T(rho * rho / 16), &cxx, &czz, &cxz, &l11, &l21, &l22);
    const double model = double(L::glint(L::vec(d.x, d.y, d.z), L::vec(sun.x, sun.y, sun.z), T(ior), T(mx), T(mz), cxx,
                                         czz, cxz));
    // Monte Carlo over the Gaussian without the disk's variance (the disk is the real one here).
    double a11, a21, a22, dummy1, dummy2, dummy3;
    kd::sea_lean_covariance(vxx, vzz, vxz, 0.0, &dummy1, &dummy2, &dummy3, &a11, &a21, &a22);
    const long samples = 10000000;
    double sum = 0;
    const double cos_rho = std::cos(rho);
    for (long k = 0; k < samples; ++k) {
      const double u1 = gauss(rng), u2 = gauss(rng);
      const double sx = mx + a11 * u1, sz = mz + a21 * u1 + a22 * u2;
      const kd::real3 n = kd::sea_lean_normal(sx, sz);
      const double cos_i = -kd::dot(d, n);
      if (cos_i <= 0) continue;
      const kd::real3 r = kd::reflect_dir(d, n);
      if (kd::dot(r, sun) >= cos_rho) sum += kd::fresnel_reflectance(cos_i, 1.0, ior);
    }
    const double mc = sum / (samples * omega);
    const double hits = mc * samples * omega / 0.03;  // about how many facets hit (F ~ 0.03)
    std::printf("[ numbers  ] glint view %.0f deg, sun %.0f deg: model %.4f, Monte Carlo %.4f (%+.2f %%, ~%.0f hits)\n",
                c.view_elev_deg, c.sun_elev_deg, model, mc, 100 * (model / mc - 1), hits);
    EXPECT_NEAR(model, mc, 0.03 * mc) << c.view_elev_deg;
  }
}

// The pixel's glint is the glint's mean over the pixel's solid angle, against 64 x 64 directions: under
// ocean_sunset's 5° sun near the horizon (3 x 3 directions; the centre alone is 11–32 % off there) within
// 1 %, and under a 45° sun, where the glint is slow across the pixel and the centre alone is taken, within
// the rule's 1 %; a pixel half above the horizon counts its water half only; one wholly above has none.
TYPED_TEST(SeaLean, PixelGlintIsTheMeanOverThePixel) {
  using T = TypeParam;
  using L = Lean<T>;
  using V = typename L::V;
  const T ior = T(1.34), cxx = T(0.0079), czz = T(0.0199), cxz = T(0.0036);
  const double pixel = 2 * std::tan(55.0 * M_PI / 360) / 36;  // ocean_sunset's camera at 64 x 36
  auto scale = [](V v, double k) { return V{T(v.x * k), T(v.y * k), T(v.z * k)}; };
  auto add = [](V a, V b) { return V{a.x + b.x, a.y + b.y, a.z + b.z}; };
  const V fwd = L::unit(L::vec(0, -4, -80)), right = L::vec(1, 0, 0);
  const V up = L::unit(L::vec(0, 80, -4));
  const V du = scale(right, pixel), dv = scale(up, -pixel);
  struct Case {
    double elevation_deg, sun_zenith_deg, tolerance;
  };
  for (const Case& c : {Case{-2.0, 85.0, 0.01}, Case{-3.6, 85.0, 0.01}, Case{-7.0, 85.0, 0.01}, Case{-30.0, 45.0, 0.01}}) {
    const double e = c.elevation_deg * M_PI / 180, z = c.sun_zenith_deg * M_PI / 180;
    const V d = L::vec(0, std::sin(e), -std::cos(e));
    const V sun = L::vec(0, std::cos(z), -std::sin(z));
    const V centre = scale(d, 1 / dotd(d, fwd));
    double fine = 0;
    const int m = 64;
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) {
        const V dk = L::unit(add(centre, add(scale(du, (i + 0.5) / m - 0.5), scale(dv, (j + 0.5) / m - 0.5))));
        if (dk.y < 0) fine += double(L::glint(dk, sun, ior, T(0.0), T(0.01), cxx, czz, cxz));
      }
    fine /= m * m;
    const double got = double(L::pixelGlint(d, fwd, du, dv, sun, ior, T(0.0), T(0.01), cxx, czz, cxz));
    const double at_centre = double(L::glint(d, sun, ior, T(0.0), T(0.01), cxx, czz, cxz));
    std::printf("[ measured ] elevation %.1f°, sun %.0f°: pixel glint / 64x64 %.4f, centre / 64x64 %.4f\n", c.elevation_deg,
                c.sun_zenith_deg, got / fine, at_centre / fine);
    EXPECT_GT(fine, 0.0);
    EXPECT_NEAR(got / fine, 1.0, c.tolerance) << c.elevation_deg;
  }
  // A pixel wholly above the horizon: nothing; one across it: its part below.
  const V sun = L::vec(0, std::cos(85 * M_PI / 180), -std::sin(85 * M_PI / 180));
  const V high = L::unit(L::vec(0, 0.05, -1));
  EXPECT_EQ(double(L::pixelGlint(high, fwd, du, dv, sun, ior, T(0), T(0), cxx, czz, cxz)), 0.0);
  const V across = L::unit(L::vec(0, -1e-4, -1));
  const double part = double(L::pixelGlint(across, fwd, du, dv, sun, ior, T(0), T(0), cxx, czz, cxz));
  EXPECT_TRUE(std::isfinite(part));
  EXPECT_GT(part, 0.0);
}

// In the glint's tail a small move is a large factor: half a pixel that moves the half vector's slope by
// δ < 0.2 σ still changes exp(−q/2) by e^{d δ} at d σ from the facets' mean. Footprints drawn at random
// (slope variance 1e-4 to 0.03, views 0.3–15° below the horizon, suns 1–30° up, 480 x 270 pixels of a 55°
// camera), kept where the centre lies 2–5.8 σ from the mean and the pixel moves the slope by less than
// 0.2 σ: the pixel's glint within 1 % of the mean over 48 x 48 directions (the centre alone was up to 19 %
// off at 5–6 σ).
TYPED_TEST(SeaLean, PixelGlintIsTheMeanInTheTail) {
  using T = TypeParam;
  using L = Lean<T>;
  using V = typename L::V;
  auto scale = [](V v, double k) { return V{T(v.x * k), T(v.y * k), T(v.z * k)}; };
  auto add = [](V a, V b) { return V{a.x + b.x, a.y + b.y, a.z + b.z}; };
  const double pixel = 2 * std::tan(55.0 * M_PI / 360) / 270;
  const V fwd = L::unit(L::vec(0, -0.05, -1)), up = L::unit(L::vec(0, 1, -0.05));
  const V du = scale(L::vec(1, 0, 0), pixel), dv = scale(up, -pixel);
  const T ior = T(1.34), mx = T(0), mz = T(0.01);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0, 1);
  int cases = 0;
  double worst = 0;
  for (int c = 0; c < 20000 && cases < 300; ++c) {
    const double e = -(0.3 + 15 * u(rng)) * M_PI / 180, az = (u(rng) - 0.5) * 0.3;
    const double z = (60 + 29 * u(rng)) * M_PI / 180, saz = (u(rng) - 0.5) * 0.6;
    const double var = std::pow(10.0, -4 + 2.5 * u(rng));
    const T cxx = T(var), czz = T(var * (0.3 + 0.7 * u(rng))), cxz = T(0.2 * var * (u(rng) - 0.5));
    const V d = L::unit(L::vec(std::sin(az) * std::cos(e), std::sin(e), -std::cos(az) * std::cos(e)));
    const V sun = L::vec(std::sin(saz) * std::sin(z), std::cos(z), -std::cos(saz) * std::sin(z));
    // The centre's distance and the half pixel's move, in σ, from the double evaluation.
    const kd::real3 dd{double(d.x), double(d.y), double(d.z)}, sd{double(sun.x), double(sun.y), double(sun.z)};
    double sx, sz, cc;
    if (!kd::sea_lean_half_slope(dd, sd, &sx, &sz, &cc)) continue;
    const double det = double(cxx) * czz - double(cxz) * cxz;
    auto sigma2 = [&](double dx, double dz) { return (czz * dx * dx - 2 * double(cxz) * dx * dz + cxx * dz * dz) / det; };
    const double dist = std::sqrt(sigma2(sx - double(mx), sz - double(mz)));
    if (dist < 2 || dist > 5.8) continue;
    const V centre = scale(d, 1 / dotd(d, fwd));
    double move = 0;
    for (const V& half : {scale(du, 0.5), scale(dv, 0.5)}) {
      const V h = L::unit(add(centre, half));
      double ex, ez, ec;
      if (!kd::sea_lean_half_slope(kd::real3{double(h.x), double(h.y), double(h.z)}, sd, &ex, &ez, &ec)) move = 1;
      else move = std::max(move, sigma2(ex - sx, ez - sz));
    }
    if (move >= 0.04) continue;
    double fine = 0;
    const int m = 48;
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) {
        const V dk = L::unit(add(centre, add(scale(du, (i + 0.5) / m - 0.5), scale(dv, (j + 0.5) / m - 0.5))));
        if (dk.y < 0) fine += double(L::glint(dk, sun, ior, mx, mz, cxx, czz, cxz));
      }
    fine /= m * m;
    if (!(fine > 0)) continue;
    const double got = double(L::pixelGlint(d, fwd, du, dv, sun, ior, mx, mz, cxx, czz, cxz));
    worst = std::max(worst, std::fabs(got / fine - 1));
    EXPECT_NEAR(got / fine, 1.0, 0.01) << "case " << c << ": " << dist << " sigma from the mean";
    ++cases;
  }
  std::printf("[ measured ] %d tail pixels (2-5.8 sigma): worst |pixel glint / 48x48 - 1| %.4f\n", cases, worst);
  EXPECT_EQ(cases, 300);
}

TYPED_TEST(SeaLean, StiffCasesStayFinite) {
  using T = TypeParam;
  using L = Lean<T>;
  T cxx, czz, cxz, l11, l21, l22;
  // Zero variance and a point sun: the floor keeps det > 0; the glint is a huge but finite spike.
  L::covariance(T(0), T(0), T(0), T(0), &cxx, &czz, &cxz, &l11, &l21, &l22);
  const auto d = L::vec(0, -0.6, -0.8);
  const auto mirror_sun = L::vec(0, 0.6, -0.8);
  const T spike = L::glint(d, mirror_sun, T(1.34), T(0), T(0), cxx, czz, cxz);
  EXPECT_TRUE(std::isfinite(double(spike)));
  EXPECT_GT(double(spike), 0.0);
  // A correlation beyond ±1 (rounding of the differences of averages) is clamped: Cholesky exists.
  L::covariance(T(0.01), T(0.01), T(0.02), T(0), &cxx, &czz, &cxz, &l11, &l21, &l22);
  EXPECT_TRUE(std::isfinite(double(l22)));
  EXPECT_GT(double(cxx * czz - cxz * cxz), 0.0);
  // The sun at the horizon behind the view: half vector at the horizon, no glint.
  EXPECT_EQ(double(L::glint(L::vec(0, -1e-7, -1), L::vec(0, 0, 1), T(1.34), T(0), T(0), cxx, czz, cxz)), 0.0);
  // Sun exactly opposite the view (sun - d = 0): no half vector.
  EXPECT_EQ(double(L::glint(L::vec(0, -1, 0), L::vec(0, -1, 0), T(1.34), T(0), T(0), cxx, czz, cxz)), 0.0);
  // Steep mean slopes (capped) with a large variance, views from straight down to grazing: the rule
  // (either kind) gives a finite mean in [0, 1].
  L::covariance(T(50), T(50), T(0), T(0), &cxx, &czz, &cxz, &l11, &l21, &l22);
  for (const auto& view : {L::vec(0, -1, 0), d, L::vec(0, -1e-6, -1)}) {
    bool split = false;
    const double f = double(L::fresnelMean(view, T(20), T(-20), l11, l21, l22, T(1.34), &split));
    EXPECT_TRUE(std::isfinite(f));
    EXPECT_GE(f, 0.0);
    EXPECT_LE(f, 1.0 + 1e-6);
  }
}

}  // namespace
