#include "quality/sea_auto.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>
#include <tuple>

#include "device/kernel_source.h"
#include "quality/quality_search.h"
#include "quality/render_frame.h"
#include "reference/compare.h"
#include "spectral/jerlov.h"
#include "spectral/wavelength_grid.h"
#include "util/error.h"
#include "util/hash.h"
#include "util/paths.h"

namespace seasim {

namespace {

// Bump when the search or its rule changes meaning, so old cache entries are not reused.
constexpr const char* kAutoVersion = "sea-auto 1";
constexpr const char* kKnobs[] = {"sea_nz", "sea_nd", "sea_map_size"};

bool isAuto(const Scene& scene, const char* name) {
  const auto it = scene.quality.find(name);
  return it != scene.quality.end() && it->second.automatic;
}

int fixedValue(const Scene& scene, const char* name, int fallback) {
  const auto it = scene.quality.find(name);
  return it == scene.quality.end() || it->second.automatic ? fallback : static_cast<int>(it->second.value);
}

int startMap(const Scene& scene) { return scene.bottom.type == BottomDesc::Type::HeightField ? 64 : 32; }

// Everything the decision depends on, as text (%.17g: exact doubles). Spectra are taken at the
// scene's band centres, which is all the sea passes read of them.
std::string describe(Device& device, const Scene& scene, const SeaAutoOptions& o) {
  std::ostringstream s;
  s.precision(17);
  auto v3 = [&](Vec3 v) { s << v.x << ',' << v.y << ',' << v.z << ';'; };
  s << kAutoVersion << '\n';
  s << "device " << device.info().platform_name << '|' << device.info().name << '|' << device.info().driver << '\n';
  for (const char* file : {"sea_single.cl", "sea_second.cl"})
    s << "kernel " << file << ' ' << hex64(fnv1a64(assembleKernelSource(file).text)) << '\n';
  const CameraDesc& c = scene.camera;
  s << "camera ";
  v3(c.position);
  v3(c.look_at);
  v3(c.up);
  s << c.fov_y << ';' << c.width << ';' << c.height << ';' << c.exposure_ev << '\n';
  const SunDesc& sun = scene.sun;
  s << "sun " << sun.enabled << ';' << sun.zenith << ';' << sun.azimuth << ';' << sun.irradiance << ';'
    << sun.angular_radius << '\n';
  s << "sky " << int(scene.sky.model) << ';' << scene.sky.radiance << ';' << scene.sky.turbidity << ';'
    << (scene.sky.chromaticity_on_daylight_locus ? "locus;" : "")
    << (scene.sky.image.empty() ? std::string("-") : fileChecksum(scene.sky.image)) << '\n';
  const SpectralDesc& sp = scene.spectral;
  s << "spectral " << sp.count << ';' << sp.min_nm << ';' << sp.max_nm << ';' << sp.sensor << ';' << sp.white_balance
    << '\n';
  const WavelengthGrid grid = makeGrid(sp.count, sp.min_nm, sp.max_nm);
  const BandOptics water = resolveWater(scene.water, grid);
  s << "water " << scene.water.g << ';' << scene.water.ior;
  for (size_t i = 0; i < grid.centers_nm.size(); ++i) s << ';' << water.a[i] << ',' << water.b[i];
  s << '\n';
  const SurfaceDesc& f = scene.surface;
  s << "surface " << int(f.type) << ';' << f.wind_speed << ';' << f.wind_direction << ';' << f.patch_size << ';'
    << f.grid << ';' << f.choppiness << ';' << f.directional_exponent << ';' << f.small_wave << ';' << f.depth << ';'
    << f.loop_period << ';' << f.time << ';' << f.seed << '\n';
  const BottomDesc& b = scene.bottom;
  s << "bottom " << int(b.type) << ';' << b.depth << ';' << b.min_depth << ';' << b.max_depth << ';' << b.extent << ';'
    << (b.heightfield.empty() ? std::string("-") : fileChecksum(b.heightfield));
  for (double nm : grid.centers_nm) s << ';' << b.albedo.at(nm);
  s << '\n';
  s << "sea " << scene.sea.single_scattering << ';' << scene.sea.second_order << ';' << scene.sea.reflection << '\n';
  for (const auto& [name, knob] : scene.quality) {
    if (name.rfind("sea_", 0) == 0 || name.rfind("ocean", 0) == 0)
      s << "knob " << name << ' ' << (knob.automatic ? std::string("auto") : std::to_string(knob.value)) << '\n';
  }
  s << "search " << o.threshold_levels << ';' << o.max_nz << ";nd";
  for (int v : o.nd_ladder) s << ',' << v;
  s << ";map";
  for (int v : o.map_ladder) s << ',' << v;
  s << ';' << o.start_nz << ';' << o.start_nd << ';' << o.max_rounds << ';' << o.downscale << ';' << o.min_long_side
    << ';' << o.max_long_side << '\n';
  return s.str();
}

bool readCache(const std::string& path, SeaAutoResult& r) {
  const std::map<std::string, std::string> kv = readCacheEntries(path);
  if (kv.empty()) return false;
  try {
    r.n_z = std::stoi(kv.at("n_z"));
    r.n_d = std::stoi(kv.at("n_d"));
    r.map_size = std::stoi(kv.at("map_size"));
    r.nz_step_8bit = std::stod(kv.at("nz_step_8bit"));
    r.nd_step_8bit = std::stod(kv.at("nd_step_8bit"));
    r.map_step_8bit = std::stod(kv.at("map_step_8bit"));
    r.met = kv.at("met") == "1";
    r.converged = kv.at("converged") == "1";
    r.search_width = std::stoi(kv.at("search_width"));
    r.search_height = std::stoi(kv.at("search_height"));
  } catch (const std::exception&) {
    return false;  // a damaged or older entry: search again and overwrite it
  }
  return r.n_z >= 1 && r.n_d >= 1 && r.map_size >= 1;
}

void writeCache(const std::string& path, const SeaAutoResult& r, const std::string& description) {
  std::ostringstream s;
  s.precision(17);
  s << "n_z " << r.n_z << "\nn_d " << r.n_d << "\nmap_size " << r.map_size << "\nnz_step_8bit " << r.nz_step_8bit
    << "\nnd_step_8bit " << r.nd_step_8bit << "\nmap_step_8bit " << r.map_step_8bit << "\nmet " << (r.met ? 1 : 0)
    << "\nconverged " << (r.converged ? 1 : 0) << "\nsearch_width " << r.search_width << "\nsearch_height "
    << r.search_height << '\n';
  s << "# steps: knob n_z n_d map_size next max_diff_8bit\n";
  for (const auto& t : r.steps)
    s << "# " << t.knob << ' ' << t.n_z << ' ' << t.n_d << ' ' << t.map_size << ' ' << t.next << ' ' << t.max_diff_8bit
      << '\n';
  writeCacheEntries(path, "seasim sea second-order auto quality (host/quality/sea_auto.h)", description, s.str());
}

// Renders the reduced scene at a setting, once per setting.
class Renderer {
 public:
  Renderer(Device& device, const Scene& small) : device_(device), scene_(small) {}
  const Image& at(int n_z, int n_d, int map) {
    const auto key = std::make_tuple(n_z, n_d, map);
    const auto it = images_.find(key);
    if (it != images_.end()) return it->second;
    Scene s = scene_;
    s.quality["sea_nz"] = Knob{false, double(n_z)};
    s.quality["sea_nd"] = Knob{false, double(n_d)};
    s.quality["sea_map_size"] = Knob{false, double(map)};
    const FrameResult f = renderFrame(device_, s, makePlan(s));
    if (f.nonfinite > 0) {
      throw RuntimeError("sea auto quality: n_z = " + std::to_string(n_z) + ", n_d = " + std::to_string(n_d) +
                         ", map " + std::to_string(map) + " produced NaN/Inf values");
    }
    return images_.emplace(key, f.rgb).first->second;
  }
  int renders() const { return static_cast<int>(images_.size()); }

