#include "quality/shafts_method_auto.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include "passes/shafts_pass.h"
#include "plan/plan.h"
#include "plan/scene_facts.h"
#include "quality/quality_search.h"
#include "quality/shafts_auto.h"
#include "reference/compare.h"
#include "reference/shafts_reference.h"
#include "util/error.h"
#include "util/hash.h"
#include "util/paths.h"

namespace seasim {

namespace {

// Bump when the search or its pick rule changes meaning, so old cache entries are not reused.
constexpr const char* kMethodVersion = "shafts-method-auto 1";

const std::vector<int> kMarchSteps = {5, 10, 20, 40, 80, 160};
const std::vector<int> kPlanes = {8, 10, 15, 20, 30, 40, 60, 80, 120, 160, 200};
const std::vector<int> kSubplanes = {1, 2, 3, 4, 6, 8, 12, 16, 25};

// The planes' work per pixel up to a constant, and the margin beyond which a setting cannot be
// cheaper than one within budget (shafts_auto.cpp derives both).
double planesWork(int n, int m) { return double(n) * (m + 1); }
constexpr double kWorkMargin = 1.5;

// The ladder of a count knob: its value when the scene gives a number, else the options' list or
// the default, sorted, without duplicates or values below 1.
std::vector<int> ladder(const Scene& scene, const char* name, const std::vector<int>& given,
                        const std::vector<int>& fallback) {
  const auto it = scene.quality.find(name);
  if (it != scene.quality.end() && it->second.given && !it->second.automatic) return {static_cast<int>(it->second.value)};
  std::vector<int> v = given.empty() ? fallback : given;
  v.erase(std::remove_if(v.begin(), v.end(), [](int x) { return x < 1; }), v.end());
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  if (v.empty()) throw RuntimeError("shafts method search: the candidate list of '" + std::string(name) + "' is empty");
  return v;
}

std::string describe(Device& device, const Scene& scene, const ShaftsMethodOptions& o) {
  std::ostringstream s;
  s.precision(17);
  s << kMethodVersion << '\n' << shaftsSearchInputs(device, scene, false);
  for (const char* k : {"shafts_march_steps", "shafts_panel_deg", "shafts_panel_texels"}) {
    const auto it = scene.quality.find(k);
    s << "knob " << k << ' '
      << (it == scene.quality.end() ? std::string("-")
                                     : std::to_string(it->second.value) + (it->second.given ? " given" : ""))
      << '\n';
  }
  for (const char* k : {"shafts_planes", "shafts_subplanes"}) {
    const auto it = scene.quality.find(k);
    s << "given " << k << ' ' << (it != scene.quality.end() && it->second.given) << '\n';
  }
  s << "search " << o.budget_levels << ';' << o.reference_steps << ';' << o.downscale << ';' << o.min_long_side
    << ';' << o.max_long_side;
  for (const auto* list : {&o.march_steps, &o.planes, &o.subplanes}) {
    s << ";";
    for (int x : *list) s << x << ',';
  }
  s << '\n';
  return s.str();
}

ShaftsMethod methodFromName(const std::string& name) {
  if (name == "intervals") return ShaftsMethod::Intervals;
  if (name == "march") return ShaftsMethod::March;
  if (name == "planes") return ShaftsMethod::Planes;
  throw std::invalid_argument("unknown method " + name);
}

bool readCache(const std::string& path, ShaftsMethodChoice& r) {
  const std::map<std::string, std::string> kv = readCacheEntries(path);
  if (kv.empty()) return false;
  try {
    ShaftsMethodCandidate& c = r.chosen;
    c.method = methodFromName(kv.at("method"));
    c.planes = std::stoi(kv.at("planes"));
    c.subplanes = std::stoi(kv.at("subplanes"));
    c.march_steps = std::stoi(kv.at("march_steps"));
    c.rmse_8bit = std::stod(kv.at("rmse_8bit"));
    c.shadow_ms = std::stod(kv.at("shadow_ms"));
    c.pixel_ms = std::stod(kv.at("pixel_ms"));
    c.predicted_ms = std::stod(kv.at("predicted_ms"));
    r.met_budget = kv.at("met_budget") == "1";
    r.search_width = std::stoi(kv.at("search_width"));
    r.search_height = std::stoi(kv.at("search_height"));
  } catch (const std::exception&) {
    return false;  // a damaged or older entry: search again and overwrite it
  }
  const ShaftsMethodCandidate& c = r.chosen;
  return (c.method != ShaftsMethod::Planes || (c.planes >= 1 && c.subplanes >= 1)) &&
         (c.method != ShaftsMethod::March || c.march_steps >= 1);
}

void writeCache(const std::string& path, const ShaftsMethodChoice& r, const std::string& description) {
  std::ostringstream s;
  s.precision(17);
  const ShaftsMethodCandidate& c = r.chosen;
  s << "method " << shaftsMethodName(c.method) << "\nplanes " << c.planes << "\nsubplanes " << c.subplanes
    << "\nmarch_steps " << c.march_steps << "\nrmse_8bit " << c.rmse_8bit << "\nshadow_ms " << c.shadow_ms
    << "\npixel_ms " << c.pixel_ms << "\npredicted_ms " << c.predicted_ms << "\nmet_budget " << (r.met_budget ? 1 : 0)
    << "\nsearch_width " << r.search_width << "\nsearch_height " << r.search_height << '\n';
  s << "# candidates: setting | rmse_8bit | shadow_ms pixel_ms at the search size | predicted_ms\n";
  for (const auto& x : r.candidates)
    s << "# " << describeShaftsSetting(x) << " | " << x.rmse_8bit << " | " << x.shadow_ms << ' ' << x.pixel_ms << " | "
      << x.predicted_ms << (x.timed_at_full_size ? " (timed at full size)" : "") << '\n';
  writeCacheEntries(path, "seasim shafts method (host/quality/shafts_method_auto.h)", description, s.str());
}

// Renders and judges the candidates of the search at its reduced size against one reference.
class MethodSearch {
 public:
  MethodSearch(Device& device, const Scene& small, double pixel_ratio, const Image& reference, double budget)
      : device_(device), small_(small), pixel_ratio_(pixel_ratio), reference_(reference), budget_(budget) {}

