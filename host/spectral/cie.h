// cie.h — CIE colorimetry from data/: the CIE 1931 2° colour matching functions
// (cie1931_2deg_cmf.csv, 360–830 nm at 1 nm, ȳ(555) = 1), illuminant D65 (cie_d65.csv, 300–780 nm
// at 5 nm) and the XYZ -> linear sRGB matrix (IEC 61966-2-1: Rec. 709 primaries, D65 white).
// The tables are read once per process and kept.
#pragma once
#include <array>

#include "spectral/spectrum.h"

namespace seasim {

struct CieCmf {
  Spectrum x_bar, y_bar, z_bar;  // dimensionless, tabulated 360–830 nm; read with responseAt()
};

// The CIE 1931 2° observer from data/cie1931_2deg_cmf.csv. RuntimeError if the file is missing or
// malformed.
const CieCmf& cie1931Cmf();

// A tabulated response curve (CMF, camera sensitivity) at lambda_nm: linear between samples and 0
// outside the tabulated range — a sensor does not respond where nobody measured it responding
// (unlike Spectrum::at, which holds the end values, the right rule for media and illuminants).
double responseAt(const Spectrum& response, double lambda_nm);

// CIE D65 relative spectral power from data/cie_d65.csv, scaled to 1 at 560 nm (the file has 100).
// Outside 300–780 nm Spectrum::at holds the end values.
Spectrum d65();

// Row-major 3x3 matrix taking CIE XYZ to linear sRGB, derived from the sRGB primaries
// R(0.64, 0.33), G(0.30, 0.60), B(0.15, 0.06) and white D65 (0.3127, 0.3290) with Y_white = 1, so
// XYZ of the D65 white point maps to (1, 1, 1). Agrees with the rounded matrix printed in
// IEC 61966-2-1 (3.2406, -1.5372, -0.4986, ...) to 4e-4 (the printed one was rounded twice).
const std::array<double, 9>& xyzToLinearSrgbMatrix();
std::array<double, 3> xyzToLinearSrgb(const std::array<double, 3>& xyz);

}  // namespace seasim
