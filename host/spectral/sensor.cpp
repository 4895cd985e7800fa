// sensor.cpp — sensor weights for 002 eq. 4.8 and their normalisation (described in sensor.h).
#include "spectral/sensor.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>

#include "io/data_files.h"
#include "spectral/csv_table.h"
#include "spectral/von_kries.h"
#include "util/error.h"
#include "util/paths.h"

namespace seasim {

namespace {

// ∫_lo^hi f dλ for an f that is a product of at most three piecewise-linear curves with breakpoints
// among `knots`: 2-point Gauss–Legendre on every piece between knots is exact for such a product up
// to degree 3, and it never evaluates a piece's ends, where a response may jump to 0.
double integrate(const std::function<double(double)>& f, std::vector<double> knots, double lo, double hi) {
  knots.push_back(lo);
  knots.push_back(hi);
  std::sort(knots.begin(), knots.end());
  knots.erase(std::unique(knots.begin(), knots.end()), knots.end());
  const double g = 0.5 / std::sqrt(3.0);
  double sum = 0.0;
  for (std::size_t i = 0; i + 1 < knots.size(); ++i) {
    const double a = knots[i], b = knots[i + 1];
    if (a < lo || b > hi) continue;
    const double mid = 0.5 * (a + b), h = b - a;
    sum += 0.5 * h * (f(mid - g * h) + f(mid + g * h));
  }
  return sum;
}

std::vector<double> knotsOf(std::initializer_list<const Spectrum*> spectra) {
  std::vector<double> k;
  for (const Spectrum* s : spectra) k.insert(k.end(), s->wavelengths_nm.begin(), s->wavelengths_nm.end());
  return k;
}

// The luminance row of linear sRGB -> XYZ (0.2126, 0.7152, 0.0722), from the same derivation as M.
std::array<double, 3> srgbLuminanceRow() {
  const auto& m = xyzToLinearSrgbMatrix();
  // Row 1 (Y) of M^-1 by cofactors.
  const double a = m[0], b = m[1], c = m[2], d = m[3], e = m[4], f = m[5], g = m[6], h = m[7], i = m[8];
  const double det = a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g);
  return {-(d * i - f * g) / det, (a * i - c * g) / det, -(a * f - c * d) / det};
}

}  // namespace

std::array<double, 3> Sensor::apply(const double* band_values) const {
  double r = 0.0, g = 0.0, b = 0.0;
  for (std::size_t i = 0; i < to_r.size(); ++i) {
    r += band_values[i] * to_r[i];
    g += band_values[i] * to_g[i];
    b += band_values[i] * to_b[i];
  }
  return {r, g, b};
}

std::vector<std::string> cameraNamesIn(const std::string& dir) {
  std::vector<std::string> names;
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) return names;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec))
    if (entry.is_regular_file() && entry.path().extension() == ".csv") names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

std::vector<std::string> cameraNames(const std::string& camera_dir) {
  std::vector<std::string> names;
  for (const auto& d : cameraDirs(camera_dir)) {
    const std::vector<std::string> in_dir = cameraNamesIn(d);
    names.insert(names.end(), in_dir.begin(), in_dir.end());
  }
  std::sort(names.begin(), names.end());
  names.erase(std::unique(names.begin(), names.end()), names.end());
  return names;
}

std::string unknownCameraMessage(const std::string& name, const std::string& camera_dir) {
  std::string dirs, list;
  for (const auto& d : cameraDirs(camera_dir)) dirs += (dirs.empty() ? "" : ", ") + d;
  for (const auto& n : cameraNames(camera_dir)) list += (list.empty() ? "" : ", ") + n;
  return "unknown sensor '" + name + "': not \"cie1931\" and no file " + name + ".csv in " + dirs +
         " (cameras: " + list + "); other curves go in a folder named by spectral.camera_dir or $SEASIM_CAMERA_DIR";
}

