// underwater_ordinates_bands_test.cpp — underwater.model = "discrete_ordinates" on the band lanes
// (kernels/common/underwater_ordinates_bands.h, one band per lane on the host) with its rows of the band
// table (host/underwater/underwater_band_table.cpp), against the scalar uwi_band_radiance of
// common/underwater_ordinates.h, in float and double: every material (none, surface, bottom, object), g
// from 0 to 0.95, clear to turbid water, no absorption (k at its floor), no scattering, the two-stream's
// resonance k = m, with and without a bottom, the sun high, low and at the horizon, the camera at the
// surface and at 1000 m, rays straight up and down, with and without the froxel split.
// tests/kernels/underwater_ordinates_kernel_test.cpp runs the lanes on PoCL in floatN.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include "math/kernel_math.h"
#include "underwater/underwater_band_table.h"
#include "underwater/underwater_ordinates_setup.h"
#include "underwater/underwater_ordinates_solver.h"

namespace {

namespace kd = seasim::kmath_d;
namespace kf = seasim::kmath_f;

constexpr int kBands = 5;

// Five bands of one water type family, g, bottom depth H (0: none) and sun cosine in water mu_w; the
// two-stream's bands, or (ordinates) the discrete ordinates' (the default diffuse).
seasim::UnderwaterSetup makeSetup(double g, double H, double mu_w, double a0, double b0, bool ordinates = false) {
  seasim::UnderwaterSetup s;
  s.params.g = float(g);
  s.params.bottom_depth = float(H);
  s.params.ior = 1.34f;
  s.params.sun_dir_water[0] = float(std::sqrt(1 - mu_w * mu_w));
  s.params.sun_dir_water[1] = float(mu_w);
  s.params.band_count = kBands;
  s.params.object_count = 2;
  for (int k = 0; k < kBands; ++k) {
    UwBand v{};
    v.a = float(a0 * (1 + 0.3 * k));
    v.b = float(b0 * (1 - 0.1 * k));
    v.c = v.a + v.b;
    v.kd = 0.2f;  // the thesis's; unused by the discrete-ordinates model
    v.e_sky0 = float(0.3 + 0.05 * k);
    v.e_sun0 = float(1.0 - 0.1 * k);
    v.e_beam0 = float(v.e_sun0 / mu_w);
    v.sky_radiance = float(0.1 + 0.02 * k);
    v.bottom_albedo = float(0.2 + 0.05 * k);
    v.w_r = 0.3f;
    v.w_g = 0.5f;
    v.w_b = 0.2f;
    s.bands.push_back(v);
  }
  s.objects.resize(2);
  for (int o = 0; o < 2; ++o)
    for (int k = 0; k < kBands; ++k) s.albedo.push_back(float(0.1 + 0.2 * o + 0.05 * k));
  s.ordinates = ordinates ? seasim::makeUwiBandsFromOrdinates(s.params, s.bands)
                         : seasim::makeUwiBands(s.params, s.bands, seasim::diffuseMeanCosines(g));
  return s;
}

struct Ray {
  int mat;
  double S, o_d, vis, sky_l;
  double d[3], n[3], s_w[3];
  // Surface hits: the object the reflected ray meets (uwi_surface's UwiMirrorHit; s_m = 1e30: none).
  double s_m = 1e30;
  int mat_m = 1;
  double n_m[3] = {0.0, 0.6, 0.8};
  double vis_m = 1.0;
  double vis_b = 1.0;  // the share of the sand an object's face sees that is sunlit (uwi_bottom_visibility)
};

// kd_multiple.cl's discrete-ordinates band loop for band k (real = float or double): the per-pixel phases, the
// lanes, the material chosen per pixel.
#define LANES_RADIANCE(NS, Real)                                                                              \
  Real lanes_##NS(const std::vector<float>& table, const seasim::UnderwaterSetup& s, int k, const Ray& r,    \
                  int single) {                                                                              \
    namespace ns = seasim::kmath_##NS;                                                                       \
    const int stride = UW_BAND_STRIDE(kBands), uwi_row0 = UW_ROWS + s.params.object_count;                   \
    const ns::real3 d{Real(r.d[0]), Real(r.d[1]), Real(r.d[2])}, s_w{Real(r.s_w[0]), Real(r.s_w[1]),        \
                                                                     Real(r.s_w[2])};                        \
    const ns::real3 n{Real(r.n[0]), Real(r.n[1]), Real(r.n[2])};                                             \
    const Real S = Real(r.S), o_d = Real(r.o_d), H = Real(s.params.bottom_depth), g = Real(s.params.g);      \
    const Real cos_s = ns::dot(d, s_w);                                                                      \
    const Real phase = ns::hg_phase(cos_s, g);                                                               \
    const Real cos_r = cos_s - Real(2) * d.y * s_w.y;                                                        \
    const Real phase_r = ns::hg_phase(cos_r, g);                                                             \
    const int node = ns::uwi_source_node(d.y), node_r = ns::uwi_source_node(-d.y);                         \
    const Real cos_dphi = ns::uwi_cos_azimuth(cos_s, d.y, s_w.y);                                           \
    const Real cos_dphi_r = ns::uwi_cos_azimuth(cos_r, -d.y, s_w.y);                                        \
    ns::UwiLanes v;                                                                                      \
    ns::uwi_lanes_load(table.data(), stride, uwi_row0, k, &v);                                           \
    ns::UwiWeights w, w_r;                                                                               \
    ns::uwi_lanes_weights(table.data(), stride, uwi_row0, k, node, cos_dphi, &w);                        \
    ns::uwi_lanes_weights(table.data(), stride, uwi_row0, k, node_r, cos_dphi_r, &w_r);                  \
    ns::UwiStart a;                                                                                      \
    ns::uwi_start_camera(table.data(), stride, uwi_row0, k, &a);                                         \
    auto row = [&](int rw) { return Real(table[size_t(rw) * stride + k]); };                                 \
    const Real y = std::max(o_d - S * d.y, Real(0));                                                         \
    ns::UwiEnds e;                                                                                       \
    ns::uwi_ends(&v, H, S, y, single, &e);                                                               \
    Real strict;                                                                                             \
    Real L = ns::uwi_lanes_multiple(&v, &w, &a, &e, phase, H, S, d.y, single, &strict);                      \
    Real frac_a;                                                                                             \
    const int node_a = ns::uwi_aureole_node(cos_s, &frac_a);                                                 \
    L = std::max(L + ns::uwi_lanes_forward_peak(table.data(), stride, uwi_row0, k, &v, node_a, frac_a, node, cos_dphi, phase, \
                                                d.y, o_d, r.mat == UW_MAT_SURFACE ? Real(0) : y, s_w.y, strict), \
                 Real(0));                                                                                   \
    if (r.mat == UW_MAT_SURFACE) {                                                                           \
      const ns::real3 n_m{Real(r.n_m[0]), Real(r.n_m[1]), Real(r.n_m[2])};                                   \
      Real frac_m;                                                                                           \
      const int tilt_node_m = ns::uwi_tilt_node(n_m.y, &frac_m);                                             \
      const Real cos_phi_m = ns::uwi_cos_azimuth(ns::dot(n_m, s_w), n_m.y, s_w.y);                           \
      ns::UwiWeights tilt_m;                                                                             \
      if (r.s_m < Real(1e29))                                                                            \
        ns::uwi_lanes_tilt(table.data(), stride, uwi_row0, k, tilt_node_m, frac_m, cos_phi_m, Real(1), &tilt_m);\
      else                                                                                               \
        ns::uwi_lanes_down(&v, &tilt_m);                                                                 \
      L += ns::uwi_lanes_surface(&v, &w_r, e.k, Real(r.sky_l), row(uwi_row0 + UWI_ROW_BOTTOM_L),         \
                                 row(uwi_row0 + UWI_ROW_EXP_K_H), phase_r, H, d.y, Real(s.params.ior), 1,    \
                                 Real(r.s_m), row(UW_ROWS + r.mat_m), &tilt_m, ns::dot(n_m, s_w), Real(r.vis_m)); \
    } else if (r.mat == UW_MAT_BOTTOM) {                                                                     \
      ns::UwiWeights down;                                                                               \
      ns::uwi_lanes_down(&v, &down);                                                                     \
      L += ns::uwi_lanes_lambert(&v, &e, &down, row(UW_ROW_BOTTOM_ALBEDO), H, ns::dot(n, s_w), Real(r.vis)); \
    } else if (r.mat != UW_MAT_NONE) {                                                                       \
      Real frac;                                                                                             \
      const int tilt_node = ns::uwi_tilt_node(n.y, &frac);                                                   \
      ns::UwiWeights tilt;                                                                               \
      ns::uwi_lanes_tilt(table.data(), stride, uwi_row0, k, tilt_node, frac,                             \
                         ns::uwi_cos_azimuth(ns::dot(n, s_w), n.y, s_w.y), Real(r.vis_b), &tilt);        \
      L += ns::uwi_lanes_lambert(&v, &e, &tilt, row(UW_ROWS + r.mat), H, ns::dot(n, s_w), Real(r.vis));      \
    }                                                                                                        \
    return L;                                                                                                \
  }
