// von_kries.cpp — 003 eq. 15–17 (see the header).
#include "spectral/von_kries.h"

#include <cmath>
#include <cstdlib>

#include "util/error.h"

namespace seasim {

namespace {

Mat3 inverse(const Mat3& m) {
  const double a = m[0], b = m[1], c = m[2], d = m[3], e = m[4], f = m[5], g = m[6], h = m[7], i = m[8];
  const double A = e * i - f * h, B = -(d * i - f * g), C = d * h - e * g;
  const double det = a * A + b * B + c * C;
  return {A / det, -(b * i - c * h) / det, (b * f - c * e) / det,
          B / det, (a * i - c * g) / det,  -(a * f - c * d) / det,
          C / det, -(a * h - b * g) / det, (a * e - b * d) / det};
}

}  // namespace

const Mat3& xyzToLmsMatrix() {
  static const Mat3 m = {0.400, 0.707, -0.080,   // 003 eq. 15
                         -0.023, 1.165, 0.046,
                         0.000, 0.000, 0.912};
  return m;
}

const Mat3& lmsToXyzMatrix() {
  static const Mat3 m = inverse(xyzToLmsMatrix());
  return m;
}

Mat3 multiply(const Mat3& a, const Mat3& b) {
  Mat3 r{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) r[i * 3 + j] += a[i * 3 + k] * b[k * 3 + j];
  return r;
}

Vec3d apply(const Mat3& m, const Vec3d& v) {
  return {m[0] * v[0] + m[1] * v[1] + m[2] * v[2], m[3] * v[0] + m[4] * v[1] + m[5] * v[2],
          m[6] * v[0] + m[7] * v[1] + m[8] * v[2]};
}

Mat3 vonKriesXyzTransform(const Vec3d& white_src_xyz, const Vec3d& white_dst_xyz) {
  const Vec3d src = apply(xyzToLmsMatrix(), white_src_xyz), dst = apply(xyzToLmsMatrix(), white_dst_xyz);
  Mat3 diag{};
  for (int k = 0; k < 3; ++k) {
    if (!(src[k] > 0)) throw RuntimeError("von Kries adaptation: the white point has no response in cone channel " +
                                          std::string(1, "LMS"[k]));
    diag[k * 4] = dst[k] / src[k];  // 003 eq. 17 (÷ the white's), then × the display white's
  }
  return multiply(lmsToXyzMatrix(), multiply(diag, xyzToLmsMatrix()));
}

double blackbody(double lambda_nm, double kelvin) {
  // B(λ, T) ∝ λ⁻⁵ / (exp(hc / (λ k T)) - 1); c2 = hc/k = 1.438777e-2 m K. λ in μm keeps it O(1).
  const double um = lambda_nm * 1e-3;
  return 1.0 / (um * um * um * um * um * std::expm1(1.438777e4 / (um * kelvin)));
}

bool parseVonKriesSensor(const std::string& name, double* kelvin) {
  if (name == "vonkries") {
    *kelvin = 6504.0;
    return true;
  }
  const std::string prefix = "vonkries:";
  if (name.rfind(prefix, 0) != 0) return false;
  const std::string t = name.substr(prefix.size());
  char* end = nullptr;
  const double k = std::strtod(t.c_str(), &end);
  if (t.empty() || end != t.c_str() + t.size() || !(k >= 1000 && k <= 40000))
    throw RuntimeError("sensor '" + name + "': expected \"vonkries\" or \"vonkries:<kelvin>\" with 1000 <= kelvin <= 40000");
  *kelvin = k;
  return true;
}

}  // namespace seasim
