// preview_quality.h — the preview's quality levels and its frame-time budget (responsive
// while the view moves, then accurate). Level 3 is the scene's own quality; each level below halves
// the numeric [quality] knobs again (sampling planes, froxel slices, depth planes and directions, map
// and table sizes; never below a floor, "auto" knobs left alone; the shafts intervals' panel widths
// double instead, up to a ceiling), levels 1 and 0 also render at 1/2
// and 1/4 of the width and height (the window scales the image up), and the wavelength count is
// halved per level down to 3 bands. Unit-tested in tests/unit/preview_quality_test.cpp; the error of
// each level against level 3 is measured by tests/perf/preview_levels.sh (results/BENCHMARKS.md).
#pragma once
#include <array>
#include <string>
#include <vector>

#include "scene/scene.h"
#include "scene/scene_parser.h"

namespace seasim {

constexpr int kPreviewLevels = 4;
constexpr int kPreviewFullLevel = kPreviewLevels - 1;
// The default frame-time budget while the view moves: 25 frames a second, the rate at which a moving
// view reads as motion rather than as a slide show. Full quality follows when the view stops.
constexpr double kPreviewMovingBudgetMs = 40.0;

// The overrides that render `scene` at `level` (0..3). Every level names the same keys, so going back
// to level 3 sets them to the scene's own values.
std::vector<Override> qualityLevelOverrides(const Scene& scene, int level);

// Chooses the level of the next frame from the frame times measured so far.
//   moving: the highest level whose predicted time fits the budget (the last time measured at that
//           level, else the nearest lower level's time x 4 per level up; level 1 when nothing is known).
//           Only frames at the same level as the frame before count: the frame that switches level
//           also sets passes up again (tables, FFT plans), which a moving view at that level does not
//           pay each frame. A time kStaleFrames frames old is forgotten, so a level measured once in a
//           slow moment is tried again;
//   still:  one level above the last one shown, up to level 3 (refining step by step).
// A budget of 0 or less means no budget: always level 3.
class QualityBudget {
 public:
  explicit QualityBudget(double budget_ms) : budget_ms_(budget_ms) {}
  int next(bool moving) const;
  // The frame just shown and its time (counted only when the level is the previous frame's).
  void record(int level, double frame_ms);
  double predictedMs(int level) const;  // 0 when nothing is known
  static constexpr long kStaleFrames = 8;

 private:
  double budget_ms_;
  std::array<double, kPreviewLevels> ms_{};  // last measured frame time per level, 0 = not yet
  std::array<long, kPreviewLevels> measured_at_{};  // frame count when measured
  long frames_ = 0;
  int shown_ = -1;
};

// "level 2/3 (moving)" for the window title.
std::string levelText(int level, bool moving, bool fixed_preset);

}  // namespace seasim
