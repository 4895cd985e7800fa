// preview_quality_test.cpp — the preview's quality levels and frame-time budget
// (host/preview/preview_quality.h).
#include <gtest/gtest.h>

#include <map>

#include "passes/underwater_lamps_pass.h"
#include "preview/preview_quality.h"
#include "scene/scene_parser.h"

namespace {

using namespace seasim;

const char* kShafts = R"(
[camera]
position = [0, 1.6, 9]
look_at = [0, 1.6, 0]
width = 720
height = 480
[air]
density = 0.04
[[spotlights]]
position = [0, 5, 0]
[quality]
shafts_planes = 30
shafts_subplanes = 6
froxel_z = "auto"
[spectral]
count = 16
)";

std::map<std::string, std::string> asMap(const std::vector<Override>& overrides) {
  std::map<std::string, std::string> out;
  for (const auto& o : overrides) out[o.key] = o.value_toml;
  return out;
}

TEST(PreviewQuality, FullLevelIsTheScenesOwnQuality) {
  const Scene scene = parseScene(kShafts, "t.toml");
  const auto full = asMap(qualityLevelOverrides(scene, kPreviewFullLevel));
  EXPECT_EQ(full.at("quality.shafts_planes"), "30");
  EXPECT_EQ(full.at("quality.shafts_subplanes"), "6");
  EXPECT_EQ(full.at("quality.shadow_map_size"), "512");  // a default, named so a lower level can go back
  EXPECT_EQ(full.at("camera.width"), "720");
  EXPECT_EQ(full.at("spectral.count"), "16");
  EXPECT_EQ(full.count("quality.froxel_z"), 0u);  // "auto" is left to its method
  // Applied to the scene, level 3 changes nothing.
  const Scene same = parseScene(kShafts, "t.toml", qualityLevelOverrides(scene, kPreviewFullLevel));
  EXPECT_EQ(same.quality.at("shafts_planes").value, 30);
  EXPECT_EQ(same.camera.height, 480);
}

TEST(PreviewQuality, EachLevelHalvesDownToAFloor) {
  const Scene scene = parseScene(kShafts, "t.toml");
  const auto l2 = asMap(qualityLevelOverrides(scene, 2));
  EXPECT_EQ(l2.at("quality.shafts_planes"), "15");
  EXPECT_EQ(l2.at("quality.shafts_subplanes"), "3");
  EXPECT_EQ(l2.at("camera.width"), "720");
  EXPECT_EQ(l2.at("spectral.count"), "8");
  const auto l1 = asMap(qualityLevelOverrides(scene, 1));
  EXPECT_EQ(l1.at("quality.shafts_planes"), "7");
  EXPECT_EQ(l1.at("camera.width"), "360");
  EXPECT_EQ(l1.at("camera.height"), "240");
  const auto l0 = asMap(qualityLevelOverrides(scene, 0));
  EXPECT_EQ(l0.at("quality.shafts_planes"), "6");  // floor 6, not 30 >> 3 = 3
  EXPECT_EQ(l0.at("quality.shafts_subplanes"), "1");
  EXPECT_EQ(l0.at("camera.width"), "180");
  EXPECT_EQ(l0.at("spectral.count"), "3");  // never below 3 bands
  // Every level is a valid scene.
  for (int level = 0; level <= kPreviewFullLevel; ++level)
    EXPECT_NO_THROW(parseScene(kShafts, "t.toml", qualityLevelOverrides(scene, level))) << level;
  EXPECT_THROW(qualityLevelOverrides(scene, 4), std::exception);
}

// The shafts' intervals method (the default for these scenes) gets cheaper with wider panels: each
// level doubles them, up to a ceiling, and a scene already past the ceiling keeps its own.
TEST(PreviewQuality, IntervalPanelsWidenPerLevelUpToACeiling) {
  const Scene scene = parseScene(kShafts, "t.toml");
  const auto full = asMap(qualityLevelOverrides(scene, kPreviewFullLevel));
  EXPECT_EQ(full.at("quality.shafts_panel_deg"), "4.0");
  EXPECT_EQ(full.at("quality.shafts_panel_texels"), "2.0");
  const auto l2 = asMap(qualityLevelOverrides(scene, 2));
  EXPECT_EQ(l2.at("quality.shafts_panel_deg"), "8.0");
  EXPECT_EQ(l2.at("quality.shafts_panel_texels"), "4.0");
  const auto l0 = asMap(qualityLevelOverrides(scene, 0));
  EXPECT_EQ(l0.at("quality.shafts_panel_deg"), "32.0");
  EXPECT_EQ(l0.at("quality.shafts_panel_texels"), "16.0");
  const Scene coarse = parseScene(kShafts, "t.toml", qualityLevelOverrides(scene, 0));
  EXPECT_DOUBLE_EQ(coarse.quality.at("shafts_panel_deg").value, 32.0);

  const Scene wide = parseScene("[quality]\nshafts_panel_deg = 45.5\nshafts_panel_texels = 0.25\n", "t.toml");
  const auto w0 = asMap(qualityLevelOverrides(wide, 0));
  EXPECT_EQ(w0.at("quality.shafts_panel_deg"), "45.5");      // past the ceiling: left as it is
  EXPECT_EQ(w0.at("quality.shafts_panel_texels"), "2.0");    // 0.25 x 2^3
  EXPECT_NO_THROW(parseScene("", "t.toml", qualityLevelOverrides(wide, 0)));
}

