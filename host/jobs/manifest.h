// manifest.h — the record of a shard's items: <output_dir>/manifest.json (manifest-<i>of<N>.json
// when sharded), rewritten atomically after every item. Each entry is an item that finished
// ("done": its files with checksums) or failed ("failed": the error), so `--resume` skips what is
// done and intact and retries the rest.
#pragma once
#include <nlohmann/json.hpp>

#include <set>
#include <string>
#include <vector>

namespace seasim {

struct ManifestEntry {
  std::string name;
  bool done = false;            // false: failed
  std::string error;            // when failed
  nlohmann::json files;         // when done: {"item/image.exr": "fnv1a64:...", ...}
  double kernel_ms = 0.0;
  double wall_ms = 0.0;         // when done: the item's render time in the runner (0 in older manifests)
  double build_ms = 0.0;        // when done: of which kernel builds (or cache loads)
};

class Manifest {
 public:
  explicit Manifest(std::string job_file) : job_file_(std::move(job_file)) {}
  // Reads `path` (a missing file gives an empty manifest). A file that is not JSON or not shaped
  // like a manifest is a RuntimeError naming it and saying what to do.
  static Manifest load(const std::string& path, const std::string& job_file);

  void recordDone(const std::string& name, const nlohmann::json& files, double kernel_ms, double wall_ms = 0.0,
                  double build_ms = 0.0);
  void recordFailed(const std::string& name, const std::string& error);
  const std::vector<ManifestEntry>& entries() const { return entries_; }
  void save(const std::string& path) const;  // atomic (io/atomic_file.h)

 private:
  void replace(ManifestEntry entry);
  std::string job_file_;
  std::vector<ManifestEntry> entries_;
};

// Which items are finished is decided against the job, not the manifest alone: finishedItems in
// jobs/farm_items.h.

}  // namespace seasim
