// shallow_cli_test.cpp — shallow water (paper 003) through the real CLI: the mountain lake renders on
// both paths, the table build is timed on the table path only, nothing is NaN/Inf, and the table path
// stays within the error measured for it against the exact spectral path (results/shallow/: RMSE 2.75,
// max 11.7 levels at full size; allowed here 4 and 20 at 96×54); the spectral EXR holds each band's
// radiance, which through the sensor gives the exact path's RGB; [display] tone_map = "eq18" changes
// the PNG and nothing else.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "io/image_io.h"
#include "run_command.h"
#include "scene/scene_parser.h"
#include "spectral/sensor.h"
#include "spectral/wavelength_grid.h"

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

TEST_F(ShallowCli, SpectralExrHoldsTheBandsOfTheExactPath) {
  // A camera sensor (non-negative curves), so that no channel of the water's colour is out of gamut
  // and clamped: then the exact path's RGB is exactly the bands through the sensor.
  const std::string camera = "canon_eos_5d_mark_ii_rawtoaces";
  const std::string small = " --set camera.width=32 --set camera.height=18 --set spectral.spectral_exr=true"
                            " --set 'spectral.sensor=\"" + camera + "\"'";
  std::vector<float> exact_bands;
  for (const char* path : {"exact", "table"}) {
    const fs::path out = dir_ / path;
    const auto r = seasim_test::runCommand(kBinary + " render " + kScene + small + " --set 'shallow.path=\"" + path +
                                           "\"' --output exr,spectral_exr --out " + out.string());
    ASSERT_EQ(r.code, 0) << r.output;
    const seasim::SpectralImage bands = seasim::readSpectralExr((out / "spectral.exr").string());
    const seasim::Scene scene = seasim::loadScene(kScene);
    const seasim::WavelengthGrid grid =
        seasim::makeGrid(scene.spectral.count, scene.spectral.min_nm, scene.spectral.max_nm);
    ASSERT_EQ(bands.wavelengths_nm.size(), grid.size());
    ASSERT_EQ(bands.data.size(), size_t(32 * 18) * grid.size());
    for (float v : bands.data) ASSERT_TRUE(std::isfinite(v) && v >= 0) << path;
    if (std::string(path) == "table") {
      // The tables hold RGB only: the table path's bands are the exact eq. 20, the same numbers.
      EXPECT_EQ(bands.data, exact_bands);
      continue;
    }
    exact_bands = bands.data;
    const seasim::Image rgb = seasim::readImage((out / "image.exr").string());
    const seasim::Sensor sensor = seasim::makeSensor(camera, grid, scene.spectral.white_balance);
    double worst = 0, scale = 0;
    for (size_t px = 0; px < size_t(32 * 18); ++px) {
      double sum[3] = {0, 0, 0};
      for (size_t i = 0; i < grid.size(); ++i) {
        const float v = bands.data[px * grid.size() + i];
        sum[0] += sensor.to_r[i] * v, sum[1] += sensor.to_g[i] * v, sum[2] += sensor.to_b[i] * v;
      }
      for (int c = 0; c < 3; ++c) {
        worst = std::max(worst, std::fabs(sum[c] - rgb.pixels[px * 3 + c]));
        scale = std::max(scale, std::fabs(double(rgb.pixels[px * 3 + c])));
      }
    }
    std::printf("[ measured ] exact path: |sensor(bands) - rgb| max %.3g of max rgb %.3g\n", worst, scale);
    ASSERT_GT(scale, 0);
    EXPECT_LT(worst, 1e-5 * scale);  // the same per-band sums, in float
  }
}

TEST_F(ShallowCli, Eq18ToneMapChangesOnlyThePng) {
  const std::string small = " --set camera.width=32 --set camera.height=18 --output exr,png";
  const auto def = seasim_test::runCommand(kBinary + " render " + kScene + small + " --out " + (dir_ / "d").string());
  ASSERT_EQ(def.code, 0) << def.output;
  const auto eq18 = seasim_test::runCommand(kBinary + " render " + kScene + small +
                                            " --set 'display.tone_map=\"eq18\"' --set display.gamma_world=1.3 --out " +
                                            (dir_ / "e").string());
  ASSERT_EQ(eq18.code, 0) << eq18.output;
  const seasim::Image exr_d = seasim::readImage((dir_ / "d" / "image.exr").string());
  const seasim::Image exr_e = seasim::readImage((dir_ / "e" / "image.exr").string());
  EXPECT_EQ(exr_d.pixels, exr_e.pixels);  // the linear image is not touched
  const seasim::Image png_d = seasim::readImage((dir_ / "d" / "image.png").string());
  const seasim::Image png_e = seasim::readImage((dir_ / "e" / "image.png").string());
  ASSERT_EQ(png_d.pixels.size(), png_e.pixels.size());
  EXPECT_NE(png_d.pixels, png_e.pixels);
  // White = the image's largest L_d by default: some channel reaches full scale.
  float brightest = 0;
  for (float v : png_e.pixels) brightest = std::max(brightest, v);
  EXPECT_GT(brightest, 0.99f);
  const auto bad = seasim_test::runCommand(kBinary + " render " + kScene + small +
                                           " --set 'display.tone_map=\"eq18\"' --set display.white=-1 --out " +
                                           (dir_ / "bad").string());
  EXPECT_NE(bad.code, 0);
  EXPECT_NE(bad.output.find("display.white"), std::string::npos) << bad.output;
  EXPECT_FALSE(fs::exists(dir_ / "bad" / "image.png"));
}

}  // namespace
