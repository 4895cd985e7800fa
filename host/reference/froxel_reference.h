// froxel_reference.h — the froxel single-scattering pass (kernels/froxel.cl, 002 §5) on the CPU, and
// the brute-force integral it approximates:
//
//  * froxelEvaluateCpu: the same froxel algorithm in double (kmath_d, the same common/froxel.h code):
//    shadow map, injection, front-to-back integration; froxelResolveCpu reads it per pixel as
//    kd_multiple.cl does. The kernels are tested against it.
//  * froxelBruteForcePixelArea: the single-scattering integral along N×N rays per pixel,
//      L_SS = ∫_0^S e^{-c z} b p(θ) E_beam(y(z)) V(x_z) C(x_z) dz,   E_beam(y) = e_beam0 e^{-c y/μ_w},
//    every band on one set of points, the midpoint rule in u = 1 - e^{-c_min z} (the slowest band's
//    transmittance is the measure: no truncation in deep water), an exact shadow ray along sun_dir_water to the surface through the
//    objects at every step, the caustic texture when the scene has it, S the true first hit of
//    uw_scene_hit (not clamped to froxel_far: the froxel method's truncation is part of its error),
//    accumulated to sensor RGB with the bands' w_r, w_g, w_b (002 eq. 4.8). Always spectral: it is the
//    truth RGB injection is measured against.
//
// The set-up the pass and this CPU evaluation share is in underwater/froxel_setup.h.
#pragma once
#include <vector>

#include "math/vec3.h"
#include "scene/scene.h"
#include "underwater/froxel_setup.h"
#include "underwater/underwater_setup.h"

extern "C" {
#include "common/froxel_params.h"
}

namespace seasim {

struct FroxelCpuVolume {
  std::vector<float> shadow_map;  // shadow_size² texels (empty without a map)
  std::vector<float> light;       // V·C per froxel
  std::vector<float> volume;      // 4 floats per froxel (common/froxel_params.h)
};

// The froxel pass in double (shared code of common/froxel.h; caustics when setup.params.caustic_mode
// is UW_CAUSTICS_TEXTURE, or UW_CAUSTICS_MAP with `caustic_maps` = CausticStack::hostMaps()).
// Stored as float, as the kernel stores them.
FroxelCpuVolume froxelEvaluateCpu(const UnderwaterSetup& setup, const FroxelParams& params,
                                  const std::vector<float>* caustic_maps = nullptr);

// The first hit distance S of every pixel's centre ray (uw_scene_hit, double); >= UW_INFINITE (1e30)
// for rays into deep water. Row-major, width × height of setup.params.
std::vector<double> froxelPixelDistances(const UnderwaterSetup& setup);

// froxel_lookup per pixel (RGB, 3 per pixel) at distances S (width × height).
std::vector<double> froxelResolveCpu(const FroxelParams& params, const std::vector<float>& volume,
                                     const std::vector<double>& distances, int width, int height);

// The brute-force L_SS averaged over each pixel's area: subpixels × subpixels rays through the centres
// of a regular grid of sub-pixels, each to its own first hit (what a pixel of the image integrates; the
// path tracer jitters over the same area; subpixels = 1: the pixel centre's ray). All bands share one set of points per ray, the midpoint
// rule in u = 1 - e^{-c z} of the band with the smallest c (so the shadow ray and the caustic are
// evaluated once per point): `steps` points per ray. Sensor RGB, 3 per pixel, oneTBB over rows.
std::vector<double> froxelBruteForcePixelArea(const UnderwaterSetup& setup, int steps, int subpixels);

}  // namespace seasim
