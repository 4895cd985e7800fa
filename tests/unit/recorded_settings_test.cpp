// recorded_settings_test.cpp — jobs/recorded_settings.h: where an image's settings are found, and
// which differences count (scene settings) and which are the knobs error-vs-time varies on purpose.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "jobs/recorded_settings.h"
#include "scene/scene_parser.h"

namespace fs = std::filesystem;

namespace seasim {
namespace {

const std::string kScene = std::string(SEASIM_SOURCE_DIR) + "/scenes/flat_sea.toml";

TEST(RecordedSettings, DifferencesSplitSceneSettingsFromKnobs) {
  const Scene at40 = loadScene(kScene, {{"sun.zenith_deg", "40", {"t", 0}}});
  const Scene at60 = loadScene(kScene, {{"sun.zenith_deg", "60", {"t", 0}}});
  EXPECT_TRUE(settingsDifferences(settingsJson(at40), settingsJson(at40)).empty());
  const auto d = settingsDifferences(settingsJson(at60), settingsJson(at40));
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].key, "sun_zenith_deg");
  EXPECT_EQ(d[0].test, "60");  // 60 degrees through radians and back still reads 60
  EXPECT_EQ(d[0].reference, "40");
  EXPECT_FALSE(d[0].knob);
  const Scene bands = loadScene(kScene, {{"spectral.count", "8", {"t", 0}}, {"quality.sea_lut_size", "16", {"t", 0}}});
  const auto k = settingsDifferences(settingsJson(bands), settingsJson(at40));
  ASSERT_FALSE(k.empty());
  for (const auto& diff : k) EXPECT_TRUE(diff.knob) << diff.key;
}

TEST(RecordedSettings, FoundInTheRendersReportOrBesideTheReference) {
  const fs::path dir = fs::temp_directory_path() / ("seasim_recorded_" + std::to_string(::getpid()));
  fs::create_directories(dir / "render");
  const Scene scene = loadScene(kScene);
  EXPECT_TRUE(recordedSettings((dir / "ref.exr").string()).is_null());
  writeSettingsSidecar((dir / "ref.exr").string(), scene, "test");
  EXPECT_TRUE(fs::exists(dir / "ref.settings.json"));
  EXPECT_EQ(recordedSettings((dir / "ref.exr").string()), settingsJson(scene));
  nlohmann::json report = {{"outputs", {"image.exr", "image.png"}}, {"settings", {{"exposure_ev", 2.5}}}};
  std::ofstream(dir / "render" / "report.json") << report.dump();
  EXPECT_EQ(recordedSettings((dir / "render" / "image.exr").string())["exposure_ev"], 2.5);
  EXPECT_TRUE(recordedSettings((dir / "render" / "other.exr").string()).is_null()) << "not one of the report's outputs";
  std::ofstream(dir / "broken.settings.json") << "{ not json";
  EXPECT_THROW(recordedSettings((dir / "broken.exr").string()), std::runtime_error);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace seasim
