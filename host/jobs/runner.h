// runner.h — runs a job file: shards, a lock per shard, resume from the manifest, atomic outputs,
// progress, and per-item isolation (a failing item is recorded and the job goes on).
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "scene/scene_parser.h"

namespace seasim {

struct RunOptions {
  std::string device;      // overrides the job's device when not empty
  int shard_index = 0;     // --shard i/N: this process renders shard i of N, balanced by cost (jobs/shard_balance.h)
  int shard_count = 1;
  bool resume = false;     // skip items the manifest records as finished with intact files
  std::string output_dir;  // replaces the job's output_dir when not empty (-o)
  std::vector<Override> overrides;  // `run --set`: applied to every item after its own overrides
  std::vector<std::string> layers;  // `run --output LAYER`: added to every item's outputs.layers
  // When set, called after each item (handled so far, items of this shard, item name, outcome) in place
  // of the progress lines on stderr (the Python package draws its own bar).
  std::function<void(int handled, int total, const std::string& item, const std::string& outcome)> on_item;
};

struct FailedItem {
  std::string name;
  std::string error;
};

struct RunSummary {
  int rendered = 0;
  int skipped = 0;  // finished earlier (resume)
  int other_shards = 0;
  std::vector<FailedItem> failed;  // recorded in the manifest; `--resume` retries them
  std::string output_dir;
  std::string manifest;
  std::string contact_sheet;  // <output_dir>/index.html (jobs/contact_sheet.h); unsharded runs only
};

// The manifest of a shard: <output_dir>/manifest.json (or manifest-<i>of<N>.json when sharded),
// rewritten atomically after every item, finished or failed (jobs/manifest.h).
std::string manifestPath(const std::string& output_dir, int shard_index, int shard_count);

// Throws InputError for a bad job file (before anything renders), RuntimeError when the shard is
// locked by another run, the output folder or a manifest cannot be used, and DeviceError when no
// device opens. An item that fails (its input files at job start, or its render) does not stop
// the job: it is recorded in the manifest and listed in RunSummary::failed.
RunSummary runJob(const std::string& job_path, const RunOptions& options);

}  // namespace seasim
