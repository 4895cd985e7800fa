// compare_test.cpp — host/reference/compare: the error metrics on images with known answers.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "io/tonemap.h"
#include "reference/compare.h"
#include "util/error.h"

namespace seasim {
namespace {

Image constant(int w, int h, float r, float g, float b) {
  Image img;
  img.resize(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      img.at(x, y, 0) = r;
      img.at(x, y, 1) = g;
      img.at(x, y, 2) = b;
    }
  return img;
}

// The linear grey that the tone map (exposure 0) shows as display value d: invert sRGB, then
// Reinhard (d_lin = g / (1 + g)  =>  g = d_lin / (1 - d_lin)).
float greyShownAs(double d) {
  const double lin = srgbDecode(d);
  return static_cast<float>(lin / (1.0 - lin));
}

TEST(Compare, IdenticalImagesHaveZeroError) {
  Image a;
  a.resize(9, 7, 3);
  for (std::size_t i = 0; i < a.pixels.size(); ++i) a.pixels[i] = 0.013f * static_cast<float>(i % 97);
  const CompareResult r = compareImages(a, a);
  EXPECT_EQ(r.rmse_8bit, 0.0);
  EXPECT_EQ(r.max_abs_8bit, 0.0);
  EXPECT_EQ(r.rel_l2, 0.0);
  EXPECT_EQ(r.hue_sat_distance, 0.0);
  EXPECT_EQ(r.nonfinite, 0);
  EXPECT_EQ(r.width, 9);
  EXPECT_EQ(r.height, 7);
}

TEST(Compare, ConstantDisplayOffsetGivesKnownRmse) {
  // Display 0.5 vs 0.6 everywhere: 0.1 * 255 = 25.5 levels in every channel.
  const float g5 = greyShownAs(0.5), g6 = greyShownAs(0.6);
  const CompareResult r = compareImages(constant(8, 6, g6, g6, g6), constant(8, 6, g5, g5, g5));
  EXPECT_NEAR(r.rmse_8bit, 25.5, 1e-3);
  EXPECT_NEAR(r.max_abs_8bit, 25.5, 1e-3);
  EXPECT_NEAR(r.hue_sat_distance, 0.0, 1e-12);  // greys: no hue, no saturation
  EXPECT_NEAR(r.rel_l2, (g6 - g5) / g5, 1e-6);

  // The offset in half of the pixels only: RMSE = 25.5 / sqrt(2), max still 25.5.
  Image half = constant(8, 6, g5, g5, g5);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 8; ++x)
      for (int c = 0; c < 3; ++c) half.at(x, y, c) = g6;
  const CompareResult h = compareImages(half, constant(8, 6, g5, g5, g5));
  EXPECT_NEAR(h.rmse_8bit, 25.5 / std::sqrt(2.0), 1e-3);
  EXPECT_NEAR(h.max_abs_8bit, 25.5, 1e-3);
}

TEST(Compare, RelativeL2IsOnLinearValuesAndIgnoresExposure) {
  const Image ref = constant(5, 5, 2.0f, 1.0f, 0.5f);
  const Image test = constant(5, 5, 2.2f, 1.1f, 0.55f);  // +10 % everywhere
  const CompareResult r0 = compareImages(test, ref, 0.0);
  const CompareResult r3 = compareImages(test, ref, -3.0);
  EXPECT_NEAR(r0.rel_l2, 0.1, 1e-6);
  EXPECT_EQ(r0.rel_l2, r3.rel_l2);
  EXPECT_NE(r0.rmse_8bit, r3.rmse_8bit);  // the display metrics follow the exposure
  EXPECT_EQ(compareImages(constant(2, 2, 0, 0, 0), constant(2, 2, 0, 0, 0)).rel_l2, 0.0);
  EXPECT_TRUE(std::isinf(compareImages(constant(2, 2, 1, 0, 0), constant(2, 2, 0, 0, 0)).rel_l2));
}

TEST(Compare, HueSaturationDistanceOfPrimaries) {
  // 002 §6.1: points (S cos H, S sin H); red (H=0, S=1) vs green (H=120°, S=1) are
  // |e^{i0} - e^{i 2π/3}| = sqrt(3) apart, whatever their brightness.
  const CompareResult rg = compareImages(constant(4, 4, 0, 3.0f, 0), constant(4, 4, 0.5f, 0, 0));
  EXPECT_NEAR(rg.hue_sat_distance, std::sqrt(3.0), 1e-6);
  // Red vs cyan: opposite hues, the diameter.
  const CompareResult rc = compareImages(constant(4, 4, 0, 1, 1), constant(4, 4, 1, 0, 0));
  EXPECT_NEAR(rc.hue_sat_distance, 2.0, 1e-6);
  // Value is ignored: the same pure hue at another brightness is no hue/saturation error.
  const CompareResult rr = compareImages(constant(4, 4, 0, 0, 5.0f), constant(4, 4, 0, 0, 0.2f));
  EXPECT_NEAR(rr.hue_sat_distance, 0.0, 1e-6);
  EXPECT_GT(rr.rmse_8bit, 10.0);
  // Grey vs a saturated colour: the distance is the saturation.
  const float grey[3] = {0.4f, 0.4f, 0.4f}, half_sat_red[3] = {0.8f, 0.4f, 0.4f};
  EXPECT_NEAR(hueSatDistance(grey, half_sat_red), 0.5, 1e-6);
}

TEST(Compare, HueWrapsAround) {
  // H = 359° and H = 1° at S = 1: a 2° chord of the unit circle, 2 sin(1°), not 358° apart.
  const float h359[3] = {1.0f, 0.0f, 1.0f / 60.0f}, h1[3] = {1.0f, 1.0f / 60.0f, 0.0f};
  double h, s, v;
  rgbToHsv(h359, h, s, v);
  EXPECT_NEAR(h, 359.0, 1e-4);
  EXPECT_NEAR(s, 1.0, 1e-12);
  rgbToHsv(h1, h, s, v);
  EXPECT_NEAR(h, 1.0, 1e-4);
  const double expected = 2.0 * std::sin(std::numbers::pi / 180.0);
  EXPECT_NEAR(hueSatDistance(h359, h1), expected, 1e-6);
  EXPECT_LT(hueSatDistance(h359, h1), 0.035);
  // HSV sextants.
  const float yellow[3] = {1, 1, 0}, blue[3] = {0, 0, 1}, magenta[3] = {1, 0, 1};
  rgbToHsv(yellow, h, s, v);
  EXPECT_NEAR(h, 60.0, 1e-9);
  rgbToHsv(blue, h, s, v);
  EXPECT_NEAR(h, 240.0, 1e-9);
  rgbToHsv(magenta, h, s, v);
  EXPECT_NEAR(h, 300.0, 1e-9);
}

TEST(Compare, NonFiniteValuesAreCountedAndShownAsZero) {
  Image test = constant(3, 3, 0.5f, 0.5f, 0.5f);
  const Image ref = test;
  test.at(1, 1, 0) = std::numeric_limits<float>::quiet_NaN();
  test.at(2, 2, 2) = std::numeric_limits<float>::infinity();
  const CompareResult r = compareImages(test, ref);
  EXPECT_EQ(r.nonfinite, 2);
  // Each bad channel shows as 0 where the reference shows the display value of 0.5 grey.
  float shown[3];
  const float grey[3] = {0.5f, 0.5f, 0.5f};
  toneMapRgb(grey, 1.0, shown);
  EXPECT_NEAR(r.max_abs_8bit, 255.0 * shown[0], 0.5);  // the pixel's other channels shift too (Y drops)
  EXPECT_TRUE(std::isfinite(r.rmse_8bit));
  EXPECT_EQ(r.rel_l2, 0.0);  // non-finite values are left out of the linear metric
}

TEST(Compare, GreyImagesAndChannelLayouts) {
  Image a, b;
  a.resize(2, 2, 1);
  b.resize(2, 2, 1);
  const float g5 = greyShownAs(0.5), g6 = greyShownAs(0.6);
  std::fill(a.pixels.begin(), a.pixels.end(), g6);
  std::fill(b.pixels.begin(), b.pixels.end(), g5);
  EXPECT_NEAR(compareImages(a, b).rmse_8bit, 25.5, 1e-3);
  // RGBA against RGB: alpha ignored.
  Image rgba;
  rgba.resize(2, 2, 4);
  for (int i = 0; i < 4; ++i) {
    rgba.pixels[i * 4 + 0] = rgba.pixels[i * 4 + 1] = rgba.pixels[i * 4 + 2] = g5;
    rgba.pixels[i * 4 + 3] = 0.25f;
  }
  EXPECT_EQ(compareImages(rgba, constant(2, 2, g5, g5, g5)).rmse_8bit, 0.0);
}

TEST(Compare, MismatchedImagesAreErrors) {
  EXPECT_THROW(compareImages(constant(4, 3, 0, 0, 0), constant(3, 4, 0, 0, 0)), RuntimeError);
  Image grey;
  grey.resize(4, 3, 1);
  EXPECT_THROW(compareImages(grey, constant(4, 3, 0, 0, 0)), RuntimeError);
  Image spectral;
  spectral.resize(4, 3, 16);
  EXPECT_THROW(compareImages(spectral, spectral), RuntimeError);
  try {
    compareImages(constant(4, 3, 0, 0, 0), constant(5, 3, 0, 0, 0));
  } catch (const RuntimeError& e) {
    EXPECT_NE(std::string(e.what()).find("4x3"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("5x3"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace seasim
