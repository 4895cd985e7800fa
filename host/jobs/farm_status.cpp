#include "jobs/farm_status.h"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>

#include "jobs/farm_items.h"
#include "jobs/runner.h"
#include "jobs/shard_balance.h"
#include "jobs/shard_lock.h"

namespace fs = std::filesystem;

namespace seasim {

namespace {

std::string thisHost() {
  char buf[256] = {};
  if (::gethostname(buf, sizeof buf - 1) != 0) return "";
  return buf;
}

// The shard's lock: "" when there is none, else the owner, and whether the owner is known dead
// (same host, no such process); another host's owner cannot be checked and counts as alive.
struct LockState {
  bool held = false, stale = false;
  std::string owner;
};

LockState readLock(const std::string& path) {
  LockState l;
  if (!fs::exists(path)) return l;
  l.held = true;
  try {
    std::ifstream in(path);
    const nlohmann::json j = nlohmann::json::parse(in);
    const std::string host = j.at("host").get<std::string>();
    const long pid = j.at("pid").get<long>();
    l.owner = "pid " + std::to_string(pid) + " on " + host + " since " + j.at("started").get<std::string>();
    l.stale = host == thisHost() && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH;
  } catch (const std::exception&) {
    l.owner = "unknown (lock file being written or unreadable)";
  }
  return l;
}

std::string formatSeconds(double s) {
  if (s < 0) return "unknown";
  const long t = std::lround(s);
  char buf[32];
  if (t >= 3600)
    std::snprintf(buf, sizeof buf, "%ldh%02ldm", t / 3600, (t / 60) % 60);
  else if (t >= 60)
    std::snprintf(buf, sizeof buf, "%ldm%02lds", t / 60, t % 60);
  else
    std::snprintf(buf, sizeof buf, "%lds", t);
  return buf;
}

}  // namespace

int detectShardCount(const std::string& output_dir) {
  int n = 1;
  const std::regex manifest_re(R"(manifest-\d+of(\d+)\.json)"), plan_re(R"(shard-plan-(\d+)\.json)");
  std::smatch m;
  for (const std::string& dir : {output_dir, output_dir + "/farm"}) {
    if (!fs::is_directory(dir)) continue;
    for (const auto& entry : fs::directory_iterator(dir)) {
      const std::string name = entry.path().filename().string();
      if (std::regex_match(name, m, manifest_re) || std::regex_match(name, m, plan_re))
        n = std::max(n, std::stoi(m[1].str()));
    }
  }
  return n;
}

FarmStatus farmStatus(const Job& job, int shard_count) {
  FarmStatus st;
  st.job = job.name;
  st.output_dir = job.output_dir;
  st.items = static_cast<int>(job.items.size());
  st.shard_count = shard_count > 0 ? shard_count : detectShardCount(job.output_dir);
  const ShardPlan plan = loadOrEstimateShardPlan(job, st.shard_count);
  st.balance = std::string(plan.source == CostSource::Measured ? "measured timings" : "estimated cost") +
               (fs::exists(shardPlanPath(job.output_dir, st.shard_count))
                    ? ", farm/shard-plan-" + std::to_string(st.shard_count) + ".json"
                    : ", computed");
  const std::vector<ItemState> states = readItemStates(job, job.output_dir, false);

  // The job's rate: render time per unit of cost, over the done items with a timing.
  double done_ms = 0, done_cost = 0;
  for (size_t i = 0; i < states.size(); ++i)
    if (states[i].status == ItemState::Status::Done && states[i].wall_ms > 0) {
      done_ms += states[i].wall_ms;
      done_cost += double(plan.costs[i]);
    }
  const double ms_per_cost = done_cost > 0 ? done_ms / done_cost : -1;

  st.total.state = "";
  st.total.remaining_s = 0;
  for (int s = 0; s < st.shard_count; ++s) {
    ShardStatus sh;
    sh.shard = s;
    const LockState lock = readLock(shardLockPath(manifestPath(job.output_dir, s, st.shard_count)));
    sh.lock = lock.owner;
    const bool active = lock.held && !lock.stale;
    int current = -1;  // the item a running shard is on
    if (active) {
      for (size_t i = 0; i < states.size() && current < 0; ++i)
        if (plan.shard_of[i] == s && states[i].status == ItemState::Status::Missing) current = int(i);
      for (size_t i = 0; i < states.size() && current < 0; ++i)
        if (plan.shard_of[i] == s && states[i].status == ItemState::Status::Failed) current = int(i);
    }
    double remaining_cost = 0;
    for (size_t i = 0; i < states.size(); ++i) {
      if (plan.shard_of[i] != s) continue;
      if (int(i) == current) {
        ++sh.running;
        remaining_cost += double(plan.costs[i]);
      } else if (states[i].status == ItemState::Status::Done) {
        ++sh.done;
      } else if (states[i].status == ItemState::Status::Failed) {
        ++sh.failed;
      } else {
        ++sh.left;
        remaining_cost += double(plan.costs[i]);
      }
    }
    if (active)
      sh.state = "running";
    else if (lock.held)
      sh.state = "stale lock";
    else if (sh.left == 0 && sh.failed == 0)
      sh.state = "finished";
    else if (sh.left == 0)
      sh.state = "failed";
    else if (sh.done == 0 && sh.failed == 0)
      sh.state = "not started";
    else
      sh.state = "stopped";
    sh.remaining_s = remaining_cost == 0 ? 0 : (ms_per_cost > 0 ? remaining_cost * ms_per_cost / 1000.0 : -1);
    st.total.done += sh.done;
    st.total.running += sh.running;
    st.total.failed += sh.failed;
    st.total.left += sh.left;
    if (st.total.remaining_s >= 0)
      st.total.remaining_s = sh.remaining_s < 0 ? -1 : std::max(st.total.remaining_s, sh.remaining_s);
    st.shards.push_back(sh);
  }
  return st;
}

std::string formatFarmStatus(const FarmStatus& st) {
  std::string out = "job '" + st.job + "': " + std::to_string(st.items) + " items in " +
                    std::to_string(st.shard_count) + " shard(s), balanced by " + st.balance + "\n" + st.output_dir +
                    "\n";
  char line[256];
  std::snprintf(line, sizeof line, "%-6s %-12s %6s %8s %7s %6s  %s\n", "shard", "state", "done", "running", "failed",
                "left", "remaining");
  out += line;
  for (const ShardStatus& sh : st.shards) {
    std::snprintf(line, sizeof line, "%-6d %-12s %6d %8d %7d %6d  %s\n", sh.shard, sh.state.c_str(), sh.done,
                  sh.running, sh.failed, sh.left, formatSeconds(sh.remaining_s).c_str());
    out += line;
    if (!sh.lock.empty()) out += "         lock: " + sh.lock + "\n";
  }
  std::snprintf(line, sizeof line, "%-6s %-12s %6d %8d %7d %6d  %s\n", "all", "", st.total.done, st.total.running,
                st.total.failed, st.total.left, formatSeconds(st.total.remaining_s).c_str());
  out += line;
  return out;
}

nlohmann::json farmStatusJson(const FarmStatus& st) {
  const auto shardJson = [](const ShardStatus& sh) {
    nlohmann::json j = {{"done", sh.done}, {"running", sh.running}, {"failed", sh.failed},
                        {"left", sh.left}, {"state", sh.state},     {"lock", sh.lock}};
    j["remaining_s"] = sh.remaining_s < 0 ? nlohmann::json(nullptr) : nlohmann::json(sh.remaining_s);
    return j;
  };
  nlohmann::json shards = nlohmann::json::array();
  for (const ShardStatus& sh : st.shards) {
    nlohmann::json j = shardJson(sh);
    j["shard"] = sh.shard;
    shards.push_back(j);
  }
  nlohmann::json total = shardJson(st.total);
  total.erase("state");
  total.erase("lock");
  return {{"job", st.job},         {"output_dir", st.output_dir},
          {"items", st.items},     {"shard_count", st.shard_count},
          {"balance", st.balance}, {"shards", shards},
          {"total", total}};
}

}  // namespace seasim
