#include "jobs/runner.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include "device/device.h"
#include "io/atomic_file.h"
#include "jobs/job.h"
#include "jobs/progress.h"
#include "jobs/render_item.h"
#include "passes/nodes/standard_passes.h"
#include "render/renderer.h"
#include "scene/scene_parser.h"
#include "util/error.h"
#include "util/hash.h"

namespace fs = std::filesystem;

namespace seasim {

std::string manifestPath(const std::string& output_dir, int shard_index, int shard_count) {
  if (shard_count <= 1) return output_dir + "/manifest.json";
  return output_dir + "/manifest-" + std::to_string(shard_index) + "of" + std::to_string(shard_count) + ".json";
}

namespace {

// Items recorded as finished in any manifest of the folder whose files still match their checksums.
std::set<std::string> finishedItems(const std::string& output_dir) {
  std::set<std::string> done;
  if (!fs::exists(output_dir)) return done;
  for (const auto& entry : fs::directory_iterator(output_dir)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("manifest", 0) != 0 || entry.path().extension() != ".json") continue;
    nlohmann::json manifest;
    try {
      std::ifstream in(entry.path());
      manifest = nlohmann::json::parse(in);
    } catch (const std::exception&) {
      continue;  // unreadable manifest: its items render again
    }
    for (const auto& item : manifest.value("items", nlohmann::json::array())) {
      bool intact = true;
      const nlohmann::json files = item.value("files", nlohmann::json::object());  // not a temporary: items() refers into it
      for (const auto& [file, checksum] : files.items()) {
        if (fileChecksum(output_dir + "/" + file) != checksum.get<std::string>()) intact = false;
      }
      if (intact) done.insert(item.value("name", ""));
    }
  }
  return done;
}

// The keys whose value differs between two override lists (set in one only, or to other values).
std::vector<std::string> changedKeys(const std::vector<Override>& before, const std::vector<Override>& after) {
  std::map<std::string, std::string> a, b;
  for (const Override& o : before) a[o.key] = o.value_toml;
  for (const Override& o : after) b[o.key] = o.value_toml;
  std::vector<std::string> changed;
  for (const auto& [key, value] : a)
    if (!b.count(key) || b[key] != value) changed.push_back(key);
  for (const auto& [key, value] : b)
    if (!a.count(key)) changed.push_back(key);
  return changed;
}

}  // namespace

RunSummary runJob(const std::string& job_path, const RunOptions& options) {
  if (options.shard_count < 1 || options.shard_index < 0 || options.shard_index >= options.shard_count) {
    throw RuntimeError("--shard must be i/N with 0 <= i < N");
  }
  Job job = loadJob(job_path);  // validates every item's scene before anything renders
  if (!options.output_dir.empty()) job.output_dir = fs::absolute(options.output_dir).lexically_normal().string();
  RunSummary summary;
  summary.output_dir = job.output_dir;
  fs::create_directories(job.output_dir);

  const std::set<std::string> finished = options.resume ? finishedItems(job.output_dir) : std::set<std::string>{};
  const std::string manifest_file = manifestPath(job.output_dir, options.shard_index, options.shard_count);
  nlohmann::json manifest = {{"job", job.file}, {"items", nlohmann::json::array()}};
  if (options.resume && fs::exists(manifest_file)) {
    try {
      std::ifstream in(manifest_file);
      manifest = nlohmann::json::parse(in);
    } catch (const std::exception&) {
      manifest = {{"job", job.file}, {"items", nlohmann::json::array()}};
    }
  }

  std::vector<const RenderItem*> mine;
  for (size_t i = 0; i < job.items.size(); ++i) {
    if (static_cast<int>(i % static_cast<size_t>(options.shard_count)) == options.shard_index) {
      mine.push_back(&job.items[i]);
    } else {
      ++summary.other_shards;
    }
  }

  const std::string selector = options.device.empty() ? job.device : options.device;
  std::unique_ptr<Device> device;  // opened on the first item that needs rendering
  std::unique_ptr<Renderer> renderer;
  const RenderItem* previous = nullptr;
  Progress progress(static_cast<int>(mine.size()), stderrIsTerminal());
  for (const RenderItem* item : mine) {
    progress.start(item->name);
    if (finished.count(item->name)) {
      ++summary.skipped;
      progress.finish(item->name, "finished earlier (resume)");
      continue;
    }
    if (!device) device = std::make_unique<Device>(chooseDevice(selector));
    const Scene scene = loadScene(item->scene_file, item->overrides);
    // Items on the scene file of the item before (a sweep, frames) share its renderer: only the
    // passes that read a changed key run again.
    if (renderer && previous && previous->scene_file == item->scene_file) {
      renderer->update(scene, changedKeys(previous->overrides, item->overrides));
    } else {
      renderer = std::make_unique<Renderer>(*device, scene, standardPasses());
    }
    previous = item;
    ItemOutputs outputs;
    outputs.formats = item->outputs;
    outputs.reference = item->reference;
    const std::string item_dir = job.output_dir + "/" + item->name;
    const nlohmann::json report = renderItem(*device, *renderer, outputs, item_dir);

    nlohmann::json files = nlohmann::json::object();
    for (const auto& f : report["outputs"]) {
      const std::string rel = item->name + "/" + f.get<std::string>();
      files[rel] = fileChecksum(job.output_dir + "/" + rel);
    }
    files[item->name + "/report.json"] = fileChecksum(item_dir + "/report.json");
    auto& items = manifest["items"];
    for (auto it = items.begin(); it != items.end(); ++it) {
      if ((*it).value("name", "") == item->name) {
        items.erase(it);
        break;
      }
    }
    items.push_back({{"name", item->name}, {"files", files}, {"kernel_ms", report["kernel_ms_total"]}});
    writeTextAtomic(manifest_file, manifest.dump(2) + "\n");
    ++summary.rendered;
    char outcome[64];
    std::snprintf(outcome, sizeof outcome, "done (%.1f ms kernels)", report["kernel_ms_total"].get<double>());
    progress.finish(item->name, outcome);
  }
  progress.done();
  return summary;
}

}  // namespace seasim
