// fourflow_waves.h — the four-flow model's air–water coefficients over the FFT ocean's wave patch
// (paper 003 eq. 10; the per-facet maths and our reading of each term are in
// kernels/common/fourflow_waves.h). The patch is the scene's [surface] type = "fft" at surface.time,
// computed on the host by OceanCpu (double), once per scene: it is the paper's preprocessing.
#pragma once

#include <array>
#include <vector>

#include "scene/scene.h"

namespace seasim {

// The coefficients of 003 eq. 6–7 (FfSurface of kernels/common/fourflow.h, in double).
struct FourFlowSurface {
  double T_dd = 0, T_df = 0, T_ff = 0;     // air -> water
  double Rw_dd = 0, Rw_df = 0, Rw_ff = 0;  // reflected back down under the surface ("~")
};

// The flat water mirror (fourflow.h ff_flat_surface).
FourFlowSurface flatFourFlowSurface(double mu_sun, double n_water);

// Eq. 10 averaged over facets with unit normals `normals` (y up): the sun at zenith angle sun_zenith,
// azimuth sun_azimuth (radians from +x towards +z), a uniform sky; intervals: Simpson intervals per
// piece of each facet's hemisphere integral (0: FF_WAVE_INTERVALS). Facets with n_y <= 0 (folded) are skipped.
FourFlowSurface waveAveragedSurface(const std::vector<std::array<double, 3>>& normals, double sun_zenith,
                                    double sun_azimuth, double n_water, int intervals = 0);

// The unit normals of the scene's FFT patch (surface.time), every stride-th texel along each axis so
// that at most max_side x max_side facets are returned.
std::vector<std::array<double, 3>> oceanFacetNormals(const SurfaceDesc& surface, int max_side = 64);

}  // namespace seasim
