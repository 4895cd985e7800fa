#include "io/data_files.h"

#include <system_error>

#include "io/image_io.h"

namespace seasim {

DataFiles::Stamp DataFiles::stampOf(const std::string& path) {
  std::error_code ec;
  Stamp s;
  s.size = std::filesystem::file_size(path, ec);
  if (ec) return Stamp{};  // the reader reports a missing file, with its own message
  s.mtime = std::filesystem::last_write_time(path, ec);
  return s;
}

const CsvTable& DataFiles::csv(const std::string& path) {
  const Stamp stamp = stampOf(path);
  auto it = csv_.find(path);
  if (it != csv_.end() && it->second.first == stamp) return it->second.second;
  CsvTable table = loadCsv(path);  // throws before anything is kept
  ++reads_;
  auto& slot = csv_[path];
  slot = {stamp, std::move(table)};
  return slot.second;
}

const Image& DataFiles::image(const std::string& path) {
  const Stamp stamp = stampOf(path);
  auto it = images_.find(path);
  if (it != images_.end() && it->second.first == stamp) return it->second.second;
  Image img = readImage(path);
  ++reads_;
  auto& slot = images_[path];
  slot = {stamp, std::move(img)};
  return slot.second;
}

CsvTable readCsvVia(DataFiles* files, const std::string& path) { return files ? files->csv(path) : loadCsv(path); }

Image readImageVia(DataFiles* files, const std::string& path) { return files ? files->image(path) : readImage(path); }

}  // namespace seasim
