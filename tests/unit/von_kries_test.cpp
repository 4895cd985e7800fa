// von_kries_test.cpp — the von Kries sensor of paper 003 eq. 15–17 (host/spectral/von_kries.h,
// sensor "vonkries[:<kelvin>]"): the white point renders white, the adaptation really moves colours
// (the same lamp is orange through the plain CIE sensor), 6504 K is close to the plain sensor, and
// the eq. 15 matrix round-trips.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "spectral/sensor.h"
#include "spectral/von_kries.h"
#include "spectral/wavelength_grid.h"
#include "util/error.h"

namespace {

using seasim::blackbody;

// The sensor's RGB of a black body at `kelvin`, scaled to luminance 1 through the CIE sensor.
std::array<double, 3> rgbOfBlackbody(const seasim::Sensor& s, const seasim::Sensor& cie,
                                     const seasim::WavelengthGrid& g, double kelvin) {
  std::vector<double> bands(g.size());
  for (size_t i = 0; i < g.size(); ++i) bands[i] = blackbody(g.centers_nm[i], kelvin);
  const auto y = cie.apply(bands.data());
  const double lum = 0.2126 * y[0] + 0.7152 * y[1] + 0.0722 * y[2];
  auto rgb = s.apply(bands.data());
  for (double& v : rgb) v /= lum;
  return rgb;
}

TEST(VonKries, Eq15MatrixRoundTrips) {
  const seasim::Mat3 id = seasim::multiply(seasim::lmsToXyzMatrix(), seasim::xyzToLmsMatrix());
  for (int i = 0; i < 9; ++i) EXPECT_NEAR(id[i], i % 4 == 0 ? 1.0 : 0.0, 1e-14) << i;
  // The same white in and out: no change.
  const seasim::Mat3 same = seasim::vonKriesXyzTransform({0.95, 1.0, 1.09}, {0.95, 1.0, 1.09});
  for (int i = 0; i < 9; ++i) EXPECT_NEAR(same[i], i % 4 == 0 ? 1.0 : 0.0, 1e-14) << i;
}

TEST(VonKries, TheWhitePointShowsAsWhite) {
  const seasim::WavelengthGrid g = seasim::makeGrid(64, 380.0, 780.0);
  const seasim::Sensor cie = seasim::makeSensor("cie1931", g, true);
  for (double kelvin : {2700.0, 3200.0, 5000.0, 9000.0}) {
    const seasim::Sensor vk = seasim::makeSensor("vonkries:" + std::to_string(int(kelvin)), g, true);
    const auto adapted = rgbOfBlackbody(vk, cie, g, kelvin);
    const auto plain = rgbOfBlackbody(cie, cie, g, kelvin);
    // Adapted: grey, to the band sum's accuracy (64 bands).
    EXPECT_NEAR(adapted[0] / adapted[1], 1.0, 5e-3) << kelvin;
    EXPECT_NEAR(adapted[2] / adapted[1], 1.0, 5e-3) << kelvin;
    // Not adapted: a warm lamp is orange, a cold sky blue.
    if (kelvin < 5000) EXPECT_GT(plain[0] / plain[2], 1.5) << kelvin;
    if (kelvin > 7000) EXPECT_LT(plain[0] / plain[2], 0.95) << kelvin;
  }
  // Near D65 the adaptation is close to the plain, white-balanced CIE sensor.
  const seasim::Sensor vk = seasim::makeSensor("vonkries", g, true);
  for (size_t i = 0; i < g.size(); ++i) {
    const double scale = std::max({std::fabs(cie.to_r[i]), std::fabs(cie.to_g[i]), std::fabs(cie.to_b[i])}) + 1e-3;
    EXPECT_NEAR(vk.to_g[i], cie.to_g[i], 0.05 * scale) << g.centers_nm[i];
  }
}

TEST(VonKries, BadTemperaturesAreRefused) {
  double k = 0;
  EXPECT_FALSE(seasim::parseVonKriesSensor("cie1931", &k));
  EXPECT_TRUE(seasim::parseVonKriesSensor("vonkries:3200", &k));
  EXPECT_DOUBLE_EQ(k, 3200);
  EXPECT_THROW(seasim::parseVonKriesSensor("vonkries:hot", &k), seasim::RuntimeError);
  EXPECT_THROW(seasim::parseVonKriesSensor("vonkries:100", &k), seasim::RuntimeError);
}

}  // namespace
