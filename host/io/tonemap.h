// tonemap.h — the one display transform: what the PNG shows and what the 8-bit error metrics of
// host/reference/compare.h measure (DESIGN.md "Error against run time": RMSE and max |Δ| in 8-bit
// levels "after the same tone map").
//
// linear RGB  --x 2^exposure_ev-->  clamp negatives to 0  -->  Reinhard on luminance
//   Y' = Y / (1 + Y), RGB scaled by Y'/Y = 1/(1+Y)   (Y = 0.2126 R + 0.7152 G + 0.0722 B, Rec. 709)
//   --> if a channel still exceeds 1 (saturated bright colours), divide all three by the largest
//   --> sRGB OETF (IEC 61966-2-1)  -->  display value in [0,1]  -->  8-bit = round(255 v)
//
// Why this curve: it never clips a highlight to flat white (sun glint and bright sky near the
// horizon keep their gradient), it is close to linear in the dark range where water colour lives
// (slope 1 at 0, so 2^exposure_ev sets the brightness of the sea), and both steps keep the ratio
// R:G:B, so hue and saturation of the linear colour reach the display unchanged (the hue metric
// of 002 §6.1 is not disturbed by the tone map itself). A mid-grey of Y = 1 shows as 0.5 linear.
//
// Negative linear values (out-of-gamut spectra after XYZ -> RGB) are clamped to 0. NaN and ±Inf
// become 0 and are counted: every function returns the number of non-finite values it met.
#pragma once
#include <cstdint>
#include <vector>

#include "io/image.h"

namespace seasim {

// sRGB OETF (IEC 61966-2-1): linear [0,1] -> encoded [0,1]; input is clamped to [0,1].
double srgbEncode(double linear);
// Inverse of srgbEncode, for tests and for reading 8-bit files back into linear values.
double srgbDecode(double encoded);

// Display value in [0,1] -> 8-bit level, rounded to nearest.
std::uint8_t toByte(float display);

// One linear RGB colour -> display sRGB in [0,1]. `scale` = 2^exposure_ev. Returns how many of the
// three inputs were NaN/Inf (those components count as 0).
int toneMapRgb(const float linear[3], double scale, float display[3]);

// Whole image -> display floats in [0,1], same size and channel layout. Channels: 1 (grey, shown
// as R=G=B), 2 (grey + alpha), 3 (RGB) or 4 (RGBA); alpha is clamped to [0,1], not tone mapped.
// Any other channel count throws RuntimeError. Returns the number of NaN/Inf values met.
long long toneMapImage(const Image& linear, double exposure_ev, Image& display);

// Same, quantised to 8 bits per channel (the PNG's bytes), interleaved like `linear`.
long long toneMapImage8(const Image& linear, double exposure_ev, std::vector<std::uint8_t>& bytes);

}  // namespace seasim
