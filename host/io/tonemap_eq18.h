// tonemap_eq18.h — the tone-mapping operator of 003 eq. 18, a display mode beside the project's
// default curve (io/tonemap.h), chosen by the scene's [display] table and usable by every model.
//
//   L_d  = m(L_wa) L_da (L_w / L_wa)^(γ_w / γ_d)             (003 eq. 18, first line)
//   L_df = L_d (1 + L_d / L_white²) / (1 + L_d)              (003 eq. 18, second line)
//
// L_w is the luminance of one pixel of the linear image (Rec. 709 weights of its RGB, after the
// exposure 2^exposure_ev), L_df the luminance shown, 1 = the display's white. The pixel's RGB is
// scaled by L_df / L_w, which keeps R:G:B (hue and saturation), then brought back into the gamut
// along the same ray and sRGB-encoded exactly as io/tonemap.h does.
//
// The paper leaves the constants to its reference [14] (Barladian 2003), which we do not have. Our
// reading, every constant a [display] key (scenes/README.md):
//   L_wa  world adaptation luminance: "log_mean" (default; exp of the mean of ln(δ + L_w), δ = 1e-6,
//         Reinhard et al. 2002's key), "mean" (arithmetic mean), or a number in the image's units;
//   L_da  display adaptation luminance, as a fraction of the display's white (default 0.18: the
//         adapted scene luminance shows as middle grey before the compression of line two);
//   γ_w, γ_d  the world's and the display's contrast exponents (Tumblin–Rushmeier); only their ratio
//         acts. Default 1 and 1;
//   m     the contrast scale m(L_wa) (default 1). Tumblin–Rushmeier (1999) take
//         m = C_max^((γ_w/γ_d − 1)/2) for a display of contrast C_max; give that number here;
//   L_white  the smallest L_d that shows as full white: "max" (default, the image's largest L_d, so
//         nothing burns out) or a number > 0.
// With γ_w = γ_d and m = 1 the operator is Reinhard et al.'s global operator (2002, eq. 3-4).
// Properties the unit tests check: L_df(0) = 0, L_df(L_white) = 1, L_df increasing in L_w for every
// parameter set (dL_df/dL_d = (1 + 2L_d/L_white² + L_d²/L_white²)/(1 + L_d)² > 0), and L_d = L_da
// at L_w = L_wa when m = 1.
#pragma once
#include <cstdint>
#include <vector>

#include "io/image.h"

namespace seasim {

struct Eq18Params {
  enum class Adaptation { LogMean, Mean, Given };
  Adaptation adaptation = Adaptation::LogMean;
  double world_adaptation = 1.0;     // L_wa when adaptation = Given (file: adaptation_luminance = <number>)
  double display_adaptation = 0.18;  // L_da, fraction of display white (file: display_adaptation)
  double gamma_world = 1.0;          // γ_w (file: gamma_world)
  double gamma_display = 1.0;        // γ_d (file: gamma_display)
  double contrast_scale = 1.0;       // m(L_wa) (file: contrast_scale)
  bool white_from_image = true;      // L_white = the image's largest L_d (file: white = "max")
  double white = 1.0;                // L_white when white_from_image is false (file: white = <number>)
};

// [display]: how the linear image becomes the PNG's 8-bit values.
struct DisplayDesc {
  enum class ToneMap { Default, Eq18 };
  ToneMap tone_map = ToneMap::Default;  // "default": io/tonemap.h; "eq18": 003 eq. 18 (this file)
  Eq18Params eq18;
};

// First line of eq. 18: L_d for a world luminance L_w >= 0 and a world adaptation L_wa > 0.
double eq18DisplayLuminance(double world_luminance, double world_adaptation, const Eq18Params& p);
// Second line of eq. 18: L_df for L_d >= 0 and L_white > 0.
double eq18Compress(double display_luminance, double white);

// L_wa of an image (after the exposure `scale`) as `p` asks; non-finite pixels are skipped. An image
// with no light at all gives the smallest positive value, so that every L_d is 0.
double eq18WorldAdaptation(const Image& linear, double scale, const Eq18Params& p);

// The whole image through eq. 18 into display floats in [0,1] (channels as io/tonemap.h's
// toneMapImage: 1, 2, 3 or 4; alpha clamped, not mapped). Returns the number of NaN/Inf values met
// (they show as 0).
long long toneMapImageEq18(const Image& linear, double exposure_ev, const Eq18Params& p, Image& display);
// Same, quantised to 8 bits per channel (the PNG's bytes).
long long toneMapImage8Eq18(const Image& linear, double exposure_ev, const Eq18Params& p,
                            std::vector<std::uint8_t>& bytes);

}  // namespace seasim
