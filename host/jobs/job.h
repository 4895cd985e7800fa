// job.h — job files: a list of renders (and sweeps expanded into renders) for the farm.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "scene/scene_parser.h"

namespace seasim {

struct RenderItem {
  std::string name;                  // unique within the job; names the output files
  std::string scene_file;            // absolute
  std::vector<Override> overrides;   // applied in order (job-level first, then the item's)
  std::vector<std::string> outputs;  // of "exr", "png", "spectral_exr", "npy"; default exr+png
  std::string reference;             // optional reference EXR (absolute) to report error against
  SourceLoc reference_loc;           // where `reference` was written
  std::string reference_key;         // its dotted key ("render[0].reference"), for messages
  SourceLoc loc;                     // the [[render]] / [[sweep]] / [sample] table
  // [sample] items (jobs/job_sampling.h): the keys drawn for this item, also the last of
  // `overrides`; the job's seed and the item's draw index. The runner writes labels.json for them.
  std::vector<Override> sampled;
  std::uint64_t sample_seed = 0;
  std::uint64_t sample_index = 0;
};

struct Job {
  std::string file;        // absolute
  std::string name;
  std::string output_dir;  // absolute; default <repo-or-cwd>/results/<name>
  std::string device;      // default "" = automatic choice
  std::vector<RenderItem> items;
};

struct JobLoadOptions {
  std::vector<Override> extra_overrides;  // appended to every item's overrides (`run --set`), so they win
  std::vector<std::string> ignored_keys;  // job-file keys read as absent (`validate` finding every error)
  bool check_scenes = true;               // load every item's scene with its overrides
};

// Parses and validates a job file, and validates every scene it names with its overrides, so a
// bad job fails before anything renders. Throws InputError.
Job loadJob(const std::string& path, const JobLoadOptions& options = {});
Job parseJob(const std::string& toml_text, const std::string& path, const JobLoadOptions& options = {});

// True when the file looks like a job (has [job], [[render]], [[sweep]] or [sample]), for `seasim validate`.
bool isJobFile(const std::string& path);

}  // namespace seasim
