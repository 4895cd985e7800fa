// csv.cpp — formatting with std::to_chars: locale-independent and round-trip exact.
#include "io/csv.h"

#include <charconv>
#include <cmath>

#include "io/atomic_file.h"
#include "util/error.h"

namespace seasim {

std::string csvQuote(const std::string& text) {
  const bool needs = text.find_first_of(",\"\r\n") != std::string::npos ||
                     (!text.empty() && (text.front() == ' ' || text.back() == ' ' || text.front() == '\t' ||
                                        text.back() == '\t'));
  if (!needs) return text;
  std::string out = "\"";
  for (char ch : text) {
    if (ch == '"') out += '"';
    out += ch;
  }
  return out + "\"";
}

std::string CsvCell::format(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

std::string CsvCell::field() const { return is_number_ ? text_ : csvQuote(text_); }

CsvWriter::CsvWriter(std::vector<std::string> header) : header_(std::move(header)) {
  if (header_.empty()) throw RuntimeError("a CSV table needs at least one column");
}

void CsvWriter::addRow(std::vector<CsvCell> row) {
  if (row.size() != header_.size())
    throw RuntimeError("CSV row has " + std::to_string(row.size()) + " fields, the header has " +
                       std::to_string(header_.size()));
  rows_.push_back(std::move(row));
}

std::string CsvWriter::str() const {
  std::string out;
  for (std::size_t i = 0; i < header_.size(); ++i) out += (i ? "," : "") + csvQuote(header_[i]);
  out += "\n";
  for (const auto& row : rows_) {
    for (std::size_t i = 0; i < row.size(); ++i) out += (i ? "," : "") + row[i].field();
    out += "\n";
  }
  return out;
}

void CsvWriter::write(const std::string& path) const { writeTextAtomic(path, str()); }

}  // namespace seasim