 private:
  Device& device_;
  Scene scene_;
  std::map<std::tuple<int, int, int>, Image> images_;
};

}  // namespace

bool seaSecondWantsAuto(const Scene& scene) {
  for (const char* k : kKnobs)
    if (isAuto(scene, k)) return true;
  return false;
}

std::string seaAutoKey(Device& device, const Scene& scene, const SeaAutoOptions& options) {
  return hex64(fnv1a64(describe(device, scene, options)));
}

SeaAutoResult chooseSeaSecondQuality(Device& device, const Scene& scene, const SeaAutoOptions& options) {
  if (!(options.threshold_levels > 0)) throw RuntimeError("sea auto quality: the threshold must be > 0 levels");
  if (options.max_nz < 2 || options.nd_ladder.size() < 2 || options.map_ladder.size() < 2 || options.max_rounds < 1) {
    throw RuntimeError("sea auto quality: max_nz must be >= 2, each ladder needs >= 2 values, max_rounds >= 1");
  }
  for (const auto* ladder : {&options.nd_ladder, &options.map_ladder}) {
    if (!std::is_sorted(ladder->begin(), ladder->end()) || ladder->front() < 1 ||
        std::adjacent_find(ladder->begin(), ladder->end()) != ladder->end()) {
      throw RuntimeError("sea auto quality: the n_d and map ladders must be increasing positive integers");
    }
  }
  if (!scene.water.present || !scene.sea.second_order) {
    throw RuntimeError("sea auto quality: scene '" + scene.name + "' has no second-order sea scattering to tune");
  }
  SeaAutoResult result;
  std::string description, cache_file;
  if (options.use_cache) {
    description = describe(device, scene, options);
    cache_file = searchCacheFile(options.cache_dir, "sea_auto", "", description);
    if (!cache_file.empty() && readCache(cache_file, result)) {
      result.from_cache = true;
      result.cache_file = cache_file;
      return result;
    }
  }

  const auto t0 = std::chrono::steady_clock::now();
  Scene small = scene;
  searchResolution(scene.camera, options.downscale, options.min_long_side, options.max_long_side, small.camera.width,
                   small.camera.height);
  result.search_width = small.camera.width;
  result.search_height = small.camera.height;
  Renderer render(device, small);
  const double ev = scene.camera.exposure_ev;
  // Max |image(setting) - image(setting with knob `which` at `next`)| in 8-bit levels, recorded.
  auto diff = [&](int which, int nz, int nd, int map, int next) {
    const Image& a = render.at(nz, nd, map);  // std::map nodes: references stay valid
    const Image& b = render.at(which == 0 ? next : nz, which == 1 ? next : nd, which == 2 ? next : map);
    SeaAutoStep step{kKnobs[which], nz, nd, map, next, compareImages(b, a, ev).max_abs_8bit};
    result.steps.push_back(step);
    return step.max_diff_8bit;
  };
  struct Pick {
    int value;
    double step;
    bool met;
  };
  // n_z: the first n with max |L(n) - L(n + 1)| under the threshold (000 §6.1, Fig. 7).
  auto searchNz = [&](int nd, int map) -> Pick {
    for (int n = 1; n < options.max_nz; ++n) {
      const double d = diff(0, n, nd, map, n + 1);
      if (d < options.threshold_levels) return {n, d, true};
    }
    return {options.max_nz, result.steps.back().max_diff_8bit, false};
  };
  // n_d, M: the first rung whose step to the next rung is under the threshold (Fig. 8).
  auto searchLadder = [&](int which, const std::vector<int>& ladder, int nz, int nd, int map) -> Pick {
    for (size_t i = 0; i + 1 < ladder.size(); ++i) {
      const int v = ladder[i], next = ladder[i + 1];
      const double d = which == 1 ? diff(1, nz, v, map, next) : diff(2, nz, nd, v, next);
      if (d < options.threshold_levels) return {v, d, true};
    }
    return {ladder.back(), result.steps.back().max_diff_8bit, false};
  };

  const bool auto_nz = isAuto(scene, kKnobs[0]), auto_nd = isAuto(scene, kKnobs[1]),
             auto_map = isAuto(scene, kKnobs[2]);
  int nz = auto_nz ? options.start_nz : fixedValue(scene, kKnobs[0], 12);
  int nd = auto_nd ? options.start_nd : fixedValue(scene, kKnobs[1], 128);
  int map = auto_map ? startMap(scene) : fixedValue(scene, kKnobs[2], startMap(scene));
  for (int round = 0; round < options.max_rounds; ++round) {
    bool changed = false;
    result.met = true;
    if (auto_nz) {
      const Pick p = searchNz(nd, map);
      changed |= p.value != nz;
      nz = p.value;
      result.nz_step_8bit = p.step;
      result.met &= p.met;
    }
    if (auto_nd) {
      const Pick p = searchLadder(1, options.nd_ladder, nz, nd, map);
      changed |= p.value != nd;
      nd = p.value;
      result.nd_step_8bit = p.step;
      result.met &= p.met;
    }
    if (auto_map) {
      const Pick p = searchLadder(2, options.map_ladder, nz, nd, map);
      changed |= p.value != map;
      map = p.value;
      result.map_step_8bit = p.step;
      result.met &= p.met;
    }
    if (!changed) {
      result.converged = true;
      break;
    }
  }
  result.n_z = nz;
  result.n_d = nd;
  result.map_size = map;
  result.renders = render.renders();
  result.search_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (!cache_file.empty()) {
    writeCache(cache_file, result, description);
    result.cache_file = cache_file;
  }
  return result;
}

SeaSecondPass::Config seaSecondConfigWithAuto(Device& device, const Scene& scene) {
  SeaSecondPass::Config config = SeaSecondPass::configFromScene(scene);
  if (!seaSecondWantsAuto(scene)) return config;
  const SeaAutoResult r = chooseSeaSecondQuality(device, scene);
  if (isAuto(scene, kKnobs[0])) config.n_z = r.n_z;
  if (isAuto(scene, kKnobs[1])) SeaSecondPass::splitDirections(r.n_d, &config.n_theta, &config.n_phi);
  if (isAuto(scene, kKnobs[2])) config.map_size = r.map_size;
  if (!r.from_cache) {
    std::fprintf(stderr,
                 "sea_second: auto quality n_z = %d, n_d = %d, map %dx%d (steps to the next setting %.3f, %.3f, "
                 "%.3f levels at %dx%d); %d frames in %.1f s%s%s\n",
                 r.n_z, r.n_d, r.map_size, r.map_size, r.nz_step_8bit, r.nd_step_8bit, r.map_step_8bit,
                 r.search_width, r.search_height, r.renders, r.search_ms * 1e-3,
                 r.cache_file.empty() ? "" : ", cached in ", r.cache_file.c_str());
  }
  if (!r.met || !r.converged) {
    std::fprintf(stderr,
                 "sea_second: warning: auto quality on '%s' %s; using n_z = %d, n_d = %d, map %d\n", scene.name.c_str(),
                 !r.met ? "did not get under the threshold before a ladder ran out" : "did not settle within the rounds",
                 r.n_z, r.n_d, r.map_size);
  }
  return config;
}

}  // namespace seasim
