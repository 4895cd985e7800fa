// lamp_spectrum.h — a spotlight's spectral intensity on its axis per wavelength band, I(λ_i) in
// W sr^-1 nm^-1: the scene's `intensity` times the lamp's relative spectral distribution S(λ),
// normalised to S(560 nm) = 1 (as D65 is, cie.h), so `intensity` is the value at 560 nm.
//   temperature_k = T   S = B(λ, T) / B(560 nm, T), Planck's law B = 2hc²/λ⁵ / (e^{hc/λkT} - 1)
//                       (expm1 keeps it exact where hc/λkT is small)
//   spectrum = "f.csv"  column 1 (nm) against column 2 (relative power), linear between samples and
//                       held at the end values outside them (Spectrum::at), divided by its value at 560
//   neither             S = 1: an equal-energy lamp
#pragma once
#include <array>
#include <vector>

#include "scene/scene.h"
#include "spectral/sensor.h"
#include "spectral/wavelength_grid.h"

namespace seasim {

// Planck's spectral radiance at lambda_nm and temperature_k, relative to its value at 560 nm.
double planckRelative(double lambda_nm, double temperature_k);

// I(λ_i) for each band of `grid`. RuntimeError naming the CSV for a file without a positive value at
// 560 nm or with a negative value.
// files: read the CSV through it (io/data_files.h), or directly when null.
std::vector<double> lampSpectralIntensity(const SpotlightDesc& lamp, const WavelengthGrid& grid,
                                          DataFiles* files = nullptr);

// The lamp's intensity seen through the sensor: Σ_i I(λ_i) (to_r, to_g, to_b)_i, W/sr in the sensor's
// linear RGB (what the spotlight shafts in air, a grey medium, multiply by).
std::array<double, 3> lampSensorRgb(const SpotlightDesc& lamp, const WavelengthGrid& grid, const Sensor& sensor,
                                    DataFiles* files = nullptr);

// What the shafts in air (a grey medium: the same ρ, κ at every λ) multiply by, per R, G, B (W/sr):
// for a spectral lamp (temperature_k or spectrum) lampSensorRgb through the scene's [spectral] grid and
// sensor, which is exact since nothing else in air depends on λ; for a lamp without either, intensity
// × color as before (an RGB lamp: the sensor does not see it).
Vec3 shaftsLampRgb(const SpotlightDesc& lamp, const SpectralDesc& spectral, DataFiles* files = nullptr);

}  // namespace seasim
