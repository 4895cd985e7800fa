// shafts_method_auto.h — quality.shafts_method = "auto": the spotlight shafts' integrator
// (plan/shafts_method.h: the intervals, paper 001's sampling planes, the march) chosen per scene and
// device by measurement — the method and setting with the least predicted kernel time whose RMS error
// against the ray-marched reference is within quality.shafts_error_budget (8-bit display levels).
//
// Why measured and not a rule: the methods' costs cross with the budget and the scene. On PoCL
// (results/BENCHMARKS.md "Spotlight shafts in air") the planner's rule — intervals up to 15 objects,
// else planes — is within 18 % of the cheapest setting for errors up to about 0.3 levels, but at a
// 1-level budget the march at 5 steps is 2.2–2.5x cheaper on two of three scenes; on a GPU the
// planes' texture reads shift the balance again.
//
// The search renders the scene at the (n, m) search's reduced size (shafts_auto.h) against one CPU
// reference (host/reference/shafts_reference.h, 4000 steps). Candidates: the intervals at the
// scene's panel knobs (up to 15 objects); the march at 5, 10, 20, 40, 80, 160 steps, stopping at the
// first within budget (more steps only cost more); the planes' (n, m) ladder, cheapest work first,
// pruned as shafts_auto.cpp prunes it. A knob the scene gives as a number (shafts_march_steps,
// shafts_planes, shafts_subplanes) is not searched. Each candidate's predicted time at the scene's
// size is its shadow maps' time (they do not scale with the image) plus its per-pixel kernel's time
// times the ratio of pixels; the least of three runs for candidates within budget. The finalists (up to
// 4 admitted candidates predicted within 1.5x the least) are then timed at the scene's own size, where
// small images' per-launch costs no longer distort the ranking, and those times decide: the search costs
// one reference at the reduced size plus at most 16 full-size frames of settings within 1.5x the fastest
// (measured: 0.8 s on spot_sphere, 1.3-1.5 s with 21 objects, 3.7-5.6 s on stage's 5 lamps).
// When nothing meets the budget, the cheapest candidate at the error floor is taken (within 2 % of the
// least error; pickShaftsMethod) and met_budget is false; a ladder stops at the floor as at the budget.
//
// The decision is cached like the (n, m) search's (folder shafts_auto), keyed by everything it
// depends on except the camera's pose (shaftsSearchInputs(..., false)): an animation, a preview or a
// farm job that moves the camera keeps the first frame's method instead of searching per frame, and
// every frame of a shot renders with one method.
//
// Where it applies: quality/auto_quality.h gives the Renderer this choice as a plan choice, made
// before it plans, so `render`, jobs, the preview, `bench` and Python render alike. `seasim plan`
// (no device opened for rendering) shows the decision cached for the default device, else the rule's
// method with a line saying the first render measures it.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "device/device.h"
#include "plan/shafts_method.h"
#include "scene/scene.h"
#include "scene/scene_parser.h"

namespace seasim {

struct ShaftsMethodOptions {
  double budget_levels = 1.0;   // RMS budget in 8-bit levels (scene: quality.shafts_error_budget)
  int reference_steps = 4000;   // ray-march steps of the reference at the search size
  int downscale = 4;            // search size as the (n, m) search's: 1/downscale per side, ...
  int min_long_side = 64;       // ... the long side in [min_long_side, max_long_side]
  int max_long_side = 192;
  std::vector<int> march_steps;         // empty: 5, 10, 20, 40, 80, 160
  std::vector<int> planes, subplanes;   // empty: shafts_auto.h's (n, m) ladders
  bool use_cache = true;
  bool search = true;           // false: only read the cache (nullopt when nothing is cached)
  std::string cache_dir;        // "" = the shafts_auto cache folder
};

struct ShaftsMethodCandidate {
  ShaftsMethod method = ShaftsMethod::Intervals;
  int planes = 0, subplanes = 0;  // the planes' (n, m)
  int march_steps = 0;            // the march's steps
  double rmse_8bit = 0;           // against the reference at the search size, 8-bit levels
  double shadow_ms = 0;           // shadow maps at the search size (the planes with objects)
  double pixel_ms = 0;            // the per-pixel shafts kernel at the search size
  double predicted_ms = 0;        // shadow_ms + pixel_ms x (scene pixels / search pixels), or measured:
  bool timed_at_full_size = false;  // a finalist, timed at the scene's size (least of 3 runs)
};

struct ShaftsMethodChoice {
  ShaftsMethodCandidate chosen;
  double budget_levels = 1.0;
  bool met_budget = false;      // false: nothing met the budget; the cheapest at the error floor was taken
  bool from_cache = false;
  int search_width = 0, search_height = 0;
  double search_ms = 0;         // wall time of the search (0 from the cache)
  std::vector<ShaftsMethodCandidate> candidates;  // in the order tried (empty from the cache)
  std::string cache_file;
};

// "intervals", "planes" or "march", as quality.shafts_method spells them.
const char* shaftsMethodName(ShaftsMethod method);
// One line naming the method and its setting: "march, 5 steps", "planes, n = 10, m = 2", "intervals".
std::string describeShaftsSetting(const ShaftsMethodCandidate& c);

// The pick rule: the least predicted_ms among candidates with rmse_8bit <= budget (ties: the lower
// error); when none meets the budget, the same among those at the error floor (within
// kErrorFloorTolerance of the least error, quality_search.h). -1 for an empty table.
int pickShaftsMethod(const std::vector<ShaftsMethodCandidate>& candidates, double budget_levels);

// quality.shafts_method is "auto" as written (not absent) and the shafts light air (the only scenes
// the ray-marched reference models: spotlights without water).
bool shaftsMethodMeasured(const Scene& scene);

// Searches (or reads from the cache) the method for a scene where shaftsMethodMeasured holds;
// nullopt only when options.search is false and nothing is cached. Throws RuntimeError for a
// candidate that renders NaN/Inf.
std::optional<ShaftsMethodChoice> chooseShaftsMethod(Device& device, const Scene& scene,
                                                     const ShaftsMethodOptions& options);

// The scene with the chosen method and its setting written in as given knobs (no "auto" left for
// them, so the shafts pass searches nothing again).
Scene withShaftsMethod(const Scene& scene, const ShaftsMethodCandidate& chosen);

// For a scene where shaftsMethodMeasured holds, the method and setting chosen at its
// quality.shafts_error_budget (one line to stderr when it searched, a warning when nothing met the
// budget); nullopt for any other scene.
std::optional<ShaftsMethodCandidate> measuredShaftsMethod(Device& device, const Scene& scene);

// The Renderer's plan choice: withShaftsMethod(scene, measuredShaftsMethod(...)), or nullopt.
std::optional<Scene> sceneWithMeasuredShaftsMethod(Device& device, const Scene& scene);

// The choice as overrides (quality.shafts_method and the chosen method's knobs), for a caller that
// parses the scene again with more overrides: the preview's reduced levels then scale the chosen
// method's knobs instead of searching again per level.
std::vector<Override> shaftsMethodOverrides(const ShaftsMethodCandidate& chosen);

// The search's cache key (hex FNV-1a 64 of its inputs), for tests and reports.
std::string shaftsMethodKey(Device& device, const Scene& scene, const ShaftsMethodOptions& options);

}  // namespace seasim
