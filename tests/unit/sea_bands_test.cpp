// sea_bands_test.cpp — sea_single.cl's band lanes (kernels/common/sea_bands.h, one band per lane on the
// host) and its band table (host/passes/sea_band_table.cpp) against the scalar terms of sea_surface.h
// and the kernel's old per-band LUT read, in float and double: no bottom, c -> 0, grazing angles, the
// LUT's mirrored ends. tests/kernels/sea_single_test.cpp runs the lanes on PoCL in floatN against the
// double reference, with band counts that do not fill the lanes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "math/kernel_math.h"
#include "passes/sea_band_table.h"

namespace {

namespace kd = seasim::kmath_d;
namespace kf = seasim::kmath_f;

// The kernel's Catmull–Rom read before the lanes (one band's LUT, mirrored ends), in double.
double oldLutRead(const std::vector<double>& lut, double x) {
  const int n = static_cast<int>(lut.size());
  const int j = std::clamp(static_cast<int>(x), 0, n - 2);
  const double t = x - j;
  const int jm = j > 0 ? j - 1 : 1;
  const int jp = j + 2 < n ? j + 2 : n - 2;
  const double p0 = lut[jm], p1 = lut[j], p2 = lut[j + 1], p3 = lut[jp];
  return p1 + 0.5 * t * (p2 - p0 + t * (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3 + t * (3.0 * (p1 - p2) + p3 - p0)));
}

template <typename Math, typename Real>
Real lanesLutRead(const std::vector<double>& lut, Real x) {
  int jm = -1, j = -1, jp = -1;
  const Real t = Math::sea_lut_taps(static_cast<int>(lut.size()), x, &jm, &j, &jp);
  return Math::sea_lut_read_b(static_cast<Real>(lut[jm]), static_cast<Real>(lut[j]), static_cast<Real>(lut[j + 1]),
                              static_cast<Real>(lut[jp]), t);
}

struct KF {
  static float sea_lut_taps(int n, float x, int* a, int* b, int* c) { return kf::sea_lut_taps(n, x, a, b, c); }
  static float sea_lut_read_b(float a, float b, float c, float d, float t) { return kf::sea_lut_read_b(a, b, c, d, t); }
};
struct KD {
  static double sea_lut_taps(int n, double x, int* a, int* b, int* c) { return kd::sea_lut_taps(n, x, a, b, c); }
  static double sea_lut_read_b(double a, double b, double c, double d, double t) {
    return kd::sea_lut_read_b(a, b, c, d, t);
  }
};

TEST(SeaBands, LutTapsAndReadMatchTheOldPerBandRead) {
  for (int n : {2, 3, 5, 64}) {
    std::vector<double> lut(n);
    for (int j = 0; j < n; ++j) lut[j] = std::cos(1.3 * j / std::max(n - 1, 1)) + 0.1 * j;
    for (double x : {0.0, 1e-7, 0.25, 0.5, 1.0, 1.5, n - 2.0, n - 1.5, n - 1.0 - 1e-6, n - 1.0}) {
      if (x > n - 1) continue;
      const double expected = oldLutRead(lut, x);
      EXPECT_NEAR((lanesLutRead<KD, double>(lut, x)), expected, 1e-15 * (1 + std::fabs(expected))) << n << " " << x;
      EXPECT_NEAR((lanesLutRead<KF, float>(lut, static_cast<float>(x))), expected, 2e-6 * (1 + std::fabs(expected)))
          << n << " " << x;
    }
  }
  // Catmull–Rom reproduces a straight line between interior entries exactly.
  std::vector<double> line(9);
  for (int j = 0; j < 9; ++j) line[j] = 2.0 + 3.0 * j;
  for (double x : {1.0, 1.25, 3.5, 6.75}) EXPECT_NEAR((lanesLutRead<KD, double>(line, x)), 2.0 + 3.0 * x, 1e-13);
}

TEST(SeaBands, SingleScatteringMatchesTheScalarEq5) {
  // (sun, t_in, t_out, beta, c, albedo, c_f, cos_io, cos_ji, z_d): ordinary, no bottom, clear water
  // (k -> 0, the series branch), turbid and deep (the direct branch), grazing view, c = 0 with no bottom.
  const double cases[][10] = {{1.2, 0.97, 0.72, 0.05, 0.3, 0.6, 0.9, 0.85, 0.7, 8.0},
                              {1.2, 0.97, 0.72, 0.05, 0.3, 0.6, 0.9, 0.85, 0.7, -1.0},
                              {0.8, 0.9, 0.7, 1e-6, 2e-6, 0.5, 0.9, 0.9, 0.8, 5.0},
                              {0.8, 0.9, 0.7, 2.0, 9.0, 0.8, 0.95, 0.66, 0.9, 1000.0},
                              {0.8, 0.9, 0.01, 0.02, 0.1, 0.2, 0.9, 0.66, 1e-4, 8.0},
                              {0.8, 0.9, 0.7, 0.0, 0.0, 0.0, 0.9, 0.66, 0.5, -1.0}};
  for (const auto& v : cases) {
    const double expected = kd::sea_single_scattering(v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8], v[9]);
    EXPECT_NEAR(kd::sea_single_scattering_b(v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8], v[9]), expected,
                1e-14 * std::fabs(expected));
    const float f = kf::sea_single_scattering_b(float(v[0]), float(v[1]), float(v[2]), float(v[3]), float(v[4]),
                                                float(v[5]), float(v[6]), float(v[7]), float(v[8]), float(v[9]));
    EXPECT_TRUE(std::isfinite(f));
    EXPECT_NEAR(f, expected, 2e-5 * std::fabs(expected)) << v[4] << " " << v[9];
  }
}

