#include "quality/quality_search.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "io/atomic_file.h"
#include "util/error.h"
#include "util/hash.h"
#include "util/paths.h"

namespace seasim {

void searchResolution(const CameraDesc& camera, int downscale, int min_long_side, int max_long_side, int& width,
                      int& height) {
  const int W = camera.width, H = camera.height, L = std::max(W, H);
  const int lo = std::min(L, std::max(1, min_long_side));
  const int target = std::clamp(L / std::max(1, downscale), lo, std::max(lo, max_long_side));
  const double s = double(std::min(target, L)) / L;
  width = std::max(1, static_cast<int>(std::lround(W * s)));
  height = std::max(1, static_cast<int>(std::lround(H * s)));
}

std::string searchCacheFile(const std::string& dir, const std::string& subfolder, const std::string& prefix,
                            const std::string& description) {
  const std::string folder = dir.empty() ? cacheDir(subfolder) : dir;
  return folder.empty() ? std::string() : folder + "/" + prefix + hex64(fnv1a64(description)) + ".txt";
}

std::map<std::string, std::string> readCacheEntries(const std::string& path) {
  std::map<std::string, std::string> kv;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    const size_t sp = line.find(' ');
    if (sp != std::string::npos) kv[line.substr(0, sp)] = line.substr(sp + 1);
  }
  return kv;
}

void writeCacheEntries(const std::string& path, const std::string& title, const std::string& inputs,
                       const std::string& entries) {
  std::ostringstream s;
  s << "# " << title << "; inputs:\n";
  std::istringstream d(inputs);
  for (std::string line; std::getline(d, line);) s << "# " << line << '\n';
  s << entries;
  try {
    writeTextAtomic(path, s.str());
  } catch (const RuntimeError&) {
    // A cache that cannot be written only costs the search next time.
  }
}

}  // namespace seasim
