// tonemap_eq18.cpp — 003 eq. 18; see tonemap_eq18.h for the operator, its constants and why.
#include "io/tonemap_eq18.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "io/tonemap.h"
#include "util/error.h"

namespace seasim {

namespace {

// Rec. 709 luminance, the weights io/tonemap.h uses.
double luminance(const double rgb[3]) { return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]; }

// One pixel's linear RGB (after the exposure, negatives clamped to 0, non-finite counted as 0).
int pixelRgb(const float* in, bool grey, double scale, double rgb[3]) {
  int nonfinite = 0;
  const float v[3] = {in[0], grey ? in[0] : in[1], grey ? in[0] : in[2]};
  for (int c = 0; c < 3; ++c) {
    if (!std::isfinite(v[c])) {
      ++nonfinite;
      rgb[c] = 0.0;
    } else {
      rgb[c] = std::max(0.0, static_cast<double>(v[c]) * scale);
    }
  }
  return grey && nonfinite > 0 ? 1 : nonfinite;
}

void checkImage(const Image& linear, double exposure_ev) {
  const int nc = linear.channels;
  if (nc < 1 || nc > 4)
    throw RuntimeError("cannot tone map an image with " + std::to_string(nc) +
                       " channels (expected 1, 2, 3 or 4)");
  if (linear.pixels.size() != linear.pixelCount() * static_cast<std::size_t>(nc))
    throw RuntimeError("image pixel buffer does not match its size");
  if (!std::isfinite(exposure_ev)) throw RuntimeError("exposure_ev must be finite");
}

}  // namespace

double eq18DisplayLuminance(double world_luminance, double world_adaptation, const Eq18Params& p) {
  if (!(world_luminance > 0)) return 0.0;
  // 003 eq. 18, line 1. The power of a ratio, not a ratio of powers: L_w^(γ_w/γ_d) alone would
  // overflow for bright pixels with a large exponent ratio long before the ratio itself does.
  return p.contrast_scale * p.display_adaptation *
         std::pow(world_luminance / world_adaptation, p.gamma_world / p.gamma_display);
}

double eq18Compress(double display_luminance, double white) {
  const double ld = display_luminance;
  if (!(ld > 0)) return 0.0;
  if (std::isinf(ld)) return std::numeric_limits<double>::infinity();
  // 003 eq. 18, line 2, written as L_d/(1+L_d) + L_d²/(L_white² (1+L_d)): both terms stay finite for
  // L_d up to DBL_MAX (the product form L_d (1 + L_d/L_w²) overflows first).
  const double a = ld / (1.0 + ld);
  return a + a * (ld / white) / white;
}

double eq18WorldAdaptation(const Image& linear, double scale, const Eq18Params& p) {
  if (p.adaptation == Eq18Params::Adaptation::Given) return p.world_adaptation;
  const int nc = linear.channels;
  const bool grey = nc <= 2;
  const double delta = 1e-6;  // Reinhard 2002's δ: black pixels do not send the log mean to 0
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < linear.pixelCount(); ++i) {
    double rgb[3];
    if (pixelRgb(&linear.pixels[i * nc], grey, scale, rgb) > 0) continue;
    const double y = luminance(rgb);
    sum += p.adaptation == Eq18Params::Adaptation::Mean ? y : std::log(delta + y);
    ++n;
  }
  if (n == 0) return std::numeric_limits<double>::min();
  const double mean = sum / static_cast<double>(n);
  const double wa = p.adaptation == Eq18Params::Adaptation::Mean ? mean : std::exp(mean);
  return std::max(wa, std::numeric_limits<double>::min());
}

long long toneMapImageEq18(const Image& linear, double exposure_ev, const Eq18Params& p, Image& display) {
  checkImage(linear, exposure_ev);
  const double scale = std::exp2(exposure_ev);
  const int nc = linear.channels;
  const bool grey = nc <= 2;
  const bool has_alpha = nc == 2 || nc == 4;
  const double wa = eq18WorldAdaptation(linear, scale, p);
  const std::size_t n = linear.pixelCount();

  double white = p.white;
  if (p.white_from_image) {  // the largest L_d shows as white
    white = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      double rgb[3];
      pixelRgb(&linear.pixels[i * nc], grey, scale, rgb);
      white = std::max(white, eq18DisplayLuminance(luminance(rgb), wa, p));
    }
    if (!(white > 0) || !std::isfinite(white)) white = 1.0;  // a black image: any white will do
  }

  display.resize(linear.width, linear.height, nc);
  display.channel_names = linear.channel_names;
  long long nonfinite = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const float* in = &linear.pixels[i * nc];
    float* out = &display.pixels[i * nc];
    double rgb[3];
    nonfinite += pixelRgb(in, grey, scale, rgb);
    const double lw = luminance(rgb);
    const double ldf = eq18Compress(eq18DisplayLuminance(lw, wa, p), white);
    // Scale RGB by L_df / L_w (keeps R:G:B), then into the gamut along the same ray (io/tonemap.h).
    const double k = lw > 0 && std::isfinite(ldf) ? ldf / lw : 0.0;
    double m = 0.0;
    for (double& v : rgb) {
      v *= k;
      m = std::max(m, v);
    }
    const double gamut = m > 1.0 ? 1.0 / m : 1.0;
    out[0] = static_cast<float>(srgbEncode(rgb[0] * gamut));
    if (!grey) {
      out[1] = static_cast<float>(srgbEncode(rgb[1] * gamut));
      out[2] = static_cast<float>(srgbEncode(rgb[2] * gamut));
    }
    if (has_alpha) {
      const float a = in[nc - 1];
      if (!std::isfinite(a)) ++nonfinite;
      out[nc - 1] = std::isfinite(a) ? std::clamp(a, 0.0f, 1.0f) : 0.0f;
    }
  }
  return nonfinite;
}

long long toneMapImage8Eq18(const Image& linear, double exposure_ev, const Eq18Params& p,
                            std::vector<std::uint8_t>& bytes) {
  Image display;
  const long long nonfinite = toneMapImageEq18(linear, exposure_ev, p, display);
  bytes.resize(display.pixels.size());
  std::transform(display.pixels.begin(), display.pixels.end(), bytes.begin(), toByte);
  return nonfinite;
}

}  // namespace seasim
