#include "util/paths.h"

#include <cstdlib>
#include <filesystem>
#include <vector>

#include "util/error.h"

namespace fs = std::filesystem;

namespace seasim {

std::string installedShareDir() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec || exe.parent_path().filename() != "bin") return "";
  const fs::path share = exe.parent_path().parent_path() / "share" / "seasim";
  return fs::is_directory(share / "data", ec) ? share.string() : "";
}

std::string installedExample(const std::string& relative_path) {
  const std::string share = installedShareDir();
  if (share.empty() || relative_path.empty() || fs::path(relative_path).is_absolute()) return "";
  const fs::path p = fs::path(share) / relative_path;
  std::error_code ec;
  return fs::is_regular_file(p, ec) ? p.lexically_normal().string() : "";
}

std::string dataDir() {
  std::vector<std::string> candidates;
  if (const char* env = std::getenv("SEASIM_DATA_DIR")) candidates.emplace_back(env);
  if (const std::string share = installedShareDir(); !share.empty()) candidates.emplace_back(share + "/data");
  candidates.emplace_back(std::string(SEASIM_SOURCE_DIR) + "/data");
  candidates.emplace_back("data");
  std::string looked;
  for (const auto& dir : candidates) {
    if (fs::exists(fs::path(dir) / "cie1931_2deg_cmf.csv")) return fs::absolute(dir).lexically_normal();
    looked += (looked.empty() ? "" : ", ") + dir;
  }
  throw RuntimeError("cannot find the data folder (looked in " + looked + "); set SEASIM_DATA_DIR");
}

std::vector<std::string> cameraDirs(const std::string& scene_camera_dir) {
  std::vector<std::string> dirs;
  if (!scene_camera_dir.empty()) dirs.push_back(scene_camera_dir);
  if (const char* env = std::getenv("SEASIM_CAMERA_DIR"); env && *env)
    dirs.push_back(fs::absolute(env).lexically_normal().string());
  dirs.push_back((fs::path(dataDir()) / "cameras").string());
  return dirs;
}

std::string cameraFile(const std::string& name, const std::string& scene_camera_dir) {
  if (name.empty() || name.find('/') != std::string::npos) return "";
  for (const auto& dir : cameraDirs(scene_camera_dir)) {
    fs::path p = fs::path(dir) / (name + ".csv");
    if (fs::is_regular_file(p)) return p.string();
  }
  return "";
}

std::string resolveRelativeTo(const std::string& anchor_file, const std::string& path) {
  fs::path p(path);
  if (p.is_absolute()) return p.lexically_normal();
  fs::path base = fs::absolute(anchor_file).parent_path();
  return (base / p).lexically_normal();
}

std::string cacheDir(const std::string& sub) {
  std::string base;
  if (const char* d = std::getenv("SEASIM_CACHE_DIR"); d && *d) base = d;
  else if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) base = std::string(x) + "/seasim";
  else if (const char* h = std::getenv("HOME"); h && *h) base = std::string(h) + "/.cache/seasim";
  if (base.empty() || sub.empty()) return base;
  return base + "/" + sub;
}

}  // namespace seasim
