#include "jobs/runner.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <set>

#include "device/device.h"
#include "io/atomic_file.h"
#include "io/data_files.h"
#include "jobs/contact_sheet.h"
#include "jobs/farm_items.h"
#include "jobs/item_labels.h"
#include "jobs/job.h"
#include "jobs/job_inputs.h"
#include "jobs/manifest.h"
#include "jobs/progress.h"
#include "jobs/recorded_settings.h"
#include "jobs/render_item.h"
#include "jobs/shard_balance.h"
#include "jobs/shard_lock.h"
#include "plan/plan.h"
#include "quality/auto_quality.h"
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

// The first line of an error, for the progress line (the manifest keeps all of it).
std::string firstLine(const std::string& text) { return text.substr(0, text.find('\n')); }

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

// The renderer of the item before, kept so that items on the same scene file (a sweep, frames) only
// rerun the passes that read a changed key.
struct RendererCache {
  std::unique_ptr<Renderer> renderer;
  const RenderItem* previous = nullptr;
  std::shared_ptr<DataFiles> files = std::make_shared<DataFiles>();  // the whole job's data files
};

// Renders one item and returns its manifest files (relative path -> checksum), kernel ms and kernel
// build ms.
nlohmann::json renderOne(Device& device, RendererCache& cache, const RenderItem& item, const std::string& output_dir,
                         const std::vector<std::string>& layers, double& kernel_ms, double& build_ms) {
  Scene scene = loadScene(item.scene_file, item.overrides);
  addOutputLayers(scene.outputs, layers, "--output");
  scene.files = cache.files;  // read each data file once per job
  if (cache.renderer && cache.previous && cache.previous->scene_file == item.scene_file) {
    cache.renderer->update(scene, changedKeys(cache.previous->overrides, item.overrides));
  } else {
    cache.renderer = std::make_unique<Renderer>(device, scene, shippedPasses());
  }
  // Planned (with its measured choices), before any buffer exists: a render too big for the device
  // fails here, naming its settings. The renderer now holds that scene: the next item starts afresh.
  try {
    checkRenderFitsDevice(device, cache.renderer->scene(), cache.renderer->plan());
  } catch (...) {
    cache.renderer.reset();
    cache.previous = nullptr;
    throw;
  }
  cache.previous = &item;
  ItemOutputs outputs;
  outputs.formats = item.outputs;
  outputs.reference = item.reference;
  const std::string item_dir = output_dir + "/" + item.name;
  const nlohmann::json report = renderItem(device, *cache.renderer, outputs, item_dir);
  nlohmann::json files = nlohmann::json::object();
  for (const auto& f : report["outputs"]) {
    const std::string rel = item.name + "/" + f.get<std::string>();
    files[rel] = fileChecksum(output_dir + "/" + rel);
  }
  files[item.name + "/report.json"] = fileChecksum(item_dir + "/report.json");
  // A dataset item's labels: after the images, before the manifest records the item done, so an
  // interrupted item is rendered again on --resume (jobs/farm_items.cpp expects the file).
  if (!item.sampled.empty()) {
    const std::string rel = item.name + "/" + writeItemLabels(scene, item, item_dir);
    files[rel] = fileChecksum(output_dir + "/" + rel);
  }
  kernel_ms = report["kernel_ms_total"].get<double>();
  build_ms = report["kernel_build_ms"].get<double>();
  return files;
}

// The items of `mine` a resumed run keeps as finished. An item finished with other settings (a
// `run --set` since, or an edited job) is rendered again. The [quality] knobs are left out: "auto"
// ones are recorded as the values they resolved to.
std::set<std::string> finishedAsTheyAreNow(const Job& job, const std::vector<const RenderItem*>& mine) {
  std::set<std::string> finished = finishedItems(job, job.output_dir);
  for (const RenderItem* item : mine) {
    if (!finished.count(item->name)) continue;
    if (!item->sampled.empty() && labelsRecordOtherDraws(*item, job.output_dir + "/" + item->name)) {
      std::fprintf(stderr, "%s: drawn with other values ([sample] changed): rendering it again\n", item->name.c_str());
      finished.erase(item->name);
      continue;
    }
    const nlohmann::json recorded = reportSettings(job.output_dir + "/" + item->name);
    if (recorded.is_null()) continue;  // a report without settings (older seasim): kept as finished
    for (const SettingsDifference& d : settingsDifferences(settingsJson(loadScene(item->scene_file, item->overrides)), recorded))
      if (d.key.rfind("quality.", 0) != 0) {
        std::fprintf(stderr, "%s: rendered with %s = %s, now %s: rendering it again\n", item->name.c_str(),
                     d.key.c_str(), d.reference.c_str(), d.test.c_str());
        finished.erase(item->name);
        break;
      }
  }
  return finished;
}

}  // namespace

