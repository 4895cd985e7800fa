// underwater_ordinates_solver.h — underwater.model = "discrete_ordinates" with underwater.diffuse =
// "discrete_ordinates": one band's coefficients (UwiBand, common/underwater_ordinates_params.h) from a
// discrete-ordinates solution of the plane-parallel water (discrete_ordinates.h), not the two-stream.
//
// The kernel's diffuse field is three exponentials in depth, e^{-k y}, e^{-k (H - y)} and the delta-M
// beam's e^{-m y} (m = c'/μ_w), for each of E_d, E_u, the scalar irradiance E_0 and the horizontal flux
// F_h. Here they are fitted, by weighted least squares in relative error over the depths the frame sees
// ([0, H] over a bottom; down to 5 attenuation lengths c'^-1 below the camera without one), to the
// discrete ordinates' field less the kernel's delta-M beam (the diffuse light the kernel's beam does not
// carry); k is the one of a scan over [0.8, 2.5] K∞ with the least error (the field near the surface
// decays faster than its asymptotic K∞). E_d and E_u light the surfaces; E_0 and F_h are kept for the
// record (the two-stream's first-order source uses its own).
//
// The view rays' source is the solver's own in-scatter towards UWI_SOURCE_NODES (129) cosines, azimuth
// modes 0–2 (DiscreteOrdinates::inscatterProfile), fitted per cosine over the same depths to the same three
// exponentials: UwiBand.src. The solver runs at the delta-M order kOrdinatesSourceMoments, the one number
// fitted to the path tracer, and the kernel's delta-M is the solver's (c' its ĉ, m its beam's): the view
// rays integrate the source in the frame it was computed in. At order 3 the phase has three Legendre
// terms, so azimuth modes 0–2 are all the in-scatter has, and the table holds it whole. By default
// (underwater.source_streams > 0) the table is then fitted instead to the radiance of a
// solution at a high delta-M order, carried with the kernel's c' (ordinates_high_order.h), but towards
// the beam's direction, where the order-3 in-scatter stays.
//
// The objects' faces are lit by the solver's irradiance on their tilted plane (DiscreteOrdinates::
// tiltedIrradianceProfile, azimuth modes 0–2 at UWI_TILT_NODES normals), fitted the same way: UwiBand.tilt.
#pragma once
#include <vector>

extern "C" {
#include "common/underwater_params.h"
#include "common/underwater_ordinates_params.h"
}

namespace seasim {

struct ForwardPeak;     // forward_peak.h
struct SkyWindowModes;  // sky_window_modes.h

// The delta-M order (phase moments kept, f = g^M) of the discrete-ordinates solution whose in-scatter is
// the kernel's source and whose extinction ĉ = a + b (1 - g^M) attenuates the view rays (fitted to the
// path tracer: docs/journal/underwater_regions_3_*.md).
inline constexpr int kOrdinatesSourceMoments = 3;

// How well the exponentials hold the discrete ordinates' field: the largest relative error over the
// fitted depths of E_d (against the total with the beam), E_u, E_0 (with the beam) and F_h (relative to E_0).
struct OrdinatesFitError {
  double down = 0, up = 0, scalar = 0, horizontal = 0;
  double source = 0;  // the in-scatter table's (azimuth modes 0–2, relative to the average's size)
  double tilt = 0;    // the tilted plane's irradiance table's (the same; its end nodes are E_d's and E_u's)
};

// The streams (and delta-M order) of the solution the view rays' source is fitted to (16 to 48 gave
// the same regions; ordinates_high_order.h); underwater.source_streams. 0: the order-3 field's
// own in-scatter.
inline constexpr int kOrdinatesHighOrderStreams = 32;

// One band. mu_w: the refracted sun's cosine (any value in (0, 1] when the sun is off); bottom_depth <= 0:
// no bottom; view_depth: the camera's depth (diffuseViewDepth). streams: the discrete ordinates'
// cosines per hemisphere. fit (optional): the fit's errors (the source's: of the order-3 field's own
// in-scatter). source_streams: kOrdinatesHighOrderStreams' meaning.
// peak: the forward peak of g and f = g³ (forward_peak.h), the same for every band; null: computed here.
// sky: the sky's shape below the surface (DiscreteOrdinatesLayer::sky_shape); null: a uniform sky.
UwiBand makeUwiBandFromOrdinates(const UwBand& band, double g, double mu_w, double bottom_depth, double ior,
                                 double view_depth, int streams = 16, OrdinatesFitError* fit = nullptr,
                                 int source_streams = kOrdinatesHighOrderStreams, const ForwardPeak* peak = nullptr,
                                 const SkyWindowModes* sky = nullptr);

// All bands of a set-up (params.g, bottom_depth, ior, sun_dir_water[1], the camera's depth of
// diffuseViewDepth); sky as above, each band taking its share (UwBand::sky_w_*).
std::vector<UwiBand> makeUwiBandsFromOrdinates(const UwParams& params, const std::vector<UwBand>& bands,
                                               int source_streams = kOrdinatesHighOrderStreams,
                                               const SkyWindowModes* sky = nullptr);

}  // namespace seasim
