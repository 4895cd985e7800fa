#include "jobs/farm_items.h"

#include <algorithm>
#include <filesystem>
#include <map>

#include "jobs/manifest.h"
#include "util/hash.h"

namespace fs = std::filesystem;

namespace seasim {

const char* statusName(ItemState::Status s) {
  switch (s) {
    case ItemState::Status::Done:
      return "done";
    case ItemState::Status::Damaged:
      return "damaged";
    case ItemState::Status::Failed:
      return "failed";
    case ItemState::Status::Missing:
      return "missing";
  }
  return "?";
}

namespace {

// Which of two states of one item wins: done over damaged over failed over missing.
int rank(ItemState::Status s) {
  switch (s) {
    case ItemState::Status::Done:
      return 3;
    case ItemState::Status::Damaged:
      return 2;
    case ItemState::Status::Failed:
      return 1;
    case ItemState::Status::Missing:
      return 0;
  }
  return 0;
}

ItemState stateOf(const ManifestEntry& e, const std::string& output_dir, bool verify) {
  ItemState s;
  s.name = e.name;
  if (!e.done) {
    s.status = ItemState::Status::Failed;
    s.detail = e.error;
    return s;
  }
  s.status = ItemState::Status::Done;
  s.files = e.files;
  s.wall_ms = e.wall_ms;
  s.kernel_ms = e.kernel_ms;
  if (!verify) return s;
  for (const auto& [file, checksum] : e.files.items()) {
    const std::string path = output_dir + "/" + file;
    const std::string actual = fileChecksum(path);
    if (actual == checksum.get<std::string>()) continue;
    s.status = ItemState::Status::Damaged;
    s.detail = actual.empty() ? "'" + file + "' is missing" : "'" + file + "' does not match its checksum";
    break;
  }
  return s;
}

}  // namespace

std::vector<ItemState> readItemStates(const Job& job, const std::string& output_dir, bool verify_checksums) {
  std::map<std::string, ItemState> best;
  if (fs::is_directory(output_dir)) {
    std::vector<fs::path> manifests;
    for (const auto& entry : fs::directory_iterator(output_dir)) {
      const std::string name = entry.path().filename().string();
      if (name.rfind("manifest", 0) == 0 && entry.path().extension() == ".json" && entry.is_regular_file())
        manifests.push_back(entry.path());
    }
    std::sort(manifests.begin(), manifests.end());  // the same answer whatever the directory order
    for (const fs::path& path : manifests) {
      const Manifest manifest = Manifest::load(path.string(), "");
      for (const ManifestEntry& e : manifest.entries()) {
        ItemState s = stateOf(e, output_dir, verify_checksums);
        auto it = best.find(e.name);
        if (it == best.end())
          best.emplace(e.name, std::move(s));
        else if (rank(s.status) > rank(it->second.status))
          it->second = std::move(s);
      }
    }
  }
  std::vector<ItemState> states;
  for (const RenderItem& item : job.items) {
    auto it = best.find(item.name);
    if (it != best.end()) {
      states.push_back(it->second);
    } else {
      ItemState s;
      s.name = item.name;
      states.push_back(s);
    }
  }
  return states;
}

}  // namespace seasim
