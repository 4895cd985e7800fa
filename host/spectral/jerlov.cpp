// jerlov.cpp — Jerlov water types from data/jerlov_{a,b,kd}.csv, the empty-cell rule and the
// Solonenko & Mobley (2015) eq. (3) Kd model (all described in jerlov.h).
#include "spectral/jerlov.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>

#include "spectral/csv_table.h"
#include "util/error.h"
#include "util/paths.h"

namespace seasim {

namespace {

std::string upper(std::string s) {
  for (char& ch : s) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  return s;
}

// Fills the empty tail cells of each type's column in a or b (jerlov.h, "Empty cells").
void fillEmptyCells(CsvTable& t, bool is_absorption) {
  const std::vector<std::string>& types = jerlovTypes();
  const int type_i = t.find("I");
  if (type_i < 0) throw RuntimeError(t.file + ": no column 'I'");
  // Anchors and references use published cells only, never cells filled earlier in this loop.
  const std::vector<std::vector<double>> published = t.columns;
  const std::vector<double>& a_I = published[static_cast<std::size_t>(type_i)];
  for (const CsvTable::EmptyCell& cell : t.empty_cells) {
    const std::string& name = t.names[cell.column];
    const auto pos = std::find(types.begin(), types.end(), name);
    if (pos == types.end() || cell.column == 0)
      throw RuntimeError(t.file + ":" + std::to_string(cell.line) + ": unexpected empty cell in column '" + name + "'");
    const std::vector<double>& v = published[cell.column];
    // λ0: the type's last published wavelength below the gap.
    std::size_t r0 = cell.row;
    while (r0 > 0 && std::isnan(v[r0 - 1])) --r0;
    if (r0 == 0)
      throw RuntimeError(t.file + ":" + std::to_string(cell.line) + ": empty cell in column '" + name +
                         "' with no published value at a shorter wavelength to anchor the fill rule");
    --r0;
    // R: the nearest more turbid type with values at λ0 and λ.
    const std::vector<double>* ref = nullptr;
    for (auto it = pos + 1; it != types.end() && !ref; ++it) {
      const int ci = t.find(*it);
      if (ci < 0) throw RuntimeError(t.file + ": no column '" + *it + "'");
      const std::vector<double>& cand = published[static_cast<std::size_t>(ci)];
      if (!std::isnan(cand[r0]) && !std::isnan(cand[cell.row])) ref = &cand;
    }
    if (!ref)
      throw RuntimeError(t.file + ":" + std::to_string(cell.line) + ": empty cell in column '" + name +
                         "' and no more turbid type has a value there to fill it from");
    const std::vector<double>& R = *ref;
    const std::size_t r = cell.row;
    if (is_absorption) {
      const double excess_ref0 = R[r0] - a_I[r0];
      if (!(excess_ref0 > 0.0))
        throw RuntimeError(t.file + ": fill rule for '" + name + "' needs the reference type to absorb more than type I");
      t.columns[cell.column][r] = a_I[r] + (v[r0] - a_I[r0]) * (R[r] - a_I[r]) / excess_ref0;
    } else {
      t.columns[cell.column][r] = v[r0] * R[r] / R[r0];
    }
  }
}

struct JerlovTables {
  CsvTable a, b, kd;
};

const JerlovTables& tables() {
  static const JerlovTables t = [] {
    const std::string dir = dataDir();
    JerlovTables j{loadCsv(dir + "/jerlov_a.csv"), loadCsv(dir + "/jerlov_b.csv"), loadCsv(dir + "/jerlov_kd.csv")};
    fillEmptyCells(j.a, true);
    fillEmptyCells(j.b, false);
    if (!j.kd.empty_cells.empty())
      throw RuntimeError(j.kd.file + ":" + std::to_string(j.kd.empty_cells.front().line) +
                         ": empty cell; Jerlov's Kd table is expected to be complete");
    return j;
  }();
  return t;
}

}  // namespace

const std::vector<std::string>& jerlovTypes() {
  static const std::vector<std::string> types = {"I", "IA", "IB", "II", "III", "1C", "3C", "5C", "7C", "9C"};
  return types;
}

WaterSpectra jerlovWater(const std::string& type) {
  const std::string key = upper(type);
  const auto& types = jerlovTypes();
  if (std::find(types.begin(), types.end(), key) == types.end()) {
    std::string list;
    for (const auto& t : types) list += (list.empty() ? "" : ", ") + t;
    throw RuntimeError("unknown Jerlov water type '" + type + "' (known: " + list + ")");
  }
  const JerlovTables& t = tables();
  // CsvTable::spectrum rejects NaN; after filling there is none left.
  return WaterSpectra{t.a.spectrum(key), t.b.spectrum(key), t.kd.spectrum(key)};
}

double kdFromIops(double a, double b, double lambda_nm, double mu_w) {
  // Solonenko & Mobley (2015) eq. (3); b·η = b_w, the water's own scattering (their eq. (8)), capped at b.
  const double b_w = 0.00583 * std::pow(400.0 / lambda_nm, 4.322);
  const double b_eta = std::min(b_w, b);
  const double b_G = b * (0.451 * mu_w - 0.205) + b_eta * (2.584 * mu_w - 0.521);
  return std::sqrt(std::max(0.0, a * a + a * b_G)) / mu_w;
}

BandOptics resolveWater(const WaterDesc& water, const WavelengthGrid& grid, double mu_w) {
  if (!(mu_w >= 0.6 && mu_w <= 1.0))
    throw RuntimeError("water: mu_w (cosine of the refracted sun zenith) must be in [0.6, 1], got " +
                       std::to_string(mu_w));
  WaterSpectra s;
  if (!water.jerlov.empty()) s = jerlovWater(water.jerlov);
  if (!water.a.empty()) s.a = water.a;
  if (!water.b.empty()) s.b = water.b;
  if (!water.kd.empty()) s.kd = water.kd;
  if (s.a.empty() || s.b.empty())
    throw RuntimeError("water: give a Jerlov type or both the absorption a and scattering b spectra");

  BandOptics o;
  const std::size_t n = grid.size();
  o.a.resize(n), o.b.resize(n), o.c.resize(n), o.kd.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double lambda = grid.centers_nm[i];
    const double a = s.a.at(lambda), b = s.b.at(lambda);
    const double kd = s.kd.empty() ? kdFromIops(a, b, lambda, mu_w) : s.kd.at(lambda);
    for (auto [name, v] : {std::pair{"a", a}, std::pair{"b", b}, std::pair{"kd", kd}})
      if (!std::isfinite(v) || v < 0.0)
        throw RuntimeError("water: " + std::string(name) + " at " + std::to_string(lambda) +
                           " nm is " + std::to_string(v) + "; it must be finite and >= 0");
    o.a[i] = a;
    o.b[i] = b;
    o.c[i] = a + b;
    o.kd[i] = kd;
  }
  return o;
}

}  // namespace seasim