LANES_RADIANCE(d, double)
LANES_RADIANCE(f, float)
#undef LANES_RADIANCE

double scalarRadiance(const seasim::UnderwaterSetup& s, int k, const Ray& r, int single) {
  const UwBand& b = s.bands[k];
  const double albedo = r.mat >= 0 ? s.albedo[size_t(r.mat) * kBands + k] : b.bottom_albedo;
  const kd::real3 d{r.d[0], r.d[1], r.d[2]}, n{r.n[0], r.n[1], r.n[2]}, s_w{r.s_w[0], r.s_w[1], r.s_w[2]};
  const kd::UwiMirrorHit m{r.s_m, kd::real3{r.n_m[0], r.n_m[1], r.n_m[2]}, s.albedo[size_t(r.mat_m) * kBands + k],
                           r.vis_m};
  return kd::uwi_band_radiance(&s.ordinates[k], &b, s.params.g, r.mat, r.S, n, d, r.o_d, s_w, albedo, r.vis, r.vis_b, r.sky_l,
                               s.params.ior, s.params.bottom_depth, single, 1, m);
}

float scalarRadianceFloat(const seasim::UnderwaterSetup& s, int k, const Ray& r, int single) {
  const UwBand& b = s.bands[k];
  const float albedo = r.mat >= 0 ? s.albedo[size_t(r.mat) * kBands + k] : b.bottom_albedo;
  const kf::real3 d{float(r.d[0]), float(r.d[1]), float(r.d[2])}, n{float(r.n[0]), float(r.n[1]), float(r.n[2])};
  const kf::real3 s_w{float(r.s_w[0]), float(r.s_w[1]), float(r.s_w[2])};
  const kf::UwiMirrorHit m{float(r.s_m), kf::real3{float(r.n_m[0]), float(r.n_m[1]), float(r.n_m[2])},
                           s.albedo[size_t(r.mat_m) * kBands + k], float(r.vis_m)};
  return kf::uwi_band_radiance(&s.ordinates[k], &b, s.params.g, r.mat, float(r.S), n, d, float(r.o_d), s_w, albedo,
                               float(r.vis), float(r.vis_b), float(r.sky_l), s.params.ior, s.params.bottom_depth, single,
                               1, m);
}

