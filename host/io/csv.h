// csv.h — a small CSV table (RFC 4180: comma separated, "\n" line ends, fields with a comma, quote,
// CR/LF or leading/trailing space quoted with "" doubling) written atomically. Numbers are written
// in the shortest form that reads back to the same double; NaN and ±Inf as nan, inf, -inf (what
// pandas and numpy read).
#pragma once
#include <string>
#include <type_traits>
#include <vector>

namespace seasim {

// One field: a string (quoted when needed) or a number (formatted on construction).
class CsvCell {
 public:
  CsvCell(std::string text) : text_(std::move(text)), is_number_(false) {}
  CsvCell(const char* text) : text_(text), is_number_(false) {}
  template <class T>
    requires std::is_arithmetic_v<T> && (!std::is_same_v<T, bool>)
  CsvCell(T value) : text_(format(value)), is_number_(true) {}
  CsvCell(bool value) : text_(value ? "true" : "false"), is_number_(false) {}

  // The field as it appears in the file.
  std::string field() const;

 private:
  static std::string format(double v);
  static std::string format(long long v) { return std::to_string(v); }
  static std::string format(unsigned long long v) { return std::to_string(v); }
  template <class T>
  static std::string format(T v) {
    if constexpr (std::is_floating_point_v<T>) return format(static_cast<double>(v));
    else if constexpr (std::is_signed_v<T>) return format(static_cast<long long>(v));
    else return format(static_cast<unsigned long long>(v));
  }
  std::string text_;
  bool is_number_;
};

class CsvWriter {
 public:
  explicit CsvWriter(std::vector<std::string> header);
  // A row must have as many fields as the header (RuntimeError otherwise).
  void addRow(std::vector<CsvCell> row);
  std::size_t rows() const { return rows_.size(); }
  std::string str() const;
  // Writes str() to `path` atomically, creating parent folders.
  void write(const std::string& path) const;

 private:
  std::vector<std::string> header_;
  std::vector<std::vector<CsvCell>> rows_;
};

// `text` as a CSV field: unchanged, or in double quotes with inner quotes doubled.
std::string csvQuote(const std::string& text);

}  // namespace seasim
