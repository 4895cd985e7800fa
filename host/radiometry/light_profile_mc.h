// light_profile_mc.h — the plane-parallel light profile (light_profile.h) by Monte Carlo photon tracing:
// the reference the discrete-ordinates profile is measured against. It shares the water, the surface's
// Fresnel law and the samplers of the path tracer (kernels/common/path_tracer.h: counter-based random
// numbers, free flights; kernels/common/phase.h: the phase's tabulated inverse CDF and value table), and
// nothing of the discrete-ordinates solver (no quadrature, no delta-M, no truncated moments, no
// source-function integration).
//
// Photons start just below the surface (the sun's refracted beam, and a uniform sky's light refracted
// through the surface) carrying W m^-2 per photon, and travel in depth z and direction cosine μ only (the
// water is horizontally uniform). The surface reflects by Fresnel's law (total internal reflection outside
// Snell's window), the bottom is Lambertian (weight ρ, a cosine-distributed direction up).
//
// Two estimators of the same quantities at each depth z (docs/radiometry.md, "The Monte Carlo reference"):
//
// Analog: absorption is a weight ω = b/c per collision with Russian roulette below 1e-3, the surface's
// reflection is sampled, and the photons score where they go:
//   E_d, E_u       the weights crossing the plane z down / up;
//   E_0d, E_0u     track length inside the layer [z - Δ, z + Δ] (clipped to the water) over its thickness,
//                  split by the direction (finite variance, unlike Σ w/|μ| at grazing crossings);
//                  Δ = 0.005 / c, a bias of order (K Δ)² / 6; on a Lambertian bottom E_0u = 2 E_u exactly
//                  (the expectation over the bottom's directions: the layer's mean would be ~1.5 % low);
//   L_u            upward crossings within cap_deg of the zenith, Σ w / (|μ| Ω_cap): the mean radiance over
//                  that cap.
// Next event (the default): each score is replaced by its expectation given where the photon is, so every
// collision informs every depth:
//   - a flight that starts at the surface (the sources; a Fresnel reflection, now a weight R) scores
//     each plane ahead its transmittance e^{-c Δz/|μ|} (E_d, E_u) and the expected track length in each
//     layer ahead, (e^{-c s_a} - e^{-c s_b}) / c over the thickness (E_0d, E_0u);
//   - a collision scores the same for the scattered flight, averaged over the phase by three directions:
//     one from the phase, one uniform on the sphere, one uniform on the L_u cap around the zenith, each
//     weighted by the balance heuristic β̃ / (β̃ + 1/4π + 1_cap/Ω_cap) (Veach 1997, ch. 9): unbiased, and
//     bounded (≤ 4π, ≤ Ω_cap^-1) where the phase's forward peak would make a plain local estimate's
//     variance infinite. L_u is the mean radiance over a cap of local_cap_deg (5°: the local estimate's
//     β̃(ψ) e^{-c Δz}, bounded), the radiance each direction in the cap sees being e^{-c Δz/|μ|} / (|μ| Ω_cap).
//     A cap's mean differs from the nadir value by L's curvature there, ~ θ_cap² / 2 relative (0.4 % at 5°
//     for L ∝ 1 + θ²); with Petzold's peak a 1° cap's standard error is ~3x the 5° one's at the same photons;
//   - the bottom scores its exact Lambertian expectation (ρ w times 2∫ μ (...) dμ, precomputed per depth).
//   Deep, dark depths are reached by a weight window in depth: splitting and Russian roulette about
//   W(z) = w_0 e^{-κ z} (κ = c min(1, √(3 (1 - ω)(1 - ω g))), the diffusion estimate of K_∞; W held below the
//   deepest depth asked), checked at every collision and where a flight crosses one of the planes 0.5/κ
//   apart (geometric splitting: the free path is memoryless, so a flight stopped there restarts exactly).
//   Unbiased, and it keeps the photon population roughly constant down to the deepest depth, so the
//   sun's rare deep collisions, which carry most of E_d and E_u there, are sampled often.
// Where the analog estimator is already good (forward-peaked phase, high albedo: nearly every photon
// crosses each shallow plane once) the next event's irradiances are no better per photon (Petzold at
// ω = 0.9: up to 2x the standard error) and each photon costs 3.5-6x the time; its L_u is better everywhere
// (results/BENCHMARKS.md, "Radiometry").
// Standard errors from `batches` contiguous, independent blocks of photons (reference/batch_error.h: the
// spread of the block means; a photon's split copies stay in its block).
#pragma once
#include <vector>

#include "radiometry/light_profile.h"

namespace seasim {

struct MonteCarloSettings {
  enum class Estimator { Analog, NextEvent };
  long long photons = 1000000;
  int batches = 64;           // >= 2; photons >= batches
  unsigned seed = 1;
  Estimator estimator = Estimator::NextEvent;
  double cap_deg = 10;        // the analog L_u's polar cap half-angle
  double local_cap_deg = 5;   // the next-event L_u's cap half-angle
  double importance_per_m = -1;  // the weight window's κ (1/m); < 0: the diffusion estimate above; 0: no window
};

struct LightProfileMc {
  LightProfile mean;
  std::vector<LightAtDepth> standard_error;  // the same depths; each field the standard error of the mean's
  double l_w_se = 0, r_rs_se = 0;
  double seconds = 0;
  long long collisions = 0;   // scattering events traced, split copies included (the work)
};

LightProfileMc solveLightProfileMonteCarlo(const PlaneParallelWater& water, const PhaseFunction& phase,
                                           const std::vector<double>& depths, const MonteCarloSettings& settings = {});

}  // namespace seasim
