// cie_daylight.cpp — the CIE daylight basis from data/ (provenance in data/README.md §CIE daylight).
#include "spectral/cie_daylight.h"

#include "spectral/cie.h"
#include "spectral/csv_table.h"
#include "util/paths.h"

namespace seasim {

const CieDaylightBasis& cieDaylightBasis() {
  static const CieDaylightBasis basis = [] {
    const auto table = loadCsv(dataDir() + "/cie_daylight_components.csv");
    return CieDaylightBasis{table.spectrum("s0"), table.spectrum("s1"), table.spectrum("s2")};
  }();
  return basis;
}

std::array<double, 3> daylightBandWeights(double lambda_nm) {
  const CieDaylightBasis& b = cieDaylightBasis();
  const double d65 = seasim::d65().at(lambda_nm);
  return {b.s0.at(lambda_nm) / (100 * d65), b.s1.at(lambda_nm) / (100 * d65), b.s2.at(lambda_nm) / (100 * d65)};
}

std::array<double, 3> daylightLuminanceWeights() {
  const CieDaylightBasis& b = cieDaylightBasis();
  const Spectrum illum = d65();
  const Spectrum& y_bar = cie1931Cmf().y_bar;
  double n[3] = {0, 0, 0}, d = 0;
  for (int l = 360; l <= 780; ++l) {
    const double y = responseAt(y_bar, l);
    n[0] += b.s0.at(l) * y, n[1] += b.s1.at(l) * y, n[2] += b.s2.at(l) * y;
    d += illum.at(l) * y;
  }
  return {n[0] / (100 * d), n[1] / (100 * d), n[2] / (100 * d)};
}

std::array<double, 2> chromaticityOf(const Spectrum& spd) {
  const CieCmf& cmf = cie1931Cmf();
  double X = 0, Y = 0, Z = 0;
  for (int l = 360; l <= 780; ++l) {
    const double s = spd.at(l);
    X += s * responseAt(cmf.x_bar, l), Y += s * responseAt(cmf.y_bar, l), Z += s * responseAt(cmf.z_bar, l);
  }
  return {X / (X + Y + Z), Y / (X + Y + Z)};
}

}  // namespace seasim
