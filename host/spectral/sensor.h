// sensor.h — per-band spectral values -> linear sRGB through a sensor's response curves, by the
// rectangle rule of 002 eq. 4.8:  L_RGB = ∫ L(λ) f(λ) dλ ≈ w Σ_i L(λ_i) f(λ_i),
// with λ_i the band centres and w = Δλ_i the band width (wavelength_grid.h).
//
// Sensors (the `sensor` key of [spectral]):
//   "identity"  no sensor: image.exr holds the raw bands, L(λ_i) in W m⁻² sr⁻¹ nm⁻¹ (the spectral.exr
//               layout); the three RGB channels carry the CIE luminance Y (D65 × 1 -> 1), a grey
//               preview for image.png, compare and sweeps. White balance does not apply.
//   "cie1931"   the CIE 1931 2° observer (data/cie1931_2deg_cmf.csv): f = (x̄, ȳ, z̄) gives XYZ, then
//               the sRGB matrix (cie.h) gives linear sRGB.
//   <camera>    a file stem of <dir>/*.csv for the folders of cameraDirs() (util/paths.h): the
//               scene's camera_dir, $SEASIM_CAMERA_DIR, then the shipped data/cameras (columns
//               nm,r,g,b; provenance data/README.md §5), e.g. "nikon_d5100_npl",
//               "canon_eos_5d_mark_ii_rawtoaces": f = the camera's r, g, b
//               sensitivities, linear between samples and 0 outside the measured range. Its output
//               is the camera's own (white-balanced) RGB shown as linear sRGB, as 002 §6 compares
//               renders per camera; no colour-correction matrix is applied (the data has none).
//
// Normalisation. Let [λmin, λmax] be the grid's range and D65 the illuminant scaled to 1 at 560 nm
// (cie.h). The constants below are continuum integrals over [λmin, λmax] (exact quadrature of the
// tabulated curves, not the band sum), so they do not depend on n and the only n-dependent error is
// that of eq. 4.8 itself, which vanishes as n grows (tested):
//   cie1931:  XYZ = Σ_i L(λ_i) (x̄, ȳ, z̄)(λ_i) Δλ_i / N,  N = ∫ D65 ȳ dλ  -> a radiance of D65 × 1
//             has Y = 1; sRGB = M · XYZ. With white balance each sRGB channel is further scaled by
//             1 / (M · XYZ_D65)_k, a correction of < 1 % that makes D65 exactly (1, 1, 1). On a
//             narrow range D65 falls outside the sRGB gamut (a channel of M · XYZ_D65 <= 0): X and Z
//             are then scaled first (von Kries) to put D65 on its white point, and a curve that sees
//             nothing over the range (z̄ above ~650 nm) leaves its channel unbalanced.
//   camera, white balance:     rgb_k = Σ_i L(λ_i) f_k(λ_i) Δλ_i / ∫ D65 f_k dλ   -> D65 = (1, 1, 1)
//   camera, no white balance:  rgb_k = Σ_i L(λ_i) f_k(λ_i) Δλ_i / S, one S for all channels chosen so
//             that D65 has luminance 0.2126 r + 0.7152 g + 0.0722 b = 1: raw channel ratios, same scale.
// So in every case a grey surface under D65 light renders with luminance ≈ 1 × its reflectance, and
// scene radiance scales (sun.irradiance, sky.radiance: multiples of D65) carry through linearly.
#pragma once
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "spectral/cie.h"
#include "spectral/spectrum.h"
#include "spectral/wavelength_grid.h"

namespace seasim {

class DataFiles;  // io/data_files.h

struct Sensor {
  std::string name;
  bool white_balance = true;
  // Per band i: the weight of band value L(λ_i) in each linear sRGB channel (Δλ_i included).
  std::vector<double> to_r, to_g, to_b;

  std::size_t size() const { return to_r.size(); }
  // (r, g, b) = Σ_i band_values[i] · (to_r, to_g, to_b)[i]; band_values has size() entries.
  std::array<double, 3> apply(const double* band_values) const;
};

// A camera's r, g, b sensitivity curves from <dir>/<name>.csv (cameraDirs(camera_dir)).
struct CameraCurves {
  Spectrum r, g, b;
};
// RuntimeError for an unknown name (naming the folders searched and listing the known names), a
// malformed file or a negative value.
// files: read the CSV through it (io/data_files.h), or directly when null.
CameraCurves loadCamera(const std::string& name, const std::string& camera_dir = "", DataFiles* files = nullptr);

// Sorted file stems of <dir>/*.csv over cameraDirs(camera_dir): the camera names makeSensor accepts.
std::vector<std::string> cameraNames(const std::string& camera_dir = "");

// Sorted file stems of <dir>/*.csv for one folder (empty when it is not a folder).
std::vector<std::string> cameraNamesIn(const std::string& dir);

// "unknown sensor 'name': no name.csv in dir1, dir2, ... (cameras: ...)" for the folders searched.
std::string unknownCameraMessage(const std::string& name, const std::string& camera_dir = "");

// "cie1931" or a camera name (above). RuntimeError for an unknown name or a sensor with no response
// over the grid's range.
// camera_dir: the scene's spectral.camera_dir (absolute, "" for none).
Sensor makeSensor(const std::string& name, const WavelengthGrid& grid, bool white_balance,
                  const std::string& camera_dir = "", DataFiles* files = nullptr);

// The sun's spectral irradiance per band: D65(λ_i) × scale (D65 = 1 at 560 nm), W m^-2 nm^-1.
// D65 is held at its end values outside 300–780 nm. scale must be finite and >= 0.
std::vector<double> sunIrradianceBands(const WavelengthGrid& grid, double scale);

}  // namespace seasim
