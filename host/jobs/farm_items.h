// farm_items.h — the state of every item of a job as the shared results folder shows it, read from
// all the manifests there (one per shard, any shard count). Used by `seasim farm merge` (with the
// checksums verified) and `seasim farm status` (without: it is polled while shards write).
#pragma once
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "jobs/job.h"

namespace seasim {

struct ItemState {
  enum class Status {
    Done,     // a manifest records it done with every file the job expects of it (report.json and one
              // per output) in its list, and, when verified, every listed file matches its checksum
    Damaged,  // recorded done, but a file the job expects is not listed, or (verified only) a listed
              // file is missing or no longer matches its checksum
    Failed,   // the last attempt recorded an error
    Missing,  // no manifest mentions it
  };
  std::string name;
  Status status = Status::Missing;
  std::string detail;    // Failed: the error; Damaged: which file and why
  nlohmann::json files;  // Done: relative path -> checksum
  double wall_ms = 0, kernel_ms = 0;
};

const char* statusName(ItemState::Status s);

// One state per item of `job`, in job order. An item done in one manifest and failed in another
// (a later run of another shard count) counts as done when its files are intact.
std::vector<ItemState> readItemStates(const Job& job, const std::string& output_dir, bool verify_checksums);

// The items `--resume` skips: done (readItemStates verified: every file the job expects listed, and
// every listed file on disk with its checksum). Throws like Manifest::load for a manifest it
// cannot use.
std::set<std::string> finishedItems(const Job& job, const std::string& output_dir);

}  // namespace seasim
