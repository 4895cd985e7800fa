// reference_cli_test.cpp — `seasim reference` as a user drives it: the scene's quality.reference_spp /
// quality.reference_steps are the defaults of --steps, "auto" is refused, --seed picks the path
// tracer's paths (same seed, same image; another seed, another image), and the per-pixel standard
// error is written beside the reference as OUT.stderr.exr.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "io/image_io.h"
#include "run_command.h"

namespace fs = std::filesystem;

namespace {

const std::string kBinary = SEASIM_BINARY;
const std::string kRepo = SEASIM_SOURCE_DIR;

using seasim_test::Result;

Result run(const std::string& args) { return seasim_test::runCommand(kBinary + " " + args); }

class ReferenceCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = seasim_test::freshTestDir("seasim_ref_");
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

const std::string kSmallUnderwater = kRepo + "/scenes/seabed.toml --set camera.width=16 --set camera.height=9"
                                             " --set spectral.count=4 --device pocl";

TEST_F(ReferenceCli, UnderwaterTakesQualityReferenceSppSeedAndWritesTheStandardError) {
  const std::string a = (dir_ / "a.exr").string(), b = (dir_ / "b.exr").string(), c = (dir_ / "c.exr").string();
  Result r = run("reference " + kSmallUnderwater + " -o " + a + " --set quality.reference_spp=3");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("3 paths per pixel"), std::string::npos) << r.output;
  ASSERT_TRUE(fs::exists(dir_ / "a.stderr.exr")) << r.output;
  const seasim::Image se = seasim::readImage((dir_ / "a.stderr.exr").string());
  EXPECT_EQ(se.width, 16);
  double se_sum = 0;
  for (float v : se.pixels) {
    ASSERT_TRUE(v >= 0) << "a standard error";
    se_sum += v;
  }
  EXPECT_GT(se_sum, 0) << "3 paths per pixel leave noise";

  r = run("reference " + kSmallUnderwater + " -o " + b + " --steps 3 --seed 1");
  ASSERT_EQ(r.code, 0) << r.output;
  r = run("reference " + kSmallUnderwater + " -o " + c + " --steps 3 --seed 7");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("seed 7"), std::string::npos) << r.output;
  const seasim::Image ia = seasim::readImage(a), ib = seasim::readImage(b), ic = seasim::readImage(c);
  EXPECT_EQ(ia.pixels, ib.pixels) << "seed 1 is the default: the same paths";
  EXPECT_NE(ia.pixels, ic.pixels) << "another seed traces other paths";
}

TEST_F(ReferenceCli, SeaTakesQualityReferenceStepsAndRefusesAuto) {
  const std::string scene = kRepo + "/scenes/flat_sea.toml --set camera.width=16 --set camera.height=9";
  Result r = run("reference " + scene + " -o " + (dir_ / "s.exr").string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("200 quadrature steps"), std::string::npos) << r.output;
  r = run("reference " + scene + " -o " + (dir_ / "t.exr").string() + " --set quality.reference_steps=37");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("37 quadrature steps"), std::string::npos) << r.output;
  r = run("reference " + scene + " -o " + (dir_ / "u.exr").string() + " --set quality.reference_steps='\"auto\"'");
  EXPECT_NE(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("reference_steps"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir_ / "u.exr"));
}

TEST_F(ReferenceCli, HelpSaysWhatEachModelsReferenceIs) {
  const Result r = run("reference --help");
  EXPECT_NE(r.output.find("path tracer in OpenCL"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("paths per"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("--seed"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("quality.reference_spp"), std::string::npos) << r.output;
}

}  // namespace