// The lamps' orders model's lattice cell widens as a level's image shrinks (up to 4°), so that the lattice
// keeps its step in pixels; every pixel (0) stays so, and a scene without lamps gets no such override.
TEST(PreviewQuality, LampsLatticeCellsWidenPerLevel) {
  const Scene scene = seasim::loadScene(std::string(SEASIM_SOURCE_DIR) + "/scenes/rov_lights.toml");
  EXPECT_EQ(asMap(qualityLevelOverrides(scene, kPreviewFullLevel)).at("quality.lamps_ms_cell_deg"), "1.0");
  EXPECT_EQ(asMap(qualityLevelOverrides(scene, 2)).at("quality.lamps_ms_cell_deg"), "1.0");  // full size
  EXPECT_EQ(asMap(qualityLevelOverrides(scene, 1)).at("quality.lamps_ms_cell_deg"), "2.0");  // half
  EXPECT_EQ(asMap(qualityLevelOverrides(scene, 0)).at("quality.lamps_ms_cell_deg"), "4.0");  // a quarter
  // Level 0 of its 320x180 is 80x45 at 60°: 1.33° per pixel, so 4° cells are every 3 pixels, as 1° cells
  // are at full size (1° cells would be every pixel there).
  const Scene l0 = seasim::loadScene(std::string(SEASIM_SOURCE_DIR) + "/scenes/rov_lights.toml",
                                     qualityLevelOverrides(scene, 0));
  EXPECT_EQ(seasim::lampsMsLatticeStep(l0), 3);
  const Scene every = parseScene("[quality]\nlamps_ms_cell_deg = 0\n[[spotlights]]\nposition = [0, 1, 0]\n"
                                 "direction = [0, -1, 0]\n", "t.toml");
  EXPECT_EQ(asMap(qualityLevelOverrides(every, 0)).count("quality.lamps_ms_cell_deg"), 0u);
  EXPECT_EQ(asMap(qualityLevelOverrides(parseScene("", "t.toml"), 0)).count("quality.lamps_ms_cell_deg"), 0u);
}

// The orders model's view-ray steps halve per level down to 3; a scene that asks for fewer keeps them, and a
// scene without lamps gets no such override.
TEST(PreviewQuality, LampsViewRayStepsHalvePerLevelDownToAFloor) {
  const Scene scene = seasim::loadScene(std::string(SEASIM_SOURCE_DIR) + "/scenes/rov_lights.toml");
  EXPECT_EQ(asMap(qualityLevelOverrides(scene, kPreviewFullLevel)).at("quality.lamps_ms_steps"), "12");
  EXPECT_EQ(asMap(qualityLevelOverrides(scene, 2)).at("quality.lamps_ms_steps"), "6");
  EXPECT_EQ(asMap(qualityLevelOverrides(scene, 1)).at("quality.lamps_ms_steps"), "3");
  EXPECT_EQ(asMap(qualityLevelOverrides(scene, 0)).at("quality.lamps_ms_steps"), "3");
  const Scene few = parseScene("[quality]\nlamps_ms_steps = 2\n[[spotlights]]\nposition = [0, 1, 0]\n"
                               "direction = [0, -1, 0]\n", "t.toml");
  EXPECT_EQ(asMap(qualityLevelOverrides(few, 0)).at("quality.lamps_ms_steps"), "2");
  EXPECT_NO_THROW(seasim::loadScene(std::string(SEASIM_SOURCE_DIR) + "/scenes/rov_lights.toml", qualityLevelOverrides(scene, 0)));
  EXPECT_EQ(asMap(qualityLevelOverrides(parseScene("", "t.toml"), 0)).count("quality.lamps_ms_steps"), 0u);
}