  // Renders `c` (method and setting filled in), fills its error and times, keeps it; returns whether it
  // settles its method's ladder: within budget, or at the error floor — no better than the best
  // candidate before it by more than kErrorFloorTolerance (more work there buys nothing the floor allows).
  bool measure(ShaftsMethodCandidate& c) {
    const Scene scene = withShaftsMethod(small_, c);
    const Plan plan = makePlan(scene);
    const PassPlan* entry = plan.find("shafts");
    if (entry == nullptr) throw RuntimeError("shafts method search: the scene plans no shafts pass");
    ShaftsPass pass(device_, scene, *entry, ShaftsPass::configFromScene(scene));
    const int method = static_cast<int>(c.method);
    if (!warmed_[method]) {
      (void)pass.run();  // PoCL compiles each method's kernels at their first launch
      warmed_[method] = true;
    }
    (void)pass.run();
    c.shadow_ms = pass.shadowMapMs();
    c.pixel_ms = pass.shaftsMs();
    Image img;
    img.resize(small_.camera.width, small_.camera.height, 3);
    pass.readRgb(img.pixels);
    const CompareResult cmp = compareImages(img, reference_, small_.camera.exposure_ev);
    if (cmp.nonfinite > 0)
      throw RuntimeError("shafts method search: " + describeShaftsSetting(c) + " produced NaN/Inf values");
    c.rmse_8bit = cmp.rmse_8bit;
    const bool at_floor = atErrorFloor(c.rmse_8bit, least_error_);
    least_error_ = least_error_ < 0 ? c.rmse_8bit : std::min(least_error_, c.rmse_8bit);
    const bool settles = c.rmse_8bit <= budget_ || at_floor;
    if (settles) {
      // The times that decide: the least of three (other work on a shared machine only adds time).
      for (int i = 0; i < 2; ++i) {
        (void)pass.run();
        c.shadow_ms = std::min(c.shadow_ms, pass.shadowMapMs());
        c.pixel_ms = std::min(c.pixel_ms, pass.shaftsMs());
      }
    }
    c.predicted_ms = c.shadow_ms + c.pixel_ms * pixel_ratio_;
    candidates.push_back(c);
    return settles;
  }

