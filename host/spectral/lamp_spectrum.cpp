#include "spectral/lamp_spectrum.h"

#include <cmath>

#include "io/data_files.h"
#include "spectral/csv_table.h"
#include "util/error.h"

namespace seasim {

namespace {

// hc/k in nm K: the second radiation constant c2 = 1.438776877503934e-2 m K (exact from the SI-defined
// h, c and k).
constexpr double kC2NmK = 1.438776877503934e7;

// B(λ, T) up to the constant 2hc²: λ⁻⁵ / (e^{c2/λT} - 1).
double planckShape(double lambda_nm, double temperature_k) {
  const double x = kC2NmK / (lambda_nm * temperature_k);
  return 1.0 / (std::pow(lambda_nm, 5) * std::expm1(x));
}

}  // namespace

double planckRelative(double lambda_nm, double temperature_k) {
  return planckShape(lambda_nm, temperature_k) / planckShape(560.0, temperature_k);
}

std::vector<double> lampSpectralIntensity(const SpotlightDesc& lamp, const WavelengthGrid& grid, DataFiles* files) {
  std::vector<double> out(grid.size(), lamp.intensity);
  if (lamp.temperature_k > 0) {
    for (size_t i = 0; i < grid.size(); ++i) out[i] *= planckRelative(grid.centers_nm[i], lamp.temperature_k);
  } else if (!lamp.spectrum.empty()) {
    const CsvTable t = readCsvVia(files, lamp.spectrum);
    if (t.names.size() < 2) throw RuntimeError(lamp.spectrum + ": a lamp spectrum needs two columns: nm, relative power");
    const Spectrum s = t.spectrum(t.names[1]);
    for (size_t r = 0; r < s.values.size(); ++r)
      if (s.values[r] < 0)
        throw RuntimeError(lamp.spectrum + ":" + std::to_string(t.lines[r]) + ": negative relative power");
    const double at560 = s.at(560.0);
    if (!(at560 > 0)) throw RuntimeError(lamp.spectrum + ": a lamp spectrum needs a positive value at 560 nm");
    for (size_t i = 0; i < grid.size(); ++i) out[i] *= s.at(grid.centers_nm[i]) / at560;
  }
  return out;
}

std::array<double, 3> lampSensorRgb(const SpotlightDesc& lamp, const WavelengthGrid& grid, const Sensor& sensor,
                                    DataFiles* files) {
  const std::vector<double> I = lampSpectralIntensity(lamp, grid, files);
  return sensor.apply(I.data());
}

Vec3 shaftsLampRgb(const SpotlightDesc& lamp, const SpectralDesc& spectral, DataFiles* files) {
  if (lamp.temperature_k <= 0 && lamp.spectrum.empty()) return lamp.color * lamp.intensity;
  const WavelengthGrid grid = makeGrid(spectral.count, spectral.min_nm, spectral.max_nm);
  const Sensor sensor = makeSensor(spectral.sensor, grid, spectral.white_balance, spectral.camera_dir, files);
  const std::array<double, 3> rgb = lampSensorRgb(lamp, grid, sensor, files);
  return Vec3{rgb[0], rgb[1], rgb[2]};
}

}  // namespace seasim
