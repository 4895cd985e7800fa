// farm_cli_test.cpp — `seasim farm slurm|status|merge` through the real binary, with shards run by
// hand (no scheduler: tests/farm/farm_slurm_test.sh runs them under a real Slurm).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "run_command.h"

namespace fs = std::filesystem;

namespace {

const std::string kBinary = SEASIM_BINARY;
const std::string kRepo = SEASIM_SOURCE_DIR;

using seasim_test::run;
using seasim_test::contains;

class FarmCli : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = seasim_test::freshTestDir("seasim_farm_cli_"); }
  void TearDown() override { fs::remove_all(dir_); }
  // Three renders of different sizes (the big one alone in a shard of two).
  std::string job(const std::string& last_name = "item2") {
    std::ostringstream t;
    t << "[job]\nname = \"fc\"\noutput_dir = \"out\"\n";
    const int widths[] = {40, 40, 120};
    for (int i = 0; i < 3; ++i)
      t << "[[render]]\nname = \"" << (i == 2 ? last_name : "item" + std::to_string(i)) << "\"\nscene = \"" << kRepo
        << "/scenes/flat_sea.toml\"\noverrides = { \"camera.width\" = " << widths[i]
        << ", \"camera.height\" = 20, \"spectral.count\" = 4 }\n";
    const std::string path = (dir_ / "job.toml").string();
    std::ofstream(path) << t.str();
    return path;
  }
  fs::path dir_;
};

TEST_F(FarmCli, SlurmPrintsTheScriptsAndShardsByHandThenStatusAndMerge) {
  const std::string j = job();
  const fs::path out = dir_ / "out";
  seasim_test::Result r = run("farm slurm " + j + " --tasks 2 --retries 1 --partition gpu --time 10:00");
  ASSERT_EQ(r.code, 0) << r.output;
  for (const char* part :
       {"#SBATCH --array=0-1", "--shard \"$shard\" --resume", "#SBATCH --partition=gpu", "#SBATCH --time=10:00",
        "farm merge", "--dependency=afterok:$ARRAY --kill-on-invalid-dep=yes", "--dependency=afternotok:$ARRAY",
        "by item count (index % N)", "balanced by estimate (used)"})
    EXPECT_TRUE(contains(r.output, part)) << part << "\n" << r.output;
  EXPECT_TRUE(fs::exists(out / "farm" / "tasks.sbatch"));
  EXPECT_TRUE(fs::exists(out / "farm" / "merge.sbatch"));
  std::ifstream plan_in(out / "farm" / "shard-plan-2.json");
  const nlohmann::json plan = nlohmann::json::parse(plan_in);
  EXPECT_EQ(plan["items"][2]["shard"], 0);  // the big item alone
  EXPECT_EQ(plan["items"][0]["shard"], 1);
  EXPECT_EQ(plan["items"][1]["shard"], 1);

  r = run("farm status " + j);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "not started")) << r.output;
  EXPECT_TRUE(contains(r.output, "balanced by estimated cost, farm/shard-plan-2.json")) << r.output;

  // The shards, by hand: shard 0 renders only the big item, as the plan says.
  r = run("run " + j + " --shard 0/2 --device pocl");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "1 rendered, 0 finished earlier, 2 left to other shards")) << r.output;
  r = run("farm status " + j + " --json");
  ASSERT_EQ(r.code, 0) << r.output;
  nlohmann::json st = nlohmann::json::parse(r.output);
  EXPECT_EQ(st["shard_count"], 2);
  EXPECT_EQ(st["shards"][0]["state"], "finished");
  EXPECT_EQ(st["shards"][1]["state"], "not started");
  EXPECT_EQ(st["total"]["done"], 1);
  EXPECT_EQ(st["total"]["left"], 2);
  EXPECT_TRUE(st["total"]["remaining_s"].is_number()) << "a rate from the done item";

  r = run("farm merge " + j);
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_TRUE(contains(r.output, "2 of 3 items are missing")) << r.output;
  EXPECT_TRUE(contains(r.output, "item0 (not rendered)")) << r.output;

  r = run("run " + j + " --shard 1/2 --device pocl");
  ASSERT_EQ(r.code, 0) << r.output;
  r = run("farm merge " + j);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "all 3 items present with intact files")) << r.output;
  std::ifstream report_in(out / "farm" / "report.json");
  const nlohmann::json report = nlohmann::json::parse(report_in);
  EXPECT_TRUE(report["complete"].get<bool>());
  for (const auto& item : report["items"]) {
    EXPECT_GT(item["wall_ms"].get<double>(), 0.0);
    EXPECT_TRUE(contains(item["device"]["label"].get<std::string>(), "pocl")) << item.dump();
  }

  // A damaged output: the merge names it, and --resume renders that item again.
  std::ofstream(out / "item1" / "image.png", std::ios::app) << "x";
  r = run("farm merge " + j);
  EXPECT_EQ(r.code, 1);
  EXPECT_TRUE(contains(r.output, "item1 (damaged: 'item1/image.png' does not match its checksum)")) << r.output;

  // Timings now exist: a new plan balances by them.
  r = run("farm slurm " + j + " --tasks 2");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "balanced by measured timings (used)")) << r.output;
}

TEST_F(FarmCli, SubmitWithoutSlurmFailsNamingTheCommand) {
  const seasim_test::Result r =
      seasim_test::runCommand("PATH=/nonexistent " + kBinary + " farm slurm " + job() + " --tasks 2 --submit");
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_TRUE(contains(r.output, "submitting the array of shards failed (exit code 127): sbatch --parsable"))
      << r.output;
}

TEST_F(FarmCli, AnItemNamedFarmIsReserved) {
  const seasim_test::Result r = run("validate " + job("farm"));
  EXPECT_NE(r.code, 0);
  EXPECT_TRUE(contains(r.output, "item name 'farm' is reserved")) << r.output;
}

}  // namespace
