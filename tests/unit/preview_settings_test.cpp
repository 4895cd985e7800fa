// preview_settings_test.cpp — the preview's keys without a window (host/preview/preview_settings.h):
// the script syntax, each key's setting, the camera moves, what differs from the scene, and the
// scene file `S` writes (host/scene/scene_writer.h) reading back to the same scene.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "preview/preview_settings.h"
#include "scene/scene_parser.h"
#include "scene/scene_writer.h"
#include "util/error.h"

namespace {

using namespace seasim;
namespace fs = std::filesystem;

const char* kSea = R"(
[scene]
name = "sea"
[camera]
position = [0, 10, 0]
look_at = [0, 0, -100]
[sun]
zenith_deg = 40
azimuth_deg = 10
[water]
jerlov = "IB"
[bottom]
type = "flat"
depth = 8
)";

const char* kUnderwater = R"(
[camera]
position = [0, -5, 0]
look_at = [0, -5, -10]
[water]
jerlov = "II"
)";

PreviewInput key(const std::string& name) { return {PreviewInput::Kind::Key, name, 0, 0}; }

std::string valueOf(const PreviewSettings& s, const std::string& key) {
  for (const Override& o : s.overrides())
    if (o.key == key) return o.value_toml;
  return "";
}

Scene withOverrides(const char* text, const PreviewSettings& s) { return parseScene(text, "t.toml", s.overrides()); }

TEST(PreviewScript, TokensRepeatsAndMouse) {
  const auto inputs = parseKeyScript("up*3  left orbit:40,-2.5 WAIT*2 zoom:1 S");
  ASSERT_EQ(inputs.size(), 9u);
  EXPECT_EQ(inputs[0].key, "UP");
  EXPECT_EQ(inputs[2].key, "UP");
  EXPECT_EQ(inputs[3].key, "LEFT");
  EXPECT_EQ(inputs[4].kind, PreviewInput::Kind::Orbit);
  EXPECT_DOUBLE_EQ(inputs[4].dx, 40);
  EXPECT_DOUBLE_EQ(inputs[4].dy, -2.5);
  EXPECT_EQ(inputs[5].kind, PreviewInput::Kind::Wait);
  EXPECT_EQ(inputs[7].kind, PreviewInput::Kind::Zoom);
  EXPECT_EQ(inputs[8].key, "S");
  EXPECT_TRUE(parseKeyScript("").empty());
}

TEST(PreviewScript, BadTokensNameThemselves) {
  for (const char* bad : {"UP FLY", "UP*0", "UP*x", "ORBIT:3", "ORBIT:a,b", "DRAG:1,2", "UP*1.5"}) {
    try {
      parseKeyScript(bad);
      ADD_FAILURE() << bad << " was accepted";
    } catch (const RuntimeError& e) {
      EXPECT_NE(std::string(e.what()).find("--script"), std::string::npos) << e.what();
    }
  }
}

TEST(PreviewSettings, SunKeysStepAndClamp) {
  PreviewSettings s(parseScene(kSea, "t.toml"));
  EXPECT_TRUE(s.apply(key("UP")).changed);
  EXPECT_EQ(valueOf(s, "sun.zenith_deg"), "35");
  for (int i = 0; i < 20; ++i) s.apply(key("UP"));
  EXPECT_EQ(valueOf(s, "sun.zenith_deg"), "0");
  for (int i = 0; i < 40; ++i) s.apply(key("DOWN"));
  EXPECT_EQ(valueOf(s, "sun.zenith_deg"), "89");
  s.apply(key("LEFT"));
  s.apply(key("LEFT"));
  s.apply(key("LEFT"));
  EXPECT_EQ(valueOf(s, "sun.azimuth_deg"), "355");  // wraps at 0
  const Scene moved = withOverrides(kSea, s);
  EXPECT_NEAR(moved.sun.zenith * 180 / M_PI, 89, 1e-12);
}

