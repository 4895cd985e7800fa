#include "util/paths.h"

#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
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
  for (size_t i = 0; i < candidates.size(); ++i) {
    const std::string& dir = candidates[i];
    std::error_code ec;
    if (fs::exists(fs::path(dir) / "cie1931_2deg_cmf.csv", ec)) return fs::absolute(dir).lexically_normal();
    // A folder that cannot be read (mode 000) threw a bare "filesystem error"; the one the user
    // named in SEASIM_DATA_DIR is not passed over in silence.
    if (ec && i == 0 && std::getenv("SEASIM_DATA_DIR"))
      throw RuntimeError("cannot read the data folder '" + dir + "' (SEASIM_DATA_DIR): " + ec.message());
    looked += (looked.empty() ? "" : ", ") + dir + (ec ? " (" + ec.message() + ")" : "");
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
  // A sensor name from a file may make an unusable path: absent, not an error.
  for (const auto& dir : cameraDirs(scene_camera_dir)) {
    fs::path p = fs::path(dir) / (name + ".csv");
    std::error_code ec;
    if (fs::is_regular_file(p, ec)) return p.string();
  }
  return "";
}

std::string makeTempFolder(const std::string& stem) {
  const char* tmp = std::getenv("TMPDIR");
  const std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/" + stem + "-XXXXXX";
  std::vector<char> name(pattern.begin(), pattern.end());
  name.push_back('\0');
  return ::mkdtemp(name.data()) ? std::string(name.data()) : std::string();
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

std::string inputFileProblem(const std::string& path) {
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (ec && ec != std::errc::no_such_file_or_directory && ec != std::errc::not_a_directory) {
    const std::string shown = path.size() > 120 ? path.substr(0, 120) + "..." : path;
    return "cannot use the path '" + shown + "': " + ec.message();
  }
  if (!fs::is_regular_file(st)) return "file not found: " + path;
  if (::access(path.c_str(), R_OK) != 0) return "cannot read '" + path + "': " + std::strerror(errno);
  return "";
}

std::string outputDirProblem(const std::string& dir) {
  if (dir.empty()) return "it is empty";
  if (dir.find('\0') != std::string::npos) return "it contains a NUL byte, which no file name can hold";
  if (dir.size() > 4095) return "the path is " + std::to_string(dir.size()) + " bytes long; the limit is 4095";
  for (const auto& part : fs::path(dir))
    if (part.string().size() > 255)
      return "the name '" + part.string().substr(0, 40) + "...' is " + std::to_string(part.string().size()) +
             " bytes long; file systems allow 255";
  std::error_code ec;
  const fs::file_status st = fs::status(dir, ec);
  if (fs::exists(st)) {
    if (!fs::is_directory(st)) return "'" + dir + "' exists and is not a folder";
    if (::access(dir.c_str(), W_OK) != 0) return "the folder '" + dir + "' is not writable";
    return "";
  }
  // Not there yet: it will be created under its nearest existing parent.
  fs::path parent = fs::path(dir).parent_path();
  while (!parent.empty() && !fs::exists(parent, ec)) parent = parent.parent_path();
  if (parent.empty()) return "";
  if (!fs::is_directory(parent, ec)) return "'" + parent.string() + "' is a file, so no folder can be made under it";
  if (::access(parent.c_str(), W_OK) != 0) return "cannot create it: '" + parent.string() + "' is not writable";
  return "";
}

}  // namespace seasim
