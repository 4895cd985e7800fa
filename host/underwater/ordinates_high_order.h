// ordinates_high_order.h — the view rays' source for underwater.model = "discrete_ordinates", fitted to the radiance of
// a discrete-ordinates solution at a high delta-M order (underwater.source_streams).
//
// The kernel attenuates view rays by the delta-M extinction c' of order 3 (f = g³) and adds the delta-M
// beam's single scattering with the exact phase (TMS). The order-3 field's own in-scatter, in azimuth
// modes 0-2, misses the azimuthal shape of the light the forward peak spreads around the beam: at 3.8 m,
// near-horizontal views at g >= 0.9 came out 0.84-1.12 of a 32-stream solution by azimuth, the pattern
// the path tracer showed (docs/journal/underwater_regions_4_*.md).
// Along any ray the high-order radiance L_f obeys
//   dL_f/ds = -c' L_f + [J_f + SS_f - (c_f - c') L_f]
// (J_f its in-scatter, SS_f its beam's single scattering with the exact phase, c_f its extinction): so a
// segment of length S from depth y0 along cosine ν gathers exactly
//   ∫_0^S [...] e^{-c' s} ds = L_f(y0) - e^{-c' S} L_f(y0 - ν S)
// with c'. The bracket itself has layers as thin as |ν|/c_f at the surface and the bottom, which the
// table's three exponentials in depth cannot follow; its integrals can be held instead. So the table is
// fitted, per cosine and azimuth mode, to those segment integrals (less the kernel's own TMS term) from the
// camera's depth and from the surface (the mirror rays), at lengths of 1/4 to 32 of c''s optical depths
// and to the surface or the bottom, with the bracket itself as a weak regulariser. L_f at the table's
// cosines comes from integrating J_f + SS_f along each direction through the layer with the surface's and
// the bottom's conditions (the source-function integration of DISORT's user angles).
//
// The table holds azimuth modes 0-2; the kernel's TMS carries every mode of the delta-M beam. Where the
// beam's phase has structure in azimuth beyond mode 2 (within a few peak widths of the beam's direction),
// the high-order field's low modes would be paired with the delta-M beam's high ones, so there the order-3
// field's own in-scatter is kept (beamTaper).
#pragma once
#include <array>
#include <vector>

#include "underwater/discrete_ordinates.h"

namespace seasim {

// The high-order solution's radiance L_f and source J_f + SS_f at the cosines `nus` (symmetric about 0) on
// an even depth grid from 0, per azimuth mode (the coefficient of cos m Δφ, Δφ from the beam's azimuth).
struct HighOrderField {
  double c = 0;     // its delta-M extinction, 1/m
  double step = 0;  // the grid's depth step, m
  int depths = 0, cosines = 0, modes = 0;
  std::array<std::vector<double>, 3> radiance, source;  // depths x cosines per mode
  std::array<std::vector<double>, 3> beam_phase;        // b p_m(ν, μ_sun) e_beam per cosine: the exact
                                                        // phase's single scattering per unit of beam
  // Mode `mode`'s radiance (source) at cosine index u and depth y, linear between the grid's depths
  // (clamped to the grid).
  double radianceAt(int mode, int u, double y) const { return lerp(radiance[mode], u, y); }
  double sourceAt(int mode, int u, double y) const { return lerp(source[mode], u, y); }

 private:
  double lerp(const std::vector<double>& v, int u, double y) const;
};

// Solved at `streams` cosines per hemisphere and the same delta-M order (the split quadrature), in azimuth
// modes 0..modes-1 (1..3), to depth y_end (the bottom's depth when there is one; without a bottom the grid
// goes 30 of the solution's optical depths deeper, where rays looking up gather from), in steps of at most
// half its optical depth and of y_end / 100 (a quarter and y_end / 200: the same regions to 0.001,
// docs/journal/underwater_regions_4_*.md), at most 6000 steps.
HighOrderField solveHighOrderField(const DiscreteOrdinatesLayer& layer, int streams, int modes,
                                   const std::vector<double>& nus, double y_end);

// The kernel's view-ray source basis (common/underwater_ordinates.h: e^{-k y}, e^{-k (H - y)} with a bottom,
// e^{-m y}; extinction c_kernel) and where its rays start.
struct SourceTableBasis {
  double k = 0, m = 0, c_kernel = 0;
  double bottom_depth = 0;  // m; 0: no bottom
  double depth_end = 0;     // m: the depth samples' end (the bottom's depth with one)
  double view_depth = 0;    // m: the camera's depth
  int samples = 2;          // the depth samples of the weak source rows
  // The kernel's TMS term per unit of e^{-m y} in azimuth modes (the coefficient of cos m Δφ) per table
  // cosine, which the targets leave out: b e_beam0 min(p_HG, p_clip) (forward_peak.h); empty: the
  // field's beam_phase, the whole p_HG. The kernel's aureole is not taken off: the field has the forward
  // peak's light in the modes the table holds, and the kernel adds only the aureole's higher modes where
  // the fit was taken (UwiBand.aureole_modes, forward_peak.h setAureoleModesHeld, from fit_weight).
  std::array<std::vector<double>, 3> tms;
};

// Fits `table` (UwiBand.src's layout: cosine j's coefficients of the three exponentials, 3 per mode) to the
// field as above, blended by beamTaper with what `table` held (the order-3 field's fit) for a beam at
// cosine mu_sun (e_sun0 > 0; none: the field everywhere).
// fit_weight (optional, one per cosine): the blend's weight where the fit was taken, left as it was where
// the order-3 row was kept (within the beam's taper's core, or a singular fit).
void fitSourceTableToField(const HighOrderField& field, const std::vector<double>& nus, const SourceTableBasis& basis,
                           double mu_sun, bool beam, float* table, int terms_per_cosine, float* fit_weight = nullptr);

// The weight of the high-order fit against the order-3 one at downward cosine nu for a beam at mu_sun: 0
// within delta0 of the beam's polar angle, 1 beyond delta1 (radians), smooth between.
double beamTaper(double nu, double mu_sun, double delta0, double delta1);

}  // namespace seasim
