#include "jobs/manifest.h"

#include <filesystem>
#include <fstream>

#include "io/atomic_file.h"
#include "util/error.h"

namespace fs = std::filesystem;

namespace seasim {

namespace {

[[noreturn]] void notAManifest(const std::string& path, const std::string& what) {
  throw RuntimeError("'" + path + "' is not a seasim job manifest (" + what +
                     "); move it out of the output folder or delete it (its items then render again)");
}

// One entry, checked field by field so a foreign JSON file gets a message, not a type error.
ManifestEntry parseEntry(const nlohmann::json& j, size_t index, const std::string& path) {
  const std::string where = "items[" + std::to_string(index) + "]";
  if (!j.is_object()) notAManifest(path, where + " is not an object");
  ManifestEntry e;
  if (!j.contains("name") || !j["name"].is_string()) notAManifest(path, where + " has no string 'name'");
  e.name = j["name"].get<std::string>();
  // Manifests written before failed items were recorded have no status: all their entries are done.
  const std::string status = j.contains("status") && j["status"].is_string() ? j["status"].get<std::string>() : "done";
  if (status != "done" && status != "failed") notAManifest(path, where + " has status '" + status + "'");
  e.done = status == "done";
  if (j.contains("error") && j["error"].is_string()) e.error = j["error"].get<std::string>();
  e.files = nlohmann::json::object();
  if (j.contains("files")) {
    if (!j["files"].is_object()) notAManifest(path, where + ".files is not an object");
    for (const auto& [file, sum] : j["files"].items())
      if (!sum.is_string()) notAManifest(path, where + ".files['" + file + "'] is not a checksum string");
    e.files = j["files"];
  }
  if (j.contains("kernel_ms") && j["kernel_ms"].is_number()) e.kernel_ms = j["kernel_ms"].get<double>();
  if (j.contains("wall_ms") && j["wall_ms"].is_number()) e.wall_ms = j["wall_ms"].get<double>();
  if (j.contains("build_ms") && j["build_ms"].is_number()) e.build_ms = j["build_ms"].get<double>();
  return e;
}

}  // namespace

Manifest Manifest::load(const std::string& path, const std::string& job_file) {
  Manifest m(job_file);
  if (!fs::exists(path)) return m;
  nlohmann::json j;
  try {
    std::ifstream in(path);
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    notAManifest(path, std::string("not valid JSON: ") + e.what());
  }
  if (!j.is_object()) notAManifest(path, "the top level is not an object");
  if (!j.contains("items") || !j["items"].is_array()) notAManifest(path, "it has no 'items' array");
  for (size_t i = 0; i < j["items"].size(); ++i) m.entries_.push_back(parseEntry(j["items"][i], i, path));
  return m;
}

void Manifest::replace(ManifestEntry entry) {
  std::erase_if(entries_, [&](const ManifestEntry& e) { return e.name == entry.name; });
  entries_.push_back(std::move(entry));
}

void Manifest::recordDone(const std::string& name, const nlohmann::json& files, double kernel_ms, double wall_ms,
                          double build_ms) {
  replace(ManifestEntry{name, true, "", files, kernel_ms, wall_ms, build_ms});
}

void Manifest::recordFailed(const std::string& name, const std::string& error) {
  replace(ManifestEntry{name, false, error, nlohmann::json::object(), 0.0, 0.0, 0.0});
}

void Manifest::save(const std::string& path) const {
  nlohmann::json items = nlohmann::json::array();
  for (const ManifestEntry& e : entries_) {
    if (e.done)
      items.push_back({{"name", e.name},
                       {"status", "done"},
                       {"files", e.files},
                       {"kernel_ms", e.kernel_ms},
                       {"wall_ms", e.wall_ms},
                       {"build_ms", e.build_ms}});
    else
      items.push_back({{"name", e.name}, {"status", "failed"}, {"error", e.error}});
  }
  const nlohmann::json j = {{"job", job_file_}, {"items", items}};
  writeTextAtomic(path, j.dump(2) + "\n");
}

}  // namespace seasim
