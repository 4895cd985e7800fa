// light_profile.h — the plane-parallel light field oceanographers measure, at the depths they name, by
// the discrete-ordinates solver (host/underwater/discrete_ordinates.h) with any phase function
// (phase_function.h). Quantities and conventions: docs/radiometry.md.
//
// The water: homogeneous a, b and phase, a flat surface of index n, a Lambertian bottom or none. The
// light: the sun's beam (irradiance normal to the beam in air, zenith angle in air) and a uniform sky
// (its irradiance on a horizontal plane in air). Per depth z (m, positive down, 0 just below the surface):
//   E_d, E_u    plane irradiances, down and up (the beam included in E_d);
//   E_0d, E_0u  scalar irradiances of each hemisphere (the beam's E/μ_w in E_0d);
//   L_u         the radiance travelling straight up (nadir-viewing radiance).
// Above the surface: L_w = L_u(0) (1 - r(0)) / n² (the radiance leaving the water, r(0) Fresnel at
// normal incidence; radiance/n² conserved), R_rs = L_w / E_d(0+).
//
// L_u is not one of the quadrature's streams: it is the source function integrated along the vertical
// from the bottom (or from 40 delta-M optical depths below the deepest depth asked) upward, DISORT's
// user-angle method: J = the diffuse in-scatter towards straight up from the solver's streams (its
// delta-M phase) + the beam's single scattering by the exact phase b β̃(π - θ_w) F_0 e^{-ĉ z/μ_w}
// (Nakajima & Tanaka 1988's TMS), attenuated by ĉ; J linear between samples 0.05 μ_w / ĉ apart.
#pragma once
#include <vector>

#include "radiometry/phase_function.h"

namespace seasim {

struct PlaneParallelWater {
  double a = 0, b = 0;             // 1/m
  double ior = 1.34;               // water / air
  double bottom_depth = 0;         // m; <= 0: none (semi-infinite)
  double bottom_albedo = 0;        // Lambertian reflectance in [0, 1]
  double sun_zenith = 0;           // rad, in air, [0, π/2)
  double sun_irradiance = 0;       // W m^-2 (nm^-1) normal to the beam, in air
  double sky_irradiance = 0;       // W m^-2 (nm^-1) on a horizontal plane in air
  // The sky's irradiance on a horizontal plane just below the surface; < 0: a uniform sky's,
  // (1 - r̄) sky_irradiance. The solver spreads it as a uniform sky's through Snell's window.
  double sky_transmitted = -1;
};

struct LightAtDepth {
  double depth = 0;                // m
  double e_d = 0, e_u = 0, e_0d = 0, e_0u = 0, l_u = 0;
};

struct LightProfile {
  std::vector<LightAtDepth> rows;  // the depths asked, in their order
  double e_d_air = 0;              // E_d(0+), in air
  double l_w = 0, r_rs = 0;        // water-leaving radiance and remote-sensing reflectance (1/sr)
};

// The share of a uniform sky's irradiance a flat surface of index ior transmits from air, 1 - 2 ∫ r(μ) μ dμ.
double uniformSkyTransmittance(double ior);

// streams: the solver's cosines per hemisphere (>= 2), its quality knob. depths >= 0 (m). Throws
// std::invalid_argument on bad input (negative IOPs, depths, an albedo outside [0, 1]).
LightProfile solveLightProfile(const PlaneParallelWater& water, const PhaseFunction& phase,
                               const std::vector<double>& depths, int streams = 16);

}  // namespace seasim
