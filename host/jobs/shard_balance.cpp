#include "jobs/shard_balance.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <numeric>

#include "io/atomic_file.h"
#include "jobs/manifest.h"
#include "plan/pass_descriptor.h"
#include "scene/scene_parser.h"
#include "util/error.h"

namespace fs = std::filesystem;

namespace seasim {

namespace {

// Per item and pixel, whatever the passes: reading the scene, writing EXR and PNG, the renderer's
// set-up; about 1 µs per pixel on the same VM, i.e. 40 sea_single pixel-bands.
constexpr double kPerPixelOverhead = 40.0;

const char* sourceName(CostSource s) { return s == CostSource::Measured ? "measured" : "estimate"; }

}  // namespace

int64_t estimateItemCost(const Scene& scene, const Plan& plan) {
  double per_band = 0;
  // Each pass's weight at the scene's knobs, from its descriptor (plan/pass_descriptor.h); an entry
  // without one (a plan built by hand) counts as much as sea_single.
  for (const PassPlan& p : plan.passes) {
    const PassDescriptor* d = descriptorOf(p);
    per_band += d && d->cost ? d->cost(scene, p) : 1.0;
  }
  const double cost =
      double(scene.camera.width) * scene.camera.height * (scene.spectral.count * per_band + kPerPixelOverhead);
  // Clamped so that a sum over a million items stays far from int64's limit.
  return std::clamp<int64_t>(std::llround(cost), 1, int64_t(1) << 42);
}

std::vector<int> balanceShards(const std::vector<int64_t>& costs, int shard_count) {
  if (shard_count < 1) throw RuntimeError("the number of shards must be at least 1");
  std::vector<size_t> order(costs.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return costs[a] > costs[b]; });
  std::vector<int64_t> load(static_cast<size_t>(shard_count), 0);
  std::vector<int> shard_of(costs.size(), 0);
  for (size_t item : order) {
    const auto lightest = std::min_element(load.begin(), load.end());  // first of equal loads
    shard_of[item] = static_cast<int>(lightest - load.begin());
    *lightest += costs[item];
  }
  return shard_of;
}

std::vector<int64_t> shardLoads(const std::vector<int64_t>& costs, const std::vector<int>& shard_of, int shard_count) {
  std::vector<int64_t> load(static_cast<size_t>(shard_count), 0);
  for (size_t i = 0; i < costs.size(); ++i) load[static_cast<size_t>(shard_of[i])] += costs[i];
  return load;
}

double imbalance(const std::vector<int64_t>& loads) {
  if (loads.empty()) return 1.0;
  const double total = std::accumulate(loads.begin(), loads.end(), 0.0);
  if (total <= 0) return 1.0;
  return double(*std::max_element(loads.begin(), loads.end())) / (total / double(loads.size()));
}

std::string shardPlanPath(const std::string& output_dir, int shard_count) {
  return output_dir + "/farm/shard-plan-" + std::to_string(shard_count) + ".json";
}

std::vector<int64_t> estimateJobCosts(const Job& job) {
  std::vector<int64_t> costs;
  costs.reserve(job.items.size());
  for (const RenderItem& item : job.items) {
    const Scene scene = loadScene(item.scene_file, item.overrides);
    costs.push_back(estimateItemCost(scene, makePlan(scene)));
  }
  return costs;
}

bool measuredJobCosts(const Job& job, const std::vector<int64_t>& estimates, const std::string& output_dir,
                      std::vector<int64_t>& costs) {
  std::map<std::string, double> wall_ms;
  if (fs::is_directory(output_dir)) {
    for (const auto& entry : fs::directory_iterator(output_dir)) {
      const std::string name = entry.path().filename().string();
      if (name.rfind("manifest", 0) != 0 || entry.path().extension() != ".json") continue;
      const Manifest manifest = Manifest::load(entry.path().string(), "");
      for (const ManifestEntry& e : manifest.entries())
        // Without the kernel build: a one-off per node and kernel cache, not a cost of the item.
        if (e.done && e.wall_ms > 0) wall_ms[e.name] = std::max(1.0, e.wall_ms - e.build_ms);
    }
  }
  std::vector<double> ratios;
  for (size_t i = 0; i < job.items.size(); ++i)
    if (auto it = wall_ms.find(job.items[i].name); it != wall_ms.end())
      ratios.push_back(it->second / double(estimates[i]));
  if (ratios.empty()) return false;
  std::sort(ratios.begin(), ratios.end());
  const double median_ms_per_unit = ratios[ratios.size() / 2];
  costs.clear();
  for (size_t i = 0; i < job.items.size(); ++i) {
    const auto it = wall_ms.find(job.items[i].name);
    const double ms = it != wall_ms.end() ? it->second : median_ms_per_unit * double(estimates[i]);
    costs.push_back(std::max<int64_t>(1, std::llround(ms * 1000.0)));  // microseconds
  }
  return true;
}

