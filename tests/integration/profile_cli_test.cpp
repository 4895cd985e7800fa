// profile_cli_test.cpp — `seasim profile` and `seasim canonical-problems` through the real CLI: the CSV's
// rows and columns (every band and the sensor's channels at every depth), E_d falling with depth and K_d
// from it, the SVG plot; the Monte Carlo solver's standard-error columns; bad input (a negative depth, an
// unknown solver, a phase key misused) exits non-zero naming the problem and writes nothing; and images
// and radiometry agree: the path tracer's camera looking straight down at 3 m (tests/data/radiometry/
// nadir_view.toml) reads the profile's L_u at 3 m through the same sensor.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "io/image_io.h"
#include "run_command.h"

namespace fs = std::filesystem;

namespace {

const std::string kBinary = SEASIM_BINARY;
const std::string kScene = std::string(SEASIM_SOURCE_DIR) + "/scenes/open_ocean.toml";

std::vector<std::vector<std::string>> readCsv(const fs::path& p) {
  std::ifstream in(p);
  std::vector<std::vector<std::string>> rows;
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    std::string c;
    while (std::getline(ss, c, ',')) cells.push_back(c);
    rows.push_back(cells);
  }
  return rows;
}

class ProfileCli : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = seasim_test::freshTestDir("seasim_profile_cli_"); }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(ProfileCli, WritesEveryBandAndChannelAtEveryDepth) {
  const fs::path csv = dir_ / "p.csv", svg = dir_ / "p.svg";
  const auto r = seasim_test::runCommand(kBinary + " profile " + kScene + " --depths 0,1,5,10 --set spectral.count=4 --csv " +
                                         csv.string() + " --plot " + svg.string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("sensor_g: L_w"), std::string::npos) << r.output;
  const auto rows = readCsv(csv);
  ASSERT_EQ(rows.size(), 1u + (4 + 3) * 4);
  EXPECT_EQ(rows[0][0], "channel");
  EXPECT_EQ(rows[0][9], "K_d");
  for (size_t i = 1; i + 1 < rows.size(); ++i) {
    // Per band (the sensor's linear sRGB channels go negative where the light lies outside sRGB's gamut).
    if (rows[i][0] != rows[i + 1][0] || rows[i][0].rfind("band_", 0) != 0) continue;
    EXPECT_GT(std::stod(rows[i][3]), std::stod(rows[i + 1][3])) << "E_d must fall with depth: row " << i;
    EXPECT_GT(std::stod(rows[i + 1][9]), 0.0) << "K_d: row " << i + 1;
  }
  EXPECT_TRUE(fs::file_size(svg) > 1000);
}

TEST_F(ProfileCli, MonteCarloHasStandardErrors) {
  const fs::path csv = dir_ / "mc.csv";
  const auto r = seasim_test::runCommand(kBinary + " profile " + kScene +
                                         " --solver monte_carlo --photons 3000 --depths 1,5 --set spectral.count=3 --csv " +
                                         csv.string());
  ASSERT_EQ(r.code, 0) << r.output;
  const auto rows = readCsv(csv);
  ASSERT_EQ(rows.size(), 1u + (3 + 3) * 2);
  EXPECT_EQ(rows[0][14], "E_d_se");
  EXPECT_GT(std::stod(rows[1][14]), 0.0);
}

TEST_F(ProfileCli, BadInputWritesNothing) {
  const fs::path csv = dir_ / "bad.csv";
  auto r = seasim_test::runCommand(kBinary + " profile " + kScene + " --depths 0,-1 --csv " + csv.string());
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("depths"), std::string::npos) << r.output;
  r = seasim_test::runCommand(kBinary + " profile " + kScene + " --solver fast --csv " + csv.string());
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("--solver"), std::string::npos) << r.output;
  // open_ocean.toml gives g: with phase = "petzold" g is the phase's own, so the file's g is an error at
  // its line.
  r = seasim_test::runCommand(kBinary + " profile " + kScene + " --set water.phase=petzold --csv " + csv.string());
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("open_ocean.toml:"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("water.g"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(csv));
}

TEST_F(ProfileCli, CanonicalProblemsPassAtEightStreams) {
  const fs::path md = dir_ / "README.md";
  const auto r = seasim_test::runCommand(kBinary + " canonical-problems --streams 8 --photons 2000 --out " + md.string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("streams 8"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::file_size(md) > 2000);
}

// The camera's pixels (a 2° field of view about the nadir, 80000 paths each) against L_u of the discrete
// ordinates (32 streams): within 4 standard errors of the image's mean plus 2 % (the discrete ordinates'
// own error against the Monte Carlo profile in this water, and the field of view's 1° off the nadir).
// Measured (image at 20000 paths / profile): HG R -0.01144 / -0.01168, G 0.03688 / 0.03718, B 0.09392 /
// 0.09256; Petzold at 320000 paths: R -0.01140 ± 0.0006 / -0.01168, G 0.03681 ± 0.0007 / 0.03747,
// B 0.0919 ± 0.0015 / 0.0931 (the Monte Carlo profile: -0.01245, 0.03743, 0.09350).
void expectNadirPixelIsLu(const fs::path& dir, const std::string& scene_name) {
  const std::string scene = std::string(SEASIM_SOURCE_DIR) + "/tests/data/radiometry/" + scene_name;
  const fs::path& dir_ = dir;
  const fs::path exr = dir_ / "nadir.exr", csv = dir_ / "nadir.csv";
  auto r = seasim_test::runCommand(kBinary + " reference " + scene + " -o " + exr.string() + " --steps 80000 --device pocl");
  ASSERT_EQ(r.code, 0) << r.output;
  r = seasim_test::runCommand(kBinary + " profile " + scene + " --depths 3 --streams 32 --csv " + csv.string());
  ASSERT_EQ(r.code, 0) << r.output;
  const seasim::Image img = seasim::readImage(exr.string());
  const seasim::Image se = seasim::readImage((dir_ / "nadir.stderr.exr").string());
  const auto rows = readCsv(csv);
  for (int c = 0; c < 3; ++c) {
    double mean = 0, var = 0;
    const int n = img.width * img.height;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) {
        mean += img.at(x, y, c) / n;
        var += se.at(x, y, c) * se.at(x, y, c) / (double(n) * n);
      }
    const std::string channel = c == 0 ? "sensor_r" : c == 1 ? "sensor_g" : "sensor_b";
    double l_u = NAN;
    for (const auto& row : rows)
      if (row[0] == channel) l_u = std::stod(row[7]);
    EXPECT_NEAR(mean, l_u, 4 * std::sqrt(var) + 0.02 * std::abs(l_u)) << channel;
  }
}

TEST_F(ProfileCli, NadirPixelReadsTheProfilesUpwellingRadiance) { expectNadirPixelIsLu(dir_, "nadir_view.toml"); }

// The same with Petzold's phase: the path tracer samples it from its inverse CDF and weighs the sun's
// next-event estimate by its value table (reference.cl SEASIM_PT_PHASE_TABLE); the profile by its moments.
TEST_F(ProfileCli, NadirPixelReadsTheProfilesUpwellingRadianceWithPetzoldsPhase) {
  expectNadirPixelIsLu(dir_, "nadir_view_petzold.toml");
}

}  // namespace