TEST(PreviewSettings, DifferencesListOnlyWhatDiffers) {
  PreviewSettings s(parseScene(kSea, "t.toml"));
  EXPECT_EQ(s.differences(), "");
  s.apply(key("UP"));
  EXPECT_EQ(s.differences(), "sun.zenith_deg=35");
  s.apply(key("DOWN"));  // back to the scene's 40: still told to the renderer, no longer listed
  EXPECT_EQ(s.differences(), "");
  EXPECT_EQ(valueOf(s, "sun.zenith_deg"), "40");
}

TEST(PreviewSettings, WaterTypeCyclesThroughJerlovTypes) {
  PreviewSettings s(parseScene(kSea, "t.toml"));
  s.apply(key("RIGHT_BRACKET"));
  EXPECT_EQ(valueOf(s, "water.jerlov"), "\"II\"");
  s.apply(key("LEFT_BRACKET"));
  s.apply(key("LEFT_BRACKET"));
  EXPECT_EQ(valueOf(s, "water.jerlov"), "\"IA\"");
  s.apply(key("LEFT_BRACKET"));
  s.apply(key("LEFT_BRACKET"));  // before "I" comes the last type
  EXPECT_EQ(withOverrides(kSea, s).water.jerlov, "9C");
}

TEST(PreviewSettings, WavelengthCountHalvesAndDoubles) {
  PreviewSettings s(parseScene(kSea, "t.toml"));  // 3 bands
  s.apply(key("EQUAL"));
  EXPECT_EQ(valueOf(s, "spectral.count"), "6");
  s.apply(key("MINUS"));
  s.apply(key("MINUS"));
  s.apply(key("MINUS"));
  EXPECT_EQ(valueOf(s, "spectral.count"), "1");
  EXPECT_FALSE(s.apply(key("MINUS")).changed);
}

TEST(PreviewSettings, PassSwitchesFollowThePlan) {
  PreviewSettings sea(parseScene(kSea, "t.toml"));
  ASSERT_EQ(sea.switches().size(), 3u);  // flat surface: no bottom caustics switch
  EXPECT_EQ(sea.switches()[0].key, "sea.reflection");
  sea.apply(key("1"));
  EXPECT_FALSE(withOverrides(kSea, sea).sea.reflection);
  sea.apply(key("3"));
  EXPECT_TRUE(withOverrides(kSea, sea).sea.second_order);
  EXPECT_FALSE(sea.apply(key("9")).changed);  // no ninth switch

  PreviewSettings under(parseScene(kUnderwater, "t.toml"));
  ASSERT_EQ(under.switches().size(), 3u);
  EXPECT_EQ(under.switches()[2].key, "underwater.caustics");
  under.apply(key("3"));
  EXPECT_EQ(withOverrides(kUnderwater, under).underwater.caustics, UnderwaterDesc::Caustics::None);
  under.apply(key("3"));
  EXPECT_EQ(withOverrides(kUnderwater, under).underwater.caustics, UnderwaterDesc::Caustics::Texture);
}

TEST(PreviewSettings, OrbitKeepsTheDistanceAndTheTarget) {
  const Scene scene = parseScene(kSea, "t.toml");
  PreviewSettings s(scene);
  s.apply({PreviewInput::Kind::Orbit, "", 300, 0});  // 90 degrees round
  const Scene moved = withOverrides(kSea, s);
  const double before = length(scene.camera.position - scene.camera.look_at);
  EXPECT_NEAR(length(moved.camera.position - moved.camera.look_at), before, 1e-9 * before);
  EXPECT_NEAR(moved.camera.look_at.z, -100, 1e-12);
  EXPECT_NEAR(moved.camera.position.y, 10, 1e-9);  // a horizontal drag keeps the height
  // Pitching past the pole stops at 89 degrees.
  s.apply({PreviewInput::Kind::Orbit, "", 0, 1000});
  const Scene top = withOverrides(kSea, s);
  const Vec3 offset = top.camera.position - top.camera.look_at;
  EXPECT_NEAR(std::asin(offset.y / length(offset)) * 180 / M_PI, 89, 1e-9);
}

