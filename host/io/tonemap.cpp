// tonemap.cpp — see tonemap.h for the curve and why it was chosen.
#include "io/tonemap.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "util/error.h"

namespace seasim {

double srgbEncode(double linear) {
  const double v = std::clamp(linear, 0.0, 1.0);
  return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
}

double srgbDecode(double encoded) {
  const double v = std::clamp(encoded, 0.0, 1.0);
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

std::uint8_t toByte(float display) {
  if (std::isnan(display)) return 0;  // std::clamp passes NaN through
  return static_cast<std::uint8_t>(std::lround(std::clamp(display, 0.0f, 1.0f) * 255.0f));
}

int toneMapRgb(const float linear[3], double scale, float display[3]) {
  int nonfinite = 0;
  double rgb[3];
  for (int c = 0; c < 3; ++c) {
    if (!std::isfinite(linear[c])) {
      ++nonfinite;
      rgb[c] = 0.0;
    } else {
      rgb[c] = std::max(0.0, static_cast<double>(linear[c]) * scale);
    }
  }
  // Reinhard on luminance: scaling RGB by 1/(1+Y) keeps R:G:B (hue and saturation).
  const double Y = 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
  const double k = 1.0 / (1.0 + Y);
  double m = 0.0;
  for (double& v : rgb) {
    v *= k;
    m = std::max(m, v);
  }
  // Saturated colours (a bright pure blue has small Y) can still exceed 1: scale back into the
  // gamut along the same R:G:B ray instead of clipping channels one by one, which would shift hue.
  const double gamut = m > 1.0 ? 1.0 / m : 1.0;
  for (int c = 0; c < 3; ++c) display[c] = static_cast<float>(srgbEncode(rgb[c] * gamut));
  return nonfinite;
}

long long toneMapImage(const Image& linear, double exposure_ev, Image& display) {
  const int nc = linear.channels;
  if (nc < 1 || nc > 4)
    throw RuntimeError("cannot tone map an image with " + std::to_string(nc) +
                       " channels (expected 1, 2, 3 or 4)");
  if (linear.pixels.size() != linear.pixelCount() * static_cast<std::size_t>(nc))
    throw RuntimeError("image pixel buffer does not match its size (" + std::to_string(linear.width) +
                       "x" + std::to_string(linear.height) + "x" + std::to_string(nc) + ")");
  if (!std::isfinite(exposure_ev)) throw RuntimeError("exposure_ev must be finite");
  const double scale = std::exp2(exposure_ev);
  display.resize(linear.width, linear.height, nc);
  display.channel_names = linear.channel_names;
  const bool has_alpha = nc == 2 || nc == 4;
  const bool grey = nc <= 2;
  long long nonfinite = 0;
  const std::size_t n = linear.pixelCount();
  for (std::size_t i = 0; i < n; ++i) {
    const float* in = &linear.pixels[i * nc];
    float* out = &display.pixels[i * nc];
    float rgb[3] = {in[0], grey ? in[0] : in[1], grey ? in[0] : in[2]};
    float shown[3];
    const int bad = toneMapRgb(rgb, scale, shown);
    nonfinite += grey ? (bad > 0 ? 1 : 0) : bad;
    out[0] = shown[0];
    if (!grey) {
      out[1] = shown[1];
      out[2] = shown[2];
    }
    if (has_alpha) {
      const float a = in[nc - 1];
      if (!std::isfinite(a)) ++nonfinite;
      out[nc - 1] = std::isfinite(a) ? std::clamp(a, 0.0f, 1.0f) : 0.0f;
    }
  }
  return nonfinite;
}

long long toneMapImage8(const Image& linear, double exposure_ev, std::vector<std::uint8_t>& bytes) {
  Image display;
  const long long nonfinite = toneMapImage(linear, exposure_ev, display);
  bytes.resize(display.pixels.size());
  std::transform(display.pixels.begin(), display.pixels.end(), bytes.begin(), toByte);
  return nonfinite;
}

}  // namespace seasim
