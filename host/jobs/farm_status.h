// farm_status.h — `seasim farm status JOB`: how far a sharded job has got, from the manifests and
// shard locks in the shared results folder (no scheduler is asked, so it reads the same for shards
// run by Slurm, by hand or on this machine). Per shard: done, running, failed and left items and
// the estimated time remaining.
//
// "running" is the item a shard holding its lock is on: the first of its items in job order that no
// manifest mentions (the runner goes through them in that order), or its first failed item when a
// retry is going through those. The time remaining is the cost of a shard's running and left items
// at the job's measured rate (render time per unit of cost of its done items); unknown until an
// item is done. The job's is its slowest shard's: shards run side by side.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "jobs/job.h"

namespace seasim {

struct ShardStatus {
  int shard = 0;
  std::string state;  // "running", "stale lock", "not started", "stopped", "finished", "failed"
  std::string lock;   // the lock's owner ("pid 123 on host h since T") when locked
  int done = 0, running = 0, failed = 0, left = 0;
  double remaining_s = -1;  // < 0: unknown
};

struct FarmStatus {
  std::string job, output_dir;
  int items = 0, shard_count = 1;
  std::string balance;  // "estimate" or "measured", and where the plan comes from
  std::vector<ShardStatus> shards;
  ShardStatus total;  // sums; remaining_s = the slowest shard's
};

// The shard count a folder was run with: the largest N of its manifests "manifest-<i>of<N>.json" and
// shard plans "farm/shard-plan-<N>.json"; 1 when there is none.
int detectShardCount(const std::string& output_dir);

// shard_count 0: detectShardCount.
FarmStatus farmStatus(const Job& job, int shard_count);

std::string formatFarmStatus(const FarmStatus& status);
nlohmann::json farmStatusJson(const FarmStatus& status);

}  // namespace seasim
