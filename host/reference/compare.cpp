// compare.cpp — image error metrics; definitions and sources in compare.h.
#include "reference/compare.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "io/tonemap.h"
#include "util/error.h"

namespace seasim {

void rgbToHsv(const float rgb[3], double& h_deg, double& s, double& v) {
  const double r = rgb[0], g = rgb[1], b = rgb[2];
  const double mx = std::max({r, g, b}), mn = std::min({r, g, b});
  const double chroma = mx - mn;
  v = mx;
  s = mx > 0.0 ? chroma / mx : 0.0;
  if (chroma <= 0.0) {
    h_deg = 0.0;
    return;
  }
  double h;
  if (mx == r) h = std::fmod((g - b) / chroma, 6.0);
  else if (mx == g) h = (b - r) / chroma + 2.0;
  else h = (r - g) / chroma + 4.0;
  h *= 60.0;
  if (h < 0.0) h += 360.0;
  h_deg = h;
}

double hueSatDistance(const float a[3], const float b[3]) {
  // 002 §6.1: V normalised away; (S, H) as polar coordinates, Euclidean distance in the disc.
  double ha, sa, va, hb, sb, vb;
  rgbToHsv(a, ha, sa, va);
  rgbToHsv(b, hb, sb, vb);
  constexpr double deg = std::numbers::pi / 180.0;
  const double dx = sa * std::cos(ha * deg) - sb * std::cos(hb * deg);
  const double dy = sa * std::sin(ha * deg) - sb * std::sin(hb * deg);
  return std::sqrt(dx * dx + dy * dy);
}

namespace {

void checkLayout(const Image& img, const char* which) {
  if (img.channels < 1 || img.channels > 4)
    throw RuntimeError(std::string("compare: the ") + which + " image has " + std::to_string(img.channels) +
                       " channels; expected grey, grey+alpha, RGB or RGBA");
  if (img.pixels.size() != img.pixelCount() * static_cast<std::size_t>(img.channels))
    throw RuntimeError(std::string("compare: the ") + which + " image's pixel buffer does not match its size");
}

// The linear colour of pixel i (grey images repeat their one value).
void colourAt(const Image& img, std::size_t i, float rgb[3]) {
  const float* p = &img.pixels[i * img.channels];
  if (img.channels >= 3) {
    rgb[0] = p[0];
    rgb[1] = p[1];
    rgb[2] = p[2];
  } else {
    rgb[0] = rgb[1] = rgb[2] = p[0];
  }
}

}  // namespace

CompareResult compareImages(const Image& test, const Image& reference, double exposure_ev) {
  checkLayout(test, "test");
  checkLayout(reference, "reference");
  if (test.width != reference.width || test.height != reference.height)
    throw RuntimeError("compare: image sizes differ (test " + std::to_string(test.width) + "x" +
                       std::to_string(test.height) + ", reference " + std::to_string(reference.width) + "x" +
                       std::to_string(reference.height) + ")");
  if ((test.channels >= 3) != (reference.channels >= 3))
    throw RuntimeError("compare: one image is grey and the other RGB (" + std::to_string(test.channels) + " vs " +
                       std::to_string(reference.channels) + " channels)");
  if (!std::isfinite(exposure_ev)) throw RuntimeError("compare: exposure must be finite");

  CompareResult r;
  r.width = test.width;
  r.height = test.height;
  const double scale = std::exp2(exposure_ev);
  const std::size_t n = test.pixelCount();
  const bool grey = test.channels < 3;
  double sum_sq8 = 0, max8 = 0, diff_l2 = 0, ref_l2 = 0, hue_sat = 0;
  for (std::size_t i = 0; i < n; ++i) {
    float a[3], b[3], da[3], db[3];
    colourAt(test, i, a);
    colourAt(reference, i, b);
    const int bad_a = toneMapRgb(a, scale, da), bad_b = toneMapRgb(b, scale, db);
    // A grey pixel's one value was repeated into three: count it once.
    r.nonfinite += grey ? (bad_a > 0) + (bad_b > 0) : bad_a + bad_b;
    for (int c = 0; c < 3; ++c) {
      const double d8 = 255.0 * (static_cast<double>(da[c]) - db[c]);
      sum_sq8 += d8 * d8;
      max8 = std::max(max8, std::fabs(d8));
      if (std::isfinite(a[c]) && std::isfinite(b[c])) {
        const double d = static_cast<double>(a[c]) - b[c];
        diff_l2 += d * d;
        ref_l2 += static_cast<double>(b[c]) * b[c];
      }
    }
    hue_sat += hueSatDistance(da, db);
  }
  if (n > 0) {
    r.rmse_8bit = std::sqrt(sum_sq8 / (3.0 * static_cast<double>(n)));
    r.hue_sat_distance = hue_sat / static_cast<double>(n);
  }
  r.max_abs_8bit = max8;
  r.rel_l2 = ref_l2 > 0 ? std::sqrt(diff_l2 / ref_l2) : (diff_l2 > 0 ? INFINITY : 0.0);
  return r;
}

double referenceNoise8bit(const Image& reference, const Image& std_error, double exposure_ev) {
  checkLayout(reference, "reference");
  checkLayout(std_error, "standard-error");
  if (reference.width != std_error.width || reference.height != std_error.height ||
      (reference.channels >= 3) != (std_error.channels >= 3))
    throw RuntimeError("compare: the reference's standard-error image is " + std::to_string(std_error.width) + "x" +
                       std::to_string(std_error.height) + "x" + std::to_string(std_error.channels) +
                       ", the reference " + std::to_string(reference.width) + "x" +
                       std::to_string(reference.height) + "x" + std::to_string(reference.channels));
  if (!std::isfinite(exposure_ev)) throw RuntimeError("compare: exposure must be finite");
  const double scale = std::exp2(exposure_ev);
  const std::size_t n = reference.pixelCount();
  const int sources = reference.channels >= 3 ? 3 : 1;  // grey: one value drives all three
  double sum_var = 0;
  for (std::size_t i = 0; i < n; ++i) {
    float b[3], se[3], d0[3];
    colourAt(reference, i, b);
    colourAt(std_error, i, se);
    toneMapRgb(b, scale, d0);
    for (int c = 0; c < sources; ++c) {
      if (!std::isfinite(se[c]) || se[c] <= 0.0f) continue;
      float moved[3] = {b[0], b[1], b[2]}, d1[3];
      for (int k = 0; k < 3; ++k)
        if (sources == 3 ? k == c : true) moved[k] += se[c];
      toneMapRgb(moved, scale, d1);
      for (int k = 0; k < 3; ++k) {
        const double d8 = 255.0 * (static_cast<double>(d1[k]) - d0[k]);
        sum_var += d8 * d8;
      }
    }
  }
  return n > 0 ? std::sqrt(sum_var / (3.0 * static_cast<double>(n))) : 0.0;
}

}  // namespace seasim
