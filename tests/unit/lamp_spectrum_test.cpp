// lamp_spectrum_test.cpp — spectral spotlights: Planck's law at a colour temperature
// against the textbook formula, a CSV spectrum, the sensor's view of a lamp, and the scene errors of
// lamps under water (file:line:key).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "scene/scene_parser.h"
#include "spectral/lamp_spectrum.h"
#include "spectral/sensor.h"
#include "spectral/wavelength_grid.h"
#include "util/error.h"

namespace {

using seasim::SpotlightDesc;

// 2hc²/λ⁵ / (exp(hc/λkT) - 1) with CODATA constants, SI units.
double planck(double lambda_nm, double T) {
  const double h = 6.62607015e-34, c = 2.99792458e8, k = 1.380649e-23, l = lambda_nm * 1e-9;
  return 2 * h * c * c / std::pow(l, 5) / (std::exp(h * c / (l * k * T)) - 1);
}

TEST(LampSpectrum, PlanckMatchesTheFormulaAndIsOneAt560) {
  for (double T : {1000.0, 3200.0, 6500.0, 50000.0}) {
    EXPECT_NEAR(seasim::planckRelative(560, T), 1.0, 1e-14);
    for (double l : {380.0, 450.0, 600.0, 780.0, 1000.0})
      EXPECT_NEAR(seasim::planckRelative(l, T), planck(l, T) / planck(560, T), 1e-9 * planck(l, T) / planck(560, T))
          << T << " K, " << l << " nm";
  }
  // A warm lamp is red-heavy, a hot one blue-heavy.
  EXPECT_GT(seasim::planckRelative(650, 3200), 1.0);
  EXPECT_LT(seasim::planckRelative(450, 3200), 1.0);
  EXPECT_GT(seasim::planckRelative(450, 20000), 1.0);
}

TEST(LampSpectrum, IntensityPerBandFromTemperatureCsvOrFlat) {
  const seasim::WavelengthGrid grid = seasim::makeGrid(6, 400, 700);
  SpotlightDesc lamp;
  lamp.intensity = 20;
  for (double v : seasim::lampSpectralIntensity(lamp, grid)) EXPECT_DOUBLE_EQ(v, 20);  // equal energy
  lamp.temperature_k = 3200;
  const std::vector<double> I = seasim::lampSpectralIntensity(lamp, grid);
  for (size_t i = 0; i < grid.size(); ++i)
    EXPECT_NEAR(I[i], 20 * seasim::planckRelative(grid.centers_nm[i], 3200), 1e-12);
  // A CSV, linear between its samples: 2 at 400 nm, 1 at 560, 1 at 700 -> normalised at 560.
  const std::string path = ::testing::TempDir() + "/lamp_spectrum_test.csv";
  std::ofstream(path) << "nm,power\n400,2\n560,1\n700,1\n";
  lamp.temperature_k = 0;
  lamp.spectrum = path;
  const std::vector<double> J = seasim::lampSpectralIntensity(lamp, grid);
  EXPECT_NEAR(J[0], 20 * (2 - (425.0 - 400) / 160), 1e-12);  // band centre 425 nm
  EXPECT_NEAR(J[5], 20.0, 1e-12);                           // 675 nm
  std::ofstream(path) << "nm,power\n400,1\n500,0\n600,0\n";
  EXPECT_THROW(seasim::lampSpectralIntensity(lamp, grid), seasim::RuntimeError);  // nothing at 560 nm
}

TEST(LampSpectrum, SensorRgbOfAnEqualEnergyLampIsTheSensorsSumAndRgbLampsKeepTheirColour) {
  const seasim::WavelengthGrid grid = seasim::makeGrid(16, 400, 700);
  const seasim::Sensor sensor = seasim::makeSensor("cie1931", grid, true);
  SpotlightDesc lamp;
  lamp.intensity = 3;
  const auto rgb = seasim::lampSensorRgb(lamp, grid, sensor);
  double r = 0;
  for (size_t i = 0; i < grid.size(); ++i) r += 3 * sensor.to_r[i];
  EXPECT_NEAR(rgb[0], r, 1e-12);
  // An RGB lamp (no temperature, no spectrum): intensity × colour, as before the change.
  seasim::SpectralDesc spectral;
  lamp.color = {1.0, 0.5, 0.25};
  const seasim::Vec3 c = seasim::shaftsLampRgb(lamp, spectral);
  EXPECT_DOUBLE_EQ(c.x, 3.0);
  EXPECT_DOUBLE_EQ(c.y, 1.5);
  EXPECT_DOUBLE_EQ(c.z, 0.75);
  // A warm lamp through the sensor: redder than blue.
  lamp.temperature_k = 3200;
  const seasim::Vec3 warm = seasim::shaftsLampRgb(lamp, spectral);
  EXPECT_GT(warm.x, warm.z);
}

// The message parseScene throws, or "" when it does not throw.
std::string errorOf(const std::string& text) {
  try {
    seasim::parseScene(text, "bad.toml");
  } catch (const seasim::InputError& e) {
    return e.what();
  }
  return "";
}

const char* kUnderwater = R"([camera]
position = [0, -2, 0]
look_at = [0, -3, -10]
[water]
jerlov = "IB"
[[spotlights]]
direction = [0, -1, -1]
)";

TEST(LampSpectrum, LampsUnderWaterMustBeInTheWaterAndSpectral) {
  // A lamp above the surface (the default position is y = 5): refused, naming file, line and key.
  EXPECT_NE(errorOf(std::string(kUnderwater)).find("bad.toml:6: key 'spotlights[0].position'"), std::string::npos)
      << errorOf(kUnderwater);
  EXPECT_NE(errorOf(std::string(kUnderwater) + "position = [0, 0, 0]\n").find("spotlights[0].position"),
            std::string::npos);
  EXPECT_EQ(errorOf(std::string(kUnderwater) + "position = [0, -1, 0]\ntemperature_k = 3200\n"), "");
  EXPECT_EQ(errorOf(std::string(kUnderwater) + "position = [0, -1, 0]\n"), "");  // equal energy
  EXPECT_NE(errorOf(std::string(kUnderwater) + "position = [0, -1, 0]\ncolor = [1, 0.9, 0.8]\n")
                .find("key 'spotlights[0].color'"),
            std::string::npos);
  EXPECT_NE(errorOf(std::string(kUnderwater) + "position = [0, -1, 0]\ntemperature_k = 100\n")
                .find("key 'spotlights[0].temperature_k'"),
            std::string::npos);
  EXPECT_NE(errorOf(std::string(kUnderwater) + "position = [0, -1, 0]\nspectrum = \"missing.csv\"\n")
                .find("key 'spotlights[0].spectrum'"),
            std::string::npos);
}

TEST(LampSpectrum, ColourAndSpectrumTogetherAreAnErrorInAirToo) {
  const std::string stage = "[camera]\nposition = [0, 2, 10]\n[air]\ndensity = 1\n[[spotlights]]\ncolor = [1, 1, 1]\n";
  EXPECT_EQ(errorOf(stage), "");
  EXPECT_NE(errorOf(stage + "temperature_k = 3200\n").find("key 'spotlights[0].color'"), std::string::npos);
}

}  // namespace
