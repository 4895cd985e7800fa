// shallow_cli_test.cpp — shallow water (paper 003) through the real CLI: the mountain lake renders on
// both paths, the table build is timed on the table path only, nothing is NaN/Inf, and the table path
// stays within the error measured for it against the exact spectral path (results/shallow/: RMSE 2.75,
// max 11.7 levels at full size; allowed here 4 and 20 at 96×54).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "run_command.h"

namespace fs = std::filesystem;

namespace {

const std::string kBinary = SEASIM_BINARY;
const std::string kScene = std::string(SEASIM_SOURCE_DIR) + "/scenes/mountain_lake.toml";

std::string readFile(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

double number(const std::string& text, const std::string& key) {
  std::smatch m;
  if (!std::regex_search(text, m, std::regex(key + "\\s+([0-9.eE+-]+)"))) return -1;
  return std::stod(m[1]);
}

class ShallowCli : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = seasim_test::freshTestDir("seasim_shallow_"); }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(ShallowCli, LakeTablePathIsWithinItsMeasuredErrorOfTheExactPath) {
  const std::string small = " --set camera.width=96 --set camera.height=54";
  const auto table = seasim_test::runCommand(kBinary + " render " + kScene + small + " --out " + (dir_ / "table").string());
  ASSERT_EQ(table.code, 0) << table.output;
  const auto exact = seasim_test::runCommand(kBinary + " render " + kScene + small +
                                             " --set 'shallow.path=\"exact\"' --out " + (dir_ / "exact").string());
  ASSERT_EQ(exact.code, 0) << exact.output;
  const std::string report_t = readFile(dir_ / "table" / "report.json");
  const std::string report_e = readFile(dir_ / "exact" / "report.json");
  EXPECT_NE(report_t.find("\"fourflow_tables\""), std::string::npos) << report_t;
  EXPECT_EQ(report_e.find("\"fourflow_tables\""), std::string::npos) << report_e;
  EXPECT_NE(report_t.find("\"nonfinite\": 0"), std::string::npos) << report_t;
  EXPECT_NE(report_e.find("\"nonfinite\": 0"), std::string::npos) << report_e;
  const auto cmp = seasim_test::runCommand(kBinary + " compare " + (dir_ / "table" / "image.exr").string() + " " +
                                           (dir_ / "exact" / "image.exr").string() + " --exposure 1");
  ASSERT_EQ(cmp.code, 0) << cmp.output;
  const double rmse = number(cmp.output, "rmse_8bit"), max_abs = number(cmp.output, "max_abs_8bit");
  std::printf("[ measured ] lake 96x54, table vs exact: rmse %.2f max %.2f levels\n", rmse, max_abs);
  EXPECT_GT(rmse, 0.0);  // two different paths: not the same image
  EXPECT_LT(rmse, 4.0) << cmp.output;
  EXPECT_LT(max_abs, 20.0) << cmp.output;
}

}  // namespace
