// profile_command.h — `seasim profile SCENE`: the plane-parallel light field of the scene's water, sky,
// sun, flat surface and bottom (host/radiometry/light_profile.h) at the depths asked, per wavelength
// band and through the scene's sensor: E_d, E_u, E_0d, E_0u, L_u, R = E_u/E_d, K_d and K_u between
// consecutive depths, and L_w, R_rs above the surface. CSV (written atomically) and an SVG plot.
// `seasim canonical-problems`: Mobley et al. (1993) problems 1, 2 and 6 against the published codes,
// by the discrete ordinates at each stream count and by the Monte Carlo reference; and the discrete
// ordinates' difference from the Monte Carlo by stream count with their time (results/canonical_problems/README.md).
#pragma once
#include <string>
#include <vector>

namespace seasim {

struct ProfileCmd {
  std::string scene;
  std::vector<double> depths = {0, 1, 5, 10};  // m
  int streams = 16;                            // discrete-ordinates cosines per hemisphere
  std::string solver = "discrete_ordinates";   // or "monte_carlo" (the reference, with standard errors)
  long long photons = 1000000;                 // monte_carlo only
  std::string csv, plot;
  std::vector<std::string> sets;  // scene overrides key=value
};

int cmdProfile(const ProfileCmd& cmd);

struct CanonicalProblemsCmd {
  std::vector<int> streams = {4, 8, 16, 32};
  long long photons = 1000000;  // the Monte Carlo reference's photons per problem (0: none)
  std::string values;  // the published values (default: tests/data/mobley1993/problems.csv in the source tree)
  std::string out;     // Markdown output (default: print only)
};

int cmdCanonicalProblems(const CanonicalProblemsCmd& cmd);

}  // namespace seasim
