// layers_cli_test.cpp — the ground-truth layers through the CLI (docs/layers.md): `render --output LAYER`
// adds channels to image.exr (with +inf range for open water kept by the EXR), `run --output` adds them
// to every item, and an unknown layer, layers without exr, or layers above the water fail with a clear
// message, a non-zero exit and nothing written.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "io/image_io.h"
#include "run_command.h"

namespace fs = std::filesystem;

namespace {

const std::string kBinary = SEASIM_BINARY;
const std::string kRepo = SEASIM_SOURCE_DIR;
const std::string kSmall = " --set camera.width=16 --set camera.height=9 --device pocl";

class LayersCli : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = seasim_test::freshTestDir("seasim_layers_cli_"); }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

int channel(const seasim::Image& image, const std::string& name) {
  const auto it = std::find(image.channel_names.begin(), image.channel_names.end(), name);
  return it == image.channel_names.end() ? -1 : static_cast<int>(it - image.channel_names.begin());
}

TEST_F(LayersCli, RenderOutputAddsTheLayersChannelsToImageExr) {
  // Looking down into water with no bottom: the lower rows see open water.
  const auto r = seasim_test::runCommand(kBinary + " render " + kRepo + "/scenes/seabed.toml -o " +
                                         (dir_ / "out").string() + kSmall +
                                         " --set 'bottom.depth=1000.0' --output range --output object_id,direct");
  ASSERT_EQ(r.code, 0) << r.output;
  const seasim::Image image = seasim::readImage((dir_ / "out" / "image.exr").string());
  for (const char* c : {"R", "G", "B", "range", "object_id", "direct.R", "direct.G", "direct.B"})
    EXPECT_GE(channel(image, c), 0) << c;
  EXPECT_EQ(channel(image, "clear.R"), -1);  // computed with direct, written only when asked
  EXPECT_EQ(image.channels, 8);
  EXPECT_TRUE(fs::exists(dir_ / "out" / "image.png"));  // only layers named: the default formats stay
  float largest = 0;
  for (size_t i = 0; i < image.pixelCount(); ++i)
    largest = std::max(largest, image.pixels[i * image.channels + channel(image, "range")]);
  EXPECT_GT(largest, 100.0f);  // a 1 km deep bottom or the surface far away; finite without open water
}

TEST_F(LayersCli, OpenWaterRangeIsInfiniteInTheFile) {
  const fs::path scene = dir_ / "open.toml";
  std::ofstream(scene) << "[camera]\nposition = [0, -5, 0]\nlook_at = [0, -9, -5]\n[water]\njerlov = \"II\"\n"
                          "[outputs]\nlayers = [\"range\", \"depth\", \"beta_d\"]\n";
  const auto r =
      seasim_test::runCommand(kBinary + " render " + scene.string() + " -o " + (dir_ / "out").string() + kSmall);
  ASSERT_EQ(r.code, 0) << r.output;
  const seasim::Image image = seasim::readImage((dir_ / "out" / "image.exr").string());
  int infinite = 0;
  for (size_t i = 0; i < image.pixelCount(); ++i) {
    const float range = image.pixels[i * image.channels + channel(image, "range")];
    infinite += std::isinf(range) && range > 0;
    EXPECT_EQ(image.pixels[i * image.channels + channel(image, "beta_d_mask")], std::isinf(range) ? 0.0f : 1.0f);
  }
  EXPECT_EQ(infinite, int(image.pixelCount()));  // looking down into bottomless water
}

TEST_F(LayersCli, RunOutputAddsLayersToEveryItem) {
  const fs::path job = dir_ / "job.toml";
  std::ofstream(job) << "[job]\nname = \"layers\"\noutput_dir = \"" << (dir_ / "results").string()
                     << "\"\n[[render]]\nname = \"a\"\nscene = \"" << kRepo
                     << "/scenes/seabed.toml\"\noverrides = { \"camera.width\" = 16, \"camera.height\" = 9 }\n";
  const auto r = seasim_test::runCommand(kBinary + " run " + job.string() + " --device pocl --output range,backscatter");
  ASSERT_EQ(r.code, 0) << r.output;
  const seasim::Image image = seasim::readImage((dir_ / "results" / "a" / "image.exr").string());
  EXPECT_GE(channel(image, "range"), 0);
  EXPECT_GE(channel(image, "backscatter.G"), 0);
}

TEST_F(LayersCli, BadLayerRequestsFailBeforeAnythingIsWritten) {
  const std::string seabed = kBinary + " render " + kRepo + "/scenes/seabed.toml" + kSmall + " -o ";
  auto r = seasim_test::runCommand(seabed + (dir_ / "a").string() + " --output rnage");
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("unknown"), std::string::npos) << r.output;  // neither a format nor a layer
  r = seasim_test::runCommand(seabed + (dir_ / "b").string() + " --set 'outputs.layers=[\"rnage\"]'");
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("outputs.layers[0]': unknown layer 'rnage'; did you mean 'range'?"), std::string::npos)
      << r.output;
  r = seasim_test::runCommand(seabed + (dir_ / "c").string() + " --output png --output range");
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("add exr to the outputs"), std::string::npos) << r.output;
  r = seasim_test::runCommand(kBinary + " render " + kRepo + "/scenes/flat_sea.toml" + kSmall + " -o " +
                              (dir_ / "d").string() + " --output range");
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("camera below the surface"), std::string::npos) << r.output;
  r = seasim_test::runCommand(kBinary + " run " + kRepo + "/jobs/quickstart.toml -o " + (dir_ / "e").string() +
                              " --device pocl --output rnage");
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("--output: unknown layer 'rnage'"), std::string::npos) << r.output;
  for (const char* d : {"a", "b", "c", "d", "e"}) EXPECT_FALSE(fs::exists(dir_ / d / "image.exr")) << d;
}

}  // namespace
