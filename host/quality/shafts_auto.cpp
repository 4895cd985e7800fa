#include "quality/shafts_auto.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include "device/kernel_source.h"
#include "quality/quality_search.h"
#include "passes/shafts_features.h"
#include "passes/shafts_pass.h"
#include "reference/compare.h"
#include "reference/shafts_reference.h"
#include "util/error.h"
#include "util/hash.h"
#include "util/paths.h"

namespace seasim {

namespace {

// Bump when the search or its pick rule changes meaning, so old cache entries are not reused.
constexpr const char* kAutoVersion = "shafts-auto 2";  // 2: the error floor's pick

// Work per pixel of a setting, up to a constant: each of the n planes evaluates g once and H I_l at
// m sub-sample planes. Measured on PoCL: t ≈ b n (m + r) with r ≈ 1–1.2 (spot_sphere, stage).
double work(int n, int m) { return double(n) * (m + 1); }

// If t = a + b n (m + r) for some r in [0.5, 2] (a, b > 0), a setting with more than 1.5 x the
// work of another is slower: n2 (m2 + r) >= n2 (m2 + 1) min(1, (m2 + r)/(m2 + 1)) >= 0.75 x2 >
// 1.125 x1 >= n1 (m1 + r) for r <= 1, and n2 (m2 + r) >= x2 > 1.5 x1 >= n1 (m1 + 2) for r <= 2.
constexpr double kWorkMargin = 1.5;

const Knob* findKnob(const Scene& scene, const char* name) {
  const auto it = scene.quality.find(name);
  return it == scene.quality.end() ? nullptr : &it->second;
}

bool isAuto(const Scene& scene, const char* name) {
  const Knob* k = findKnob(scene, name);
  return k == nullptr || k->automatic;
}

// The ladder for one knob: the scene's value when it is fixed, else the options' list or default.
std::vector<int> ladder(const Scene& scene, const char* name, const std::vector<int>& given,
                        const std::vector<int>& fallback) {
  if (!isAuto(scene, name)) return {static_cast<int>(findKnob(scene, name)->value)};
  std::vector<int> v = given.empty() ? fallback : given;
  v.erase(std::remove_if(v.begin(), v.end(), [](int x) { return x < 1; }), v.end());
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  if (v.empty()) throw RuntimeError("shafts auto quality: the candidate list of '" + std::string(name) + "' is empty");
  return v;
}

}  // namespace

std::string shaftsSearchInputs(Device& device, const Scene& scene, bool camera_pose) {
  std::ostringstream s;
  s.precision(17);
  auto v3 = [&](Vec3 v) { s << v.x << ',' << v.y << ',' << v.z << ';'; };
  s << "device " << device.info().platform_name << '|' << device.info().name << '|' << device.info().driver << '\n';
  s << "kernel " << hex64(fnv1a64(assembleKernelSource("shafts.cl").text)) << '\n';
  const CameraDesc& c = scene.camera;
  s << "camera ";
  if (camera_pose) {
    v3(c.position);
    v3(c.look_at);
    v3(c.up);
  }
  s << c.fov_y << ';' << c.width << ';' << c.height << ';' << c.exposure_ev << '\n';
  const AirDesc& a = scene.air;
  s << "air " << a.present << ';' << a.density << ';' << a.extinction << ';' << int(a.phase) << ';' << a.g << '\n';
  for (const SpotlightDesc& l : scene.spotlights) {
    s << "light ";
    v3(l.position);
    v3(l.direction);
    s << l.cone << ';' << l.falloff << ';' << l.intensity << ';';
    v3(l.color);
    s << (l.light_map.empty() ? std::string("-") : fileChecksum(l.light_map)) << '\n';
    // A spectral lamp's RGB comes from its spectrum through the sensor (spectral/lamp_spectrum.h);
    // written only for such lamps, so the keys of RGB lamps stay as they were.
    if (l.temperature_k > 0 || !l.spectrum.empty()) {
      s << "lamp_spectrum " << l.temperature_k << ';' << (l.spectrum.empty() ? std::string("-") : fileChecksum(l.spectrum))
        << ';' << scene.spectral.count << ';' << scene.spectral.min_nm << ';' << scene.spectral.max_nm << ';'
        << scene.spectral.sensor << ';' << scene.spectral.white_balance << ';' << scene.spectral.camera_dir << '\n';
    }
  }
  for (const ObjectDesc& ob : scene.objects) {
    s << "object " << int(ob.type) << ';';
    v3(ob.center);
    s << ob.radius << ';';
    v3(ob.box_min);
    v3(ob.box_max);
    v3(ob.point);
    v3(ob.normal);
    v3(objectAlbedoRgb(ob));
    s << '\n';
  }
  for (const char* k : {"shafts_planes", "shafts_subplanes", "shafts_table_size", "shadow_map_size", "shafts_exact"}) {
    const Knob* q = findKnob(scene, k);
    s << "knob " << k << ' ' << (q ? (q->automatic ? std::string("auto") : std::to_string(q->value)) : "-") << '\n';
  }
  // The planes' table ranges follow from the camera's pose (the lamps' distances to it).
  if (camera_pose) {
    const ShaftsRange r = ShaftsPass::rangeFor(scene);
    s << "method per-lamp cone ranges, closed-form far field\n";
    s << "range " << r.t_max << ';' << r.s_max << '\n';
  }
  return s.str();
}

namespace {

// Everything the decision depends on, as text (%.17g: exact doubles).
std::string describe(Device& device, const Scene& scene, const ShaftsAutoOptions& o) {
  std::ostringstream s;
  s.precision(17);
  s << kAutoVersion << '\n' << shaftsSearchInputs(device, scene, true);
  s << "search " << o.budget_levels << ';' << o.reference_steps << ';' << o.downscale << ';' << o.min_long_side
    << ';' << o.max_long_side << ";n";
  for (int n : o.planes) s << ',' << n;
  s << ";m";
  for (int m : o.subplanes) s << ',' << m;
  s << '\n';
  return s.str();
}

bool readCache(const std::string& path, ShaftsAutoResult& r) {
  const std::map<std::string, std::string> kv = readCacheEntries(path);
  if (kv.empty()) return false;
  try {
    r.planes = std::stoi(kv.at("planes"));
    r.subplanes = std::stoi(kv.at("subplanes"));
    r.rmse_8bit = std::stod(kv.at("rmse_8bit"));
    r.ms = std::stod(kv.at("ms"));
    r.met_budget = kv.at("met_budget") == "1";
    r.search_width = std::stoi(kv.at("search_width"));
    r.search_height = std::stoi(kv.at("search_height"));
  } catch (const std::exception&) {
    return false;  // a damaged or older entry: search again and overwrite it
  }
  return r.planes >= 1 && r.subplanes >= 1;
}

void writeCache(const std::string& path, const ShaftsAutoResult& r, const std::string& description) {
  std::ostringstream s;
  s.precision(17);
  s << "planes " << r.planes << "\nsubplanes " << r.subplanes << "\nrmse_8bit " << r.rmse_8bit << "\nms " << r.ms
    << "\nmet_budget " << (r.met_budget ? 1 : 0) << "\nsearch_width " << r.search_width << "\nsearch_height "
    << r.search_height << '\n';
  s << "# candidates: planes subplanes rmse_8bit ms\n";
  for (const auto& c : r.candidates) s << "# " << c.planes << ' ' << c.subplanes << ' ' << c.rmse_8bit << ' ' << c.ms << '\n';
  writeCacheEntries(path, "seasim shafts auto quality (host/quality/shafts_auto.h)", description, s.str());
}

}  // namespace

int pickShaftsCandidate(const std::vector<ShaftsAutoCandidate>& cands, double budget) {
  if (cands.empty()) return -1;
  double least = cands.front().rmse_8bit;
  for (const auto& c : cands) least = std::min(least, c.rmse_8bit);
  const double bar = least <= budget ? budget : errorFloorBar(least);  // none in budget: the floor
  int best = -1;
  for (int i = 0; i < static_cast<int>(cands.size()); ++i) {
    const ShaftsAutoCandidate& c = cands[i];
    if (!(c.rmse_8bit <= bar)) continue;
    if (best < 0) {
      best = i;
      continue;
    }
    const ShaftsAutoCandidate& b = cands[best];
    // Cheapest, then less work, then more accurate.
    const bool better = c.ms != b.ms ? c.ms < b.ms
                        : work(c.planes, c.subplanes) != work(b.planes, b.subplanes)
                            ? work(c.planes, c.subplanes) < work(b.planes, b.subplanes)
                            : c.rmse_8bit < b.rmse_8bit;
    if (better) best = i;
  }
  return best;
}

std::string shaftsAutoKey(Device& device, const Scene& scene, const ShaftsAutoOptions& options) {
  return hex64(fnv1a64(describe(device, scene, options)));
}

ShaftsAutoResult chooseShaftsQuality(Device& device, const Scene& scene, const PassPlan& plan,
                                     const ShaftsAutoOptions& options) {
  if (!(options.budget_levels > 0)) throw RuntimeError("shafts auto quality: the error budget must be > 0 levels");
  if (options.reference_steps < 1) throw RuntimeError("shafts auto quality: reference_steps must be at least 1");
  ShaftsAutoResult result;
  result.budget_levels = options.budget_levels;

  std::string description, cache_file;
  if (options.use_cache) {
    description = describe(device, scene, options);
    cache_file = searchCacheFile(options.cache_dir, "shafts_auto", "", description);
    if (!cache_file.empty() && readCache(cache_file, result)) {
      result.from_cache = true;
      result.cache_file = cache_file;
      result.budget_levels = options.budget_levels;
      return result;
    }
  }

  const auto t0 = std::chrono::steady_clock::now();
  Scene small = scene;
  searchResolution(scene.camera, options.downscale, options.min_long_side, options.max_long_side, small.camera.width,
                   small.camera.height);
  result.search_width = small.camera.width;
  result.search_height = small.camera.height;
  const Image reference = renderShaftsReference(small, options.reference_steps);

  struct Setting {
    int n, m;
  };
  std::vector<Setting> settings;
  for (int n : ladder(scene, "shafts_planes", options.planes, {8, 10, 15, 20, 30, 40, 60, 80, 120, 160, 200}))
    for (int m : ladder(scene, "shafts_subplanes", options.subplanes, {1, 2, 3, 4, 6, 8, 12, 16, 25}))
      settings.push_back({n, m});
  std::stable_sort(settings.begin(), settings.end(),
                   [](const Setting& a, const Setting& b) { return work(a.n, a.m) < work(b.n, b.m); });

  ShaftsPass::Config config = ShaftsPass::configFromScene(scene);
  bool warmed_up = false;
  double best_work = 0;  // work of the cheapest candidate that settled so far (0: none yet)
  double best_ms = 0;
  double least_error = -1;  // of the candidates so far (-1: none yet)
  for (const Setting& s : settings) {
    if (best_work > 0 && work(s.n, s.m) > kWorkMargin * best_work) break;  // sorted: the rest are slower
    config.planes = s.n;
    config.subplanes = s.m;
    ShaftsPass pass(device, small, plan, config);
    if (!warmed_up) {
      (void)pass.run();  // PoCL compiles the kernels at their first launch
      warmed_up = true;
    }
    ShaftsAutoCandidate c;
    c.planes = s.n;
    c.subplanes = s.m;
    c.ms = pass.run();
    Image img;
    img.resize(small.camera.width, small.camera.height, 3);
    pass.readRgb(img.pixels);
    const CompareResult cmp = compareImages(img, reference, small.camera.exposure_ev);
    if (cmp.nonfinite > 0) {
      throw RuntimeError("shafts auto quality: n = " + std::to_string(s.n) + ", m = " + std::to_string(s.m) +
                         " produced NaN/Inf values");
    }
    c.rmse_8bit = cmp.rmse_8bit;
    // A setting within budget, or at the error floor of those before it, settles the ladder (work beyond
    // kWorkMargin of it cannot be cheaper, and past the floor buys nothing).
    const bool at_floor = atErrorFloor(c.rmse_8bit, least_error);
    least_error = least_error < 0 ? c.rmse_8bit : std::min(least_error, c.rmse_8bit);
    if (c.rmse_8bit <= options.budget_levels || at_floor) {
      // The times that decide: least of three. Other work on a shared machine only ever adds time to a
      // kernel, so the least is the best estimate of its own cost (the median moved 3x under load on a
      // 2-core PoCL box).
      const double a = pass.run(), b = pass.run();
      c.ms = std::min({c.ms, a, b});
      if (best_work == 0 || c.ms < best_ms) {
        best_work = work(s.n, s.m);
        best_ms = c.ms;
      }
    }
    result.candidates.push_back(c);
  }

  const int pick = pickShaftsCandidate(result.candidates, options.budget_levels);
  if (pick < 0) throw RuntimeError("shafts auto quality: no candidate settings");
  const ShaftsAutoCandidate& chosen = result.candidates[pick];
  result.planes = chosen.planes;
  result.subplanes = chosen.subplanes;
  result.rmse_8bit = chosen.rmse_8bit;
  result.ms = chosen.ms;
  result.met_budget = chosen.rmse_8bit <= options.budget_levels;
  result.search_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (!cache_file.empty()) {
    writeCache(cache_file, result, description);
    result.cache_file = cache_file;
  }
  return result;
}

ShaftsPass::Config shaftsConfigWithAuto(Device& device, const Scene& scene, const PassPlan& plan) {
  ShaftsPass::Config c = ShaftsPass::configFromScene(scene);
  auto automatic = [&](const char* name) {
    const auto it = scene.quality.find(name);
    return it != scene.quality.end() && it->second.automatic;
  };
  if (!automatic("shafts_planes") && !automatic("shafts_subplanes")) return c;
  // n and m are the planes method's knobs: the intervals and march methods (plan/shafts_method.h) have none
  // to search.
  if (!plan.featuresAs<ShaftsFeatures>().planes()) return c;
  ShaftsAutoOptions options;
  const auto budget = scene.quality.find("shafts_error_budget");
  if (budget != scene.quality.end()) options.budget_levels = budget->second.value;
  const ShaftsAutoResult r = chooseShaftsQuality(device, scene, plan, options);
  c.planes = r.planes;
  c.subplanes = r.subplanes;
  if (!r.from_cache) {
    std::fprintf(stderr,
                 "shafts: auto quality n = %d, m = %d: RMS %.3f levels vs the ray-marched reference at %dx%d "
                 "(budget %g); %zu settings searched in %.1f s%s%s\n",
                 r.planes, r.subplanes, r.rmse_8bit, r.search_width, r.search_height, r.budget_levels,
                 r.candidates.size(), r.search_ms * 1e-3, r.cache_file.empty() ? "" : ", cached in ",
                 r.cache_file.c_str());
  }
  if (!r.met_budget) {
    std::fprintf(stderr,
                 "shafts: warning: no (n, m) reaches RMS %g levels on '%s'; using the cheapest at the error floor, n = %d, m = %d "
                 "(%.3f levels). The floor comes from quality.shadow_map_size / shafts_table_size, or raise "
                 "quality.shafts_error_budget\n",
                 r.budget_levels, scene.name.c_str(), r.planes, r.subplanes, r.rmse_8bit);
  }
  return c;
}

}  // namespace seasim
