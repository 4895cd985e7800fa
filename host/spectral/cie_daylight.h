// cie_daylight.h — the CIE daylight basis S0, S1, S2 (CIE 15:2004 §3.1) from
// data/cie_daylight_components.csv (300–830 nm at 5 nm; provenance in data/README.md): the spectral
// Preetham sky turns its chromaticity into a spectrum with it (common/sky.h sky_preetham_daylight).
#pragma once
#include <array>

#include "spectral/spectrum.h"

namespace seasim {

struct CieDaylightBasis {
  Spectrum s0, s1, s2;  // as tabulated: S0(560) = 100, S1(560) = S2(560) = 0
};

// Read once per process. RuntimeError if the file is missing or malformed.
const CieDaylightBasis& cieDaylightBasis();

// What a band at lambda_nm takes of sky_preetham_daylight's shape: S_k(λ) / (100 D65(λ)), D65 scaled
// to 1 at 560 nm (cie.h d65), so that the uniform sky's level × these weights is the daylight spectrum.
std::array<double, 3> daylightBandWeights(double lambda_nm);

// n_k = ∫ S_k ȳ dλ / (100 ∫ D65 ȳ dλ) over 360–780 nm at 1 nm (the CIE 1931 ȳ, cie.h): the luminance of
// S0 + M1 S1 + M2 S2 is (n0 + M1 n1 + M2 n2) times the uniform level's.
std::array<double, 3> daylightLuminanceWeights();

// x, y of a spectrum by the CIE 1931 observer over 360–780 nm at 1 nm.
std::array<double, 2> chromaticityOf(const Spectrum& spd);

}  // namespace seasim