TEST(SeaBands, BottomReflectionMatchesTheScalarEq9) {
  const double cases[][8] = {{1.2, 0.97, 0.72, 0.3, 0.3, 8.0, 0.85, 0.7},
                             {1.2, 0.97, 0.72, 0.3, 0.0, 8.0, 0.85, 0.7},   // c = 0: no attenuation
                             {1.2, 0.97, 0.72, 0.3, 9.0, 100.0, 0.85, 1e-4}, // underflows to 0
                             {0.8, 0.9, 0.01, 0.1, 0.1, 0.5, 0.66, 1e-4}};
  for (const auto& v : cases) {
    const double expected = kd::sea_bottom_reflection(v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7]);
    EXPECT_NEAR(kd::sea_bottom_reflection_b(v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7]), expected,
                1e-14 * std::fabs(expected));
    const float f = kf::sea_bottom_reflection_b(float(v[0]), float(v[1]), float(v[2]), float(v[3]), float(v[4]),
                                                float(v[5]), float(v[6]), float(v[7]));
    EXPECT_TRUE(std::isfinite(f));
    EXPECT_NEAR(f, expected, 1e-5 * std::fabs(expected) + 1e-30);
  }
}

TEST(SeaBands, SkyBandIsTheLevelTimesTheBandsShare) {
  const kd::real3 shape{0.5, 2.0, -4.0};
  EXPECT_DOUBLE_EQ(kd::sea_sky_band_b(SEASIM_SKY_UNIFORM, 0.7, 0.2, 0.3, 0.5, shape), 0.7 * 0.5);
  EXPECT_DOUBLE_EQ(kd::sea_sky_band_b(SEASIM_SKY_ANALYTIC, 0.7, 0.2, 0.3, 0.5, shape), 0.7 * 0.5);
  // The image's share 0.2 * 0.5 + 0.3 * 2 + 0.5 * (-4) < 0 is held at 0 (sky_view_band).
  EXPECT_DOUBLE_EQ(kd::sea_sky_band_b(SEASIM_SKY_IMAGE, 0.7, 0.2, 0.3, 0.5, shape), 0.0);
  EXPECT_DOUBLE_EQ(kd::sea_sky_band_b(SEASIM_SKY_PREETHAM, 0.7, 0.2, 0.3, 0.5, kd::real3{0.5, 2.0, 1.0}),
                   0.7 * (0.2 * 0.5 + 0.3 * 2.0 + 0.5 * 1.0));
}

