// sea_reference.h — brute-force reference for kernels/sea_single.cl: the same scene in double
// precision on the CPU (TBB), with the single-scattering integral done by midpoint quadrature over
// depth instead of the closed form of 000 eq. 5, and the spectrum integrated at the scene's bands.
#pragma once
#include <vector>

#include "io/image.h"
#include "math/vec3.h"
#include "scene/scene.h"

namespace seasim {

// `steps` quadrature intervals along each refracted view ray. FFT waves: the ocean from
// host/ocean/ocean_cpu.h in double at surface.time, read as kernels/common/sea_waves.h describes
// (mean-surface hit, local normal; sunlight through the flat mean surface); skies as
// host/passes/sea_sky.h. A height-field bottom (000 §5.4): z_Q and the floor normal from a fine march of
// the floor (reference/sea_floor_reference.h), not the kernels' cell walk.
// Water-leaving terms cross the surface as radiance / n² (T_o = (1 - R) / n², docs/radiometry.md).
// sea.model = "multiple": its closed form (common/sea_multiple.h) evaluated in double instead of eq. 5/9.
Image renderSeaReference(const Scene& scene, int steps);

// What a camera at depth z0 (m, below a flat surface) looking along view_in_water (downwards) sees of
// paper 000's water, per band of the scene's grid (W m⁻² sr⁻¹ nm⁻¹ in the water): the single scattering
// of eq. 5 from z0 down (midpoint quadrature, `steps` intervals) and the flat bottom of eq. 9, both
// without T_o. No sky reflected by the surface's underside. The n² test compares it with the sea seen
// from just above: L_air = L_water (1 - R) / n².
std::vector<double> seaUpwellingBelow(const Scene& scene, Vec3 view_in_water, double z0, int steps);

}  // namespace seasim
