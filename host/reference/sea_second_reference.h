// sea_second_reference.h — brute-force reference for kernels/sea_second.cl: second-order scattering
// L^(2) under a flat sea (000 eq. 6), integrated directly along each pixel's refracted view ray in
// double precision on the CPU (TBB) — no sampling planes, no maps, no LUTs:
//   L^(2) = T_o int_0^{z_d} exp(-c z sec theta_ji) J(z) dz sec theta_ji,
//   J(z)  = int_{4 pi} beta(alpha'(omega)) L^(1)(z, omega) d omega,
// with L^(1) the closed form of eq. 7 (common/sea_second.h; checked against quadrature along the
// sampling ray in tests/unit/sea_second_test.cpp). The sphere integral is the product of two
// Henyey–Greenstein lobes (first scattering, peaked looking back up the sun beam; second, peaked
// along the view ray), so it is split by the balance heuristic into two integrals, each over the
// inverse-CDF map of one lobe with midpoint nodes:
//   int p1 p2 I = int p1 [p1 p2 I/(p1 + p2)] + int p2 [p1 p2 I/(p1 + p2)],
// where the brackets are smooth and bounded by min(p1, p2) I, so fine grids converge fast for any g.
// The depth integral uses midpoints in the transmittance exp(-(1 + sec theta_io) tau).
// Over a height-field floor (000 §5.4) the view ray ends at the pixel's z_Q (fine march of the floor)
// and every sampling ray is walked to the floor or the surface from every node (no depth tables).
#pragma once
#include "io/image.h"
#include "scene/scene.h"

namespace seasim {

struct SeaSecondReferenceSettings {
  int depth_steps = 128;  // quadrature nodes along the view ray
  int angle_steps = 64;   // per side of each lobe's (u, phi) grid: 2 * angle_steps^2 directions
};

// L^(2) alone, linear sensor RGB (add it to renderSeaReference for single + second). Throws
// RuntimeError for scenes the reference does not model (as renderSeaReference).
Image renderSeaSecondReference(const Scene& scene, const SeaSecondReferenceSettings& settings = {});

}  // namespace seasim
