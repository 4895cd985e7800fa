// forward_peak.h — the light of the phase function's forward peak that the discrete-ordinates underwater model's delta-M
// counts as unscattered (kernels/common/underwater_ordinates.h uwi_tms_phase and uwi_aureole use it).
//
// Delta-M attenuates the sun beam by c' = a + b (1 - f): the beam e^{-c' y/μ_w} carries, besides the
// unscattered light e^{-c y/μ_w}, the light the peak turned by a few degrees. A TMS term that scattered
// that beam once more with the whole p_HG counted the peak's light twice towards the sun
// (docs/journal/underwater_regions_4_*.md: 1.26-2.66 of the path tracer at g >= 0.9). The HG phase is split into
//   p_HG = min(p_HG, p_clip) + (p_HG - p_clip)+,
// the peak (the second part) holding exactly f of the light (p_clip solves ∫ (p_HG - p_clip)+ dΩ = f). The
// TMS term keeps the first part. The peak's light is drawn as the aureole at the camera: at depth y_c the beam
// has met a Poisson number k of scatterings by the peak, mean n = (c - c') y_c / μ_w, each turning it by the
// peak's own distribution P = (p_HG - p_clip)+ / f, independently (the peak's light stays near the beam, so
// the depth it has to cross is the beam's). k scatterings spread it by P convolved k times on the sphere,
// whose Legendre moments are P's to the power k (Nakajima & Tanaka 1988 correct DISORT's intensities near
// the beam to second order on the same idea). So the light scattered twice or more is
//   F0 e^{-c' y_c/μ_w} Σ_l (2l + 1)/(4π) e^{-n} (e^{n χ_l} - 1 - n χ_l) P_l(cos θ),
// χ_l the moments of P; the once-scattered light F0 e^{-c' y_c/μ_w} n e^{-n} P(θ) is drawn exactly in the
// kernel from the pixel's p_HG. Its total is the surplus F0 (e^{-c' y_c/μ_w} - e^{-c y_c/μ_w}).
#pragma once
#include <vector>

extern "C" {
#include "common/underwater_params.h"
#include "common/underwater_ordinates_params.h"
}

namespace seasim {

// The ceiling p_clip (per sr) whose excess (p_HG - p_clip)+ integrates to f over the sphere, for HG asymmetry
// g. 0 (no ceiling) where there is no peak: g < 1e-3 or f < 1e-9 (its light is then below 1e-6 of the
// beam's). f at least what p_HG holds above its backward value is capped there (the whole phase but its
// floor).
double hgPeakCeiling(double g, double f);

// The peak of HG asymmetry g holding delta-M's f: its ceiling and the Legendre moments χ_l of P = (p_HG -
// p_clip)+ / f (χ_0 = 1), by the midpoint rule on 6000 steps in √θ over the peak, up to where 32 in a row are
// below 1e-7 (l <= 4000; g = 0.999 reaches the cap). Shared by every band of a set-up (it depends on g and f
// alone). No peak: p_clip 0, no moments.
struct ForwardPeak {
  double g = 0, f = 0, p_clip = 0;
  std::vector<double> moments;
};
ForwardPeak forwardPeak(double g, double f);

// Fills band block o's p_clip, aureole_single and aureole (UwiBand) for the peak, the refracted sun's cosine
// mu_w and the camera's depth y_c, from the band's c and e_beam0 and the block's c_dm
// and m (already set: the kernel's own extinctions, so the aureole's total is the surplus of the kernel's
// beam), and its aureole_modes to 0 (src the order-3 in-scatter, which holds none of the peak's light; a
// high-order fit sets them where it takes over: setAureoleModesHeld). No peak (hgPeakCeiling 0): p_clip and
// the aureole 0, and the kernel's TMS keeps the whole p_HG. Returns the factor the table was scaled by so that,
// read as the kernel reads it, it holds its light over the sphere (1 where there is none to hold).
double setForwardPeak(UwiBand& o, const UwBand& band, const ForwardPeak& peak, double mu_w, double y_c);

// Where the source's table was fitted to a high-order field (ordinates_high_order.h), which has the peak's
// light in azimuth modes 0-2: o.aureole_modes[3 j + m] = fit_weight[j] times mode m of the aureole at the
// camera (uwi_aureole_at_camera with p_HG at g; the midpoint rule on 256 azimuths over [0, π]) at source node
// j's cosine, for the kernel to take off (uwi_aureole). mu_w: the refracted sun's cosine as the kernel reads
// it. Set after setForwardPeak.
void setAureoleModesHeld(UwiBand& o, double g, double mu_w, const std::vector<float>& fit_weight);

}  // namespace seasim
