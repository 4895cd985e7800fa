// tonemap_eq18_test.cpp — the tone-mapping operator of 003 eq. 18 (io/tonemap_eq18.h): its fixed
// points (L_df(0) = 0, L_df(L_white) = 1, L_d(L_wa) = m L_da), monotone in the scene luminance for
// many parameter sets, Reinhard 2002 when γ_w = γ_d and m = 1, R:G:B kept, the adaptation modes;
// and the scene's [display] table selecting it, with file:line:key errors for bad values.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "io/tonemap.h"
#include "io/tonemap_eq18.h"
#include "scene/scene_parser.h"
#include "util/error.h"

using namespace seasim;

namespace {

std::string errorOf(const std::string& text) {
  try {
    parseScene(text, "bad.toml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// A 1-pixel-high grey ramp image with the given luminances.
Image greyRamp(const std::vector<float>& y) {
  Image img = Image::rgb(static_cast<int>(y.size()), 1);
  for (size_t i = 0; i < y.size(); ++i)
    for (int c = 0; c < 3; ++c) img.at(static_cast<int>(i), 0, c) = y[i];
  return img;
}

}  // namespace

TEST(ToneMapEq18, FixedPointsOfTheCompression) {
  for (double white : {0.5, 1.0, 2.0, 11.2, 1e3}) {
    EXPECT_EQ(eq18Compress(0.0, white), 0.0);
    EXPECT_NEAR(eq18Compress(white, white), 1.0, 1e-15) << white;  // L_white shows as white
    // Below L_white it stays under 1, above it goes over (clipped by the display).
    EXPECT_LT(eq18Compress(0.999 * white, white), 1.0);
    EXPECT_GT(eq18Compress(1.001 * white, white), 1.0);
  }
  // L_white → ∞: Reinhard's L/(1+L).
  EXPECT_NEAR(eq18Compress(3.0, 1e300), 0.75, 1e-15);
  // Extreme inputs stay finite and never NaN.
  EXPECT_TRUE(std::isfinite(eq18Compress(1e300, 1.0)));
  EXPECT_EQ(eq18Compress(-1.0, 1.0), 0.0);
  EXPECT_EQ(eq18Compress(std::numeric_limits<double>::quiet_NaN(), 1.0), 0.0);
}

TEST(ToneMapEq18, AdaptedLuminanceMapsToTheDisplayAdaptation) {
  Eq18Params p;
  p.display_adaptation = 0.18;
  for (double ratio : {0.5, 1.0, 1.7}) {
    p.gamma_world = ratio;
    for (double wa : {1e-3, 1.0, 250.0}) EXPECT_NEAR(eq18DisplayLuminance(wa, wa, p), 0.18, 1e-15);
  }
  p.contrast_scale = 3.0;
  EXPECT_NEAR(eq18DisplayLuminance(2.0, 2.0, p), 0.54, 1e-15);
  // The exponent γ_w/γ_d: doubling L_w multiplies L_d by 2^(γ_w/γ_d).
  p = Eq18Params{};
  p.gamma_world = 2.655;
  p.gamma_display = 1.855;
  EXPECT_NEAR(eq18DisplayLuminance(2.0, 1.0, p) / eq18DisplayLuminance(1.0, 1.0, p), std::pow(2.0, 2.655 / 1.855),
              1e-12);
  EXPECT_EQ(eq18DisplayLuminance(0.0, 1.0, p), 0.0);
}

TEST(ToneMapEq18, MonotoneInSceneLuminance) {
  const std::vector<double> ratios = {0.3, 1.0, 1.43, 3.0};
  const std::vector<double> whites = {0.1, 1.0, 5.0};
  for (double g : ratios)
    for (double white : whites)
      for (double m : {0.5, 1.0, 4.0}) {
        Eq18Params p;
        p.gamma_world = g;
        p.contrast_scale = m;
        double prev = -1.0;
        for (int i = 0; i <= 400; ++i) {
          const double lw = 1e-4 * std::pow(10.0, i * 0.02);  // 1e-4 … 1e4
          const double ldf = eq18Compress(eq18DisplayLuminance(lw, 0.7, p), white);
          ASSERT_GT(ldf, prev) << "γ ratio " << g << " white " << white << " m " << m << " L_w " << lw;
          prev = ldf;
        }
      }
}

TEST(ToneMapEq18, ReinhardWhenExponentsAreEqual) {
  // γ_w = γ_d, m = 1: L_d = L_da L_w / L_wa and L_df = L_d (1 + L_d/L_white²)/(1 + L_d) (Reinhard 2002).
  Eq18Params p;
  p.adaptation = Eq18Params::Adaptation::Given;
  p.world_adaptation = 2.0;
  p.white_from_image = false;
  p.white = 1.5;
  const std::vector<float> y = {0.0f, 0.1f, 1.0f, 4.0f, 16.0f};
  Image display;
  EXPECT_EQ(toneMapImageEq18(greyRamp(y), 0.0, p, display), 0);
  for (size_t i = 0; i < y.size(); ++i) {
    const double ld = 0.18 * y[i] / 2.0;
    const double expect = std::min(1.0, ld * (1 + ld / (1.5 * 1.5)) / (1 + ld));
    EXPECT_NEAR(display.at(static_cast<int>(i), 0, 1), srgbEncode(expect), 1e-6) << y[i];
  }
}

TEST(ToneMapEq18, WhiteFromImageAndAdaptationModes) {
  Eq18Params p;  // log mean, white = the image's largest L_d
  const std::vector<float> y = {0.01f, 0.2f, 3.0f, 50.0f};
  Image display;
  toneMapImageEq18(greyRamp(y), 0.0, p, display);
  EXPECT_NEAR(display.at(3, 0, 0), 1.0, 1e-6);  // the brightest pixel is exactly white
  EXPECT_LT(display.at(2, 0, 0), 1.0);
  // Log mean and arithmetic mean of the luminances.
  double log_sum = 0, sum = 0;
  for (float v : y) {
    log_sum += std::log(1e-6 + v);
    sum += v;
  }
  EXPECT_NEAR(eq18WorldAdaptation(greyRamp(y), 1.0, p), std::exp(log_sum / 4), 1e-6);
  p.adaptation = Eq18Params::Adaptation::Mean;
  EXPECT_NEAR(eq18WorldAdaptation(greyRamp(y), 1.0, p), sum / 4, 1e-5);
  // The exposure scales L_wa with the image: with a scene-mean adaptation the picture is unchanged.
  Image brighter;
  toneMapImageEq18(greyRamp(y), 2.0, p, brighter);
  Image base;
  toneMapImageEq18(greyRamp(y), 0.0, p, base);
  for (size_t i = 0; i < base.pixels.size(); ++i) EXPECT_NEAR(brighter.pixels[i], base.pixels[i], 1e-5);
  // A black image stays black (no 0/0).
  Image black;
  EXPECT_EQ(toneMapImageEq18(greyRamp({0.0f, 0.0f}), 0.0, Eq18Params{}, black), 0);
  EXPECT_EQ(black.pixels[0], 0.0f);
}

TEST(ToneMapEq18, KeepsHueAndCountsNonFinite) {
  Image img = Image::rgb(2, 1);
  img.at(0, 0, 0) = 0.2f;
  img.at(0, 0, 1) = 0.1f;
  img.at(0, 0, 2) = 0.05f;
  img.at(1, 0, 0) = std::numeric_limits<float>::quiet_NaN();
  Eq18Params p;
  p.adaptation = Eq18Params::Adaptation::Given;
  p.world_adaptation = 0.5;
  Image display;
  EXPECT_EQ(toneMapImageEq18(img, 0.0, p, display), 1);
  const double r = srgbDecode(display.at(0, 0, 0)), g = srgbDecode(display.at(0, 0, 1)),
               b = srgbDecode(display.at(0, 0, 2));
  EXPECT_NEAR(r / g, 2.0, 2e-3);
  EXPECT_NEAR(g / b, 2.0, 4e-3);
  EXPECT_EQ(display.at(1, 0, 0), 0.0f);
}

TEST(ToneMapEq18, SceneDisplayTableSelectsIt) {
  const Scene d = parseScene("", "d.toml");
  EXPECT_EQ(d.display.tone_map, DisplayDesc::ToneMap::Default);
  const Scene s = parseScene(
      "[display]\ntone_map = \"eq18\"\nadaptation_luminance = 0.25\ndisplay_adaptation = 0.3\n"
      "gamma_world = 2.6\ngamma_display = 1.9\ncontrast_scale = 2\nwhite = 4\n",
      "s.toml");
  EXPECT_EQ(s.display.tone_map, DisplayDesc::ToneMap::Eq18);
  EXPECT_EQ(s.display.eq18.adaptation, Eq18Params::Adaptation::Given);
  EXPECT_EQ(s.display.eq18.world_adaptation, 0.25);
  EXPECT_EQ(s.display.eq18.display_adaptation, 0.3);
  EXPECT_EQ(s.display.eq18.gamma_world, 2.6);
  EXPECT_EQ(s.display.eq18.gamma_display, 1.9);
  EXPECT_EQ(s.display.eq18.contrast_scale, 2.0);
  EXPECT_FALSE(s.display.eq18.white_from_image);
  EXPECT_EQ(s.display.eq18.white, 4.0);
  const Scene m = parseScene("[display]\ntone_map = \"eq18\"\nadaptation_luminance = \"mean\"\nwhite = \"max\"\n",
                             "m.toml");
  EXPECT_EQ(m.display.eq18.adaptation, Eq18Params::Adaptation::Mean);
  EXPECT_TRUE(m.display.eq18.white_from_image);
}

TEST(ToneMapEq18, BadDisplayValuesNameFileLineKey) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"[display]\ntone_map = \"aces\"\n", "bad.toml:2: key 'display.tone_map'"},
      {"[display]\ntone_map = \"eq18\"\nwhite = 0\n", "bad.toml:3: key 'display.white': must be in (0, 1e6]"},
      {"[display]\ntone_map = \"eq18\"\nwhite = \"min\"\n", "bad.toml:3: key 'display.white': expected \"max\""},
      {"[display]\ntone_map = \"eq18\"\nadaptation_luminance = -1\n",
       "bad.toml:3: key 'display.adaptation_luminance': must be > 0"},
      {"[display]\ntone_map = \"eq18\"\nadaptation_luminance = \"median\"\n",
       "bad.toml:3: key 'display.adaptation_luminance': expected \"log_mean\""},
      {"[display]\ntone_map = \"eq18\"\n\ngamma_display = 0\n", "bad.toml:4: key 'display.gamma_display'"},
      {"[display]\ntone_map = \"eq18\"\ngamma_world = -2\n", "bad.toml:3: key 'display.gamma_world'"},
      {"[display]\ntone_map = \"eq18\"\ncontrast_scale = 0\n", "bad.toml:3: key 'display.contrast_scale'"},
      {"[display]\ntone_map = \"eq18\"\ndisplay_adaptation = 1e9\n", "bad.toml:3: key 'display.display_adaptation'"},
      // eq. 18's constants with the default curve: not used there.
      {"[display]\nwhite = 2\n", "bad.toml:2: key 'display.white'"},
  };
  for (const auto& [text, expect] : cases) {
    const std::string msg = errorOf(text);
    EXPECT_NE(msg.find(expect), std::string::npos) << text << "\n got: " << msg;
  }
}
