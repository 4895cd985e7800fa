// sea_reference.h — brute-force reference for kernels/sea_single.cl: the same scene in double
// precision on the CPU (TBB), with the single-scattering integral done by midpoint quadrature over
// depth instead of the closed form of 000 eq. 5, and the spectrum integrated at the scene's bands.
#pragma once
#include "io/image.h"
#include "scene/scene.h"

namespace seasim {

// `steps` quadrature intervals along each refracted view ray. FFT waves: the ocean from
// host/ocean/ocean_cpu.h in double at surface.time, read as kernels/common/sea_waves.h describes
// (mean-surface hit, local normal; sunlight through the flat mean surface); skies as
// host/passes/sea_sky.h. A height-field bottom (000 §5.4): z_Q and the floor normal from a fine march of
// the floor (reference/sea_floor_reference.h), not the kernels' cell walk.
Image renderSeaReference(const Scene& scene, int steps);

}  // namespace seasim
