// compare_cli_test.cpp — `seasim compare` tells the truth about an error: the scene's exposure as
// `sweep` uses it (the same image scores the same in both), the reference's noise from its
// .stderr.exr beside the error, a warning when the two images were made with different settings;
// `sweep` without --reference makes the scene's own and says so.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "run_command.h"

namespace fs = std::filesystem;

namespace {

const std::string kRepo = SEASIM_SOURCE_DIR;

using seasim_test::run;
const std::string kSmall = " --set camera.width=48 --set camera.height=27";

// The number after "KEY " at a line's start in the output; NaN when absent.
double value(const std::string& output, const std::string& key) {
  std::istringstream in(output);
  for (std::string line; std::getline(in, line);)
    if (line.rfind(key + " ", 0) == 0) return std::stod(line.substr(key.size() + 1));
  return std::nan("");
}

class CompareCli : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = seasim_test::freshTestDir("seasim_compare_"); }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  fs::path dir_;
};

TEST_F(CompareCli, UsesTheScenesExposureAsSweepDoes) {
  const std::string scene = kRepo + "/scenes/flat_sea.toml";  // camera.exposure_ev = 1.5
  auto r = run("reference " + scene + " -o " + path("ref.exr") + " --steps 200" + kSmall);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(fs::exists(path("ref.settings.json"))) << "the reference records its settings";
  r = run("render " + scene + " -o " + path("r") + kSmall + " --set spectral.count=4");
  ASSERT_EQ(r.code, 0) << r.output;
  r = run("compare " + path("r/image.exr") + " " + path("ref.exr"));
  ASSERT_EQ(r.code, 0) << r.output;
  const double compared = value(r.output, "rmse_8bit");
  EXPECT_EQ(value(r.output, "exposure_ev"), 1.5) << r.output;
  EXPECT_NE(r.output.find("knobs that differ from the reference's: wavelength_count 4 vs"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("warning"), std::string::npos) << "only a knob differs: " << r.output;

  r = run("sweep " + scene + " --param spectral.count=4 --reference " + path("ref.exr") + " --csv " + path("s.csv") + kSmall);
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream csv(path("s.csv"));
  std::string header, row;
  std::getline(csv, header);
  std::getline(csv, row);
  ASSERT_EQ(header.substr(0, header.find(",rmse_8bit")).size(), std::string("spectral.count,kernel_ms,wall_ms").size());
  std::vector<std::string> cells;
  std::stringstream ss(row);
  for (std::string c; std::getline(ss, c, ',');) cells.push_back(c);
  ASSERT_GE(cells.size(), 4u);
  const double swept = std::stod(cells[3]);
  EXPECT_GT(compared, 0.01);
  EXPECT_NEAR(compared, swept, 1e-3) << "the same image scores the same in compare and sweep";

  // --exposure still overrides, and another exposure gives another score.
  r = run("compare " + path("r/image.exr") + " " + path("ref.exr") + " --exposure 0");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(value(r.output, "exposure_ev"), 0.0);
  EXPECT_GT(std::fabs(value(r.output, "rmse_8bit") - compared), 1e-3);
}

TEST_F(CompareCli, WarnsWhenTheImagesWereMadeWithDifferentSettings) {
  // README's first steps: a render at sun.zenith_deg = 60 against the scene's reference at 40.
  const std::string scene = kRepo + "/scenes/flat_sea.toml";
  ASSERT_EQ(run("reference " + scene + " -o " + path("ref.exr") + " --steps 100" + kSmall).code, 0);
  ASSERT_EQ(run("render " + scene + " -o " + path("r60") + kSmall + " --set sun.zenith_deg=60").code, 0);
  const auto r = run("compare " + path("r60/image.exr") + " " + path("ref.exr"));
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("warning: the image and the reference were made with different settings: sun_zenith_deg 60 vs 40"),
            std::string::npos)
      << r.output;
  // sweep says the same of its reference.
  const auto s = run("sweep " + scene + " --param spectral.count=4 --reference " + path("ref.exr") + " --csv " +
                     path("s.csv") + kSmall + " --set sun.zenith_deg=60");
  EXPECT_EQ(s.code, 0) << s.output;
  EXPECT_NE(s.output.find("warning: the reference was made with sun_zenith_deg = 40, the sweep's scene has 60"),
            std::string::npos)
      << s.output;
}

TEST_F(CompareCli, ReportsTheReferencesNoiseAndTheShareItExplains) {
  const std::string scene = kRepo + "/scenes/seabed.toml";  // under water: the path tracer, with REF.stderr.exr
  const std::string tiny = " --set camera.width=24 --set camera.height=14";
  auto r = run("reference " + scene + " -o " + path("ref.exr") + " --steps 256" + tiny);
  ASSERT_EQ(r.code, 0) << r.output;
  ASSERT_TRUE(fs::exists(path("ref.stderr.exr")));
  ASSERT_EQ(run("reference " + scene + " -o " + path("ref2.exr") + " --steps 256 --seed 2" + tiny).code, 0);
  // A second reference with other paths against the first: all of the error is noise (two draws:
  // rmse² ≈ 2 noise², so the share is about one half). Measured 0.21 at 8 paths, 0.34 at 64, 0.41
  // at 256: a few paths' standard error misses the rare bright paths of a heavy-tailed estimate.
  fs::remove(path("ref2.stderr.exr"));  // the image under test is the second draw; its noise is not the reference's
  r = run("compare " + path("ref2.exr") + " " + path("ref.exr"));
  ASSERT_EQ(r.code, 0) << r.output;
  const double rmse = value(r.output, "rmse_8bit"), noise = value(r.output, "reference_noise_8bit");
  const double share = value(r.output, "noise_share_of_rmse2");
  ASSERT_TRUE(std::isfinite(noise)) << r.output;
  EXPECT_GT(noise, 0.5);
  EXPECT_NEAR(share, 0.45, 0.15) << r.output;
  EXPECT_NEAR(value(r.output, "rmse_less_noise_8bit"), std::sqrt(std::max(0.0, rmse * rmse - noise * noise)), 1e-3);
  // Without the standard-error image there is nothing to report.
  fs::remove(path("ref.stderr.exr"));
  r = run("compare " + path("ref2.exr") + " " + path("ref.exr"));
  EXPECT_EQ(r.output.find("reference_noise_8bit"), std::string::npos) << r.output;
}

TEST_F(CompareCli, SweepWithoutReferenceMakesTheScenesOwn) {
  // scenes/README.md's `sweep ... --param quality.sea_nz=4,8,12,24` without --reference, on the flat
  // sea (open_ocean's second-order reference by direct quadrature takes minutes even at 48 x 27).
  const std::string scene = kRepo + "/scenes/flat_sea.toml";
  const auto r = run("sweep " + scene + " --param quality.sea_nz=4,12 --csv " + path("s/nz.csv") + " --plot " +
                     path("s/nz.svg") + kSmall + " --set quality.reference_steps=50");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("no --reference given: making the scene's reference"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(path("s/nz.reference.exr")));
  EXPECT_TRUE(fs::exists(path("s/nz.reference.settings.json")));
  std::ifstream svg(path("s/nz.svg"));
  const std::string text((std::istreambuf_iterator<char>(svg)), {});
  EXPECT_NE(text.find(">sea_nz=4</text>"), std::string::npos) << "points labelled with their knob values";
  EXPECT_NE(text.find(">sea_nz=12</text>"), std::string::npos);
}

}  // namespace
