// profile_command.h — `seasim profile SCENE`: the plane-parallel light field of the scene's water, sky,
// sun, flat surface and bottom (host/radiometry/light_profile.h) at the depths asked, per wavelength
// band and through the scene's sensor: E_d, E_u, E_0d, E_0u, L_u, R = E_u/E_d, K_d and K_u between
// consecutive depths, and L_w, R_rs above the surface. CSV (written atomically) and an SVG plot.
// `seasim canonical-problems`: Mobley et al. (1993) problems 1, 2 and 6 against the published codes,
// a Markdown table per stream count with the solver's time (results/canonical_problems.md).
#pragma once
#include <string>
#include <vector>

namespace seasim {

struct ProfileCmd {
  std::string scene;
  std::vector<double> depths = {0, 1, 5, 10};  // m
  int streams = 16;                            // discrete-ordinates cosines per hemisphere
  std::string csv, plot;
  std::vector<std::string> sets;  // scene overrides key=value
};

int cmdProfile(const ProfileCmd& cmd);

struct CanonicalProblemsCmd {
  std::vector<int> streams = {4, 8, 16, 32};
  std::string values;  // the published values (default: tests/data/mobley1993/problems.csv in the source tree)
  std::string out;     // Markdown output (default: print only)
};

int cmdCanonicalProblems(const CanonicalProblemsCmd& cmd);

}  // namespace seasim
