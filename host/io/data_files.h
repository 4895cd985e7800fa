// data_files.h — the data files a render reads (camera curves and lamp spectra as CSV tables; light
// maps, sky images, height fields and other textures as images), each read once and kept, keyed by
// path. A file whose size or modification time changed is read again, so an edit between two renders
// of one process is seen.
//
// Not a global: a command makes one and hands it on with the scene (Scene::files; Renderer makes one
// when the scene has none), so a job's frames, a sweep's settings and the shafts' `auto` search share
// it, and two processes never do. Not thread-safe: set-up runs on one thread.
#pragma once
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>

#include "io/image.h"
#include "spectral/csv_table.h"

namespace seasim {

class DataFiles {
 public:
  // loadCsv / readImage the first time (and after a change on disk), the kept copy after that. The
  // reference is valid until the same path is read again after a change.
  const CsvTable& csv(const std::string& path);
  const Image& image(const std::string& path);
  // Files actually read from disk so far (tests).
  int reads() const { return reads_; }

 private:
  struct Stamp {
    std::uintmax_t size = 0;
    std::filesystem::file_time_type mtime{};
    bool operator==(const Stamp&) const = default;
  };
  static Stamp stampOf(const std::string& path);
  std::map<std::string, std::pair<Stamp, CsvTable>> csv_;
  std::map<std::string, std::pair<Stamp, Image>> images_;
  int reads_ = 0;
};

// files ? files->csv(path) : loadCsv(path), and the same for images: for readers whose caller may
// have no DataFiles (tests, the references).
CsvTable readCsvVia(DataFiles* files, const std::string& path);
Image readImageVia(DataFiles* files, const std::string& path);

}  // namespace seasim
