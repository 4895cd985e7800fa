// compare.h — the error of a render against a reference image (DESIGN.md "Error against run time").
//
//   rmse_8bit, max_abs_8bit  RMS and largest |Δ| over all pixels and the R,G,B channels, in 8-bit
//                            display levels: both images go through the PNG's tone map
//                            (io/tonemap.h, same exposure) and are scaled by 255, as the papers
//                            report (001: "RMS error 2.6 % of 256 levels"; 000 §6.1: 1/255). The
//                            display values are not rounded first, so convergence curves are
//                            smooth rather than stepped by quantisation.
//   rel_l2                   ||test − ref|| / ||ref|| over the linear R,G,B values (0 when both are
//                            zero, +inf when only the reference is zero).
//   hue_sat_distance         002 §6.1: convert both display colours to HSV, ignore V ("normalizing
//                            the Value channel"), place each at polar coordinates (S, H) in the unit
//                            disc, (S cos H, S sin H), and take the Euclidean distance there — hue
//                            is cyclic, so 359° and 1° are close. Mean over pixels; range [0, 2].
//                            Computed on the tone-mapped display colours, as the thesis compared
//                            rendered screenshots (the tone curve keeps linear R:G:B; the sRGB
//                            encoding then acts per channel, as on any display). Pure red vs pure
//                            green: sqrt(3).
//   nonfinite                NaN/Inf values met in the R,G,B channels of both images; they count
//                            as 0 in the display metrics and are left out of rel_l2.
//
// Images of 1 or 2 channels are grey (+ alpha), 3 or 4 are RGB(A); alpha is ignored.
#pragma once
#include "io/image.h"

namespace seasim {

struct CompareResult {
  double rmse_8bit = 0, max_abs_8bit = 0, rel_l2 = 0, hue_sat_distance = 0;
  long long nonfinite = 0;
  int width = 0, height = 0;
};

// Different width, height or colour layout (grey vs RGB), or more than 4 channels: RuntimeError.
CompareResult compareImages(const Image& test, const Image& reference, double exposure_ev = 0);

// The reference's own noise in the units of rmse_8bit: the RMS over pixels and display channels of
// the display error one standard error of the reference makes. Per pixel the tone map is linearised
// (each linear channel c moved by its standard error se_c alone, the change in every display
// channel taken; channels' noise independent), so a display channel's variance is the sum over c of
// those changes squared. A test image that were exact would score about this rmse against the
// reference: rmse² ≈ bias² + noise² (the reference's noise is independent of the test image).
// `std_error` has the reference's size and channel layout (RuntimeError otherwise).
double referenceNoise8bit(const Image& reference, const Image& std_error, double exposure_ev = 0);

// HSV of a display colour in [0,1]: h in degrees [0, 360), s and v in [0,1] (h = s = 0 for greys).
void rgbToHsv(const float rgb[3], double& h_deg, double& s, double& v);

// 002 §6.1 distance between two display colours (see above), in [0, 2].
double hueSatDistance(const float a[3], const float b[3]);

}  // namespace seasim