TEST(PreviewSettings, FlyAndDepthMoveCameraAndTarget) {
  PreviewSettings s(parseScene(kUnderwater, "t.toml"));
  s.apply(key("PAGE_DOWN"));
  s.apply(key("I"));  // forward: 5 % of the 10 m to the target
  const Scene moved = withOverrides(kUnderwater, s);
  EXPECT_NEAR(moved.camera.position.y, -5.5, 1e-12);
  EXPECT_NEAR(moved.camera.look_at.y, -5.5, 1e-12);
  EXPECT_NEAR(moved.camera.position.z, -0.5, 1e-12);
  EXPECT_NEAR(moved.camera.look_at.z, -10.5, 1e-12);
  s.apply({PreviewInput::Kind::Zoom, "", 0, 1});  // 10 % closer
  const Scene zoomed = withOverrides(kUnderwater, s);
  EXPECT_NEAR(length(zoomed.camera.look_at - zoomed.camera.position), 9.0, 1e-9);
}

TEST(PreviewSettings, TimePlaysOnlyWhereTimeMatters) {
  PreviewSettings flat(parseScene(kSea, "t.toml"));  // flat sea seen from above: nothing moves
  flat.apply(key("T"));
  EXPECT_FALSE(flat.playing());
  PreviewSettings under(parseScene(kUnderwater, "t.toml"));  // caustics scroll
  under.apply(key("SPACE"));
  EXPECT_TRUE(under.playing());
  EXPECT_TRUE(under.advanceTime(0.5));
  EXPECT_TRUE(under.advanceTime(0.25));
  EXPECT_EQ(valueOf(under, "surface.time"), "0.75");
  under.apply(key("T"));
  EXPECT_FALSE(under.advanceTime(0.5));
}

TEST(PreviewSettings, PresetCyclesThroughTheLevels) {
  PreviewSettings s(parseScene(kSea, "t.toml"));
  EXPECT_EQ(s.preset(), -1);
  for (int level = 0; level <= 3; ++level) {
    s.apply(key("Q"));
    EXPECT_EQ(s.preset(), level);
  }
  s.apply(key("Q"));
  EXPECT_EQ(s.preset(), -1);
  EXPECT_TRUE(s.apply(key("S")).screenshot);
  EXPECT_TRUE(s.apply(key("ESCAPE")).quit);
}

TEST(SceneWriter, SavedSceneReadsBackToTheSameSceneFromAnotherFolder) {
  const fs::path dir = fs::temp_directory_path() / "seasim_scene_writer_test";
  fs::remove_all(dir);
  fs::create_directories(dir / "a");
  const std::string src = (dir / "a" / "sky.toml").string();
  // A relative image path: the saved copy, in another folder, must still find it.
  std::ofstream(src) << "[scene]\nname = \"s\"  # comment\n[camera]\nposition = [0, 10, 0]\nlook_at = [0, 0, -100]\n"
                        "[sun]\nzenith_deg = 40\n[water]\njerlov = \"IB\"\n[sky]\nmodel = \"image\"\nimage = \"sky.exr\"\n";
  std::ofstream(dir / "a" / "sky.exr") << "x";
  PreviewSettings s(loadScene(src));
  s.apply(key("UP"));
  s.apply({PreviewInput::Kind::Orbit, "", 17, 3});
  const std::string out = (dir / "b" / "saved.toml").string();
  writeSceneWithOverrides(src, s.overrides(), out);
  const Scene expected = loadScene(src, s.overrides());
  const Scene saved = loadScene(out);
  EXPECT_EQ(saved.sun.zenith, expected.sun.zenith);
  EXPECT_EQ(saved.camera.position.x, expected.camera.position.x);  // bit for bit: shortest round-trip text
  EXPECT_EQ(saved.camera.position.z, expected.camera.position.z);
  EXPECT_EQ(saved.sky.image, (dir / "a" / "sky.exr").string());
  EXPECT_EQ(saved.name, "s");
  fs::remove_all(dir);
}

}  // namespace