TEST(PreviewQuality, KnobsBelowTheirFloorStayAsTheyAre) {
  const Scene scene = parseScene("[quality]\nshafts_planes = 4\n[spectral]\ncount = 1\n", "t.toml");
  const auto l0 = asMap(qualityLevelOverrides(scene, 0));
  EXPECT_EQ(l0.at("quality.shafts_planes"), "4");
  EXPECT_EQ(l0.at("spectral.count"), "1");
}

TEST(QualityBudget, NoBudgetMeansFullQuality) {
  QualityBudget none(0);
  EXPECT_EQ(none.next(true), kPreviewFullLevel);
  EXPECT_EQ(none.next(false), kPreviewFullLevel);
}

// Two frames at one level: the first (a switch) sets passes up and is not counted, the second is.
void steady(QualityBudget& b, int level, double ms) {
  b.record(level, 10 * ms);
  b.record(level, ms);
}

TEST(QualityBudget, MovingPicksTheHighestLevelWithinTheBudget) {
  QualityBudget b(100);
  EXPECT_EQ(b.next(true), 1);  // nothing measured yet
  b.record(1, 5000);           // the first frame builds everything: not counted
  EXPECT_EQ(b.next(true), 1);
  b.record(1, 20);             // level 2 predicted 80 ms, level 3 320 ms
  EXPECT_DOUBLE_EQ(b.predictedMs(2), 80);
  EXPECT_DOUBLE_EQ(b.predictedMs(3), 320);
  EXPECT_EQ(b.next(true), 2);
  steady(b, 2, 150);  // slower than predicted: back to level 1
  EXPECT_EQ(b.next(true), 1);
  steady(b, 0, 10);
  steady(b, 1, 140);  // now even level 1 is over: level 0
  EXPECT_EQ(b.next(true), 0);
}

// The preview's default budget keeps a moving view at 25 frames a second or more: a level measured at
// 75 ms (ocean_noon's level 2 at 640x360 on two cores) is not chosen while moving, its 20 ms level 1 is.
TEST(QualityBudget, DefaultBudgetMovesAtTwentyFiveFramesASecond) {
  EXPECT_LE(kPreviewMovingBudgetMs, 1000.0 / 25.0);
  QualityBudget b(kPreviewMovingBudgetMs);
  steady(b, 1, 20);
  steady(b, 2, 75);
  EXPECT_EQ(b.next(true), 1);
  EXPECT_EQ(b.next(false), kPreviewFullLevel);  // the view stopped: one level above the last shown (2)
}

TEST(QualityBudget, AnOldTimeIsTriedAgain) {
  QualityBudget b(100);
  steady(b, 1, 250);  // level 1 measured in a slow moment
  EXPECT_EQ(b.next(true), 0);
  b.record(0, 50);  // the switch
  for (long i = 0; i + 1 < QualityBudget::kStaleFrames; ++i) {  // until level 1's time is 8 frames old
    EXPECT_EQ(b.next(true), 0) << i;
    b.record(0, 5);
  }
  // Level 1's 250 ms is now forgotten: predicted from level 0 (5 ms x 4 per level), a moving view
  // tries level 2 (80 ms; level 3 would be 320).
  EXPECT_DOUBLE_EQ(b.predictedMs(1), 20);
  EXPECT_EQ(b.next(true), 2);
  steady(b, 2, 400);
  EXPECT_EQ(b.next(true), 1);  // level 2 measured over budget, level 1 still predicted 20 ms
}

TEST(QualityBudget, StillRefinesOneLevelPerFrame) {
  QualityBudget b(100);
  b.record(0, 10);
  EXPECT_EQ(b.next(false), 1);
  b.record(1, 20);
  EXPECT_EQ(b.next(false), 2);
  b.record(2, 40);
  EXPECT_EQ(b.next(false), 3);
  b.record(3, 400);  // the full level is slow, but a still view is shown at it
  EXPECT_EQ(b.next(false), 3);
  b.record(3, 400);
  // Moving again: the refining frames were switches, so only level 3's time is known: the safe level 0.
  EXPECT_EQ(b.next(true), 0);
}

TEST(QualityBudget, LevelText) {
  EXPECT_EQ(levelText(1, true, false), "level 1/3 (moving)");
  EXPECT_EQ(levelText(2, false, false), "level 2/3 (refining)");
  EXPECT_EQ(levelText(3, false, false), "level 3/3 (full)");
  EXPECT_EQ(levelText(0, false, true), "level 0/3 (preset)");
}

}  // namespace
