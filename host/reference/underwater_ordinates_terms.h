// underwater_ordinates_terms.h — underwater.model = "discrete_ordinates" (common/underwater_ordinates.h) split into
// its terms per pixel, for diagnosis (which term a miss against the path tracer is in). Each
// pixel's centre ray is cast in double with the kernels' own geometry and shaded by the scalar model in
// double, one term at a time; the terms add up to the model's radiance (uwi_band_radiance) plus the
// froxel pass's single scattering, unshadowed.
#pragma once
#include <vector>

#include "underwater/underwater_setup.h"

namespace seasim {

// Every term summed over the bands with the sensor's weights (w_r + w_g + w_b): the units of a render's
// three channels added, as the region ratios take them.
struct UwiPixelTerms {
  // The in-scatter along the view ray (uwi_multiple): the two-stream's modes (e^{-k y}, e^{-k (H - y)}),
  // the beam's diffuse offspring (e^{-m y}), the beam scattered once at the exact phase below its peak (TMS), and the
  // froxel pass's unshadowed strict single scattering (002 eq. 5.2), which the model takes off where
  // the froxel pass runs and that pass adds back with its shadows (0 without froxels).
  double inscatter_modes = 0, inscatter_beam = 0, inscatter_tms = 0, froxel_ss = 0;
  // The forward peak's aureole at the camera (uwi_aureole): the light delta-M's beam carries that the
  // peak turned towards the view (the TMS term above scatters that beam with p_HG capped below the peak).
  double aureole = 0;
  // The surface seen from below (uwi_surface) times T(S): the sky through Snell's window, n² (1 - F) L_sky;
  // F times the reflected ray's in-scatter as the model takes it; F times the bottom (or the object in
  // the mirror, uwi_mirror_hit) it ends on.
  double window = 0, reflected_inscatter = 0, reflected_bottom = 0;
  // The beam's strict single scattering along the reflected ray (closed form, unshadowed) times T(S) F,
  // for comparison (0 without froxels): no froxel pass runs along a reflected ray, so the model keeps it
  // in reflected_inscatter as its TMS term (it does not take it off there, as along the camera's ray).
  double reflected_froxel_ss = 0;
  // 1 where the surface's reflected ray meets an object before the bottom or deep water (the model
  // traces it: uwi_mirror_hit).
  double reflected_object = 0;
  // A Lambertian hit (object or bottom) times T(S): uwi_lambert.
  double lambert = 0;
  // Of the hit's light that reaches the camera (lambert, or the surface's window and reflected terms), the
  // part delta-M counts as unscattered though it was scattered by a few degrees on the way: 1 - e^{-(c - c') S}
  // of it. The model sends it on from the same point; the water spreads it over the pixels around (its
  // point-spread; without it the objects at g >= 0.9 came out too dark, the pixels beside them too
  // bright: docs/journal/underwater_regions_3_*.md). Not in total.
  double forward = 0;
  // uwi_band_radiance + froxel_ss: the model's total (its in-scatter clamped at 0 as the kernel does).
  double total = 0;
};

// Row-major, width × height of setup.params. setup.ordinates must hold one UwiBand per band
// (underwater.model = "discrete_ordinates"; RuntimeError otherwise). multiple_scattering: the scene's
// underwater.multiple_scattering (false leaves every in-scatter term out, as the kernel does).
// A uniform sky (the surface's window takes each band's sky_radiance).
std::vector<UwiPixelTerms> ordinatesModelTerms(const UnderwaterSetup& setup, bool multiple_scattering);

}  // namespace seasim
