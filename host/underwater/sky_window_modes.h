// sky_window_modes.h — a sky that is not uniform, as the discrete-ordinates model's surface sees it: the
// azimuthal modes of the sky's shape along the light's downward direction in water, through a flat
// surface (Snell's window), so that the solver's upper boundary carries the sky's zenith and azimuth
// structure instead of a uniform sky of the same transmitted irradiance.
//
// For light travelling down at cosine μ in water and azimuth φ (from the refracted sun beam's horizontal
// direction of travel), the sky is seen along a(μ, φ) in air: sin θ_a = n √(1 − μ²) (Snell), the
// horizontal part at φ from the sun's azimuth. The shape's modes
//   S_0(μ) = (1/2π) ∫ S(a) dφ,   S_m(μ) = (1/π) ∫ S(a) cos(m φ) dφ  (m = 1, 2),
// are the coefficients of L(μ, φ) = Σ_m S_m(μ) cos(m φ), the solver's convention. Only the even part
// in φ is kept (a sky asymmetric about the sun's vertical plane loses its sin φ part: the model has
// one plane of symmetry). S is common/sky_view.h's shape (scale included); a band's is its weights'
// share of the three channels, taken linearly here (sky_view_band holds it at 0 in the rare violet
// corner where the daylight basis goes negative).
#pragma once
#include <array>
#include <vector>

#include "sky/sky_light.h"

namespace seasim {

struct SkyWindowModes {
  double mu_min = 0;  // the window's edge in water, √(1 − 1/n²): no sky below it (total reflection)
  // At `samples` cosines evenly from mu_min to 1: per mode m, the shape's R, G, B modes.
  std::vector<std::array<std::array<double, 3>, 3>> modes;
  bool grey = true;   // the uniform and CIE skies: one channel (R), no band weights

  // A band's modes S_0..2 at downward cosine mu (linear in mu between samples; 0 below mu_min), given
  // the band's share of R, G, B (UwBand::sky_w_*).
  std::array<double, 3> at(double mu, const std::array<double, 3>& band_weights) const;
};

// The modes of `sky` (its params and buffer as the kernels read them) below a flat surface of relative
// index ior, φ measured from the refracted sun's horizontal direction (sun_dir, unit, towards the sun
// in air; the sun at the zenith: from +x). The uniform sky gives S_0 = 1, S_1 = S_2 = 0 exactly.
SkyWindowModes makeSkyWindowModes(const SkyLight& sky, double ior, int samples = 64, int azimuths = 256);

}  // namespace seasim
