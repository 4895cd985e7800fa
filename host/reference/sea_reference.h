// sea_reference.h — brute-force reference for kernels/sea_single.cl: the same scene in double
// precision on the CPU (TBB), with the single-scattering integral done by midpoint quadrature over
// depth instead of the closed form of 000 eq. 5, and the spectrum integrated at the scene's bands.
#pragma once
#include "io/image.h"
#include "scene/scene.h"

namespace seasim {

// `steps` quadrature intervals along each refracted view ray. Throws RuntimeError for scenes the
// reference does not model (waves, height-field bottom, non-uniform skies).
Image renderSeaReference(const Scene& scene, int steps);

}  // namespace seasim
