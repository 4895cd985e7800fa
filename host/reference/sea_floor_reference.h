// sea_floor_reference.h — the height-field sea floor (000 §5.4) for the references, written apart from
// kernels/common/sea_bottom.h on purpose: the floor's bilinear depth (border extended outwards, as
// host/passes/sea_heightfield.h describes) and a ray's first hit by fine fixed steps and bisection,
// so the references check the kernels' cell-walking intersection instead of repeating it.
#pragma once
#include "passes/sea_heightfield.h"

namespace seasim {

// Bilinear floor depth (m) at world (x, z).
double floorDepthAt(const HeightField& floor, double x, double z);

// Unit floor normal (up, into the water) at world (x, z): (dh/dx, 1, dh/dz) of the bilinear patch.
void floorNormalAt(const HeightField& floor, double x, double z, double normal[3]);

// First t in [0, t_max] where o + t dir (world, o.y <= 0) is on or under the floor: fixed steps of
// `step` m until the ray is under it, then bisection to rounding. Returns -1 when there is none
// (the ray stays above up to t_max). A start on or under the floor gives 0.
double fineMarchFloor(const HeightField& floor, const double o[3], const double dir[3], double t_max, double step);

}  // namespace seasim
