// file_errors_test.cpp — jobs/file_errors.h: every error of a scene or job file, each as the parser
// reports it (file:line and key), in one pass; a valid file has none.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "jobs/file_errors.h"
#include "jobs/job.h"
#include "util/error.h"

namespace fs = std::filesystem;

namespace seasim {
namespace {

class FileErrors : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("seasim_file_errors_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return (dir_ / name).string();
  }
  fs::path dir_;
};

bool has(const std::vector<std::string>& errors, const std::string& what) {
  for (const auto& e : errors)
    if (e.find(what) != std::string::npos) return true;
  return false;
}

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& e : v) s += e + "\n";
  return s;
}

TEST_F(FileErrors, SceneListsEveryBadKeyTopToBottom) {
  const std::string scene = write("bad.toml",
                                  "[water]\njerlov = \"IB\"\ng = 1.2\n"  // 3: |g| >= 1
                                  "[sun]\nzenit_deg = 40\n"              // 5: unknown key
                                  "[camera]\nwidth = -5\n"               // 7: out of range
                                  "fov_deg = \"wide\"\n");               // 8: wrong type
  const auto errors = sceneFileErrors(scene);
  ASSERT_EQ(errors.size(), 4u) << joined(errors);
  EXPECT_NE(errors[0].find("bad.toml:3: key 'water.g'"), std::string::npos) << joined(errors);
  EXPECT_NE(errors[1].find("bad.toml:5: key 'sun.zenit_deg'"), std::string::npos) << joined(errors);
  EXPECT_NE(errors[2].find("bad.toml:7: key 'camera.width'"), std::string::npos) << joined(errors);
  EXPECT_NE(errors[3].find("bad.toml:8: key 'camera.fov_deg'"), std::string::npos) << joined(errors);
  // The first one is what loadScene throws.
  try {
    (void)loadScene(scene);
    FAIL() << "loadScene accepted a bad scene";
  } catch (const InputError& e) {
    EXPECT_TRUE(has(errors, e.what())) << e.what();
  }
}

TEST_F(FileErrors, ValidSceneAndSyntaxError) {
  EXPECT_TRUE(sceneFileErrors(std::string(SEASIM_SOURCE_DIR) + "/scenes/flat_sea.toml").empty());
  const auto errors = sceneFileErrors(write("syntax.toml", "[sun]\nzenith_deg = = 4\n"));
  ASSERT_EQ(errors.size(), 1u) << joined(errors);
  EXPECT_NE(errors[0].find("syntax.toml:2:"), std::string::npos) << errors[0];
}

TEST_F(FileErrors, OverridesErrorsNameWhereTheyWereWritten) {
  const std::string scene = std::string(SEASIM_SOURCE_DIR) + "/scenes/flat_sea.toml";
  const std::vector<Override> overrides = {{"sun.zenith_deg", "\"high\"", {"job.toml", 7}},
                                           {"camera.widht", "64", {"job.toml", 8}}};
  const auto errors = sceneFileErrors(scene, overrides);
  ASSERT_EQ(errors.size(), 2u) << joined(errors);
  EXPECT_TRUE(has(errors, "job.toml:7: key 'sun.zenith_deg'")) << joined(errors);
  EXPECT_TRUE(has(errors, "job.toml:8: key 'camera.widht'")) << joined(errors);
}

TEST_F(FileErrors, JobListsItsOwnErrorsAndEachItemsSceneErrors) {
  const std::string scene = std::string(SEASIM_SOURCE_DIR) + "/scenes/flat_sea.toml";
  const std::string job = write("job.toml",
                                "[job]\nname = \"t\"\ncolour = 3\n"                                   // 3: unknown key
                                "[[render]]\nname = \"a\"\nscene = \"" + scene + "\"\n"
                                "overrides = { \"sun.zenith_deg\" = 200 }\n"                          // 7: out of range
                                "[[render]]\nname = \"b\"\nscene = \"" + scene + "\"\n"
                                "outputs = [\"exr\", \"gif\"]\n"                                        // 11: unknown output
                                "overrides = { \"camera.width\" = 0 }\n");                            // 12: out of range
  const auto errors = jobFileErrors(job);
  EXPECT_EQ(errors.size(), 4u) << joined(errors);
  EXPECT_TRUE(has(errors, "job.toml:3: key 'job.colour'")) << joined(errors);
  EXPECT_TRUE(has(errors, "job.toml:11:")) << joined(errors);
  EXPECT_TRUE(has(errors, "job.toml:7: key 'sun.zenith_deg'")) << joined(errors);
  EXPECT_TRUE(has(errors, "job.toml:12: key 'camera.width'")) << joined(errors);
  EXPECT_TRUE(jobFileErrors(std::string(SEASIM_SOURCE_DIR) + "/jobs/quickstart.toml").empty());
}

TEST_F(FileErrors, ExtraOverridesReachEveryItem) {
  const std::string scene = std::string(SEASIM_SOURCE_DIR) + "/scenes/flat_sea.toml";
  const std::string job = write("two.toml", "[job]\nname = \"t\"\n[[render]]\nname = \"a\"\nscene = \"" + scene +
                                                "\"\noverrides = { \"camera.width\" = 300 }\n[[render]]\nname = \"b\"\n"
                                                "scene = \"" + scene + "\"\n");
  JobLoadOptions options;
  options.extra_overrides = {{"camera.width", "48", {"<command line>", 0}}};
  const Job j = loadJob(job, options);
  ASSERT_EQ(j.items.size(), 2u);
  for (const RenderItem& item : j.items) {
    EXPECT_EQ(loadScene(item.scene_file, item.overrides).camera.width, 48) << item.name << ": --set comes last and wins";
  }
}

}  // namespace
}  // namespace seasim
