// runner.h — runs a job file: shards, resume from the manifest, atomic outputs, progress.
#pragma once
#include <string>

namespace seasim {

struct RunOptions {
  std::string device;      // overrides the job's device when not empty
  int shard_index = 0;     // --shard i/N: this process renders items with index % N == i
  int shard_count = 1;
  bool resume = false;     // skip items the manifest records as finished with intact files
  std::string output_dir;  // replaces the job's output_dir when not empty (-o)
};

struct RunSummary {
  int rendered = 0;
  int skipped = 0;  // finished earlier (resume)
  int other_shards = 0;
  std::string output_dir;
};

// The manifest of a shard: <output_dir>/manifest.json (or manifest-<i>of<N>.json when sharded),
// rewritten atomically after every finished item with its files and checksums.
std::string manifestPath(const std::string& output_dir, int shard_index, int shard_count);

// Throws InputError for a bad job (before anything renders) and RuntimeError/DeviceError when a
// render fails (items finished before it stay recorded).
RunSummary runJob(const std::string& job_path, const RunOptions& options);

}  // namespace seasim
