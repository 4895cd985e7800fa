#include "cli/farm_command.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "io/atomic_file.h"
#include "jobs/farm_merge.h"
#include "jobs/farm_slurm.h"
#include "jobs/farm_status.h"
#include "jobs/job.h"
#include "jobs/runner.h"
#include "jobs/shard_balance.h"
#include "util/error.h"
#include "util/paths.h"

namespace fs = std::filesystem;

namespace seasim {

namespace {

// The job with -o applied (the farm needs one absolute, shared output folder).
Job loadFarmJob(const std::string& path, const std::string& output_dir) {
  if (!fs::exists(path)) throw RuntimeError("job file not found: " + path);
  Job job = loadJob(fs::absolute(path).lexically_normal().string());
  if (!output_dir.empty()) job.output_dir = fs::absolute(output_dir).lexically_normal().string();
  return job;
}

std::string thisBinary() {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  return ec ? std::string("seasim") : self.string();
}

std::string loadsText(const std::vector<int64_t>& loads, double unit) {
  std::string s;
  char buf[32];
  for (int64_t l : loads) {
    std::snprintf(buf, sizeof buf, "%s%.0f", s.empty() ? "" : " ", double(l) * unit);
    s += buf;
  }
  return s;
}

// The chosen assignment against two others, all under the plan's costs.
void printBalance(const ShardPlan& plan, const Job& job) {
  const int n = plan.shard_count;
  std::vector<int> by_count(plan.costs.size());
  for (size_t i = 0; i < by_count.size(); ++i) by_count[i] = static_cast<int>(i % static_cast<size_t>(n));
  const bool measured = plan.source == CostSource::Measured;
  const double unit = measured ? 1e-3 : 1e-6;  // ms, or millions of estimate units
  const char* unit_name = measured ? "ms of render time (an earlier run's)" : "million units (estimate)";
  const auto show = [&](const char* what, const std::vector<int>& shard_of) {
    const auto loads = shardLoads(plan.costs, shard_of, n);
    std::printf("  %-36s imbalance %.3f  (per shard: %s)\n", what, imbalance(loads), loadsText(loads, unit).c_str());
  };
  std::printf("%zu items in %d shards; cost per shard in %s; imbalance = largest shard / mean:\n", plan.costs.size(), n,
              unit_name);
  show("by item count (index % N)", by_count);
  if (measured) show("balanced by estimate", balanceShards(estimateJobCosts(job), n));
  show(measured ? "balanced by measured timings (used)" : "balanced by estimate (used)", plan.shard_of);
}

}  // namespace

int cmdFarmSlurm(const FarmSlurmCmd& cmd) {
  if (cmd.tasks < 1) throw RuntimeError("--tasks must be at least 1");
  const Job job = loadFarmJob(cmd.job, cmd.output_dir);
  // The shard plan is what every task reads: rewriting it under running shards would move items
  // between them.
  for (int i = 0; i < cmd.tasks; ++i) {
    const std::string lock = manifestPath(job.output_dir, i, cmd.tasks) + ".lock";
    if (fs::exists(lock))
      throw RuntimeError("shard " + std::to_string(i) + "/" + std::to_string(cmd.tasks) +
                         " of this job is running (lock '" + lock +
                         "'); wait for its shards to finish before writing a new farm job for the folder");
  }
  const ShardPlan plan = makeShardPlan(job, cmd.tasks, true);
  saveShardPlan(plan, job.output_dir);
  printBalance(plan, job);

  SlurmFarmOptions o;
  o.tasks = cmd.tasks;
  o.partition = cmd.partition;
  o.time_limit = cmd.time_limit;
  o.retries = cmd.retries;
  o.device = cmd.device;
  o.seasim = thisBinary();
  o.output_dir = job.output_dir;
  const SlurmScripts scripts = makeSlurmScripts(job.file, job, o);
  fs::create_directories(job.output_dir + "/farm/logs");
  writeTextAtomic(scripts.tasks_path, scripts.tasks);
  writeTextAtomic(scripts.merge_path, scripts.merge);
  std::printf("shard plan: %s\n", shardPlanPath(job.output_dir, cmd.tasks).c_str());
  if (!cmd.submit) {
    std::printf("\n==> %s <==\n%s\n==> %s <==\n%s\n", scripts.tasks_path.c_str(), scripts.tasks.c_str(),
                scripts.merge_path.c_str(), scripts.merge.c_str());
    std::printf("to submit (or run again with --submit):\n");
    for (const std::string& c : slurmSubmitCommands(scripts)) std::printf("  %s\n", c.c_str());
    return 0;
  }
  const SlurmSubmission sub = submitSlurm(scripts);
  std::printf("submitted array %s (%d tasks), merge %s (afterok), merge %s (afternotok: reports missing items)\n",
              sub.array_id.c_str(), cmd.tasks, sub.merge_id.c_str(), sub.merge_after_failure_id.c_str());
  std::printf("array_job_id=%s\nmerge_job_id=%s\nmerge_after_failure_job_id=%s\n", sub.array_id.c_str(),
              sub.merge_id.c_str(), sub.merge_after_failure_id.c_str());
  std::printf("progress: seasim farm status %s -o %s\n", job.file.c_str(), job.output_dir.c_str());
  return 0;
}

int cmdFarmMerge(const std::string& job_path, const std::string& output_dir) {
  const Job job = loadFarmJob(job_path, output_dir);
  const MergeResult r = mergeFarmJob(job);
  std::printf("summary: %s\ncontact sheet: %s\n", r.report.c_str(), r.contact_sheet.c_str());
  if (r.missing.empty()) {
    std::printf("merge: all %d items present with intact files\n", r.total);
    return 0;
  }
  std::fprintf(stderr, "seasim: merge failed: %s\n", missingItemsMessage(r).c_str());
  std::fprintf(stderr,
               "run the job's missing shards again with --resume (only these items render), then merge again\n");
  return 1;
}

int cmdFarmStatus(const FarmStatusCmd& cmd) {
  const Job job = loadFarmJob(cmd.job, cmd.output_dir);
  const FarmStatus st = farmStatus(job, cmd.tasks);
  if (cmd.json)
    std::printf("%s\n", farmStatusJson(st).dump(2).c_str());
  else
    std::printf("%s", formatFarmStatus(st).c_str());
  return 0;
}

int cmdFarmLocalCluster(const std::string& action, const std::string& dir) {
  if (action != "start" && action != "stop" && action != "env")
    throw RuntimeError("farm local-cluster: expected start, stop or env, got '" + action + "'");
  std::string script;
  for (const std::string& candidate :
       {installedShareDir().empty() ? std::string() : installedShareDir() + "/tools/slurm_localhost.sh",
        std::string(SEASIM_SOURCE_DIR) + "/tests/farm/slurm_localhost.sh"})
    if (!candidate.empty() && fs::is_regular_file(candidate)) {
      script = candidate;
      break;
    }
  if (script.empty())
    throw RuntimeError("farm local-cluster: slurm_localhost.sh is neither installed (share/seasim/tools) nor in the "
                       "source tree this binary was built from (" SEASIM_SOURCE_DIR "/tests/farm)");
  std::fflush(stdout);
  std::vector<std::string> args = {"bash", script, action, dir};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  ::execv("/bin/bash", argv.data());
  throw RuntimeError("farm local-cluster: cannot run /bin/bash " + script);
}

}  // namespace seasim
