// csv_table.cpp — the reader behind every data/*.csv file (format in csv_table.h).
#include "spectral/csv_table.h"

#include <cerrno>
#include <charconv>
#include <cstring>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "util/error.h"

namespace seasim {

namespace {

std::string trim(const std::string& s) {
  std::size_t b = 0, e = s.size();
  while (b < e && (s[b] == ' ' || s[b] == '\t' || s[b] == '\r')) ++b;
  while (e > b && (s[e - 1] == ' ' || s[e - 1] == '\t' || s[e - 1] == '\r')) --e;
  return s.substr(b, e - b);
}

std::vector<std::string> splitCommas(const std::string& line) {
  std::vector<std::string> cells;
  std::size_t start = 0;
  for (;;) {
    std::size_t comma = line.find(',', start);
    cells.push_back(trim(line.substr(start, comma == std::string::npos ? std::string::npos : comma - start)));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return cells;
}

[[noreturn]] void fail(const std::string& file, int line, const std::string& message) {
  throw RuntimeError(file + ":" + std::to_string(line) + ": " + message);
}

}  // namespace

int CsvTable::find(const std::string& name) const {
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return static_cast<int>(i);
  return -1;
}

const std::vector<double>& CsvTable::column(const std::string& name) const {
  int i = find(name);
  if (i < 0) {
    std::string have;
    for (const auto& n : names) have += (have.empty() ? "" : ", ") + n;
    throw RuntimeError(file + ": no column '" + name + "' (columns: " + have + ")");
  }
  return columns[static_cast<std::size_t>(i)];
}

Spectrum CsvTable::spectrum(const std::string& value_column) const {
  const std::vector<double>& values = column(value_column);
  const std::vector<double>& wl = columns.at(0);
  Spectrum s;
  for (std::size_t r = 0; r < rows(); ++r) {
    if (std::isnan(wl[r]) || std::isnan(values[r]))
      fail(file, lines[r], "empty cell in column '" + (std::isnan(wl[r]) ? names[0] : value_column) + "'");
    if (!s.wavelengths_nm.empty() && !(wl[r] > s.wavelengths_nm.back()))
      fail(file, lines[r], "wavelengths must increase strictly (" + names[0] + " = " + std::to_string(wl[r]) + ")");
    s.wavelengths_nm.push_back(wl[r]);
    s.values.push_back(values[r]);
  }
  return s;
}

CsvTable parseCsv(const std::string& text, const std::string& name) {
  CsvTable t;
  t.file = name;
  std::istringstream in(text);
  std::string raw;
  int line_no = 0;
  bool have_header = false;
  while (std::getline(in, raw)) {
    ++line_no;
    if (trim(raw).empty()) continue;
    if (raw.find('"') != std::string::npos) fail(name, line_no, "quoted cells are not supported");
    std::vector<std::string> cells = splitCommas(raw);
    if (!have_header) {
      for (std::size_t i = 0; i < cells.size(); ++i) {
        if (cells[i].empty()) fail(name, line_no, "header cell " + std::to_string(i + 1) + " is empty");
        for (std::size_t j = 0; j < i; ++j)
          if (cells[j] == cells[i]) fail(name, line_no, "header names column '" + cells[i] + "' twice");
      }
      t.names = cells;
      t.columns.assign(cells.size(), {});
      have_header = true;
      continue;
    }
    if (cells.size() != t.names.size())
      fail(name, line_no, "expected " + std::to_string(t.names.size()) + " cells (as in the header), found " +
                              std::to_string(cells.size()));
    const std::size_t row = t.lines.size();
    for (std::size_t c = 0; c < cells.size(); ++c) {
      const std::string& cell = cells[c];
      if (cell.empty()) {
        t.columns[c].push_back(std::numeric_limits<double>::quiet_NaN());
        t.empty_cells.push_back({row, c, line_no});
        continue;
      }
      const char* first = cell.data();
      const char* last = cell.data() + cell.size();
      if (*first == '+') ++first;  // from_chars takes no leading '+'
      double v = 0.0;
      auto [ptr, ec] = std::from_chars(first, last, v);
      if (ec != std::errc() || ptr != last || !std::isfinite(v))
        fail(name, line_no, "column '" + t.names[c] + "': '" + cell + "' is not a finite number");
      t.columns[c].push_back(v);
    }
    t.lines.push_back(line_no);
  }
  if (!have_header) throw RuntimeError(name + ": empty file (expected a header row)");
  if (t.lines.empty()) throw RuntimeError(name + ": no data rows after the header");
  return t;
}

CsvTable loadCsv(const std::string& path) {
  errno = 0;
  std::ifstream f(path, std::ios::binary);
  if (!f) throw RuntimeError(path + ": cannot open for reading" + (errno ? std::string(": ") + std::strerror(errno) : ""));
  std::ostringstream ss;
  ss << f.rdbuf();
  return parseCsv(ss.str(), path);
}

}  // namespace seasim