TEST(UnderwaterOrdinatesBands, TableRowsHoldTheBlockAndPaddingIsWeightless) {
  const seasim::UnderwaterSetup s = makeSetup(0.9, 5.0, 0.8, 0.1, 0.3);
  const std::vector<float> t = seasim::underwaterBandTable(s);
  const int stride = UW_BAND_STRIDE(kBands), row0 = UW_ROWS + 2;
  ASSERT_EQ(t.size(), size_t(row0 + UWI_ROWS) * stride);
  auto at = [&](int row, int k) { return t[size_t(row) * stride + k]; };
  for (int k = 0; k < stride; ++k) {
    const UwiBand& ib = s.ordinates[std::min(k, kBands - 1)];
    EXPECT_EQ(at(UW_ROW_W_G, k), k < kBands ? 0.5f : 0.0f);
    EXPECT_EQ(at(row0 + UWI_ROW_K, k), ib.k);
    EXPECT_EQ(at(row0 + UWI_ROW_D2, k), ib.d2);
    EXPECT_EQ(at(row0 + UWI_ROW_DP, k), ib.dp);
    EXPECT_EQ(at(row0 + UWI_ROW_C_DM, k), ib.c_dm);
    EXPECT_EQ(at(row0 + UWI_ROW_M, k), ib.m);
    // The source's rows are the band's table, and the lanes' weights are uwi_source_weight at every ν and
    // azimuth.
    for (int q = 0; q < UWI_SOURCE_NODES * UWI_SOURCE_TERMS; ++q) ASSERT_EQ(at(row0 + UWI_ROW_SRC + q, k), ib.src[q]) << q;
    for (int q = 0; q < UWI_TILT_NODES * UWI_SOURCE_TERMS; ++q) ASSERT_EQ(at(row0 + UWI_ROW_TILT + q, k), ib.tilt[q]) << q;
    for (int q = 0; q < UWI_TILT_NODES * 3; ++q) ASSERT_EQ(at(row0 + UWI_ROW_TILT_BOTTOM + q, k), ib.tilt_bottom[q]) << q;
    for (double nu : {-1.0, -0.3, 0.0, 0.7, 1.0})
      for (double cos_dphi : {-0.6, 0.0, 1.0}) {
        const int node = kd::uwi_source_node(nu);
        kd::UwiWeights w;
        kd::uwi_lanes_weights(t.data(), stride, row0, k, node, cos_dphi, &w);
        for (int q = 0; q < 3; ++q) {
          const double expect = kd::uwi_source_weight(&ib, node, cos_dphi, q);
          EXPECT_NEAR(q == 0 ? w.w1 : q == 1 ? w.w2 : w.wp, expect, 1e-12 * std::fabs(expect) + 1e-30) << nu;
        }
      }
    for (int r = 0; r < UWI_ROWS; ++r) EXPECT_TRUE(std::isfinite(at(row0 + r, k))) << r;
  }
  EXPECT_GT(at(row0 + UWI_ROW_BOTTOM_L, 0), 0.0f);
  // No bottom: no bottom radiance; the thesis model: no discrete-ordinates rows.
  EXPECT_EQ(seasim::underwaterBandTable(makeSetup(0.9, 0.0, 0.8, 0.1, 0.3))[size_t(row0 + UWI_ROW_BOTTOM_L) * stride],
            0.0f);
  seasim::UnderwaterSetup thesis = s;
  thesis.ordinates.clear();
  EXPECT_EQ(seasim::underwaterBandTable(thesis).size(), size_t(row0) * stride);
}

