// lamp_regions_cli_test.cpp — `seasim lamp-regions --max-bounces N --means`: the reference cut to N scattering
// vertices and cached apart from the all-orders one, so that a fast model cut to the same orders can be held
// to it order by order; and a bound that is not positive refused.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "run_command.h"

namespace fs = std::filesystem;

namespace {

const std::string kRepo = SEASIM_SOURCE_DIR;

// The CSV's one row (one case, one model) by column name.
std::map<std::string, double> csvRow(const fs::path& file) {
  std::ifstream in(file);
  std::string head, row;
  std::getline(in, head);
  std::getline(in, row);
  std::map<std::string, double> out;
  std::stringstream h(head), r(row);
  std::string name, value;
  while (std::getline(h, name, ',') && std::getline(r, value, ',')) {
    if (name == "model" || value.empty()) continue;
    out[name] = std::stod(value);
  }
  return out;
}

class LampRegionsCli : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = seasim_test::freshTestDir("seasim_lampregions_"); }
  void TearDown() override { fs::remove_all(dir_); }
  // lamp-regions on one case at g 0.5 over a black bottom (every vertex in the water), single scattering alone
  // in the fast model, `extra` appended.
  seasim_test::Result regions(const std::string& csv, const std::string& extra) {
    return seasim_test::run("lamp-regions " + kRepo + "/tests/perf/lamp_glow.toml --cases 0.1:0.3:0.5:20:3 " +
                            "--models single --spp 512 --rounds 1 --device pocl --set bottom.albedo=0 --cache " +
                            (dir_ / "cache").string() + " --csv " + (dir_ / csv).string() + " " + extra);
  }
  fs::path dir_;
};

TEST_F(LampRegionsCli, OneBounceReferenceIsTheSingleScatteringThePlanesGive) {
  const seasim_test::Result one = regions("one.csv", "--max-bounces 1 --means");
  ASSERT_EQ(one.code, 0) << one.output;
  EXPECT_TRUE(seasim_test::contains(one.output, "mean radiance per pixel, fast / reference")) << one.output;
  const seasim_test::Result all = regions("all.csv", "");
  ASSERT_EQ(all.code, 0) << all.output;
  // Paper 001's planes are exact single scattering: against the reference cut to one vertex they agree
  // within its noise; against all orders the beam misses the light scattered more than once (0.83 at
  // 16384 paths).
  const std::map<std::string, double> a = csvRow(dir_ / "one.csv"), b = csvRow(dir_ / "all.csv");
  EXPECT_NEAR(a.at("beam_ratio"), 1.0, 4 * a.at("beam_ref_rel_se") + 0.005);
  EXPECT_NEAR(a.at("whole_ratio"), 1.0, 4 * a.at("whole_ref_rel_se") + 0.005);
  EXPECT_LT(b.at("beam_ratio"), 0.9);
  // Two references in the cache, the cut one apart.
  int cut = 0, files = 0;
  for (const auto& e : fs::directory_iterator(dir_ / "cache")) {
    ++files;
    if (seasim_test::contains(e.path().filename().string(), ".bounces1.")) ++cut;
  }
  EXPECT_EQ(files, 4);  // an image and its standard error each
  EXPECT_EQ(cut, 2);
}

TEST_F(LampRegionsCli, ABoundThatIsNotPositiveIsRefused) {
  const seasim_test::Result r = regions("x.csv", "--max-bounces 0");
  EXPECT_NE(r.code, 0);
  EXPECT_TRUE(seasim_test::contains(r.output, "--max-bounces")) << r.output;
  EXPECT_FALSE(fs::exists(dir_ / "x.csv"));
}

}  // namespace