  std::vector<ShaftsMethodCandidate> candidates;

 private:
  Device& device_;
  const Scene& small_;
  double pixel_ratio_;
  const Image& reference_;
  double budget_;
  double least_error_ = -1;  // of the candidates before (-1: none yet)
  bool warmed_[3] = {false, false, false};
};

// The finalists — the candidates the pick rule admits (within budget, else at the floor) whose
// predicted time is within kFinalistMargin of the least — timed again at the scene's own size, their
// predicted_ms replaced by the least of three runs there. The per-pixel time does not scale with the
// pixels alone: stage's planes at n = 10, m = 1 take 8.1 ms at 180x120 and 65.7 ms at 720x480, 0.51 of
// the 16x the pixel ratio predicts, the march at 10 steps 0.85 of it.
constexpr double kFinalistMargin = 1.5;
constexpr int kMaxFinalists = 4;

void timeFinalistsAtFullSize(Device& device, const Scene& scene, double budget,
                             std::vector<ShaftsMethodCandidate>& candidates) {
  if (candidates.empty()) return;
  double least = candidates.front().rmse_8bit;
  for (const auto& c : candidates) least = std::min(least, c.rmse_8bit);
  const double bar = least <= budget ? budget : errorFloorBar(least);
  std::vector<ShaftsMethodCandidate*> admitted;
  for (auto& c : candidates)
    if (c.rmse_8bit <= bar) admitted.push_back(&c);
  std::sort(admitted.begin(), admitted.end(),
            [](const ShaftsMethodCandidate* a, const ShaftsMethodCandidate* b) { return a->predicted_ms < b->predicted_ms; });
  const double cut = admitted.front()->predicted_ms * kFinalistMargin;
  for (size_t i = 0; i < admitted.size() && i < size_t(kMaxFinalists) && admitted[i]->predicted_ms <= cut; ++i) {
    ShaftsMethodCandidate& c = *admitted[i];
    const Scene full = withShaftsMethod(scene, c);
    const Plan plan = makePlan(full);
    ShaftsPass pass(device, full, *plan.find("shafts"), ShaftsPass::configFromScene(full));
    (void)pass.run();  // buffers and the first launch at this size
    double ms = -1;
    for (int k = 0; k < 3; ++k) {
      const double t = pass.run();
      ms = ms < 0 ? t : std::min(ms, t);
    }
    c.predicted_ms = ms;
    c.timed_at_full_size = true;
  }
}

}  // namespace

const char* shaftsMethodName(ShaftsMethod method) {
  switch (method) {
    case ShaftsMethod::Intervals: return "intervals";
    case ShaftsMethod::March: return "march";
    case ShaftsMethod::Planes: return "planes";
  }
  return "?";
}

std::string describeShaftsSetting(const ShaftsMethodCandidate& c) {
  switch (c.method) {
    case ShaftsMethod::March: return "march, " + std::to_string(c.march_steps) + " steps";
    case ShaftsMethod::Planes:
      return "planes, n = " + std::to_string(c.planes) + ", m = " + std::to_string(c.subplanes);
    case ShaftsMethod::Intervals: break;
  }
  return "intervals";
}

int pickShaftsMethod(const std::vector<ShaftsMethodCandidate>& candidates, double budget) {
  if (candidates.empty()) return -1;
  double least = candidates.front().rmse_8bit;
  for (const auto& c : candidates) least = std::min(least, c.rmse_8bit);
  const double bar = least <= budget ? budget : errorFloorBar(least);
  int best = -1;
  for (int i = 0; i < static_cast<int>(candidates.size()); ++i) {
    const ShaftsMethodCandidate& c = candidates[i];
    if (!(c.rmse_8bit <= bar)) continue;
    if (best < 0) {
      best = i;
      continue;
    }
    const ShaftsMethodCandidate& b = candidates[best];
    if (c.predicted_ms != b.predicted_ms ? c.predicted_ms < b.predicted_ms : c.rmse_8bit < b.rmse_8bit) best = i;
  }
  return best;
}

bool shaftsMethodMeasured(const Scene& scene) {
  const auto it = scene.quality.find("shafts_method");
  return it != scene.quality.end() && it->second.automatic && it->second.given && spotlightsInAir(scene) &&
         scene.air.present;
}

Scene withShaftsMethod(const Scene& scene, const ShaftsMethodCandidate& chosen) {
  Scene s = scene;
  s.quality["shafts_method"] = Knob{false, static_cast<double>(static_cast<int>(chosen.method)), true};
  if (chosen.method == ShaftsMethod::March) s.quality["shafts_march_steps"] = Knob{false, double(chosen.march_steps), true};
  if (chosen.method == ShaftsMethod::Planes) {
    s.quality["shafts_planes"] = Knob{false, double(chosen.planes), true};
    s.quality["shafts_subplanes"] = Knob{false, double(chosen.subplanes), true};
  }
  return s;
}

std::string shaftsMethodKey(Device& device, const Scene& scene, const ShaftsMethodOptions& options) {
  return hex64(fnv1a64(describe(device, scene, options)));
}

std::optional<ShaftsMethodChoice> chooseShaftsMethod(Device& device, const Scene& scene,
                                                     const ShaftsMethodOptions& options) {
  if (!(options.budget_levels > 0)) throw RuntimeError("shafts method search: the error budget must be > 0 levels");
  if (options.reference_steps < 1) throw RuntimeError("shafts method search: reference_steps must be at least 1");
  ShaftsMethodChoice result;
  result.budget_levels = options.budget_levels;
  std::string description, cache_file;
  if (options.use_cache) {
    description = describe(device, scene, options);
    cache_file = searchCacheFile(options.cache_dir, "shafts_auto", "method_", description);
    if (!cache_file.empty() && readCache(cache_file, result)) {
      result.from_cache = true;
      result.cache_file = cache_file;
      return result;
    }
  }
  if (!options.search) return std::nullopt;

  const auto t0 = std::chrono::steady_clock::now();
  Scene small = scene;
  searchResolution(scene.camera, options.downscale, options.min_long_side, options.max_long_side, small.camera.width,
                   small.camera.height);
  result.search_width = small.camera.width;
  result.search_height = small.camera.height;
  const double pixel_ratio = double(scene.camera.width) * scene.camera.height /
                             (double(small.camera.width) * small.camera.height);
  const Image reference = renderShaftsReference(small, options.reference_steps);
  MethodSearch search(device, small, pixel_ratio, reference, options.budget_levels);

  if (static_cast<int>(scene.objects.size()) <= kShaftsIntervalsMaxObjects) {
    ShaftsMethodCandidate c;
    c.method = ShaftsMethod::Intervals;
    search.measure(c);
  }
  for (int steps : ladder(scene, "shafts_march_steps", options.march_steps, kMarchSteps)) {
    ShaftsMethodCandidate c;
    c.method = ShaftsMethod::March;
    c.march_steps = steps;
    if (search.measure(c)) break;  // ascending: more steps only cost more
  }
  struct Setting {
    int n, m;
  };
  std::vector<Setting> settings;
  for (int n : ladder(scene, "shafts_planes", options.planes, kPlanes))
    for (int m : ladder(scene, "shafts_subplanes", options.subplanes, kSubplanes)) settings.push_back({n, m});
  std::stable_sort(settings.begin(), settings.end(),
                   [](const Setting& a, const Setting& b) { return planesWork(a.n, a.m) < planesWork(b.n, b.m); });
  double best_work = 0, best_ms = 0;  // the cheapest planes setting that settles so far (0: none)
  for (const Setting& st : settings) {
    if (best_work > 0 && planesWork(st.n, st.m) > kWorkMargin * best_work) break;
    ShaftsMethodCandidate c;
    c.method = ShaftsMethod::Planes;
    c.planes = st.n;
    c.subplanes = st.m;
    if (search.measure(c) && (best_work == 0 || c.predicted_ms < best_ms)) {
      best_work = planesWork(st.n, st.m);
      best_ms = c.predicted_ms;
    }
  }

  result.candidates = search.candidates;
  timeFinalistsAtFullSize(device, scene, options.budget_levels, result.candidates);
  const int pick = pickShaftsMethod(result.candidates, options.budget_levels);
  if (pick < 0) throw RuntimeError("shafts method search: no candidate settings");
  result.chosen = result.candidates[pick];
  result.met_budget = result.chosen.rmse_8bit <= options.budget_levels;
  result.search_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (!cache_file.empty()) {
    writeCache(cache_file, result, description);
    result.cache_file = cache_file;
  }
  return result;
}

std::optional<ShaftsMethodCandidate> measuredShaftsMethod(Device& device, const Scene& scene) {
  if (!shaftsMethodMeasured(scene)) return std::nullopt;
  ShaftsMethodOptions options;
  const auto budget = scene.quality.find("shafts_error_budget");
  if (budget != scene.quality.end()) options.budget_levels = budget->second.value;
  const std::optional<ShaftsMethodChoice> r = chooseShaftsMethod(device, scene, options);
  if (!r) return std::nullopt;  // not reached: the search runs when nothing is cached
  if (!r->from_cache) {
    std::fprintf(stderr,
                 "shafts: method auto: %s, RMS %.3f levels vs the ray-marched reference at %dx%d (budget %g), "
                 "predicted %.1f ms at %dx%d; %zu settings searched in %.1f s%s%s\n",
                 describeShaftsSetting(r->chosen).c_str(), r->chosen.rmse_8bit, r->search_width, r->search_height,
                 r->budget_levels, r->chosen.predicted_ms, scene.camera.width, scene.camera.height,
                 r->candidates.size(), r->search_ms * 1e-3, r->cache_file.empty() ? "" : ", cached in ",
                 r->cache_file.c_str());
  }
  if (!r->met_budget) {
    std::fprintf(stderr,
                 "shafts: warning: no method reaches RMS %g levels on '%s'; using the cheapest at the error floor, %s "
                 "(%.3f levels). Raise quality.shafts_error_budget, or quality.shadow_map_size for the planes\n",
                 r->budget_levels, scene.name.c_str(), describeShaftsSetting(r->chosen).c_str(), r->chosen.rmse_8bit);
  }
  return r->chosen;
}

std::optional<Scene> sceneWithMeasuredShaftsMethod(Device& device, const Scene& scene) {
  const std::optional<ShaftsMethodCandidate> chosen = measuredShaftsMethod(device, scene);
  if (!chosen) return std::nullopt;
  return withShaftsMethod(scene, *chosen);
}

std::vector<Override> shaftsMethodOverrides(const ShaftsMethodCandidate& chosen) {
  const SourceLoc at{"<quality.shafts_method = \"auto\": measured>", 0};
  std::vector<Override> out = {{"quality.shafts_method", std::string("\"") + shaftsMethodName(chosen.method) + "\"", at}};
  if (chosen.method == ShaftsMethod::March)
    out.push_back({"quality.shafts_march_steps", std::to_string(chosen.march_steps), at});
  if (chosen.method == ShaftsMethod::Planes) {
    out.push_back({"quality.shafts_planes", std::to_string(chosen.planes), at});
    out.push_back({"quality.shafts_subplanes", std::to_string(chosen.subplanes), at});
  }
  return out;
}

}  // namespace seasim
