// underwater_improved_ordinates.h — underwater.model = "improved" with underwater.improved_diffuse =
// "discrete_ordinates": one band's coefficients (UwiBand, common/underwater_improved_params.h) from a
// discrete-ordinates solution of the plane-parallel water (discrete_ordinates.h), not the two-stream.
//
// The kernel's diffuse field is three exponentials in depth, e^{-k y}, e^{-k (H - y)} and the delta-M
// beam's e^{-m y} (m = c'/μ_w), for each of E_d, E_u, the scalar irradiance E_0 and the horizontal flux
// F_h. Here they are fitted, by weighted least squares in relative error over the depths the frame sees
// ([0, H] over a bottom; down to 5 attenuation lengths c'^-1 below the camera without one), to the
// discrete ordinates' field less the kernel's delta-M beam (the diffuse light the kernel's beam does not
// carry); k is the one of a scan over [0.8, 2.5] K∞ with the least error (the field near the surface
// decays faster than its asymptotic K∞). No table fitted to the path tracer enters: E_0 replaces the
// streams' mean cosines, and F_h adds the source's dependence on the view's azimuth from the sun.
#pragma once
#include <vector>

extern "C" {
#include "common/underwater_params.h"
#include "common/underwater_improved_params.h"
}

namespace seasim {

// How well the exponentials hold the discrete ordinates' field: the largest relative error over the
// fitted depths of E_d (against the total with the beam), E_u, E_0 (with the beam) and F_h (relative to E_0).
struct OrdinatesFitError {
  double down = 0, up = 0, scalar = 0, horizontal = 0;
};

// One band. mu_w: the refracted sun's cosine (any value in (0, 1] when the sun is off); bottom_depth <= 0:
// no bottom; view_depth: the camera's depth (diffuseViewDepth); flux_scale: s of g_flux = s g'.
// streams: the discrete ordinates' cosines per hemisphere. fit (optional): the fit's errors.
UwiBand makeUwiBandFromOrdinates(const UwBand& band, double g, double mu_w, double bottom_depth, double ior,
                                 double view_depth, double flux_scale, int streams = 16,
                                 OrdinatesFitError* fit = nullptr);

// The flux term's scale s(g) for this solver (UwiBand::g_flux = s g'), a table fitted to the path
// tracer (see the .cpp).
double ordinatesFluxScale(double g);

// All bands of a set-up (params.g, bottom_depth, ior, sun_dir_water[1], the camera's depth of
// diffuseViewDepth) with the flux scale (negative: ordinatesFluxScale(g)).
std::vector<UwiBand> makeUwiBandsFromOrdinates(const UwParams& params, const std::vector<UwBand>& bands,
                                               double flux_scale = -1);

}  // namespace seasim