// The start factors of the camera's integrals are taken at the camera's depth and follow it: at the
// surface 1 (the bottom's e^{-k H}), at 3 m e^{-κ 3}, below the bottom's depth the bottom's factor clamps
// at 1, and at 1000 m they underflow to 0 without turning into NaN or Inf; e^{-k H} does not move.
TEST(UnderwaterOrdinatesBands, CameraRowsAreTheStartFactorsAtTheCamerasDepth) {
  const int stride = UW_BAND_STRIDE(kBands), row0 = UW_ROWS + 2;
  for (double o_d : {0.0, 3.0, 6.0, 1000.0})
    for (double mu_w : {0.8, 1e-3}) {
      seasim::UnderwaterSetup s = makeSetup(0.9, 5.0, mu_w, 0.1, 0.3);
      s.params.cam_pos[1] = float(-o_d);
      const std::vector<float> t = seasim::underwaterBandTable(s);
      auto at = [&](int row, int k) { return double(t[size_t(row) * stride + k]); };
      for (int k = 0; k < stride; ++k) {
        const UwiBand& ib = s.ordinates[std::min(k, kBands - 1)];
        const double k_beam = at(UW_ROW_K_BEAM, k);
        const double expect[][2] = {{UWI_ROW_EXP_K_OD, std::exp(-double(ib.k) * o_d)},
                                    {UWI_ROW_EXP_M_OD, std::exp(-double(ib.m) * o_d)},
                                    {UWI_ROW_EXP_BEAM_OD, std::exp(-k_beam * o_d)},
                                    {UWI_ROW_EXP_K_HOD, std::exp(-double(ib.k) * std::max(5.0 - o_d, 0.0))},
                                    {UWI_ROW_EXP_K_H, std::exp(-double(ib.k) * 5.0)}};
        for (const auto& [row, value] : expect) {
          const double v = at(row0 + int(row), k);
          ASSERT_TRUE(std::isfinite(v) && v >= 0 && v <= 1) << row << " " << o_d;
          EXPECT_NEAR(v, value, 1e-7 * value + 1e-37) << row << " o_d " << o_d << " mu_w " << mu_w << " k " << k;
        }
      }
      if (o_d == 3.0) EXPECT_GT(at(row0 + UWI_ROW_EXP_K_OD, 0), 0.5);  // a real factor, not a default 0 or 1
      if (o_d == 3.0) EXPECT_LT(at(row0 + UWI_ROW_EXP_K_OD, 0), 0.999);
      if (o_d >= 5.0) EXPECT_EQ(at(row0 + UWI_ROW_EXP_K_HOD, 0), 1.0);
    }
}