CameraCurves loadCamera(const std::string& name, const std::string& camera_dir, DataFiles* files) {
  const std::string path = cameraFile(name, camera_dir);
  if (path.empty()) throw RuntimeError(unknownCameraMessage(name, camera_dir));
  const CsvTable t = readCsvVia(files, path);
  for (const char* ch : {"r", "g", "b"}) {
    const auto& col = t.column(ch);
    for (std::size_t row = 0; row < t.rows(); ++row)
      if (col[row] < 0.0)
        throw RuntimeError(path + ":" + std::to_string(t.lines[row]) + ": negative sensitivity in column '" + ch + "'");
  }
  return CameraCurves{t.spectrum("r"), t.spectrum("g"), t.spectrum("b")};
}

Sensor makeSensor(const std::string& name, const WavelengthGrid& grid, bool white_balance,
                  const std::string& camera_dir, DataFiles* files) {
  const double lo = grid.minNm(), hi = grid.maxNm();
  const Spectrum illum = d65();
  std::array<Spectrum, 3> curves;  // x̄ȳz̄ or camera r, g, b
  // "identity": the raw bands are the output (spectral.exr layout, written as image.exr); the RGB the
  // kernels still accumulate is the CIE luminance Y in all three channels, a grey preview.
  const bool identity = (name == "identity");
  double white_kelvin = 0;
  const bool von_kries = parseVonKriesSensor(name, &white_kelvin);  // 003 eq. 15-17 (von_kries.h)
  const bool cie = (name == "cie1931") || identity || von_kries;
  if (cie) {
    const CieCmf& cmf = cie1931Cmf();
    curves = {cmf.x_bar, cmf.y_bar, cmf.z_bar};
  } else {
    CameraCurves cam = loadCamera(name, camera_dir, files);
    curves = {std::move(cam.r), std::move(cam.g), std::move(cam.b)};
  }

  // Continuum response of each curve to D65 over the grid's range.
  std::array<double, 3> d65_resp{};
  for (int k = 0; k < 3; ++k) {
    const Spectrum& f = curves[static_cast<std::size_t>(k)];
    d65_resp[static_cast<std::size_t>(k)] =
        integrate([&](double l) { return illum.at(l) * responseAt(f, l); }, knotsOf({&illum, &f}), lo, hi);
  }

  // out = A · (raw band sums of the three curves): A folds in the matrix and every scale factor.
  std::array<double, 9> A{};
  const auto range = "[" + std::to_string(lo) + ", " + std::to_string(hi) + "] nm";
  if (identity) {
    if (!(d65_resp[1] > 0.0)) throw RuntimeError("sensor identity: y_bar (its grey preview) is zero over " + range);
    for (int r = 0; r < 3; ++r) A[static_cast<std::size_t>(r * 3 + 1)] = 1.0 / d65_resp[1];  // Y, D65 -> 1
  } else if (cie) {
    if (!(d65_resp[1] > 0.0)) throw RuntimeError("sensor cie1931: y_bar is zero over " + range);
    const double N = d65_resp[1];
    const auto& M = xyzToLinearSrgbMatrix();
    std::array<double, 3> gain = {1.0, 1.0, 1.0};  // on linear sRGB
    std::array<double, 3> xyz_gain = {1.0, 1.0, 1.0};  // on X, Y, Z (von Kries), narrow ranges only
    if (white_balance) {
      std::array<double, 3> d65_xyz = {d65_resp[0] / N, 1.0, d65_resp[2] / N};
      auto rgb = xyzToLinearSrgb(d65_xyz);
      if (!(rgb[0] > 0.0 && rgb[1] > 0.0 && rgb[2] > 0.0)) {
        // Over a narrow range D65 is nearly a spectral colour, outside the sRGB gamut: no diagonal gain
        // on sRGB can make it white. Scale X and Z first so that it lands on D65's white point
        // (x, y) = (0.3127, 0.3290), XYZ = (0.9505, 1, 1.0891), which sRGB maps to (1, 1, 1); the sRGB
        // gains below then only remove rounding. A curve that sees nothing over the range (z̄ above
        // 650 nm) keeps gain 1 and its channel stays unbalanced.
        const std::array<double, 3> white = {0.3127 / 0.3290, 1.0, (1.0 - 0.3127 - 0.3290) / 0.3290};
        for (int k : {0, 2}) {
          const std::size_t i = static_cast<std::size_t>(k);
          if (d65_xyz[i] > 0.0) xyz_gain[i] = white[i] / d65_xyz[i];
          d65_xyz[i] *= xyz_gain[i];
        }
        rgb = xyzToLinearSrgb(d65_xyz);
      }
      for (int k = 0; k < 3; ++k) {
        const std::size_t i = static_cast<std::size_t>(k);
        if (rgb[i] > 0.0) gain[i] = 1.0 / rgb[i];  // else (a curve blind over the range): left as it is
      }
    }
    // von Kries (003 eq. 15-17): XYZ adapted from the black-body white point (luminance 1, eq. 16) to
    // D65's, so the white point shows as D65 does; then the same sRGB matrix and balance.
    Mat3 adapt = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    if (von_kries) {
      const CieCmf& cmf = cie1931Cmf();
      Vec3d white{};
      const Spectrum* xyz_curves[3] = {&cmf.x_bar, &cmf.y_bar, &cmf.z_bar};
      for (int k = 0; k < 3; ++k)
        white[static_cast<std::size_t>(k)] = integrate(
            [&](double l) { return blackbody(l, white_kelvin) * responseAt(*xyz_curves[k], l); }, knotsOf({xyz_curves[k]}),
            lo, hi);
      if (!(white[1] > 0.0)) throw RuntimeError("sensor " + name + ": the white point has no luminance over " + range);
      const Vec3d white_xyz = {white[0] / white[1], 1.0, white[2] / white[1]};
      const Vec3d d65_xyz = {d65_resp[0] / N, 1.0, d65_resp[2] / N};
      adapt = vonKriesXyzTransform(white_xyz, d65_xyz);
    }
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) {
        double v = 0;
        for (int k = 0; k < 3; ++k)
          v += M[static_cast<std::size_t>(r * 3 + k)] * xyz_gain[static_cast<std::size_t>(k)] * adapt[static_cast<std::size_t>(k * 3 + c)];
        A[static_cast<std::size_t>(r * 3 + c)] = gain[static_cast<std::size_t>(r)] * v / N;
      }
  } else if (white_balance) {
    for (int k = 0; k < 3; ++k) {
      if (!(d65_resp[static_cast<std::size_t>(k)] > 0.0))
        throw RuntimeError("sensor " + name + ": channel " + "rgb"[k] + " does not respond over " + range);
      A[static_cast<std::size_t>(k * 4)] = 1.0 / d65_resp[static_cast<std::size_t>(k)];
    }
  } else {
    const auto Y = srgbLuminanceRow();
    const double S = Y[0] * d65_resp[0] + Y[1] * d65_resp[1] + Y[2] * d65_resp[2];
    if (!(S > 0.0)) throw RuntimeError("sensor " + name + ": no response over " + range);
    for (int k = 0; k < 3; ++k) A[static_cast<std::size_t>(k * 4)] = 1.0 / S;
  }

  Sensor s;
  s.name = name;
  s.white_balance = white_balance;
  const std::size_t n = grid.size();
  s.to_r.resize(n), s.to_g.resize(n), s.to_b.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double l = grid.centers_nm[i], w = grid.widths_nm[i];  // 002 eq. 4.8: f(λ_i) · w
    const double f0 = responseAt(curves[0], l) * w, f1 = responseAt(curves[1], l) * w, f2 = responseAt(curves[2], l) * w;
    s.to_r[i] = A[0] * f0 + A[1] * f1 + A[2] * f2;
    s.to_g[i] = A[3] * f0 + A[4] * f1 + A[5] * f2;
    s.to_b[i] = A[6] * f0 + A[7] * f1 + A[8] * f2;
  }
  return s;
}

std::vector<double> sunIrradianceBands(const WavelengthGrid& grid, double scale) {
  if (!std::isfinite(scale) || scale < 0.0)
    throw RuntimeError("sun irradiance scale must be finite and >= 0, got " + std::to_string(scale));
  const Spectrum illum = d65();
  std::vector<double> e(grid.size());
  for (std::size_t i = 0; i < grid.size(); ++i) e[i] = illum.at(grid.centers_nm[i]) * scale;
  return e;
}

}  // namespace seasim
