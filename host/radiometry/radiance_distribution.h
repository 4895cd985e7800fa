// radiance_distribution.h — the radiance distribution L(θ, φ) of the plane-parallel light field
// (light_profile.h) at chosen depths, on an equirectangular θ–φ grid, by Monte Carlo photon tracing in
// three dimensions (the profile's Monte Carlo, light_profile_mc.h, follows only μ = cos θ; the discrete
// ordinates keep no azimuth).
//
// Directions are those the light TRAVELS in: θ from the downward vertical (θ = 0 travels straight down,
// θ = π straight up, so the bottom row holds L_u), φ the azimuth from the refracted sun's direction of
// travel (φ = 0: travelling away from the sun), increasing counter-clockwise seen from above. Grid cell
// (row i, column j): θ in [i, i + 1) π / n_theta, φ in [j, j + 1) 2π / n_phi; n_theta even, so no cell
// straddles the horizon.
//
// A cell holds its mean radiance (W m^-2 sr^-1 per W m^-2 of source, as the profile): the photons'
// weights crossing the depth plane with directions in the cell over the cell's projected solid angle
// ∫_cell |cos θ| dΩ (the plane irradiance through the cell over what a uniform radiance of 1 would give).
// So Σ_cells L ∫_cell |cos θ| dΩ over each hemisphere is the plane irradiance E_d or E_u of the same
// photons exactly, and a uniform radiance (a Lambertian bottom's) reads uniform. The sun's refracted beam
// (a direction, not a distribution) lands in its one cell, as radiance spread over that cell.
//
// Photons: the profile Monte Carlo's sources, surface (Fresnel, now as a weight) and Lambertian bottom;
// the phase sampled by its tabulated inverse CDF; absorption as the weight ω per collision with Russian
// roulette below 1e-3 of the start. Standard errors from `batches` contiguous blocks of photons
// (reference/batch_error.h).
#pragma once
#include <vector>

#include "radiometry/light_profile.h"

namespace seasim {

struct RadianceDistributionSettings {
  int n_theta = 90, n_phi = 180;  // n_theta even, >= 2; n_phi >= 1
  long long photons = 1000000;
  int batches = 64;
  unsigned seed = 1;
};

struct RadianceDistribution {
  int n_theta = 0, n_phi = 0;
  std::vector<double> depths;
  // Per depth: n_theta x n_phi values, row-major (row i = θ, column j = φ).
  std::vector<std::vector<double>> radiance, standard_error;
  // The plane irradiances of the same photons (crossings) and their standard errors, per depth.
  std::vector<double> e_d, e_u, e_d_se, e_u_se;
  double seconds = 0;

  // ∫ |cos θ| dΩ of one cell of row i.
  double cellProjectedSolidAngle(int row) const;
  // Σ L ∫_cell |cos θ| dΩ over the downward (θ < π/2) or upward hemisphere at depth index k.
  double hemisphereIrradiance(size_t k, bool down) const;
};

// Throws std::invalid_argument on bad grid sizes, photon counts or depths outside the water.
RadianceDistribution solveRadianceDistribution(const PlaneParallelWater& water, const PhaseFunction& phase,
                                               const std::vector<double>& depths,
                                               const RadianceDistributionSettings& settings = {});

}  // namespace seasim
