#include "jobs/farm_slurm.h"

#include <sys/wait.h>

#include <cstdio>
#include <sstream>

#include "util/error.h"

namespace seasim {

namespace {

struct CommandResult {
  int code = -1;
  std::string output;  // stdout and stderr
};

CommandResult runShell(const std::string& command) {
  CommandResult r;
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return r;
  char buf[4096];
  while (size_t n = std::fread(buf, 1, sizeof buf, pipe)) r.output.append(buf, n);
  const int status = ::pclose(pipe);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

std::string trim(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' ')) s.pop_back();
  return s;
}

// `sbatch --parsable` prints "ID" or "ID;CLUSTER".
std::string submit(const std::string& command, const std::string& what) {
  const CommandResult r = runShell(command);
  const std::string out = trim(r.output);
  const std::string id = out.substr(0, out.find(';'));
  if (r.code != 0 || id.empty() || id.find_first_not_of("0123456789") != std::string::npos)
    throw RuntimeError("submitting the " + what + " failed (exit code " + std::to_string(r.code) + "): " + command +
                       "\n" + out + slurmConfigHint(out));
  return id;
}

std::string slurmName(const std::string& name) { return "seasim-" + name; }

}  // namespace

std::string slurmConfigHint(const std::string& out) {
  if (out.find("Could not establish a configuration source") == std::string::npos &&
      out.find("slurm.conf") == std::string::npos)
    return "";
  return "\nhint: sbatch found no Slurm cluster configuration (no /etc/slurm/slurm.conf and SLURM_CONF unset). To "
         "try the farm on this machine, start a private single-node cluster in a folder (needs root: slurmd starts "
         "the jobs as their users):\n"
         "  sudo seasim farm local-cluster start /tmp/seasim-slurm\n"
         "  export SLURM_CONF=/tmp/seasim-slurm/slurm.conf\n"
         "then submit again; stop it with `sudo seasim farm local-cluster stop /tmp/seasim-slurm` (docs/farm.md).";
}

std::string shellQuote(const std::string& word) {
  std::string q = "'";
  for (char c : word) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

SlurmScripts makeSlurmScripts(const std::string& job_file, const Job& job, const SlurmFarmOptions& o) {
  if (o.tasks < 1) throw RuntimeError("--tasks must be at least 1");
  if (o.retries < 0) throw RuntimeError("--retries must be 0 or more");
  const std::string farm = o.output_dir + "/farm";
  const std::string n = std::to_string(o.tasks);
  const std::string attempts = std::to_string(o.retries + 1);
  std::string options;
  if (!o.partition.empty()) options += "#SBATCH --partition=" + o.partition + "\n";

  std::ostringstream t;
  t << "#!/bin/bash\n"
    << "# The " << n << " shards of seasim job '" << job.name << "' (" << job_file << ") as a Slurm array.\n"
    << "# Written by `seasim farm slurm`; docs/farm.md. Each task renders its shard (balanced by cost:\n"
    << "# " << o.output_dir << "/farm/shard-plan-" << n << ".json) and retries a failed or killed run up to "
    << o.retries << " times\n# with --resume, which redoes only the shard's unfinished items.\n"
    << "#SBATCH --job-name=" << slurmName(job.name) << "\n"
    << "#SBATCH --array=0-" << o.tasks - 1 << "\n"
    << "#SBATCH --output=" << farm << "/logs/task-%a.log\n"
    << "#SBATCH --open-mode=append\n"
    << "#SBATCH --requeue\n"
    << options;
  if (!o.time_limit.empty()) t << "#SBATCH --time=" << o.time_limit << "\n";
  t << "set -u\n"
    << "shard=\"${SLURM_ARRAY_TASK_ID:?this script is a Slurm array task: submit it with sbatch}/" << n << "\"\n"
    << "# Slurm requeued this task (its node failed): the earlier run is gone, so its shard lock is stale\n"
    << "# even when it was taken on another host (seasim only takes over stale locks of its own host).\n"
    << "if [ \"${SLURM_RESTART_COUNT:-0}\" -gt 0 ]; then\n"
    << "  rm -fv " << shellQuote(o.output_dir) << "/manifest-${SLURM_ARRAY_TASK_ID}of" << n << ".json.lock\n"
    << "fi\n"
    << "rc=1\n"
    << "for attempt in $(seq 1 " << attempts << "); do\n"
    << "  echo \"seasim farm: shard $shard attempt $attempt of " << attempts
    << ", Slurm job ${SLURM_ARRAY_JOB_ID}_${SLURM_ARRAY_TASK_ID} (restart ${SLURM_RESTART_COUNT:-0}) on $(hostname) "
       "at $(date -u +%Y-%m-%dT%H:%M:%SZ)\"\n"
    << "  " << shellQuote(o.seasim) << " run " << shellQuote(job_file) << " --shard \"$shard\" --resume -o "
    << shellQuote(o.output_dir) << (o.device.empty() ? "" : " --device " + shellQuote(o.device)) << "\n"
    << "  rc=$?\n"
    << "  if [ \"$rc\" -eq 0 ]; then exit 0; fi\n"
    << "  echo \"seasim farm: shard $shard attempt $attempt failed with exit code $rc\"\n"
    << "done\n"
    << "echo \"seasim farm: shard $shard failed " << attempts
    << " times; giving up (the merge names its missing items)\"\n"
    << "exit \"$rc\"\n";

  std::ostringstream m;
  m << "#!/bin/bash\n"
    << "# Merge of seasim job '" << job.name << "' after its array (written by `seasim farm slurm`; docs/farm.md):\n"
    << "# checks every item is present with its checksum, writes farm/report.json and farm/contact_sheet.html,\n"
    << "# and fails naming the missing items otherwise.\n"
    << "#SBATCH --job-name=" << slurmName(job.name) << "-merge\n"
    << "#SBATCH --output=" << farm << "/logs/merge-%j.log\n"
    << options << "exec " << shellQuote(o.seasim) << " farm merge " << shellQuote(job_file) << " -o "
    << shellQuote(o.output_dir) << "\n";
  return {t.str(), m.str(), farm + "/tasks.sbatch", farm + "/merge.sbatch"};
}

std::vector<std::string> slurmSubmitCommands(const SlurmScripts& s) {
  return {"ARRAY=$(sbatch --parsable " + shellQuote(s.tasks_path) + ")",
          "sbatch --parsable --dependency=afterok:$ARRAY --kill-on-invalid-dep=yes " + shellQuote(s.merge_path),
          "sbatch --parsable --dependency=afternotok:$ARRAY --kill-on-invalid-dep=yes " + shellQuote(s.merge_path)};
}

SlurmSubmission submitSlurm(const SlurmScripts& s) {
  SlurmSubmission sub;
  sub.array_id = submit("sbatch --parsable " + shellQuote(s.tasks_path), "array of shards");
  try {
    sub.merge_id = submit("sbatch --parsable --dependency=afterok:" + sub.array_id + " --kill-on-invalid-dep=yes " +
                              shellQuote(s.merge_path),
                          "merge job");
    sub.merge_after_failure_id = submit("sbatch --parsable --dependency=afternotok:" + sub.array_id +
                                            " --kill-on-invalid-dep=yes " + shellQuote(s.merge_path),
                                        "merge job for a failed array");
  } catch (...) {
    // Without its merge the array's results would never be checked: take it back.
    runShell("scancel " + sub.array_id + (sub.merge_id.empty() ? "" : " " + sub.merge_id));
    throw;
  }
  return sub;
}

}  // namespace seasim