RunSummary runJob(const std::string& job_path, const RunOptions& options) {
  if (options.shard_count < 1 || options.shard_index < 0 || options.shard_index >= options.shard_count) {
    throw RuntimeError("--shard must be i/N with 0 <= i < N");
  }
  JobLoadOptions load;
  load.extra_overrides = options.overrides;
  Job job = loadJob(job_path, load);  // validates every item's scene before anything renders
  if (!options.output_dir.empty()) job.output_dir = fs::absolute(options.output_dir).lexically_normal().string();
  RunSummary summary;
  summary.output_dir = job.output_dir;
  std::error_code ec;
  fs::create_directories(job.output_dir, ec);
  if (ec) throw RuntimeError("cannot create the output folder '" + job.output_dir + "': " + ec.message());

  const std::string manifest_file = manifestPath(job.output_dir, options.shard_index, options.shard_count);
  summary.manifest = manifest_file;
  // Held until the job returns; refused while a run of another shard count uses the folder.
  const ShardLock lock(job.output_dir, options.shard_index, options.shard_count);

  // Balanced by cost, identically on every machine (jobs/shard_balance.h).
  const std::vector<int> shard_of = options.shard_count > 1 ? loadOrEstimateShardPlan(job, options.shard_count).shard_of
                                                            : std::vector<int>(job.items.size(), 0);
  std::vector<const RenderItem*> mine;
  for (size_t i = 0; i < job.items.size(); ++i) {
    if (shard_of[i] == options.shard_index) {
      mine.push_back(&job.items[i]);
    } else {
      ++summary.other_shards;
    }
  }

  // Temporary files a killed run of this shard left: its manifest's and its items' (the lock
  // guarantees no live writer owns them).
  int orphans = removeTempFilesFor(manifest_file);
  for (const RenderItem* item : mine) orphans += removeTempFiles(job.output_dir + "/" + item->name);
  if (orphans > 0) std::fprintf(stderr, "removed %d temporary file(s) left by an interrupted run\n", orphans);

  const std::set<std::string> finished = options.resume ? finishedAsTheyAreNow(job, mine) : std::set<std::string>{};
  Manifest manifest = options.resume ? Manifest::load(manifest_file, job.file) : Manifest(job.file);

  // Inputs checkable before rendering (images decode, references match the render size).
  std::vector<RenderItem> to_check;
  for (const RenderItem* item : mine)
    if (!finished.count(item->name)) to_check.push_back(*item);
  const std::map<std::string, std::string> bad_inputs = checkJobInputs(to_check);

  const std::string selector = options.device.empty() ? job.device : options.device;
  std::unique_ptr<Device> device;  // opened on the first item that needs rendering
  RendererCache renderers;
  Progress progress(static_cast<int>(mine.size()), stderrIsTerminal());
  int handled = 0;
  auto finish = [&](const std::string& name, const std::string& outcome) {
    ++handled;
    if (options.on_item) options.on_item(handled, static_cast<int>(mine.size()), name, outcome);
    else progress.finish(name, outcome);
  };
  for (const RenderItem* item : mine) {
    if (!options.on_item) progress.start(item->name);
    if (finished.count(item->name)) {
      ++summary.skipped;
      finish(item->name, "finished earlier (resume)");
      continue;
    }
    std::string error;
    if (auto bad = bad_inputs.find(item->name); bad != bad_inputs.end()) {
      error = bad->second;
    } else {
      if (!device) device = std::make_unique<Device>(chooseDevice(selector));
      char outcome[64] = "";
      bool rendered = false;
      try {
        double kernel_ms = 0, build_ms = 0;
        const auto t0 = std::chrono::steady_clock::now();
        const nlohmann::json files = renderOne(*device, renderers, *item, job.output_dir, options.layers, kernel_ms, build_ms);
        const double wall_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        manifest.recordDone(item->name, files, kernel_ms, wall_ms, build_ms);
        manifest.save(manifest_file);
        ++summary.rendered;
        std::snprintf(outcome, sizeof outcome, "done (%.1f ms kernels)", kernel_ms);
        rendered = true;
      } catch (const std::exception& e) {
        // Any failure of this item (NaN result, I/O, device memory, a bad texture) stays with it;
        // the next item starts from a fresh renderer.
        renderers.renderer.reset();
        renderers.previous = nullptr;
        error = e.what();
      }
      if (rendered) {  // outside the try: a progress callback that throws is not the item's failure
        finish(item->name, outcome);
        continue;
      }
    }
    manifest.recordFailed(item->name, error);
    manifest.save(manifest_file);
    summary.failed.push_back({item->name, error});
    finish(item->name, "FAILED: " + firstLine(error));
  }
  if (!options.on_item) progress.done();
  // A sharded run's items are spread over shards: `farm merge` writes that job's sheet.
  if (options.shard_count == 1) summary.contact_sheet = writeRunContactSheet(job);
  return summary;
}

}  // namespace seasim
