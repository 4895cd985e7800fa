// underwater_bands_test.cpp — kd_multiple.cl's band lanes (kernels/common/underwater_bands.h, one band
// per lane on the host) and its band table (host/underwater/underwater_band_table.cpp) against the
// scalar model of common/underwater.h, in float and double: every material, 002 eq. 4.7's singular
// line, deep water (S = ∞), the camera at the surface and at 1000 m, rays straight up and down, with
// and without the froxel split of the direct sun. tests/kernels/underwater_kd_test.cpp runs the lanes
// on PoCL in floatN against the double CPU evaluation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "math/kernel_math.h"
#include "underwater/underwater_band_table.h"

namespace {

namespace kd = seasim::kmath_d;
namespace kf = seasim::kmath_f;

// Three bands around the singular line K_d d_y = σ_t (K_d = 0.5, σ_t = 0.25 crosses at d_y = 0.5),
// clear water (K_d above σ_t/μ_w: the diffuse remainder clamps), no scattering, and turbid 9C.
seasim::UnderwaterSetup makeSetup(float mu_w) {
  seasim::UnderwaterSetup s;
  s.params.sun_dir_water[1] = mu_w;
  auto band = [](float a, float b, float kd, float e_sky0, float e_sun0, float mu) {
    UwBand v{};
    v.a = a;
    v.b = b;
    v.c = a + b;
    v.kd = kd;
    v.e_sky0 = e_sky0;
    v.e_sun0 = e_sun0;
    v.e_beam0 = e_sun0 / std::max(mu, 1e-4f);
    v.sky_radiance = 0.7f;
    v.bottom_albedo = 0.25f;
    v.w_r = 0.3f;
    v.w_g = 0.5f;
    v.w_b = 0.2f;
    v.sky_w_r = 0.2f;
    v.sky_w_g = 0.3f;
    v.sky_w_b = 0.5f;
    return v;
  };
  s.bands = {band(0.15f, 0.1f, 0.5f, 1.0f, 2.0f, mu_w), band(0.02f, 0.01f, 0.3f, 0.5f, 1.5f, mu_w),
             band(0.2f, 0.0f, 0.25f, 1.0f, 1.0f, mu_w), band(3.0f, 7.0f, 3.0f, 0.2f, 0.4f, mu_w)};
  s.objects.resize(2);
  s.params.object_count = 2;  // as makeUnderwaterSetup keeps them: the table's object rows follow it
  for (int o = 0; o < 2; ++o)
    for (int k = 0; k < 4; ++k) s.albedo.push_back(0.1f + 0.2f * o + 0.05f * k);
  return s;
}

// T(S) L_s + L_MS from the band lanes (real = float or double) for band k of the table.
template <typename Real, typename Lanes>
Real lanesRadiance(const std::vector<float>& table, int stride, int k, int mat, Real S, Real d_y, Real o_d,
                   Real n_y, Real n_dot_s, Real vis, Real ior, Real bottom_depth, int single, Lanes lanes) {
  auto row = [&](int r) { return static_cast<Real>(table[static_cast<size_t>(r) * stride + k]); };
  Real L = lanes.multiple(row(UW_ROW_MS_TOTAL), row(UW_ROW_MS_DIRECT), row(UW_ROW_KD), row(UW_ROW_K_BEAM),
                          row(UW_ROW_C), single, d_y, o_d, S);
  if (mat == UW_MAT_SURFACE) {
    L += lanes.surface(row(UW_ROW_SKY), row(UW_ROW_MS_TOTAL), row(UW_ROW_MS_DIRECT), row(UW_ROW_KD),
                       row(UW_ROW_K_BEAM), row(UW_ROW_C), single, 1, S, d_y, ior, bottom_depth);
  } else if (mat != UW_MAT_NONE) {
    const Real y = std::max(o_d - S * d_y, Real(0));
    L += lanes.lambert(row(mat >= 0 ? UW_ROWS + mat : UW_ROW_BOTTOM_ALBEDO), row(UW_ROW_C), row(UW_ROW_KD),
                       row(UW_ROW_K_BEAM), row(UW_ROW_E_TOTAL), row(UW_ROW_E_SUN), row(UW_ROW_E_BEAM), single, S, y,
                       n_y, n_dot_s, vis);
  }
  return L;
}

template <typename Real>
struct LanesOf;
template <>
struct LanesOf<double> {
  static double multiple(double a, double b, double c, double d, double e, int s, double f, double g, double h) {
    return kd::uw_lanes_multiple(a, b, c, d, e, s, f, g, h);
  }
  static double surface(double a, double b, double c, double d, double e, double f, int s, int m, double g,
                        double h, double i, double j) {
    return kd::uw_lanes_surface(a, b, c, d, e, f, s, m, g, h, i, j);
  }
  static double lambert(double a, double b, double c, double d, double e, double f, double g, int s, double h,
                        double i, double j, double k, double l) {
    return kd::uw_lanes_lambert(a, b, c, d, e, f, g, s, h, i, j, k, l);
  }
};
template <>
struct LanesOf<float> {
  static float multiple(float a, float b, float c, float d, float e, int s, float f, float g, float h) {
    return kf::uw_lanes_multiple(a, b, c, d, e, s, f, g, h);
  }
  static float surface(float a, float b, float c, float d, float e, float f, int s, int m, float g, float h,
                       float i, float j) {
    return kf::uw_lanes_surface(a, b, c, d, e, f, s, m, g, h, i, j);
  }
  static float lambert(float a, float b, float c, float d, float e, float f, float g, int s, float h, float i,
                       float j, float k, float l) {
    return kf::uw_lanes_lambert(a, b, c, d, e, f, g, s, h, i, j, k, l);
  }
};

TEST(UnderwaterBands, Expm1OverXLanesIsTheScalarFunction) {
  for (double x : {0.0, 1e-30, -1e-30, 1e-8, -1e-8, 0.499999, -0.499999, 0.5, -0.5, -3.0, -80.0, -1e4, 40.0}) {
    EXPECT_EQ(kd::expm1_over_x_b(x), kd::expm1_over_x(x)) << x;
    EXPECT_EQ(kf::expm1_over_x_b(float(x)), kf::expm1_over_x(float(x))) << x;
  }
}

// kd_exp_integral_ends_b (no exp: its start factor e^{-k o_d} given, as the discrete-ordinates model's rows give
// it, and its far end e^{-(k y(S) + c S)}, as the hit's irradiance takes it) against the general
// kd_exp_integral in double: across its switch to the series at |t| = 0.5, on
// the singular line k d_y = c (and 1e-7 off it), deep water (S = ∞), a camera at 1000 m looking up
// (e^{-k o_d} far below float's range, 0 in the float table), and the divergent case.
TEST(UnderwaterBands, IntegralFromItsStartFactorIsTheGeneralOne) {
  int checked = 0;
  double worst_d = 0, worst_f = 0;
  for (double k : {0.0, 0.05, 0.5, 3.0})
    for (double c : {0.0, 0.25, 1.0, 10.0})
      for (double d_y : {-1.0, -0.3, 0.0, 0.5, 1.0})
        for (double o_d : {0.0, 1e-4, 3.0, 1000.0})
          for (double S : {0.0, 1e-3, 0.5, 2.0, 30.0, 1e30}) {
            if (d_y > 0 && S * d_y > o_d) continue;  // past the surface
            // x = k d_y - c on and near 0, t = x S on both sides of the series' switch at |t| = 0.5.
            for (double c_shift : {0.0, 1e-7, -1e-7, 0.5 / std::max(S, 1e-30) + 1e-6, -0.5 / std::max(S, 1e-30)}) {
              const double cc = c + (c == 0.25 ? k * d_y - c + c_shift : 0.0);  // c = 0.25 marks "x near 0"
              if (cc < 0) continue;
              const double ref = kd::kd_exp_integral(k, cc, d_y, o_d, S);
              const float a_f = float(std::exp(-k * o_d));  // the table's row, rounded to float
              // The far end as the lanes take it, in double and float (y = max(y(S), 0)).
              const double b_d = std::exp(-(k * std::max(o_d - S * d_y, 0.0) + cc * S));
              const float yf = std::max(float(o_d) - float(S) * float(d_y), 0.0f);
              const float b_f = std::exp(-(float(k) * yf + float(cc) * float(S)));
              const double vd = kd::kd_exp_integral_ends_b(k, cc, double(a_f), b_d, d_y, S);
              const float vf = kf::kd_exp_integral_ends_b(float(k), float(cc), a_f, b_f, float(d_y), float(S));
              ASSERT_TRUE(std::isfinite(vd) && std::isfinite(vf) && vd >= 0 && vf >= 0)
                  << k << " " << cc << " " << d_y << " " << o_d << " " << S;
              // Relative to the value, per unit exponent (float rounding of an exponent x moves e^x by
              // x ε); 1e-30 absolute where e^{-k o_d} is below float's range (it is 0 in the table).
              const double scale = (std::fabs(ref) + 1e-30) * (1 + k * o_d + std::fabs(k * d_y - cc) * std::min(S, 1e3));
              worst_d = std::max(worst_d, std::fabs(vd - ref) / scale);
              worst_f = std::max(worst_f, std::fabs(vf - ref) / scale);
              EXPECT_NEAR(vd, ref, 2e-7 * scale) << k << " " << cc << " " << d_y << " " << o_d << " " << S;
              EXPECT_NEAR(vf, ref, 2e-6 * scale) << k << " " << cc << " " << d_y << " " << o_d << " " << S;
              ++checked;
            }
          }
  EXPECT_GT(checked, 1500);
  // A wrong start factor shows: e^{-k o_d} at another depth moves the value by the ratio.
  // A wrong end shows: e^{-k o_d} at another depth, or the far end at another distance.
  const double right = kd::kd_exp_integral(0.5, 1.0, -0.5, 3.0, 2.0), b = std::exp(-(0.5 * 4.0 + 2.0));
  EXPECT_NEAR(kd::kd_exp_integral_ends_b(0.5, 1.0, std::exp(-0.5 * 3.0), b, -0.5, 2.0), right, 1e-12);
  EXPECT_GT(std::fabs(kd::kd_exp_integral_ends_b(0.5, 1.0, std::exp(-0.5 * 2.9), b, -0.5, 2.0) - right), 0.04 * right);
  EXPECT_GT(std::fabs(kd::kd_exp_integral_ends_b(0.5, 1.0, std::exp(-0.5 * 3.0), b * 1.5, -0.5, 2.0) - right),
            0.04 * right);
  std::printf("kd_exp_integral_ends_b vs kd_exp_integral: double %.2e, float %.2e (relative, per unit exponent; "
              "%d values)\n",
              worst_d, worst_f, checked);
}

TEST(UnderwaterBands, TableIsPaddedWithWeightlessCopiesOfTheLastBand) {
  const seasim::UnderwaterSetup s = makeSetup(0.8f);
  const std::vector<float> t = seasim::underwaterBandTable(s);
  const int stride = UW_BAND_STRIDE(4);
  ASSERT_EQ(stride, 16);
  ASSERT_EQ(t.size(), size_t(UW_ROWS + 2) * stride);
  auto at = [&](int row, int k) { return t[size_t(row) * stride + k]; };
  for (int k = 0; k < stride; ++k) {
    const UwBand& b = s.bands[std::min(k, 3)];
    EXPECT_EQ(at(UW_ROW_W_R, k), k < 4 ? b.w_r : 0.0f);
    EXPECT_EQ(at(UW_ROW_W_B, k), k < 4 ? b.w_b : 0.0f);
    EXPECT_EQ(at(UW_ROW_C, k), b.c);
    EXPECT_FLOAT_EQ(at(UW_ROW_K_BEAM, k), b.c / 0.8f);
    EXPECT_FLOAT_EQ(at(UW_ROW_MS_TOTAL, k), b.b / (4 * float(M_PI)) * (b.e_sky0 + b.e_sun0));
    EXPECT_EQ(at(UW_ROWS + 1, k), s.albedo[4 + std::min(k, 3)]);
  }
  EXPECT_EQ(UW_BAND_STRIDE(16), 16);
  EXPECT_EQ(UW_BAND_STRIDE(17), 32);
  // The sun at the horizon (μ_w -> 0): the same 1e-4 clamp as common/underwater.h, finite.
  EXPECT_FLOAT_EQ(seasim::underwaterBandTable(makeSetup(0.0f))[UW_ROW_K_BEAM * stride], s.bands[0].c / 1e-4f);
}

TEST(UnderwaterBands, LanesMatchTheScalarModelInFloatAndDouble) {
  const double ior = 1.333;
  int checked = 0;
  double worst_d = 0, worst_f = 0;
  for (float mu_w : {0.9f, 0.3f}) {
    const seasim::UnderwaterSetup s = makeSetup(mu_w);
    const std::vector<float> table = seasim::underwaterBandTable(s);
    const int stride = UW_BAND_STRIDE(4);
    for (int single : {0, 1}) {
      for (double o_d : {0.0, 1e-4, 4.0, 1000.0}) {
        for (double d_y : {-1.0, -0.5, -0.2, 0.0, 0.3, 0.5, 0.5 + 1e-6, 0.9, 1.0}) {
          for (int mat : {UW_MAT_NONE, UW_MAT_SURFACE, UW_MAT_BOTTOM, 0, 1}) {
            if (mat == UW_MAT_SURFACE && d_y <= 0) continue;
            for (double S : {0.0, 1e-3, 2.0, 30.0, 1e30}) {
              if ((S >= 1e30) != (mat == UW_MAT_NONE)) continue;
              if (mat == UW_MAT_NONE && d_y > 0) continue;  // an upward ray meets the surface
              if (d_y > 0 && S * d_y > o_d && mat != UW_MAT_SURFACE) continue;
              const double n_y = mat == UW_MAT_BOTTOM ? 1.0 : 0.6, n_dot_s = 0.4, vis = 0.7, bottom = 5.0;
              for (int k = 0; k < 4; ++k) {
                const UwBand& band = s.bands[k];
                const double albedo = mat >= 0 ? s.albedo[mat * 4 + k] : band.bottom_albedo;
                // The scalar model; the surface's sky is the uniform level (band.sky_radiance).
                const kd::real3 d{std::sqrt(1 - d_y * d_y), d_y, 0}, sun{0, mu_w, std::sqrt(1 - double(mu_w) * mu_w)};
                const kd::real3 n{std::sqrt(1 - n_y * n_y), n_y, 0};
                // dot(n, sun) as the lanes are given it
                const double nds = n.x * sun.x + n.y * sun.y + n.z * sun.z;
                const double ref = kd::uw_band_radiance(&band, mat, S, n, d, o_d, sun, albedo, vis, ior, bottom, single, 1);
                const double lanes_d = lanesRadiance<double>(table, stride, k, mat, S, d_y, o_d, n_y, nds, vis, ior,
                                                             bottom, single, LanesOf<double>{});
                const float lanes_f =
                    lanesRadiance<float>(table, stride, k, mat, float(S), float(d_y), float(o_d), float(n_y),
                                         float(nds), float(vis), float(ior), float(bottom), single, LanesOf<float>{});
                ASSERT_TRUE(std::isfinite(lanes_f) && std::isfinite(lanes_d));
                const double scale = std::fabs(ref) + 1e-6;
                // double lanes: the table's float rounding of σ_t/μ_w and σ_s/(4π) E_0 (~6e-8 of each
                // exponent) is all that differs; float: the exponents' own float rounding.
                const double arg = 1 + band.c * std::min(S, 1e3) + band.kd * o_d;
                worst_d = std::max(worst_d, std::fabs(lanes_d - ref) / scale / arg);
                worst_f = std::max(worst_f, std::fabs(lanes_f - ref) / scale / arg);
                EXPECT_NEAR(lanes_d, ref, 1e-6 * scale * arg) << mat << " " << S << " " << d_y << " " << o_d << " " << k;
                EXPECT_NEAR(lanes_f, ref, 2e-5 * scale * arg) << mat << " " << S << " " << d_y << " " << o_d << " " << k;
                ++checked;
              }
            }
          }
        }
      }
    }
  }
  EXPECT_GT(checked, 1000);
  std::printf("band lanes vs scalar model: double %.2e, float %.2e (relative, per unit exponent)\n", worst_d, worst_f);
}

}  // namespace
