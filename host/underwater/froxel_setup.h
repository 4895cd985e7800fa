// froxel_setup.h — the set-up of the froxel single-scattering pass (kernels/froxel.cl, 002 §5) that the
// pass and its CPU evaluation (reference/froxel_reference.h) share: FroxelConfig from the scene,
// FroxelParams (grid, shadow-map frame, the RGB pseudo-bands), the bands the integration reads.
#pragma once
#include <vector>

#include "scene/scene.h"
#include "underwater/underwater_setup.h"

extern "C" {
#include "common/froxel_params.h"
}

namespace seasim {

struct FroxelConfig {
  int nx = 80, ny = 45, nz = 32;   // froxel grid: quality froxel_x, froxel_y, froxel_z
  double z_near = 0.1;             // m, underwater.froxel_near_m (end of the first slice: see froxel.h)
  double z_far = 60.0;             // m, underwater.froxel_far_m
  int shadow_map_size = 512;       // texels per side of the sun shadow map: quality shadow_map_size
  bool rgb_injection = false;      // underwater.froxel_injection = "rgb"
};

// The scene's settings. The columns are set by their angular spacing: froxel_x and froxel_y are "auto"
// unless the scene gives them, quality.froxel_columns (80) across the image's wider side, at most one
// per pixel, the other side in proportion (80×45 at 16:9); froxel_z slices (32). The defaults are the
// froxel sweep's choice against the quadrature reference (results/BENCHMARKS.md "Froxel single
// scattering").
FroxelConfig froxelConfigFromScene(const Scene& scene);

// The RGB pseudo-bands (002 eq. 5.3–5.4 in spirit): for channel k with non-negative weights
// ω_i = max(w_k,i, 0) (the sensor's response to band i, band width included):
//   σ̄_t,k = Σ ω_i c_i / Σ ω_i                  (eq. 5.4: MFP = 1/∫ σ_t f dλ, f normalised)
//   ā_k   = Σ ω_i (b_i / c_i) / Σ ω_i          (eq. 5.3: single-scattering albedo), σ̄_s,k = ā_k σ̄_t,k
//   Ē_k   = Σ_i w_k,i e_beam0,i                (the sensor's value of the beam just below the surface:
//                                               exact, so RGB differs from spectral only through the
//                                               exponentials of averaged coefficients)
// Returned as three UwBand entries (b = σ̄_s, c = σ̄_t, a = c - b, e_beam0 = Ē, w = unit vector of
// channel k; other fields 0). Σ ω_i = 0 gives a black channel.
std::vector<UwBand> froxelRgbPseudoBands(const UnderwaterSetup& setup);

// Grid, RGB pseudo-band coefficients and the sun shadow map's frame: the square map, normal to the
// refracted sun direction, covers the bounding sphere of the spheres and boxes (radius R about their
// bounding box's centre), its plane R + 1 m above that centre along sun_dir_water; shadow_size = 0 when
// there are no spheres or boxes. RuntimeError for a grid of < 1 or > 2^29 froxels or bad near/far.
FroxelParams makeFroxelParams(const UnderwaterSetup& setup, const FroxelConfig& config);

// The vertical direction d_y of every column's ray (common/froxel.h froxel_column_dir in float), row-major
// nx × ny: the one table froxel_column_extent and froxel_integrate (hence froxel_lookup) read, so the
// marking of the columns a read needs and the read itself agree on which rays reach the surface.
std::vector<float> froxelColumnDy(const UnderwaterSetup& setup, const FroxelParams& params);

// The bands froxel_integrate reads: setup.bands (spectral injection) or froxelRgbPseudoBands.
std::vector<UwBand> froxelIntegrationBands(const UnderwaterSetup& setup, const FroxelParams& params);

}  // namespace seasim
