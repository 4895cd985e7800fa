// shard_balance.h — which shard renders which item of a job (`seasim run --shard i/N`).
//
// Shards are balanced by each item's cost, not by item count: a job of small previews and a few big
// second-order frames split by count leaves one machine working long after the others. The cost of
// an item is its measured render time from an earlier run when the output folder's manifests have
// one, otherwise an estimate from the scene (pixels x bands x passes x quality, estimateItemCost).
//
// Every shard of a farm job must compute the SAME assignment, on any machine, at any time, or items
// are rendered twice or never. Estimates are a pure function of the job file; measured timings are
// not (they change while the job runs). So an assignment that uses timings is computed once, by
// `seasim farm slurm` before submitting, and frozen in <output_dir>/farm/shard-plan-<N>.json; each
// shard reads that file. Without the file, each shard computes the estimate-only assignment itself.
// Costs are integers and the greedy assignment breaks every tie by index, so the result does not
// depend on floating-point summation order.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "jobs/job.h"
#include "plan/plan.h"
#include "scene/scene.h"

namespace seasim {

// Estimated cost of rendering `scene` with `plan`, in arbitrary units: pixels x (bands x the sum over
// the plan's passes of the pass's weight x its quality knobs' ratio to their defaults + a per-pixel
// overhead). Only ratios between items matter.
int64_t estimateItemCost(const Scene& scene, const Plan& plan);

// Greedy longest-processing-time assignment: items by decreasing cost (ties: lower index first),
// each to the shard with the least total cost so far (ties: lower shard). Returns the shard of each
// item. Every item gets exactly one shard in [0, shard_count). Its makespan is at most 4/3 of the
// optimum (Graham 1969).
std::vector<int> balanceShards(const std::vector<int64_t>& costs, int shard_count);

// Total cost per shard of an assignment, and its imbalance: the largest shard's cost over the mean
// (1 = perfect; the farm job's wall time is set by the largest shard).
std::vector<int64_t> shardLoads(const std::vector<int64_t>& costs, const std::vector<int>& shard_of, int shard_count);
double imbalance(const std::vector<int64_t>& loads);

// Where each item's cost comes from.
enum class CostSource { Estimate, Measured };

struct ShardPlan {
  int shard_count = 1;
  CostSource source = CostSource::Estimate;
  std::vector<std::string> names;  // the job's items, in job order
  std::vector<int64_t> costs;      // per item (estimate units, or microseconds when measured)
  std::vector<int> shard_of;       // per item
};

// "<output_dir>/farm/shard-plan-<N>.json".
std::string shardPlanPath(const std::string& output_dir, int shard_count);

// The estimate of every item of the job (loads each scene; throws InputError like loadJob).
std::vector<int64_t> estimateJobCosts(const Job& job);

// Costs from the render times ("wall_ms" less "build_ms", the kernel build: a one-off per node) that
// the manifests in `output_dir` record for done items; an item without one gets its estimate scaled by the median
// measured/estimate ratio. Returns false (and leaves `costs` alone) when no item has a timing.
bool measuredJobCosts(const Job& job, const std::vector<int64_t>& estimates, const std::string& output_dir,
                      std::vector<int64_t>& costs);

// A new plan for the job: measured costs when the output folder has timings and `use_timings`,
// otherwise estimates.
ShardPlan makeShardPlan(const Job& job, int shard_count, bool use_timings);

// Writes the plan to shardPlanPath (atomic).
void saveShardPlan(const ShardPlan& plan, const std::string& output_dir);

// The assignment a shard uses: the frozen plan file when there is one (a RuntimeError when it was
// made for other items than the job now has, naming the file), else the estimate-only plan.
ShardPlan loadOrEstimateShardPlan(const Job& job, int shard_count);

}  // namespace seasim
