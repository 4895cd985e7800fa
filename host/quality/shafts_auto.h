// shafts_auto.h — `auto` quality for the spotlight shafts (paper 001): the cheapest (n, m) — n
// sampling planes (001 eq. 5), m sub-sample planes (001 eq. 7–9) — whose RMS error is under a
// budget in 8-bit display levels ([quality] shafts_error_budget, default 1 level of 255). Paper
// 001 fixes n = 30, m = 6 by hand and leaves the automatic choice as future work.
//
// The search renders the scene at reduced resolution (1/4 per side, the long side kept within
// [64, 192] pixels, never above the scene's own size) for a ladder of (n, m) candidates, and compares
// each with the CPU double ray-marched reference (host/reference/shafts_reference.h, 4000 steps) in
// 8-bit levels after the PNG's tone map (host/reference/compare.h, io/tonemap.h), as `seasim sweep`
// does. Why the ray marcher and not a high-quality proxy of the fast method (n = 200, m = 25): the
// budget is an error against the truth, and the proxy shares the method's own bias (shadow-map
// texels, table interpolation): on stage.toml (n = 200, m = 25) is itself 0.39 levels from the
// reference, 2/5 of the default budget, so a setting "within 1 level of the proxy" may be 1.4
// levels from the truth. At 180x120 the reference is also the cheaper of the two on PoCL (stage:
// 2.2 s for 4000 steps vs 4.0 s for the proxy; spot_sphere 0.6 s vs 0.5 s); 4000 steps are
// within 0.06 levels of 12000 on both example scenes at that size.
//
// Candidates are tried in increasing work n (m + 1) (per pixel: m shadow/light-map lookups and
// one g per plane); once a candidate meets the budget, candidates with more than 1.5 x its work
// are skipped: for any per-plane/per-sub-plane cost ratio in [0.5, 2] they cannot be cheaper
// (see shafts_auto.cpp). Each candidate's kernel time (shadow maps + shafts, OpenCL profiling) is
// measured once, and three times (the least: load only adds time) when it meets the budget, since
// those times decide.
// When no candidate meets the budget (the error floor is set by shadow_map_size or the table
// size, not by n and m), the cheapest at the floor (within 2 % of the least error, quality_search.h)
// is taken and met_budget is false; the ladder stops at the floor as at the budget.
//
// The decision is cached on disk, keyed by a hash of everything that changes it: the scene as the
// shafts pass sees it (camera, air, lights with their light-map bytes, objects, the other shafts
// knobs, the budget, the fixed knob when only one is "auto"), the sampling-plane range, the search
// settings, the kernel source and the device name. Folder: $SEASIM_CACHE_DIR/shafts_auto, else
// $XDG_CACHE_HOME/seasim/shafts_auto, else ~/.cache/seasim/shafts_auto (like the kernel binaries).
// A batch job over many frames of one scene pays the search once.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "device/device.h"
#include "passes/shafts_pass.h"
#include "plan/plan.h"
#include "scene/scene.h"

namespace seasim {

struct ShaftsAutoOptions {
  double budget_levels = 1.0;     // RMS budget in 8-bit levels (scene: quality.shafts_error_budget)
  int reference_steps = 4000;     // ray-march steps of the reference at the search resolution
  int downscale = 4;              // search image = scene image / downscale per side ...
  int min_long_side = 64;         // ... with the long side kept in [min_long_side, max_long_side]
  int max_long_side = 192;        //     (and never larger than the scene's own)
  // (n, m) ladder; empty: n in {8, 10, 15, 20, 30, 40, 60, 80, 120, 160, 200} x m in {1, 2, 3, 4,
  // 6, 8, 12, 16, 25}. A knob that is not "auto" in the scene fixes its value instead.
  std::vector<int> planes, subplanes;
  bool use_cache = true;
  std::string cache_dir;          // "" = the default folder above
};

struct ShaftsAutoCandidate {
  int planes = 0, subplanes = 0;
  double rmse_8bit = 0;           // vs the reference, 8-bit levels
  double ms = 0;                  // kernel ms at the search resolution (least of 3 when in budget)
};

struct ShaftsAutoResult {
  int planes = 30, subplanes = 6;
  double rmse_8bit = 0, ms = 0;   // of the chosen setting, at the search resolution
  double budget_levels = 1.0;
  bool met_budget = false;        // false: nothing met the budget; the cheapest at the floor was taken
  bool from_cache = false;        // true: read from the cache, no rendering done
  int search_width = 0, search_height = 0;
  double search_ms = 0;           // wall time of the search (0 from the cache)
  std::vector<ShaftsAutoCandidate> candidates;  // evaluated, in the order tried (empty from cache)
  std::string cache_file;         // "" when not cached
};

// The pick rule on a table of evaluated candidates: the lowest ms among those with
// rmse_8bit <= budget; when none qualifies, among those at the error floor (errorFloorBar of the
// least error, quality_search.h). Ties: fewer n (m + 1), then lower error. Returns the index; -1 for
// an empty table.
int pickShaftsCandidate(const std::vector<ShaftsAutoCandidate>& candidates, double budget_levels);

// Searches (or reads from the cache) the cheapest (n, m) for `scene` under options.budget_levels.
// `plan` is the "shafts" pass of makePlan(scene). Scenes the reference does not model (height-field
// objects, no [air]) throw RuntimeError.
ShaftsAutoResult chooseShaftsQuality(Device& device, const Scene& scene, const PassPlan& plan,
                                     const ShaftsAutoOptions& options);

// The settings ShaftsPass gets (through quality/auto_quality.h): ShaftsPass::configFromScene, and
// when shafts_planes or shafts_subplanes is "auto", the cheapest (n, m) whose RMS error is under
// quality.shafts_error_budget (chooseShaftsQuality). Prints one line to stderr when it searched, and
// a warning when nothing met the budget.
ShaftsPass::Config shaftsConfigWithAuto(Device& device, const Scene& scene, const PassPlan& plan);

// What every shafts search's decision depends on besides its own settings, as text for its cache key:
// the device and driver, the kernel source, the camera, the air, the lights with their light maps' and
// spectra's checksums, the objects, the shafts knobs and the planes' table ranges — the camera's pose
// and the ranges (which follow from it) only when camera_pose.
std::string shaftsSearchInputs(Device& device, const Scene& scene, bool camera_pose);

// The cache key of the search (hex FNV-1a 64 of the inputs listed above), for tests and reports.
std::string shaftsAutoKey(Device& device, const Scene& scene, const ShaftsAutoOptions& options);

}  // namespace seasim