SeaBand band(float v) {
  SeaBand b{};
  b.sun_irradiance = v;
  b.sky_radiance = v + 0.1f;
  b.a = v + 0.2f;
  b.b = v + 0.3f;
  b.c = v + 0.5f;
  b.bottom_albedo = v + 0.4f;
  b.w_r = v + 0.6f;
  b.w_g = v + 0.7f;
  b.w_b = v + 0.8f;
  b.sky_w_r = v + 0.9f;
  b.sky_w_g = v + 1.0f;
  b.sky_w_b = v + 1.1f;
  return b;
}

TEST(SeaBandTable, RowsAreBandContiguousPaddedAndTheLutIsTransposed) {
  for (int count : {1, 3, 16, 17, 31}) {
    std::vector<SeaBand> bands;
    for (int k = 0; k < count; ++k) bands.push_back(band(static_cast<float>(k)));
    const int lut_size = 5;
    std::vector<float> lut;
    for (int k = 0; k < count; ++k)
      for (int j = 0; j < lut_size; ++j) lut.push_back(100.0f * k + j);
    const std::vector<float> table = seasim::seaBandTable(bands, lut, lut_size);
    const int stride = SEA_BAND_STRIDE(count);
    EXPECT_EQ(stride % 16, 0);
    EXPECT_GE(stride, count);
    ASSERT_EQ(table.size(), static_cast<size_t>(SEA_ROWS + lut_size) * stride);
    auto at = [&](int row, int i) { return table[static_cast<size_t>(row) * stride + i]; };
    for (int i = 0; i < stride; ++i) {
      const int k = std::min(i, count - 1);
      const bool padding = i >= count;
      EXPECT_EQ(at(SEA_ROW_SUN, i), bands[k].sun_irradiance);
      EXPECT_EQ(at(SEA_ROW_SKY, i), bands[k].sky_radiance);
      EXPECT_EQ(at(SEA_ROW_A, i), bands[k].a);
      EXPECT_EQ(at(SEA_ROW_B, i), bands[k].b);
      EXPECT_EQ(at(SEA_ROW_C, i), bands[k].c);
      EXPECT_EQ(at(SEA_ROW_BOTTOM_ALBEDO, i), bands[k].bottom_albedo);
      EXPECT_EQ(at(SEA_ROW_W_R, i), padding ? 0.0f : bands[k].w_r);
      EXPECT_EQ(at(SEA_ROW_W_G, i), padding ? 0.0f : bands[k].w_g);
      EXPECT_EQ(at(SEA_ROW_W_B, i), padding ? 0.0f : bands[k].w_b);
      EXPECT_EQ(at(SEA_ROW_SKY_W_R, i), bands[k].sky_w_r);
      EXPECT_EQ(at(SEA_ROW_SKY_W_G, i), bands[k].sky_w_g);
      EXPECT_EQ(at(SEA_ROW_SKY_W_B, i), bands[k].sky_w_b);
      for (int j = 0; j < lut_size; ++j) EXPECT_EQ(at(SEA_ROW_LUT + j, i), 100.0f * k + j);
    }
  }
}

TEST(SeaBandTable, NoLutLeavesOneZeroRowAndAWrongLutSizeIsRefused) {
  const std::vector<float> table = seasim::seaBandTable({band(1.0f), band(2.0f)}, {0.0f}, 1);
  ASSERT_EQ(table.size(), static_cast<size_t>(SEA_ROWS + 1) * 16);
  for (int i = 0; i < 16; ++i) EXPECT_EQ(table[static_cast<size_t>(SEA_ROW_LUT) * 16 + i], 0.0f);
  EXPECT_THROW(seasim::seaBandTable({band(1.0f), band(2.0f)}, std::vector<float>(7, 0.0f), 4), std::runtime_error);
  EXPECT_EQ(seasim::seaBandTable({}, {}, 1).size(), static_cast<size_t>(SEA_ROWS + 1) * 16);
}

}  // namespace
