// forward_peak.h — the light of the phase function's forward peak that the improved underwater model's delta-M
// counts as unscattered (s13; kernels/common/underwater_improved.h uwi_tms_phase and uwi_aureole use it).
//
// Delta-M attenuates the sun beam by c' = a + b (1 - f): the beam e^{-c' y/μ_w} carries, besides the
// unscattered light e^{-c y/μ_w}, the light the peak turned by a few degrees. The kernel's TMS term scattered
// that beam once more with the whole p_HG, so the peak's light was counted twice towards the sun (results/
// BENCHMARKS.md s12: 1.26-2.66 of the path tracer at g >= 0.9). Here the HG phase is split into
//   p_HG = min(p_HG, p_clip) + (p_HG - p_clip)+,
// the peak (the second part) holding exactly f of the light (p_clip solves ∫ (p_HG - p_clip)+ dΩ = f). The
// TMS term keeps the first part. The peak's light is drawn as the aureole at the camera, in the small-angle
// picture (each scattering by the peak turns the light independently of the others; Nakajima & Tanaka
// 1988 correct DISORT's intensities near the beam to second order on the same idea): at depth y_c, a
// Poisson number k of scatterings with mean n = (c - c') y_c / μ_w, spread by the peak once (k = 1: the peak
// itself) or by a von Mises-Fisher distribution whose mean cosine is the peak's to the power k (k >= 2: the
// Legendre moments of a convolution multiply). Its total is the surplus F0 (e^{-c' y_c/μ_w} - e^{-c y_c/μ_w}).
#pragma once
#include <vector>

extern "C" {
#include "common/underwater_params.h"
#include "common/underwater_improved_params.h"
}

namespace seasim {

// The ceiling p_clip (per sr) whose excess (p_HG - p_clip)+ integrates to f over the sphere, for HG asymmetry
// g. 0 (no ceiling) where there is no peak: g < 1e-3 or f < 1e-9 (its light is then below 1e-6 of the
// beam's). f at least what p_HG holds above its backward value is capped there (the whole phase but its
// floor).
double hgPeakCeiling(double g, double f);

// The mean cosine of the peak (p_HG - p_clip)+ over its own integral (quadrature on 4000 steps in √θ);
// 1 without a peak (p_clip <= 0).
double hgPeakMeanCosine(double g, double p_clip);

// κ of the von Mises-Fisher distribution on the sphere whose mean cosine coth κ - 1/κ is mean_cosine in
// [0, 1): bisection in log κ. 0 at 0.
double vonMisesFisherKappa(double mean_cosine);

// The von Mises-Fisher density κ e^{κ (cos θ - 1)} / (2π (1 - e^{-2κ})) per sr; 1/(4π) as κ -> 0.
double vonMisesFisher(double cos_theta, double kappa);

// Fills band block o's p_clip, aureole_single and aureole (UwiBand) for HG asymmetry g and delta-M's f, the
// refracted sun's cosine mu_w and the camera's depth y_c, from the band's c and e_beam0 and the block's c_dm
// and m (already set: the kernel's own extinctions, so the aureole's total is the surplus of the kernel's
// beam), and its aureole_modes to 0 (src the order-3 in-scatter, which holds none of the peak's light; a
// high-order fit sets them where it takes over: setAureoleModesHeld). No peak (hgPeakCeiling 0): p_clip and
// the aureole 0, and the kernel's TMS keeps the whole p_HG.
void setForwardPeak(UwiBand& o, const UwBand& band, double g, double f, double mu_w, double y_c);

// Where the source's table was fitted to a high-order field (ordinates_high_order.h), which has the peak's
// light in azimuth modes 0-2: o.aureole_modes[3 j + m] = fit_weight[j] times mode m of the aureole at the
// camera (uwi_aureole_at_camera with p_HG at g; the midpoint rule on 256 azimuths over [0, π]) at source node
// j's cosine, for the kernel to take off (uwi_aureole). mu_w: the refracted sun's cosine as the kernel reads
// it. Set after setForwardPeak.
void setAureoleModesHeld(UwiBand& o, double g, double mu_w, const std::vector<float>& fit_weight);

}  // namespace seasim
