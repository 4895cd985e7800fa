#include "preview/preview_quality.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "preview/preview_settings.h"
#include "scene/model_keys.h"
#include "scene/toml_reader.h"
#include "util/error.h"

namespace seasim {

namespace {

// The knobs a level scales, each with the least value it may go down to.
const std::vector<std::pair<std::string, int>>& scaledKnobs() {
  static const std::vector<std::pair<std::string, int>> knobs = {
      {"sea_lut_size", 16},   {"sea_nz", 3},          {"sea_nd", 16},         {"sea_map_size", 8},
      {"shafts_planes", 6},   {"shafts_subplanes", 1}, {"shafts_table_size", 64}, {"shadow_map_size", 128},
      {"froxel_x", 20},       {"froxel_y", 12},       {"froxel_z", 8},        {"froxel_columns", 20},
      {"caustic_map_size", 64},
      {"caustic_layers", 2},  {"shafts_march_steps", 5}};
  return knobs;
}

// The intervals method's knobs (plan/shafts_method.h) work the other way: a wider quadrature panel is
// cheaper, so a level doubles them, up to a ceiling well inside the parser's range.
const std::vector<std::pair<std::string, double>>& widenedKnobs() {
  static const std::vector<std::pair<std::string, double>> knobs = {{"shafts_panel_deg", 32.0},
                                                                    {"shafts_panel_texels", 16.0}};
  return knobs;
}

// The widest lattice cell a level gives the lamps' orders model (quality.lamps_ms_cell_deg): 4°, where
// a region of the lamp study moves by a few per cent (results/BENCHMARKS.md), well inside a reduced
// level's own error against full quality; larger cells cost more again (more pixels evaluate themselves).
constexpr double kLampsCellCeilingDeg = 4.0;

// The fewest steps a level gives the orders model's view-ray sum (quality.lamps_ms_steps, 12 at full
// quality): the ray's glow, halo and orders in-scatter, about two thirds of rov_lights' lamp pass at level 0.
constexpr long kLampsStepsFloor = 3;

}  // namespace

std::vector<Override> qualityLevelOverrides(const Scene& scene, int level) {
  if (level < 0 || level > kPreviewFullLevel)
    throw RuntimeError("preview quality level " + std::to_string(level) + " is not in 0.." + std::to_string(kPreviewFullLevel));
  const int halvings = kPreviewFullLevel - level;             // knobs: 0, 1, 2, 3 halvings
  const int size_shift = level >= 2 ? 0 : (level == 1 ? 1 : 2);  // image: 1, 1, 1/2, 1/4
  const SourceLoc at{"<preview quality level " + std::to_string(level) + ">", 0};
  std::vector<Override> out;
  auto add = [&](const std::string& key, long value) { out.push_back({key, std::to_string(value), at}); };
  for (const auto& [name, floor] : scaledKnobs()) {
    const auto it = scene.quality.find(name);
    if (it == scene.quality.end() || it->second.automatic) continue;
    const long full = std::lround(it->second.value);
    add("quality." + name, std::max<long>(std::min<long>(full, floor), full >> halvings));
  }
  for (const auto& [name, ceiling] : widenedKnobs()) {
    const auto it = scene.quality.find(name);
    if (it == scene.quality.end() || it->second.automatic) continue;
    const double full = it->second.value;
    out.push_back({"quality." + name, floatText(std::max(full, std::min(ceiling, std::ldexp(full, halvings)))), at});
  }
  // The lamps' orders model evaluates its smooth part on cells of lamps_ms_cell_deg: a level that renders a
  // smaller image widens them by as much as its pixels, so that the lattice keeps its step in pixels (at
  // 1° a 160x90 image would evaluate every pixel). 0 (every pixel) stays 0.
  if (!scene.spotlights.empty()) {
    const double cell = modelKey(scene, "quality.lamps_ms_cell_deg");
    if (cell > 0)
      out.push_back({"quality.lamps_ms_cell_deg",
                     floatText(std::max(cell, std::min(kLampsCellCeilingDeg, std::ldexp(cell, size_shift)))), at});
    const long steps = std::lround(modelKey(scene, "quality.lamps_ms_steps"));
    add("quality.lamps_ms_steps", std::max(std::min(steps, kLampsStepsFloor), steps >> halvings));
  }
  add("camera.width", std::max(16, scene.camera.width >> size_shift));
  add("camera.height", std::max(9, scene.camera.height >> size_shift));
  const int bands = scene.spectral.count;
  add("spectral.count", std::max(std::min(bands, 3), bands >> halvings));
  return out;
}

double QualityBudget::predictedMs(int level) const {
  auto known = [&](int k) {
    const size_t i = static_cast<size_t>(k);
    return ms_[i] > 0 && frames_ - measured_at_[i] < kStaleFrames;
  };
  if (known(level)) return ms_[static_cast<size_t>(level)];
  for (int k = level - 1; k >= 0; --k)
    if (known(k)) return ms_[static_cast<size_t>(k)] * std::exp2(2 * (level - k));  // x4 per level
  return 0.0;
}

int QualityBudget::next(bool moving) const {
  if (!(budget_ms_ > 0)) return kPreviewFullLevel;
  if (!moving) return std::min(kPreviewFullLevel, shown_ + 1);
  int best = 0;
  bool any = false;
  for (int level = 0; level <= kPreviewFullLevel; ++level) {
    const double ms = predictedMs(level);
    if (ms > 0) any = true;
    if (ms > 0 && ms <= budget_ms_) best = level;
  }
  return any ? best : 1;
}

void QualityBudget::record(int level, double frame_ms) {
  ++frames_;
  if (level == shown_) {
    ms_[static_cast<size_t>(level)] = frame_ms;
    measured_at_[static_cast<size_t>(level)] = frames_;
  }
  shown_ = level;
}

std::string levelText(int level, bool moving, bool fixed_preset) {
  std::string text = "level " + std::to_string(level) + "/" + std::to_string(kPreviewFullLevel);
  if (fixed_preset) return text + " (preset)";
  if (level == kPreviewFullLevel) return text + " (full)";
  return text + (moving ? " (moving)" : " (refining)");
}

}  // namespace seasim
