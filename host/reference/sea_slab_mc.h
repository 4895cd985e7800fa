// sea_slab_mc.h — a double-precision CPU Monte Carlo of the sea model's geometry (paper 000), split
// by scattering order: the check of single + second order (000 eq. 5–8) against the full
// multiple-scattering answer (issue 6, "energy").
//
// Geometry, the same as kernels/sea_single.cl and sea_second.cl (flat sea, 000 §3): a collimated sun
// above a flat air–water surface at y = 0 (Fresnel transmission T_i in, Snell refraction), homogeneous
// water with absorption a, scattering b and the Henyey–Greenstein phase function g (000 eq. 2),
// optionally a flat Lambertian bottom at depth z_d (else infinitely deep), and one camera ray that
// meets the surface at P, leaves the water with T_o (000 eq. 5, 9) and is refracted into the water.
//
// What is tallied, matching what the model's terms contain:
//   - radiance in air towards the camera = T_o x the water radiance along the refracted view ray, as
//     in eq. 5, 6 and 9 (the model has no n^2 radiance factor at the interface; neither has this);
//   - sun only: no sky light enters the water (L^(1), L^(2) and eq. 9 have none);
//   - the surface seen from below is transparent by default: light scattered up to it leaves
//     (eq. 7's theta <= pi/2 branch integrates up to the surface and stops). With
//     internal_reflection it reflects by Fresnel (total beyond 48.6 deg), part of the physical
//     full answer that the model leaves out;
//   - order k = k scattering events in the water and no bottom bounce. Order 1 is the EXACT single
//     scattering integral — eq. 5 without the forward-scattering coefficient c_f, i.e. attenuation
//     c, not c (1 - w0 c_f) (slabExactSingle). Eq. 5 with c_f (slabPaperSingle, what sea_single.cl
//     evaluates) is an approximation that moves part of the forward-scattered higher orders into
//     "order 1"; the MC does not make it. Order 2 is L^(2) of eq. 6–8 (the bottom is not a source in
//     eq. 7, so paths that touch the bottom are not order 2);
//   - paths with a bottom bounce: bottom_direct (no scattering, one bounce: eq. 9, slabBottomDirect)
//     and bottom_other (every other path that touched the bottom), kept apart from the orders.
//
// Estimator: backward tracing from P along the refracted view ray with next-event estimation of
// the sun at every scattering vertex (the sun in the water is a collimated beam, so NEE is exact, not
// sampled: its irradiance at depth z is e_beam exp(-c z sec theta_io), e_beam = E_h T_i / cos theta_io,
// and the flat surface never shadows it). Free-flight distances are sampled from c e^{-c t}
// (weight 1/c, so a vertex scores w * albedo * p(s . -v) * E_beam), new directions from an equal
// mixture of the phase function about the previous direction and the same HG lobe about -s (where the
// next vertex's sun NEE peaks), weight albedo p1 / (p1/2 + p2/2) (one-sample MIS: the order-2 score is
// then bounded by 2 min(p1, p2), where pure phase sampling leaves the g = 0.9 spike of the NEE in the
// variance — 10x the standard error at g = 0.9), bottom bounces from cos/pi (weight the bottom
// albedo, with the sun's direct irradiance on the bottom as NEE). Each path scores each order at
// most once, so per-order means and standard errors come straight from per-path sums. Russian
// roulette (survival 1/2) once the weight falls under 1/10 of T_o keeps it unbiased and bounded.
//
// Determinism: Philox4x32-10 (kernels/common/ocean_spectrum.h) keyed by the seed with the path index
// and draw number as counter; paths are summed in fixed chunks, chunk sums combined in order, so the
// result is the same bit for bit for any thread count.
#pragma once
#include <cstdint>
#include <vector>

#include "math/vec3.h"
#include "scene/scene.h"

namespace seasim {

struct SlabMcSetup {
  double sun_zenith = 0.7;          // rad; >= pi/2: below the horizon (everything is 0)
  double sun_azimuth = 0.0;         // rad, from +x towards +z (as SunDesc)
  double sun_irradiance = 1.0;      // W m^-2 nm^-1 normal to the sun (E_h = E cos zenith)
  Vec3 view{0, -1, 0};              // unit direction from the camera to P (y < 0: sees the water)
  double ior = 1.333;               // water relative to air
  double a = 0.05, b = 0.2, g = 0.9;  // 1/m, 1/m, HG asymmetry (|g| < 1)
  double bottom_depth = -1;         // m; < 0: infinitely deep
  double bottom_albedo = 0;         // Lambertian reflectance (only with a bottom)
  bool internal_reflection = false; // Fresnel reflection of the surface seen from below
};

struct SlabMcSettings {
  int64_t paths = 1 << 18;
  uint32_t seed = 1;
  int max_order = 10000;  // hard cap on events per path (Russian roulette ends paths long before)
};

struct SlabMcEstimate {
  double mean = 0;
  double std_error = 0;         // standard error of the mean, from the spread of its blocks of paths
  double sample_std_error = 0;  // the same from the per-path variance (reference/batch_error.h)
};

struct SlabMcResult {
  std::vector<SlabMcEstimate> order;  // order[k - 1] = order k, k = 1..8 (no bottom bounce)
  SlabMcEstimate orders_3plus;        // all orders >= 3 (no bottom bounce)
  SlabMcEstimate all_orders;          // all orders >= 1 (no bottom bounce)
  SlabMcEstimate bottom_direct;       // eq. 9: no scattering, one bottom bounce
  SlabMcEstimate bottom_other;        // every other path that touched the bottom
  int64_t paths = 0;
  const SlabMcEstimate& order1() const { return order[0]; }
  const SlabMcEstimate& order2() const { return order[1]; }
};

// Runs the Monte Carlo (oneTBB). RuntimeError for a non-physical setup (negative a or b, |g| >= 1,
// ior <= 0, a bottom albedo outside [0, 1]) or paths < 2.
SlabMcResult runSlabMc(const SlabMcSetup& setup, const SlabMcSettings& settings = {});

// Closed forms of the same setup (radiance towards the camera):
// exact single scattering, eq. 5 with c_f = 0 (attenuation c along both legs);
double slabExactSingle(const SlabMcSetup& setup);
// eq. 5 as sea_single.cl evaluates it (attenuation c (1 - w0 c_f), c_f of the HG phase);
double slabPaperSingle(const SlabMcSetup& setup);
// eq. 9, the sun reflected once by the flat bottom (0 without a bottom).
double slabBottomDirect(const SlabMcSetup& setup);

// The setup of pixel (px, py) of a flat-sea scene at wavelength band `band` of its grid: the pixel's
// view direction, the sun, the water's a, b, g, ior, the flat bottom and its albedo at the band
// centre, and the band's sun irradiance (sunIrradianceBands), exactly as the sea passes and the
// references see them. RuntimeError for a scene they do not model (as renderSeaSecondReference).
SlabMcSetup slabSetupFromScene(const Scene& scene, int px, int py, int band);

}  // namespace seasim
