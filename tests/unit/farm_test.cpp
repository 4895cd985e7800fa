// farm_test.cpp — the farm's pieces without a scheduler: cost estimates and balanced shards (every
// item in exactly one shard, the same answer every time, better than by count), the frozen shard
// plan, the Slurm scripts (and the task script's retry loop, run by bash against a fake seasim),
// the merge's checks (missing, failed and damaged items named; complete summary and contact sheet)
// and `farm status` counting from manifests and shard locks.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numeric>
#include <set>
#include <sstream>

#include "jobs/contact_sheet.h"
#include "jobs/farm_merge.h"
#include "jobs/farm_slurm.h"
#include "jobs/farm_status.h"
#include "jobs/job.h"
#include "jobs/manifest.h"
#include "jobs/runner.h"
#include "jobs/shard_balance.h"
#include "jobs/shard_lock.h"
#include "plan/plan.h"
#include "scene/scene_parser.h"
#include "util/error.h"
#include "util/hash.h"

namespace fs = std::filesystem;
using namespace seasim;

namespace {

const std::string kRepo = SEASIM_SOURCE_DIR;

class Farm : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("seasim_farm_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
            std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // A job of items on the flat sea at the given widths (height 36), written and parsed.
  Job job(const std::vector<int>& widths) {
    std::ostringstream t;
    t << "[job]\nname = \"f\"\noutput_dir = \"out\"\n";
    for (size_t i = 0; i < widths.size(); ++i)
      t << "[[render]]\nname = \"item" << i << "\"\nscene = \"" << kRepo << "/scenes/flat_sea.toml\"\n"
        << "overrides = { \"camera.width\" = " << widths[i] << ", \"camera.height\" = 36 }\n";
    const std::string path = (dir_ / "job.toml").string();
    std::ofstream(path) << t.str();
    return loadJob(path);
  }
  // Writes an item's files (every one the job expects: its outputs exr and png, and report.json)
  // and returns its manifest "files" object.
  nlohmann::json writeItem(const Job& j, const std::string& name) {
    fs::create_directories(j.output_dir + "/" + name);
    nlohmann::json files = nlohmann::json::object();
    for (const char* f : {"image.exr", "image.png", "report.json"}) {
      const std::string rel = name + "/" + f;
      std::ofstream(j.output_dir + "/" + rel)
          << (std::string(f) == "report.json" ? R"({"device": {"label": "pocl:0 test"}, "pass_ms": {"a": 1}})"
                                              : "png of " + name);
      files[rel] = fileChecksum(j.output_dir + "/" + rel);
    }
    return files;
  }
  fs::path dir_;
};

// ------------------------------------------------------------------------------------------------
// Balanced shards

TEST(ShardBalance, EveryItemIsInExactlyOneShardAndTheAnswerIsDeterministic) {
  std::vector<int64_t> costs;
  uint64_t x = 12345;
  for (int i = 0; i < 101; ++i) {
    x = x * 6364136223846793005ull + 1442695040888963407ull;
    costs.push_back(static_cast<int64_t>(1 + (x >> 33) % 1000));
  }
  costs[7] = costs[8] = costs[9] = 500;  // ties
  for (int n : {1, 2, 3, 4, 7, 101, 150}) {
    const std::vector<int> a = balanceShards(costs, n);
    ASSERT_EQ(a.size(), costs.size());
    for (int s : a) {
      EXPECT_GE(s, 0);
      EXPECT_LT(s, n);
    }
    EXPECT_EQ(a, balanceShards(costs, n)) << "same input, same shards";
    // Loads sum to the total: each item counted once.
    const auto loads = shardLoads(costs, a, n);
    EXPECT_EQ(std::accumulate(loads.begin(), loads.end(), int64_t{0}),
              std::accumulate(costs.begin(), costs.end(), int64_t{0}));
  }
}

TEST(ShardBalance, GreedyByCostBeatsSplittingByCount) {
  // One big item every fourth: by count (index % 4) all big ones land in shard 0.
  std::vector<int64_t> costs;
  for (int i = 0; i < 16; ++i) costs.push_back(i % 4 == 0 ? 100 : 10);
  std::vector<int> by_count(costs.size());
  for (size_t i = 0; i < costs.size(); ++i) by_count[i] = static_cast<int>(i % 4);
  EXPECT_NEAR(imbalance(shardLoads(costs, by_count, 4)), 400.0 / 130.0, 1e-12);
  EXPECT_NEAR(imbalance(shardLoads(costs, balanceShards(costs, 4), 4)), 1.0, 1e-12);
  // The textbook case: LPT on {3,3,2,2,2} over 2 shards gives 7/5 (optimum 6/6).
  const auto lpt = balanceShards({3, 3, 2, 2, 2}, 2);
  EXPECT_EQ(lpt, (std::vector<int>{0, 1, 0, 1, 0}));
  EXPECT_THROW(balanceShards({1}, 0), RuntimeError);
}

TEST_F(Farm, EstimatedCostScalesWithPixelsBandsAndPasses) {
  const Job j = job({64, 128});
  const auto costs = estimateJobCosts(j);
  EXPECT_NEAR(double(costs[1]), 2.0 * double(costs[0]), 1.0);  // twice the pixels (rounded to integers)
  // Linear in the bands beyond a per-pixel overhead: equal steps of bands cost equal steps.
  const auto costWithBands = [](int bands) {
    const Scene s = loadScene(kRepo + "/scenes/flat_sea.toml", {Override{"spectral.count", std::to_string(bands), {}}});
    return estimateItemCost(s, makePlan(s));
  };
  EXPECT_GT(costWithBands(16), costWithBands(8));
  EXPECT_NEAR(double(costWithBands(24) - costWithBands(16)), double(costWithBands(16) - costWithBands(8)), 2.0);
  const Scene base = loadScene(kRepo + "/scenes/flat_sea.toml", {Override{"spectral.count", "8", {}}});
  const Scene second = loadScene(kRepo + "/scenes/flat_sea.toml",
                                 {Override{"spectral.count", "8", {}}, Override{"sea.model", "\"paper\"", {}}, Override{"sea.second_order", "true", {}}});
  ASSERT_TRUE(makePlan(second).hasPass("sea_second"));
  EXPECT_GT(estimateItemCost(second, makePlan(second)), estimateItemCost(base, makePlan(base)));
  // More second-order depth planes cost more.
  const Scene finer = loadScene(kRepo + "/scenes/flat_sea.toml",
                                {Override{"spectral.count", "8", {}}, Override{"sea.model", "\"paper\"", {}}, Override{"sea.second_order", "true", {}},
                                 Override{"quality.sea_nz", "24", {}}});
  EXPECT_GT(estimateItemCost(finer, makePlan(finer)), estimateItemCost(second, makePlan(second)));
}

// Under water the estimate follows the model and the layers kd_multiple computes: the discrete-ordinates model
// costs about 4x the thesis's per pixel-band in kd_multiple, and the split and veiling layers add a
// second and third evaluation; geometry layers alone barely change it.
TEST_F(Farm, EstimatedUnderwaterCostFollowsModelAndLayers) {
  const auto cost = [](const std::string& model, const std::string& layers) {
    const Scene s = loadScene(kRepo + "/scenes/seabed.toml",
                              {Override{"underwater.model", "\"" + model + "\"", {}},
                               Override{"underwater.single_scattering", "false", {}}, Override{"outputs.layers", layers, {}}});
    return double(estimateItemCost(s, makePlan(s)));
  };
  EXPECT_GT(cost("discrete_ordinates", "[]"), 2.0 * cost("thesis", "[]"));
  EXPECT_GT(cost("thesis", R"(["direct"])"), 1.1 * cost("thesis", "[]"));
  EXPECT_GT(cost("thesis", R"(["beta_b"])"), cost("thesis", R"(["direct"])"));
  EXPECT_GT(cost("discrete_ordinates", R"(["beta_b"])"), cost("discrete_ordinates", "[]"));
  EXPECT_LT(cost("thesis", R"(["range"])"), 1.05 * cost("thesis", "[]"));
}

// Shafts: the cost follows the lamps and the integrator the planner picks (the measured weights in
// host/jobs/shard_balance.cpp): stage's five lamps cost more than spot_sphere's one at the same size,
// and the paper's planes more than twice the intervals.
TEST_F(Farm, EstimatedShaftsCostFollowsLampsAndMethod) {
  const auto cost = [](const std::string& scene, const std::string& method) {
    const Scene s = loadScene(kRepo + "/scenes/" + scene,
                              {Override{"quality.shafts_method", "\"" + method + "\"", {}}});
    return double(estimateItemCost(s, makePlan(s)));
  };
  EXPECT_GT(cost("stage.toml", "intervals"), 2.0 * cost("spot_sphere.toml", "intervals"));
  EXPECT_GT(cost("stage.toml", "planes"), 1.8 * cost("stage.toml", "intervals"));
  EXPECT_GT(cost("spot_sphere.toml", "planes"), 1.5 * cost("spot_sphere.toml", "intervals"));
  // The march at its default 20 steps costs about the intervals; twice the steps, twice the cost.
  EXPECT_GT(cost("stage.toml", "march"), 0.5 * cost("stage.toml", "intervals"));
  const Scene fine = loadScene(kRepo + "/scenes/stage.toml", {Override{"quality.shafts_method", "\"march\"", {}},
                                                             Override{"quality.shafts_march_steps", "40", {}}});
  EXPECT_GT(double(estimateItemCost(fine, makePlan(fine))), 1.5 * cost("stage.toml", "march"));
}

TEST_F(Farm, MeasuredCostsLeaveOutKernelBuilds) {
  const Job j = job({64, 64});
  Manifest m(j.file);
  m.recordDone("item0", nlohmann::json::object(), 1.0, 9000.0, 8000.0);  // first item: built the kernels
  m.recordDone("item1", nlohmann::json::object(), 1.0, 1000.0, 0.0);
  fs::create_directories(j.output_dir);
  m.save(manifestPath(j.output_dir, 0, 1));
  std::vector<int64_t> costs;
  ASSERT_TRUE(measuredJobCosts(j, estimateJobCosts(j), j.output_dir, costs));
  EXPECT_EQ(costs, (std::vector<int64_t>{1000000, 1000000}));
}

TEST_F(Farm, ShardPlanFileIsWhatShardsUseAndMustMatchTheJob) {
  const Job j = job({64, 64, 64, 256});
  // No file: the estimate, computed the same way by every shard.
  const ShardPlan estimated = loadOrEstimateShardPlan(j, 2);
  EXPECT_EQ(estimated.source, CostSource::Estimate);
  EXPECT_EQ(estimated.shard_of, (std::vector<int>{1, 1, 1, 0}));  // the big one alone
  // Timings in a manifest: item0 was slow. The plan uses them, scaled estimates for the others.
  Manifest m(j.file);
  m.recordDone("item0", nlohmann::json::object(), 1.0, 5000.0);
  m.recordDone("item3", nlohmann::json::object(), 1.0, 1000.0);
  fs::create_directories(j.output_dir);
  m.save(manifestPath(j.output_dir, 0, 2));
  const ShardPlan measured = makeShardPlan(j, 2, true);
  EXPECT_EQ(measured.source, CostSource::Measured);
  EXPECT_EQ(measured.costs[0], 5000000);  // microseconds
  EXPECT_EQ(measured.costs[3], 1000000);
  saveShardPlan(measured, j.output_dir);
  const ShardPlan loaded = loadOrEstimateShardPlan(j, 2);
  EXPECT_EQ(loaded.shard_of, measured.shard_of);
  EXPECT_EQ(loaded.source, CostSource::Measured);
  EXPECT_EQ(loaded.shard_of[0], 0);  // the slow item alone
  EXPECT_EQ(loaded.shard_of[1], 1);
  // A plan for other items (the job changed) is an error naming the file, never a silent misassignment.
  const Job other = job({64, 64, 64});
  try {
    loadOrEstimateShardPlan(other, 2);
    FAIL() << "expected an error";
  } catch (const RuntimeError& e) {
    EXPECT_NE(std::string(e.what()).find("shard-plan-2.json"), std::string::npos) << e.what();
  }
}

// ------------------------------------------------------------------------------------------------
// Slurm scripts

TEST_F(Farm, SlurmScriptsRunEveryShardWithResumeLogsRetriesAndDependentMerge) {
  const Job j = job({64});
  SlurmFarmOptions o;
  o.tasks = 4;
  o.retries = 3;
  o.partition = "render";
  o.time_limit = "1:00:00";
  o.seasim = "/opt/seasim bin/seasim";
  o.output_dir = "/shared/out";
  const SlurmScripts s = makeSlurmScripts("/jobs/it's.toml", j, o);
  for (const char* line :
       {"#SBATCH --array=0-3\n", "#SBATCH --output=/shared/out/farm/logs/task-%a.log\n", "#SBATCH --open-mode=append\n",
        "#SBATCH --requeue\n", "#SBATCH --partition=render\n", "#SBATCH --time=1:00:00\n",
        "shard=\"${SLURM_ARRAY_TASK_ID:?", "}/4\"\n",
        "'/opt/seasim bin/seasim' run '/jobs/it'\\''s.toml' --shard \"$shard\" --resume -o '/shared/out'",
        "for attempt in $(seq 1 4)"})
    EXPECT_NE(s.tasks.find(line), std::string::npos) << line << "\n" << s.tasks;
  EXPECT_NE(s.merge.find("exec '/opt/seasim bin/seasim' farm merge '/jobs/it'\\''s.toml' -o '/shared/out'"),
            std::string::npos)
      << s.merge;
  EXPECT_NE(s.merge.find("#SBATCH --output=/shared/out/farm/logs/merge-%j.log"), std::string::npos) << s.merge;
  EXPECT_EQ(s.merge.find("--array"), std::string::npos);
  const auto cmds = slurmSubmitCommands(s);
  ASSERT_EQ(cmds.size(), 3u);
  EXPECT_NE(cmds[1].find("--dependency=afterok:$ARRAY --kill-on-invalid-dep=yes"), std::string::npos);
  EXPECT_NE(cmds[2].find("--dependency=afternotok:$ARRAY --kill-on-invalid-dep=yes"), std::string::npos);
  o.partition.clear();
  o.time_limit.clear();
  const SlurmScripts plain = makeSlurmScripts("/j.toml", j, o);
  EXPECT_EQ(plain.tasks.find("--partition"), std::string::npos);
  EXPECT_EQ(plain.tasks.find("--time"), std::string::npos);
  o.tasks = 0;
  EXPECT_THROW(makeSlurmScripts("/j.toml", j, o), RuntimeError);
}

// The task script itself, run by bash as Slurm would (its environment), against a fake seasim that
// fails a given number of times: it retries with --resume up to K times, then gives up.
TEST_F(Farm, TaskScriptRetriesUpToKTimesThenFails) {
  const Job j = job({64});
  const fs::path fake = dir_ / "fake_seasim";
  std::ofstream(fake) << "#!/bin/sh\necho \"$@\" >> " << (dir_ / "calls").string() << "\n"
                      << "n=$(wc -l < " << (dir_ / "calls").string() << ")\n"
                      << "[ \"$n\" -gt \"$FAIL_TIMES\" ] && exit 0\nkill -KILL $$\n";
  fs::permissions(fake, fs::perms::owner_all);
  SlurmFarmOptions o;
  o.tasks = 4;
  o.retries = 2;
  o.seasim = fake.string();
  o.output_dir = (dir_ / "out").string();
  const SlurmScripts s = makeSlurmScripts("/j.toml", j, o);
  std::ofstream(dir_ / "task.sh") << s.tasks;
  const auto runTask = [&](int fail_times) {
    fs::remove(dir_ / "calls");
    const std::string cmd = "cd " + dir_.string() + " && FAIL_TIMES=" + std::to_string(fail_times) +
                            " SLURM_ARRAY_TASK_ID=2 SLURM_ARRAY_JOB_ID=7 bash task.sh > task.log 2>&1";
    const int status = std::system(cmd.c_str());
    std::ifstream in(dir_ / "calls");
    std::vector<std::string> calls;
    for (std::string l; std::getline(in, l);) calls.push_back(l);
    return std::make_pair(WEXITSTATUS(status), calls);
  };
  auto [code, calls] = runTask(2);  // killed twice, the third attempt succeeds
  EXPECT_EQ(code, 0);
  ASSERT_EQ(calls.size(), 3u);
  EXPECT_EQ(calls[0], "run /j.toml --shard 2/4 --resume -o " + o.output_dir);
  std::tie(code, calls) = runTask(5);  // fails for good: 1 + K attempts, then the failing exit code
  EXPECT_EQ(calls.size(), 3u);
  EXPECT_EQ(code, 137);
  std::ifstream log(dir_ / "task.log");
  const std::string text((std::istreambuf_iterator<char>(log)), {});
  EXPECT_NE(text.find("shard 2/4 failed 3 times; giving up"), std::string::npos) << text;
}

TEST(FarmSlurm, ShellQuoteSurvivesQuotesAndSpaces) {
  EXPECT_EQ(shellQuote("a b"), "'a b'");
  EXPECT_EQ(shellQuote("it's"), "'it'\\''s'");
}

// ------------------------------------------------------------------------------------------------
// Merge

TEST_F(Farm, MergeNamesMissingFailedAndDamagedItemsAndWritesTheSummaryAnyway) {
  const Job j = job({64, 64, 64, 64});
  Manifest m0(j.file), m1(j.file);
  m0.recordDone("item0", writeItem(j, "item0"), 2.0, 20.0);
  m0.recordFailed("item2", "the render ran out of device memory\nsecond line");
  m1.recordDone("item1", writeItem(j, "item1"), 3.0, 30.0);
  fs::create_directories(j.output_dir);
  m0.save(manifestPath(j.output_dir, 0, 2));
  m1.save(manifestPath(j.output_dir, 1, 2));
  // item1's PNG was overwritten after it was recorded (a half-written copy, a bad disk).
  std::ofstream(j.output_dir + "/item1/image.png") << "half";

  MergeResult r = mergeFarmJob(j);
  EXPECT_EQ(r.total, 4);
  ASSERT_EQ(r.missing.size(), 3u);
  const std::string msg = missingItemsMessage(r);
  EXPECT_NE(msg.find("3 of 4 items are missing"), std::string::npos) << msg;
  EXPECT_NE(msg.find("item1 (damaged: 'item1/image.png' does not match its checksum)"), std::string::npos) << msg;
  EXPECT_NE(msg.find("item2 (failed: the render ran out of device memory)"), std::string::npos) << msg;
  EXPECT_NE(msg.find("item3 (not rendered)"), std::string::npos) << msg;
  std::ifstream in(r.report);
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_FALSE(report["complete"].get<bool>());
  EXPECT_EQ(report["items_done"], 1);
  EXPECT_EQ(report["missing"], (nlohmann::json{"item1", "item2", "item3"}));
  EXPECT_EQ(report["items"][0]["status"], "done");
  EXPECT_EQ(report["items"][0]["wall_ms"], 20.0);
  EXPECT_EQ(report["items"][0]["device"]["label"], "pocl:0 test");
  EXPECT_EQ(report["items"][2]["error"], "the render ran out of device memory\nsecond line");

  // Repaired: every item done and intact -> complete, contact sheet shows every PNG.
  Manifest m2(j.file);
  for (const char* name : {"item1", "item2", "item3"}) m2.recordDone(name, writeItem(j, name), 1.0, 10.0);
  m2.save(manifestPath(j.output_dir, 0, 1));
  r = mergeFarmJob(j);
  EXPECT_TRUE(r.missing.empty()) << missingItemsMessage(r);
  std::ifstream in2(r.report);
  const nlohmann::json done = nlohmann::json::parse(in2);
  EXPECT_TRUE(done["complete"].get<bool>());
  // item1 is done and intact in two manifests: the first by name (manifest-1of2.json, 30 ms) counts.
  EXPECT_EQ(done["wall_ms_total"], 20.0 + 30.0 + 10.0 + 10.0);
  EXPECT_EQ(done["devices"], (nlohmann::json{"pocl:0 test"}));
  std::ifstream sheet(r.contact_sheet);
  const std::string html((std::istreambuf_iterator<char>(sheet)), {});
  for (int i = 0; i < 4; ++i)
    EXPECT_NE(html.find("<img src=\"../item" + std::to_string(i) + "/image.png\""), std::string::npos) << html;
}

TEST_F(Farm, RunContactSheetShowsTheItemsOnDiskAndNamesTheFailedOnes) {
  const Job j = job({64, 64, 64});
  fs::create_directories(j.output_dir);
  Manifest m(j.file);
  m.recordDone("item0", writeItem(j, "item0"), 1.0, 10.0);
  m.recordFailed("item1", "no such camera file");
  m.recordDone("item2", writeItem(j, "item2"), 1.0, 10.0);
  m.save(manifestPath(j.output_dir, 0, 1));
  std::ofstream(j.output_dir + "/item2/image.png") << "changed after the run";  // no longer its checksum

  const std::string path = writeRunContactSheet(j);
  EXPECT_EQ(path, j.output_dir + "/index.html");
  std::ifstream in(path);
  const std::string html((std::istreambuf_iterator<char>(in)), {});
  EXPECT_NE(html.find("<img src=\"item0/image.png\""), std::string::npos) << html;
  EXPECT_EQ(html.find("item1/image.png"), std::string::npos) << html;
  EXPECT_NE(html.find("item1 <span class=\"bad\">failed</span>"), std::string::npos) << html;
  EXPECT_EQ(html.find("item2/image.png"), std::string::npos) << html;  // damaged: not shown as done
  EXPECT_NE(html.find("incomplete"), std::string::npos) << html;
}

// ------------------------------------------------------------------------------------------------
// Status

TEST_F(Farm, StatusCountsDoneRunningFailedAndLeftPerShard) {
  const Job j = job({64, 64, 64, 64, 64, 64});  // equal costs: shard 0 = items 0,2,4; shard 1 = 1,3,5
  const ShardPlan plan = loadOrEstimateShardPlan(j, 2);
  ASSERT_EQ(plan.shard_of, (std::vector<int>{0, 1, 0, 1, 0, 1}));
  fs::create_directories(j.output_dir);
  Manifest m0(j.file), m1(j.file);
  m0.recordDone("item0", writeItem(j, "item0"), 1.0, 1000.0);  // 1 s per item
  m1.recordFailed("item1", "bad");
  m1.recordDone("item3", writeItem(j, "item3"), 1.0, 1000.0);
  m0.save(manifestPath(j.output_dir, 0, 2));
  m1.save(manifestPath(j.output_dir, 1, 2));

  // Nobody holds a lock: shard 0 stopped with 2 left; shard 1 one failed, one left.
  FarmStatus st = farmStatus(j, 0);
  EXPECT_EQ(st.shard_count, 2);  // from the manifests' names
  ASSERT_EQ(st.shards.size(), 2u);
  EXPECT_EQ(st.shards[0].state, "stopped");
  EXPECT_EQ(st.shards[0].done, 1);
  EXPECT_EQ(st.shards[0].left, 2);
  EXPECT_EQ(st.shards[0].running, 0);
  EXPECT_NEAR(st.shards[0].remaining_s, 2.0, 1e-9);
  EXPECT_EQ(st.shards[1].failed, 1);
  EXPECT_EQ(st.shards[1].done, 1);
  EXPECT_EQ(st.shards[1].left, 1);
  EXPECT_EQ(st.total.done, 2);
  EXPECT_EQ(st.total.failed, 1);
  EXPECT_EQ(st.total.left, 3);
  EXPECT_NEAR(st.total.remaining_s, 2.0, 1e-9);  // the slowest shard

  // Shard 0 runs (a live lock: this process): item2 is its running item.
  {
    const ShardLock lock(shardLockPath(manifestPath(j.output_dir, 0, 2)));
    st = farmStatus(j, 2);
    EXPECT_EQ(st.shards[0].state, "running");
    EXPECT_EQ(st.shards[0].running, 1);
    EXPECT_EQ(st.shards[0].left, 1);
    EXPECT_EQ(st.total.running, 1);
    const std::string text = formatFarmStatus(st);
    EXPECT_NE(text.find("lock: pid " + std::to_string(::getpid())), std::string::npos) << text;
    EXPECT_EQ(farmStatusJson(st)["shards"][0]["running"], 1);
  }
  // A lock whose process is gone (SIGKILL): stale, nothing running.
  std::ofstream(shardLockPath(manifestPath(j.output_dir, 1, 2))) << nlohmann::json{
      {"host",
       [] {
         char b[256] = {};
         ::gethostname(b, 255);
         return std::string(b);
       }()},
      {"pid", 999999999L},
      {"started", "x"}}.dump();
  st = farmStatus(j, 2);
  EXPECT_EQ(st.shards[1].state, "stale lock");
  EXPECT_EQ(st.shards[1].running, 0);

  // An unsharded local run counts the same way (manifest.json).
  const FarmStatus local = farmStatus(j, 1);
  EXPECT_EQ(local.total.done + local.total.failed + local.total.left + local.total.running, 6);
}

}  // namespace
