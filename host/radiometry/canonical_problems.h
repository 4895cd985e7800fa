// canonical_problems.h — Mobley et al. (1993), "Comparison of numerical models for computing underwater
// light fields", Appl. Opt. 32(36): problems 1, 2 and 6 as plane-parallel set-ups, their published
// means and spreads (tests/data/mobley1993/problems.csv, provenance beside it), and the
// discrete-ordinates solver's values against them. Optical depth = geometric depth here (c = 1 m^-1).
#pragma once
#include <string>
#include <vector>

#include "radiometry/light_profile.h"

namespace seasim {

struct CanonicalValue {
  int problem = 0;           // 1, 2 or 6
  double albedo = 0;         // single-scattering albedo b/c
  double optical_depth = 0;  // c z
  std::string quantity;      // "Ed", "E0u" or "Lu"
  double mean = 0, cv = 0;   // the codes' mean and coefficient of variation
};

// Reads the published values (RuntimeError "FILE:LINE: ..." on a malformed row).
std::vector<CanonicalValue> loadCanonicalValues(const std::string& path);

// The set-up of a problem: flat surface, n = 1.34, sun 60° in a black sky, 1 W m^-2 normal to the beam;
// problem 1 Rayleigh-like, 2 and 6 Petzold; 6 with a bottom of reflectance 0.5 at optical depth 5.
PlaneParallelWater canonicalWater(int problem, double albedo);
PhaseFunction canonicalPhase(int problem);

// The pass rule: |computed / mean - 1| <= max(cv, 2 %) for E_d and E_0u, max(cv, 10 %) for L_u.
double canonicalTolerance(const CanonicalValue& v);

struct CanonicalResult {
  CanonicalValue published;
  double computed = 0;
  double standard_error = 0;  // the Monte Carlo's (0 for the discrete ordinates)
  double relative_error = 0;  // computed / mean - 1
  bool pass = false;
  bool resolved = true;       // the Monte Carlo: its standard error within the tolerance (else not judged)
};

// Every published value against the discrete-ordinates solver at `streams`; seconds (optional) gets the
// solver's wall time over all problems.
std::vector<CanonicalResult> solveCanonicalProblems(const std::vector<CanonicalValue>& published, int streams,
                                                    double* seconds = nullptr);

// The same by the Monte Carlo reference (light_profile_mc.h) with `photons` per problem and albedo; a value
// passes when |computed - mean| <= tolerance mean + 3 standard errors, and is not judged (resolved = false)
// when its standard error exceeds the tolerance (the deep, dark values need far more photons).
std::vector<CanonicalResult> monteCarloCanonicalProblems(const std::vector<CanonicalValue>& published,
                                                         long long photons, double* seconds = nullptr);

// A Markdown table of the results; `solver` names them ("Discrete ordinates, 16 streams per hemisphere").
std::string canonicalTableMarkdown(const std::vector<CanonicalResult>& results, const std::string& solver,
                                   double seconds);

}  // namespace seasim
