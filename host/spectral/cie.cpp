// cie.cpp — CIE 1931 CMFs and D65 from data/ (provenance in data/README.md §1–2), and the sRGB matrix
// derived from its primaries (IEC 61966-2-1).
#include "spectral/cie.h"

#include "spectral/csv_table.h"
#include "util/error.h"
#include "util/paths.h"

namespace seasim {

namespace {

using Mat3 = std::array<double, 9>;

Mat3 inverse(const Mat3& m) {
  const double a = m[0], b = m[1], c = m[2], d = m[3], e = m[4], f = m[5], g = m[6], h = m[7], i = m[8];
  const double A = e * i - f * h, B = -(d * i - f * g), C = d * h - e * g;
  const double det = a * A + b * B + c * C;
  return {A / det, -(b * i - c * h) / det, (b * f - c * e) / det,
          B / det, (a * i - c * g) / det,  -(a * f - c * d) / det,
          C / det, -(a * h - b * g) / det, (a * e - b * d) / det};
}

std::array<double, 3> mul(const Mat3& m, const std::array<double, 3>& v) {
  return {m[0] * v[0] + m[1] * v[1] + m[2] * v[2], m[3] * v[0] + m[4] * v[1] + m[5] * v[2],
          m[6] * v[0] + m[7] * v[1] + m[8] * v[2]};
}

Mat3 deriveXyzToSrgb() {
  // Columns of P: XYZ (Y = 1) of each primary from its chromaticity; scale each so that R = G = B = 1
  // gives the white point (the standard RGB-from-primaries construction).
  const double xr = 0.64, yr = 0.33, xg = 0.30, yg = 0.60, xb = 0.15, yb = 0.06, xw = 0.3127, yw = 0.3290;
  const Mat3 P = {xr / yr, xg / yg, xb / yb, 1.0, 1.0, 1.0, (1 - xr - yr) / yr, (1 - xg - yg) / yg, (1 - xb - yb) / yb};
  const std::array<double, 3> white = {xw / yw, 1.0, (1 - xw - yw) / yw};
  const std::array<double, 3> s = mul(inverse(P), white);
  Mat3 rgb_to_xyz;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) rgb_to_xyz[r * 3 + c] = P[r * 3 + c] * s[c];
  return inverse(rgb_to_xyz);
}

}  // namespace

const CieCmf& cie1931Cmf() {
  static const CieCmf cmf = [] {
    CsvTable t = loadCsv(dataDir() + "/cie1931_2deg_cmf.csv");
    return CieCmf{t.spectrum("x_bar"), t.spectrum("y_bar"), t.spectrum("z_bar")};
  }();
  return cmf;
}

double responseAt(const Spectrum& response, double lambda_nm) {
  if (response.empty() || lambda_nm < response.wavelengths_nm.front() || lambda_nm > response.wavelengths_nm.back())
    return 0.0;
  return response.at(lambda_nm);
}

Spectrum d65() {
  static const Spectrum spd = [] {
    Spectrum s = loadCsv(dataDir() + "/cie_d65.csv").spectrum("d65_relative_spd");
    const double at560 = s.at(560.0);
    if (!(at560 > 0.0)) throw RuntimeError(dataDir() + "/cie_d65.csv: no positive value at 560 nm");
    for (double& v : s.values) v /= at560;
    return s;
  }();
  return spd;
}

const std::array<double, 9>& xyzToLinearSrgbMatrix() {
  static const Mat3 m = deriveXyzToSrgb();
  return m;
}

std::array<double, 3> xyzToLinearSrgb(const std::array<double, 3>& xyz) {
  return mul(xyzToLinearSrgbMatrix(), xyz);
}

}  // namespace seasim