ShardPlan makeShardPlan(const Job& job, int shard_count, bool use_timings) {
  ShardPlan plan;
  plan.shard_count = shard_count;
  for (const RenderItem& item : job.items) plan.names.push_back(item.name);
  plan.costs = estimateJobCosts(job);
  if (use_timings) {
    std::vector<int64_t> measured;
    if (measuredJobCosts(job, plan.costs, job.output_dir, measured)) {
      plan.costs = measured;
      plan.source = CostSource::Measured;
    }
  }
  plan.shard_of = balanceShards(plan.costs, shard_count);
  return plan;
}

void saveShardPlan(const ShardPlan& plan, const std::string& output_dir) {
  nlohmann::json items = nlohmann::json::array();
  for (size_t i = 0; i < plan.names.size(); ++i)
    items.push_back({{"name", plan.names[i]}, {"shard", plan.shard_of[i]}, {"cost", plan.costs[i]}});
  const nlohmann::json j = {{"shard_count", plan.shard_count},
                            {"cost_source", sourceName(plan.source)},
                            {"cost_unit", plan.source == CostSource::Measured ? "microseconds of render time"
                                                                              : "pixel x band x pass (estimate)"},
                            {"imbalance", imbalance(shardLoads(plan.costs, plan.shard_of, plan.shard_count))},
                            {"items", items}};
  writeTextAtomic(shardPlanPath(output_dir, plan.shard_count), j.dump(2) + "\n");
}

ShardPlan loadOrEstimateShardPlan(const Job& job, int shard_count) {
  const std::string path = shardPlanPath(job.output_dir, shard_count);
  if (!fs::exists(path)) return makeShardPlan(job, shard_count, false);
  const auto bad = [&](const std::string& why) -> RuntimeError {
    return RuntimeError("the shard plan '" + path + "' " + why +
                        "; it was written by `seasim farm slurm` for this output folder. Delete it (the shards then "
                        "balance by estimate) or write it again with `seasim farm slurm`, before any shard runs");
  };
  nlohmann::json j;
  try {
    std::ifstream in(path);
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw bad(std::string("is not valid JSON (") + e.what() + ")");
  }
  ShardPlan plan;
  plan.shard_count = shard_count;
  std::map<std::string, std::pair<int, int64_t>> by_name;
  try {
    if (j.at("shard_count").get<int>() != shard_count) throw bad("is for another number of shards");
    plan.source = j.at("cost_source").get<std::string>() == "measured" ? CostSource::Measured : CostSource::Estimate;
    for (const auto& item : j.at("items"))
      by_name[item.at("name").get<std::string>()] = {item.at("shard").get<int>(), item.at("cost").get<int64_t>()};
  } catch (const nlohmann::json::exception& e) {
    throw bad(std::string("is not shaped like a shard plan (") + e.what() + ")");
  }
  if (by_name.size() != job.items.size())
    throw bad("lists " + std::to_string(by_name.size()) + " items but the job has " + std::to_string(job.items.size()));
  for (const RenderItem& item : job.items) {
    const auto it = by_name.find(item.name);
    if (it == by_name.end()) throw bad("has no item '" + item.name + "' (the job changed since it was written)");
    if (it->second.first < 0 || it->second.first >= shard_count)
      throw bad("puts '" + item.name + "' in no valid shard");
    plan.names.push_back(item.name);
    plan.shard_of.push_back(it->second.first);
    plan.costs.push_back(it->second.second);
  }
  return plan;
}

}  // namespace seasim
