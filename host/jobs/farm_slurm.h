// farm_slurm.h — a job on Slurm: an sbatch array of the job's shards and the dependent merge
// (`seasim farm slurm`). docs/farm.md explains the choices; in short:
//   - one array task per shard, each `seasim run JOB --shard $SLURM_ARRAY_TASK_ID/N --resume`, its
//     log in <output_dir>/farm/logs/task-<i>.log (appended across attempts and requeues);
//   - retries: the task retries `seasim run --resume` up to K times in its allocation (a killed or
//     failed run redoes only its unfinished items). Not `scontrol requeue`: Slurm holds a requeued
//     job for 120 s before it may start again. `--requeue` stays on so Slurm requeues a task whose
//     node failed;
//   - the merge (`seasim farm merge`) is submitted twice with --kill-on-invalid-dep=yes: after
//     `afterok` of the array (the normal case), and after `afternotok` (some task failed for good:
//     then `afterok` can never be satisfied and Slurm cancels that one, while this one runs the merge
//     to report the missing items and fail). Exactly one of the two runs.
#pragma once
#include <string>
#include <vector>

#include "jobs/job.h"

namespace seasim {

struct SlurmFarmOptions {
  int tasks = 1;           // N: array tasks = shards
  std::string partition;   // --partition (empty: the cluster's default)
  std::string time_limit;  // --time per task, Slurm's format (empty: the partition's default)
  int retries = 2;         // K: extra attempts of a failed task
  std::string device;      // seasim run --device (empty: the job's)
  std::string seasim;      // absolute path of the seasim binary on the nodes
  std::string output_dir;  // the shared results folder (absolute)
};

struct SlurmScripts {
  std::string tasks;                   // the array script
  std::string merge;                   // the merge script
  std::string tasks_path, merge_path;  // where they are written (<output_dir>/farm/)
};

// The two scripts for `job_file` (absolute). Pure: no file is read or written.
SlurmScripts makeSlurmScripts(const std::string& job_file, const Job& job, const SlurmFarmOptions& options);

// The sbatch command lines that submit them, with $ARRAY standing for the array's job id.
std::vector<std::string> slurmSubmitCommands(const SlurmScripts& scripts);

struct SlurmSubmission {
  std::string array_id, merge_id, merge_after_failure_id;
};

// Submits the array, then the two dependent merges, with `sbatch --parsable`. Throws RuntimeError
// with sbatch's output when a submission fails (cancelling what was already submitted).
SlurmSubmission submitSlurm(const SlurmScripts& scripts);

// Quotes a word for a POSIX shell ('...' with ' escaped).
std::string shellQuote(const std::string& word);

// What to tell the user about a failed sbatch's output: when it found no Slurm configuration
// ("Could not establish a configuration source": no slurm.conf, SLURM_CONF unset, no configless
// controller), how to start a private single-node cluster with `seasim farm local-cluster` and point
// the clients at it; "" for any other failure.
std::string slurmConfigHint(const std::string& sbatch_output);

}  // namespace seasim