TEST(UnderwaterOrdinatesBands, LanesMatchTheScalarModelInFloatAndDouble) {
  struct Water {
    double a, b;
  };
  // Clear, the issue's, turbid 9C-like, no scattering, no absorption (k at its floor), and the
  // two-stream's resonance k ≈ m (a = 1, b = 0.2 at g = 0 and a low sun).
  const Water waters[] = {{0.03, 0.05}, {0.1, 0.3}, {3.0, 7.0}, {0.2, 0.0}, {0.0, 0.2}, {1.0, 0.2}};
  int checked = 0;
  double worst_d = 0, worst_f = 0, worst_ff = 0;
  for (const Water& w : waters)
    for (double g : {0.0, 0.5, 0.9, 0.95})
      for (double H : {0.0, 5.0, 40.0})
        for (double mu_w : {0.95, 0.3, 1e-3})
          for (bool ordinates : {false, true}) {
          const seasim::UnderwaterSetup s = makeSetup(g, H, mu_w, w.a, w.b, ordinates);
          // The same with every E_d, E_u and source coefficient made positive: the size of the terms that cancel
          // (without absorption k sits at its floor and the bottom's pair e^{-k y}, e^{-k (H - y)}
          // carries large coefficients of opposite sign), against which rounding is measured.
          seasim::UnderwaterSetup magnitude = s;
          for (UwiBand& ib : magnitude.ordinates) {
            for (float* v : {&ib.d1, &ib.u1, &ib.d2, &ib.u2, &ib.dp, &ib.up})
              *v = std::fabs(*v);
            for (float& v : ib.src) v = std::fabs(v);
            for (float& v : ib.tilt) v = std::fabs(v);
            for (float& v : ib.tilt_bottom) v = std::fabs(v);
          }
          const double s_w[3] = {std::sqrt(1 - mu_w * mu_w), mu_w, 0};
          for (double o_d : {0.0, 1e-4, 3.0, 1000.0}) {
            if (H > 0 && o_d >= H) continue;
            // The camera's rays start at its depth: the table's per-frame rows are taken there.
            seasim::UnderwaterSetup at_depth = s;
            at_depth.params.cam_pos[1] = float(-o_d);
            const std::vector<float> table = seasim::underwaterBandTable(at_depth);
            // Rays at the listed verticals, and along the refracted sun and 2° off it: the forward peak's
            // aureole and its strict single scattering, taken off with froxels.
            std::vector<std::array<double, 3>> dirs;
            for (double d_y : {-1.0, -0.6, -0.2, 0.0, 0.3, 0.7, 1.0}) {
              const double dx = std::sqrt(1 - d_y * d_y);
              dirs.push_back({dx * 0.6, d_y, -dx * 0.8});
            }
            const double off = 2.0 * 3.14159265358979 / 180;
            dirs.push_back({s_w[0], s_w[1], s_w[2]});
            dirs.push_back({s_w[0] * std::cos(off) - s_w[1] * std::sin(off), s_w[0] * std::sin(off) + s_w[1] * std::cos(off), 0});
            for (const auto& dir : dirs)
              for (int mat : {UW_MAT_NONE, UW_MAT_SURFACE, UW_MAT_BOTTOM, 0, 1}) {
                const double d_y = dir[1];
                if (mat == UW_MAT_SURFACE && d_y <= 0) continue;
                if (mat == UW_MAT_BOTTOM && !(H > 0 && d_y < 0)) continue;
                if (mat == UW_MAT_NONE && (d_y > 0 || H > 0 && d_y < 0)) continue;  // it meets surface or bottom
                for (double S : {0.0, 1e-3, 2.0, 30.0}) {
                  Ray r{mat, S, o_d, 0.7, 0.15, {dir[0], dir[1], dir[2]}, {0.6, 0.8, 0}, {s_w[0], s_w[1], s_w[2]}};
                  // Surface hits: an object in the mirror (lit or in shadow) at S's distance, or none.
                  if (mat == UW_MAT_SURFACE && S == 1e-3) continue;  // S = 0: none
                  if (mat == UW_MAT_SURFACE && S == 2.0) r.s_m = 1.5, r.vis_m = 0.0;
                  if (mat == UW_MAT_SURFACE && S == 30.0) r.s_m = 3.0;
                  if (mat == UW_MAT_NONE) r.S = 1e30;
                  if (mat == UW_MAT_SURFACE) r.S = o_d / d_y;
                  if (mat == UW_MAT_BOTTOM) r.S = (H - o_d) / -d_y, r.n[0] = 0, r.n[1] = 1;
                  // Object 1 faces down and sideways, off the sun's azimuth (the tilted table's lower
                  // nodes and its azimuth modes).
                  // Object 1 sees sand in shadow: all of it where it is far, 5/8 at 2 m (vis_b: the tilted
                  // table's bottom part taken off in that share).
                  if (mat == 1) r.n[0] = 0.48, r.n[1] = -0.6, r.n[2] = 0.64, r.vis_b = S == 30.0 ? 0.0 : S == 2.0 ? 0.375 : 1.0;
                  if (mat >= 0 && o_d - S * d_y < 0) continue;  // above the surface
                  if (mat >= 0 && H > 0 && o_d - S * d_y > H) continue;  // below the bottom
                  for (int single : {0, 1})
                    for (int k = 0; k < kBands; ++k) {
                      const double ref = scalarRadiance(s, k, r, single);
                      const double ld = lanes_d(table, s, k, r, single);
                      const float lf = lanes_f(table, s, k, r, single);
                      const float rf = scalarRadianceFloat(s, k, r, single);
                      ASSERT_TRUE(std::isfinite(ld) && std::isfinite(lf) && ld >= 0 && lf >= 0);
                      // Relative to the size of the terms (the value, or the terms that cancel in it:
                      // the coefficients' signs, the froxel term taken off), and per unit exponent as
                      // the float rounding of an exponent of size x moves e^x by x ε.
                      const double size = std::fabs(ref) + scalarRadiance(magnitude, k, r, 0);
                      const double scale = (size + 1e-9 * (s.bands[k].e_sky0 + s.bands[k].e_sun0)) *
                                           (1 + s.bands[k].c * std::min(r.S, 1e3) + s.ordinates[k].k * o_d);
                      worst_d = std::max(worst_d, std::fabs(ld - ref) / scale);
                      worst_f = std::max(worst_f, std::fabs(lf - ref) / scale);
                      worst_ff = std::max(worst_ff, std::fabs(double(rf) - ref) / scale);
                      EXPECT_NEAR(ld, ref, 1e-6 * scale) << w.a << ":" << w.b << " g " << g << " H " << H << " mu "
                                                         << mu_w << " o_d " << o_d << " d_y " << d_y << " mat " << mat
                                                         << " S " << r.S << " single " << single << " k " << k;
                      EXPECT_NEAR(lf, ref, 2e-5 * scale) << w.a << ":" << w.b << " g " << g << " H " << H << " mu "
                                                         << mu_w << " o_d " << o_d << " d_y " << d_y << " mat " << mat
                                                         << " S " << r.S << " single " << single << " k " << k;
                      ++checked;
                    }
                }
              }
          }
        }
  EXPECT_GT(checked, 20000);
  std::printf("discrete-ordinates lanes vs scalar uwi_band_radiance (double): lanes double %.2e, lanes float %.2e, scalar "
              "float %.2e (relative, per unit exponent; %d values)\n",
              worst_d, worst_f, worst_ff, checked);
}

}  // namespace
