// light_profile_mc.h — the plane-parallel light profile (light_profile.h) by Monte Carlo photon tracing:
// the reference the discrete-ordinates profile is measured against. It shares the water, the surface's
// Fresnel law and the samplers of the path tracer (kernels/common/path_tracer.h: counter-based random
// numbers, free flights; kernels/common/phase.h: the phase's tabulated inverse CDF), and nothing of the
// discrete-ordinates solver (no quadrature, no delta-M, no truncated moments, no source-function
// integration).
//
// Photons start just below the surface (the sun's refracted beam, and a uniform sky's light refracted
// through the surface) carrying W m^-2 per photon, and travel in depth z and direction cosine μ only (the
// water is horizontally uniform). Absorption is a weight ω = b/c per collision with Russian roulette below
// 1e-3; the surface reflects by Fresnel's law (total internal reflection outside Snell's window), the
// bottom is Lambertian (weight ρ, a cosine-distributed direction up). Estimators at each depth z:
//   E_d, E_u       the weights crossing the plane z down / up;
//   E_0d, E_0u     track length inside the layer [z - Δ, z + Δ] (clipped to the water) over its thickness,
//                  split by the direction (finite variance, unlike Σ w/|μ| at grazing crossings);
//                  Δ = 0.005 / c, a bias of order (K Δ)² / 6;
//   L_u            upward crossings within 10° of the zenith, Σ w / (|μ| Ω_cap): the mean radiance over
//                  that cap (a local estimate at exactly μ = -1 has infinite variance with a forward
//                  peak such as Petzold's). The cap's mean differs from the nadir value by the
//                  curvature of L(θ) near the nadir (the 1993 Monte Carlo codes binned the same way).
// Standard errors from `batches` independent batches (the standard deviation of the batch means / √B).
#pragma once
#include <vector>

#include "radiometry/light_profile.h"

namespace seasim {

struct MonteCarloSettings {
  long long photons = 1000000;
  int batches = 20;           // >= 2
  unsigned seed = 1;
  double cap_deg = 10;        // L_u's polar cap half-angle
};

struct LightProfileMc {
  LightProfile mean;
  std::vector<LightAtDepth> standard_error;  // the same depths; each field the standard error of the mean's
  double l_w_se = 0, r_rs_se = 0;
  double seconds = 0;
};

LightProfileMc solveLightProfileMonteCarlo(const PlaneParallelWater& water, const PhaseFunction& phase,
                                           const std::vector<double>& depths, const MonteCarloSettings& settings = {});

}  // namespace seasim
