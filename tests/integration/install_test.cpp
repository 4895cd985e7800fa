// install_test.cpp — `cmake --install` into a temporary prefix: the installed binary prints its version
// and commit, finds its data beside itself with no environment variable, runs an installed example job
// from an empty folder (outputs under ./results/<job>), and records version, commit and data folder in
// report.json.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "preview/preview_window.h"
#include "run_command.h"

namespace fs = std::filesystem;

namespace {

using seasim_test::Result;

// Runs a shell command line with seasim's path variables removed from its environment.
Result shell(const std::string& cmd) {
  return seasim_test::runCommand("env -u SEASIM_DATA_DIR -u SEASIM_CAMERA_DIR -u SEASIM_KERNEL_DIR " + cmd);
}

class Install : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    prefix_ = fs::temp_directory_path() / ("seasim_install_" + std::to_string(::getpid()));
    fs::remove_all(prefix_);
    const Result r = shell(std::string(SEASIM_CMAKE) + " --install " + SEASIM_BUILD_DIR + " --prefix " +
                           prefix_.string());
    install_ok_ = r.code == 0;
    install_log_ = r.output;
  }
  static void TearDownTestSuite() { fs::remove_all(prefix_); }
  void SetUp() override { ASSERT_TRUE(install_ok_) << install_log_; }

  static fs::path prefix_;
  static bool install_ok_;
  static std::string install_log_;
};
fs::path Install::prefix_;
bool Install::install_ok_ = false;
std::string Install::install_log_;

TEST_F(Install, LaysOutBinaryDataAndExamplesWithoutNonFreeCameras) {
  EXPECT_TRUE(fs::is_regular_file(prefix_ / "bin" / "seasim"));
  EXPECT_TRUE(fs::is_regular_file(prefix_ / "lib" / "seasim" / "libseasim_oiio.so"));
  // The preview's window module, in builds that have it (CMake found GLFW and OpenGL).
  EXPECT_EQ(fs::is_regular_file(prefix_ / "lib" / "seasim" / "libseasim_preview.so"), seasim::previewBuilt());
  const fs::path share = prefix_ / "share" / "seasim";
  EXPECT_TRUE(fs::is_regular_file(share / "data" / "cie1931_2deg_cmf.csv"));
  EXPECT_TRUE(fs::is_regular_file(share / "data" / "cameras" / "nikon_d5100_npl.csv"));
  EXPECT_TRUE(fs::is_regular_file(share / "scenes" / "flat_sea.toml"));
  EXPECT_TRUE(fs::is_regular_file(share / "jobs" / "quickstart.toml"));
  for (const auto& e : fs::recursive_directory_iterator(prefix_))
    EXPECT_EQ(e.path().filename().string().rfind("camspec", 0), std::string::npos) << e.path();
}

TEST_F(Install, VersionNamesTheCommit) {
  const Result r = shell((prefix_ / "bin" / "seasim").string() + " --version");
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("seasim "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("(git "), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("(git unknown)"), std::string::npos) << "a build in a checkout knows its commit: " << r.output;
}

// An installed example job, run from an empty folder: it finds the installed scene and data and writes
// under ./results/<job name>; the report names the installed data folder and the version.
TEST_F(Install, RunsAnInstalledExampleFromAnEmptyFolder) {
  const fs::path share = prefix_ / "share" / "seasim";
  std::ofstream(share / "jobs" / "tiny.toml")
      << "[job]\nname = \"tiny\"\noutput_dir = \"../results/tiny\"\n"
         "[[render]]\nname = \"sea\"\nscene = \"../scenes/flat_sea.toml\"\n"
         "overrides = { \"camera.width\" = 24, \"camera.height\" = 16 }\noutputs = [\"exr\"]\n";
  const fs::path empty = prefix_ / "empty";
  fs::create_directories(empty);
  const Result r = shell("sh -c 'cd " + empty.string() + " && " + (prefix_ / "bin" / "seasim").string() +
                         " run jobs/tiny.toml --device pocl'");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("installed example"), std::string::npos) << r.output;
  const fs::path report = empty / "results" / "tiny" / "sea" / "report.json";
  ASSERT_TRUE(fs::is_regular_file(report)) << r.output;
  EXPECT_FALSE(fs::exists(share / "results")) << "nothing is written into the install tree";
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(report));
  EXPECT_EQ(j["seasim"]["data_dir"].get<std::string>(), (share / "data").string());
  EXPECT_FALSE(j["seasim"]["version"].get<std::string>().empty());
  EXPECT_FALSE(j["seasim"]["git_commit"].get<std::string>().empty());

  // A job that is neither here nor installed is a clear error.
  const Result missing = shell("sh -c 'cd " + empty.string() + " && " + (prefix_ / "bin" / "seasim").string() +
                               " run jobs/no_such_job.toml'");
  EXPECT_NE(missing.code, 0);
  EXPECT_NE(missing.output.find("job file not found: jobs/no_such_job.toml"), std::string::npos) << missing.output;
}

// A kernel store under <prefix>/share/seasim/kernel-store (where `make install` puts `make kernel-store`'s)
// is the installed binary's without any environment variable: `cache verify` reports it, and a render
// with empty caches compiles nothing (no entry written into its cache).
TEST_F(Install, FindsTheInstalledKernelStore) {
  const std::string bin = (prefix_ / "bin" / "seasim").string();
  const fs::path store = prefix_ / "share" / "seasim" / "kernel-store";
  const std::string scene = (prefix_ / "share" / "seasim" / "scenes" / "flat_sea.toml").string() +
                            " --set camera.width=24 --set camera.height=16 --device pocl";
  fs::remove_all(store);  // the build's own, when `make kernel-store` made one
  const Result made = shell("env -u SEASIM_KERNEL_STORE " + bin + " cache warm " + scene + " --store " + store.string());
  ASSERT_EQ(made.code, 0) << made.output;
  const fs::path caches = prefix_ / "fresh_caches";
  const std::string env = "env -u SEASIM_KERNEL_STORE SEASIM_CACHE_DIR=" + caches.string() +
                          " POCL_CACHE_DIR=" + (caches / "pocl").string() + " ";
  const Result verify = shell(env + bin + " cache verify");
  EXPECT_EQ(verify.code, 0) << verify.output;
  EXPECT_NE(verify.output.find("kernel store " + store.string() + ": "), std::string::npos) << verify.output;
  const Result r = shell(env + bin + " render " + scene + " -o " + (prefix_ / "store_out").string());
  ASSERT_EQ(r.code, 0) << r.output;
  int written = 0;
  for (const auto& e : fs::directory_iterator(caches)) written += e.path().extension() == ".bin";
  EXPECT_EQ(written, 0) << "a program was compiled although the installed store has it";
}

}  // namespace
