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

// The file each of the item's outputs is written to (render_item.cpp), relative to its folder. A
// build without OpenImageIO writes "<name>.npy" instead (io/image_io.h); either counts.
const char* outputFileName(const std::string& format) {
  if (format == "exr") return "image.exr";
  if (format == "png") return "image.png";
  if (format == "npy") return "image.npy";
  if (format == "spectral_exr") return "spectral.exr";
  return nullptr;
}

// The first file the job expects of this item that the manifest's list leaves out ("" when none):
// report.json, one file per output, and labels.json for a [sample] item. A manifest edited by
// hand, or written by a run whose job asked for fewer outputs, must not make an item count as done.
std::string unlistedFile(const RenderItem& item, const nlohmann::json& files) {
  const std::string dir = item.name + "/";
  if (!files.contains(dir + "report.json")) return dir + "report.json";
  if (!item.sampled.empty() && !files.contains(dir + "labels.json")) return dir + "labels.json";
  for (const std::string& format : item.outputs) {
    const char* name = outputFileName(format);
    if (!name) continue;  // the job parser accepts no other format
    if (!files.contains(dir + name) && !files.contains(dir + name + ".npy")) return dir + name;
  }
  return "";
}

ItemState stateOf(const ManifestEntry& e, const RenderItem* item, const std::string& output_dir, bool verify) {
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
  if (item) {
    if (const std::string file = unlistedFile(*item, e.files); !file.empty()) {
      s.status = ItemState::Status::Damaged;
      s.detail = "'" + file + "', an output the job asks for, is not among the manifest's files";
      return s;
    }
  }
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
  std::map<std::string, const RenderItem*> items;
  for (const RenderItem& item : job.items) items.emplace(item.name, &item);
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
        const auto item = items.find(e.name);
        ItemState s = stateOf(e, item == items.end() ? nullptr : item->second, output_dir, verify_checksums);
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

std::set<std::string> finishedItems(const Job& job, const std::string& output_dir) {
  std::set<std::string> done;
  for (const ItemState& s : readItemStates(job, output_dir, true))
    if (s.status == ItemState::Status::Done) done.insert(s.name);
  return done;
}

}  // namespace seasim
