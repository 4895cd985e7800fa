// csv_table.h — a numeric CSV file with one header row, read into named columns.
//
// Format (data/README.md): comma separated, one header row of column names, then rows of plain
// decimal numbers. An empty cell means "the source has no value here": it reads as NaN and is listed
// in `empty_cells`, so callers can apply (and document) their own rule for it. Anything else that is
// not a finite number — text, "nan", "inf", a row with too few or too many cells, quotes — is a
// RuntimeError whose message starts with "FILE:LINE:". CR line endings and blank lines are accepted.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "spectral/spectrum.h"

namespace seasim {

struct CsvTable {
  struct EmptyCell {
    std::size_t row;     // 0-based data row
    std::size_t column;  // 0-based column
    int line;            // 1-based line in the file
  };

  std::string file;                          // path as given, for messages
  std::vector<std::string> names;            // header, trimmed
  std::vector<std::vector<double>> columns;  // columns[c][row]; NaN where the cell is empty
  std::vector<int> lines;                    // 1-based file line of each data row
  std::vector<EmptyCell> empty_cells;        // in file order

  std::size_t rows() const { return lines.size(); }
  // Index of a column by its header name; -1 when there is none.
  int find(const std::string& name) const;
  // The column with that header name; RuntimeError naming the file and the columns it does have.
  const std::vector<double>& column(const std::string& name) const;
  // Column 0 as wavelengths (must increase strictly) against the named column, as a Spectrum.
  // RuntimeError "FILE:LINE: ..." on an empty cell in either column or a non-increasing wavelength.
  Spectrum spectrum(const std::string& value_column) const;
};

// Reads a CSV file (see the format above). Throws RuntimeError when it cannot be opened, has no
// header, has no data rows, or has a malformed row.
CsvTable loadCsv(const std::string& path);

// The same, from text in memory (tests); `name` stands for the file in messages.
CsvTable parseCsv(const std::string& text, const std::string& name);

}  // namespace seasim
