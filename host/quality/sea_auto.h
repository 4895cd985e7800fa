// sea_auto.h — `auto` quality for the sea's second-order scattering (paper 000 §6.1): per scene, the
// number of sampling planes n_z, of sampling directions n_d and the scattering-map resolution M.
//
// The measure is the paper's: render the frame (single + second order, the image a user sees) at
// settings s and next(s) and take the maximum difference over pixels and R, G, B in 8-bit display
// levels after the PNG's tone map (reference/compare.h max_abs_8bit, as `seasim sweep` reports in its
// max_diff_prev_8bit column); a knob's value is the first s on its ladder where that difference is
// under the threshold (000: epsilon = 1/255, i.e. 1 level). Ladders: n_z = 1, 2, 3, ... (n vs n + 1,
// the paper's Fig. 7), n_d = 32, 64, 128, ... 2048 and M = 16, 32, 64, 128 (each vs the next rung:
// doubling steps, since the direction grid's error is not monotonic in n_d one step at a time, see
// results/sea/open_ocean_nd.csv). The knobs interact, so the search goes round the three (n_z at the
// current n_d and M, then n_d, then M) until a round changes nothing — then each chosen value meets
// the criterion at the final values of the other two (converged = true); at most max_rounds rounds.
// A knob fixed in the scene keeps its value and is not searched.
//
// The frames are rendered at reduced resolution (1/4 per side, the long side kept in [64, 192] and
// never above the scene's own): the maps' cost does not depend on the image size, and the image is
// only the set of view directions the maximum is taken over. Each setting is rendered once
// (memoised); on open_ocean (16 bands) the search costs about two seconds on the 2-core PoCL machine.
//
// The decision is cached on disk keyed by a hash of everything it depends on (the scene as the sea
// passes see it, the knobs, the search options, both kernel sources and the device):
// $SEASIM_CACHE_DIR/sea_auto, else $XDG_CACHE_HOME/seasim/sea_auto, else ~/.cache/seasim/sea_auto.
#pragma once
#include <string>
#include <vector>

#include "device/device.h"
#include "passes/sea_second_pass.h"
#include "plan/plan.h"
#include "scene/scene.h"

namespace seasim {

struct SeaAutoOptions {
  double threshold_levels = 1.0;  // 000 §6.1: epsilon = 1/255 of the display range
  int max_nz = 48;                // n_z ladder 1 .. max_nz
  std::vector<int> nd_ladder = {32, 64, 128, 256, 512, 1024, 2048};
  std::vector<int> map_ladder = {16, 32, 64, 128};
  int start_nz = 8, start_nd = 512;  // first values of auto knobs (start_map: 32 flat, 64 height field)
  int max_rounds = 3;
  int downscale = 4;              // search image = scene image / downscale per side ...
  int min_long_side = 64;         // ... long side kept in [min_long_side, max_long_side]
  int max_long_side = 192;
  bool use_cache = true;
  std::string cache_dir;          // "" = the default folder above
};

// One measurement: the step from (n_z, n_d, map_size) to the next value of `knob` on its ladder.
struct SeaAutoStep {
  std::string knob;  // "sea_nz", "sea_nd" or "sea_map_size"
  int n_z = 0, n_d = 0, map_size = 0;
  int next = 0;      // the next value of the knob
  double max_diff_8bit = 0;
};

struct SeaAutoResult {
  int n_z = 8, n_d = 512, map_size = 32;
  double nz_step_8bit = 0, nd_step_8bit = 0, map_step_8bit = 0;  // the chosen values' own steps (0: fixed)
  bool met = false;        // every searched knob met the threshold before its ladder ran out
  bool converged = false;  // a round changed nothing: all steps hold at the final setting
  bool from_cache = false;
  int search_width = 0, search_height = 0;
  int renders = 0;         // frames rendered by the search (0 from the cache)
  double search_ms = 0;    // wall time of the search (0 from the cache)
  std::vector<SeaAutoStep> steps;  // in the order measured (empty from the cache)
  std::string cache_file;  // "" when not cached
};

// True when any of sea_nz, sea_nd, sea_map_size is "auto" in the scene.
bool seaSecondWantsAuto(const Scene& scene);

// Searches (or reads from the cache) the settings above for `scene` (a sea scene with second-order
// scattering: RuntimeError otherwise, when a frame has NaN/Inf, or when the options are invalid).
SeaAutoResult chooseSeaSecondQuality(Device& device, const Scene& scene, const SeaAutoOptions& options = {});

// The settings SeaSecondPass gets (through quality/auto_quality.h): SeaSecondPass::configFromScene
// with each "auto" knob set to the chosen value (n_d through SeaSecondPass::splitDirections); fixed
// knobs keep theirs. Prints one line to stderr after a search (not after a cache hit), and a warning
// when the threshold was not met.
SeaSecondPass::Config seaSecondConfigWithAuto(Device& device, const Scene& scene);

// The cache key (hex FNV-1a 64 of the inputs listed above).
std::string seaAutoKey(Device& device, const Scene& scene, const SeaAutoOptions& options);

}  // namespace seasim
