#include "cli/underwater_regions_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>

#include "cli/commands.h"
#include "cli/underwater_regions_dump.h"
#include "device/device.h"
#include "io/csv.h"
#include "io/npy.h"
#include "plan/pass_descriptor.h"
#include "plan/plan.h"
#include "quality/render_frame.h"
#include "reference/pixel_centre_hits.h"
#include "reference/underwater_ordinates_terms.h"
#include "reference/underwater_reference.h"
#include "reference/underwater_regions.h"
#include "scene/scene_parser.h"
#include "spectral/sensor.h"
#include "spectral/wavelength_grid.h"
#include "underwater/underwater_setup.h"
#include "util/error.h"

namespace seasim {

namespace {

namespace fs = std::filesystem;

Override set(const std::string& key, const std::string& value) { return {key, value, {"underwater-regions", 0}}; }

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.4g", v);
  std::string s = b;
  if (s.find_first_of(".e") == std::string::npos) s += ".0";
  return s;
}

// The scene's geometry (tests/perf/underwater_regions.toml, scenes/seabed.toml's) at bottom depth
// `depth` (0: no bottom, the rocks as at 5 m), camera 1.2 m above the bottom, looking as `view` says:
// "level" (the seabed view, slightly down: bottom near and far, rocks, water up), "up" (30° up: the
// water looking up and Snell's window), "down" (45° down: the near bottom, or deep water), "sun" (at
// the refracted sun, sun_w its direction in the water: the beam's forward peak, Snell's window).
std::vector<Override> geometry(double depth, const std::string& view, const double sun_w[3]) {
  const double h = depth > 0 ? depth : 5.0;
  const double cam_y = -(h - 1.2);
  std::vector<Override> o = {set("camera.position", "[0.0, " + num(cam_y) + ", 0.0]"),
                             set("objects[0].center", "[-1.4, " + num(-(h - 0.5)) + ", -5.0]"),
                             set("objects[1].min", "[0.8, " + num(-h) + ", -7.5]"),
                             set("objects[1].max", "[2.2, " + num(-(h - 1.2)) + ", -6.3]"),
                             set("objects[2].center", "[0.3, " + num(-(h - 0.8)) + ", -10.5]")};
  if (depth > 0) {
    o.push_back(set("bottom.depth", num(depth)));
    o.push_back(set("bottom.albedo", "0.35"));  // sand (not a key of type = "none")
  }
  else o.push_back(set("bottom.type", "\"none\""));
  if (view == "sun") {
    o.push_back(set("camera.look_at",
                    "[" + num(8 * sun_w[0]) + ", " + num(cam_y + 8 * sun_w[1]) + ", " + num(8 * sun_w[2]) + "]"));
    return o;
  }
  double dy = -0.7;  // level: scenes/seabed.toml's look_at 0.7 m lower, 8 m ahead
  if (view == "up") dy = 8.0 * std::tan(30.0 * M_PI / 180.0);
  else if (view == "down") dy = -8.0;
  else if (view != "level")
    throw RuntimeError("underwater-regions: unknown view '" + view + "' (level, up, down, sun)");
  o.push_back(set("camera.look_at", "[0.0, " + num(cam_y + dy) + ", -8.0]"));
  return o;
}

// The scene file's text, the overrides, the path count and the pixel sampling name a reference (a
// changed scene is new; jittered references keep the names they had before centre rays existed).
std::string cacheKey(const std::string& scene_file, const std::vector<Override>& over, int spp, bool jitter) {
  std::ifstream in(scene_file, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  text += "|" + std::to_string(spp);
  if (!jitter) text += "|centre";
  for (const Override& o : over) text += "|" + o.key + "=" + o.value_toml;
  char b[32];
  std::snprintf(b, sizeof b, "%016zx", std::hash<std::string>{}(text));
  return b;
}

// The reference of one case at `spp` paths: the cached images at `stem`, or traced and cached there.
void loadOrTraceReference(Device& device, const UnderwaterSetup& setup, const std::string& stem, int spp, bool jitter,
                          Image& ref, Image& se) {
  if (fs::exists(stem + ".rgb.npy") && fs::exists(stem + ".se.npy")) {
    ref = readNpy(stem + ".rgb.npy");
    se = readNpy(stem + ".se.npy");
    return;
  }
  UnderwaterReferenceSettings settings;
  settings.samples_per_pixel = spp;
  settings.jitter = jitter;
  const UnderwaterReferenceResult r = renderUnderwaterReference(device, setup, settings);
  ref = r.rgb;
  se = r.std_error;
  writeNpy(stem + ".se.npy", se);
  writeNpy(stem + ".rgb.npy", ref);
}

}  // namespace

int refinedPathCount(int spp, double noise, double target, int max_spp) {
  if (!(target > 0) || !(noise > target)) return spp;
  const double want = spp * (noise / target) * (noise / target);
  long long n = spp;
  while (n < want && n <= max_spp) n *= 2;
  return n <= max_spp ? static_cast<int>(n) : 0;
}

namespace {

// One case's reference, from the cache or traced at --spp; with --target-noise traced again with the most
// paths a judged region within reach of --max-spp needs (a region that would need more does not hold the
// others back). Returns the paths per pixel of the reference in `ref` and `se`.
int caseReference(Device& device, const UnderwaterRegionsCmd& cmd, const std::string& cache,
                  const std::vector<Override>& base, const UnderwaterSetup& setup, const std::vector<UwRegion>& regions,
                  Image& ref, Image& se) {
  int spp = cmd.spp;
  loadOrTraceReference(device, setup, cache + "/" + cacheKey(cmd.scene, base, spp, cmd.jitter), spp, cmd.jitter, ref,
                       se);
  if (cmd.target_noise <= 0) return spp;
  int refined = spp;
  for (const UwRegionStat& s : underwaterRegionStats(regions, ref, ref, se))
    if (s.pixels >= kRegionsJudgedMinPixels)
      refined = std::max(refined, refinedPathCount(spp, s.relNoise(), cmd.target_noise, cmd.max_spp));
  if (refined == spp) return spp;
  std::printf("(a judged region's reference noise is above %g at %d paths: traced again at %d)\n", cmd.target_noise,
              spp, refined);
  loadOrTraceReference(device, setup, cache + "/" + cacheKey(cmd.scene, base, refined, cmd.jitter), refined, cmd.jitter,
                       ref, se);
  return refined;
}

}  // namespace

int cmdUnderwaterRegions(const UnderwaterRegionsCmd& cmd) {
  Device device(chooseDevice(cmd.device));
  std::printf("device: %s\n", device.info().label().c_str());
  std::string cache = cmd.cache_dir;
  if (cache.empty()) {
    const char* env = std::getenv("SEASIM_CACHE_DIR");
    cache = (env && *env ? std::string(env) : std::string("build")) + "/underwater_regions";
  }
  fs::create_directories(cache);
  const std::string& kd_pass = descriptorFor(PassRole::UnderwaterShading).name;
  std::vector<std::string> header = {"a", "b", "g", "depth_m", "view", "model", kd_pass + "_ms", "reference_spp"};
  for (int r = 0; r < kUwRegionCount; ++r) {
    const std::string name = uwRegionName(static_cast<UwRegion>(r));
    for (const char* col : {"_pixels", "_ratio", "_ref_rel_se"}) header.push_back(name + col);
  }
  CsvWriter table(header);
  std::printf("%-5s %-5s %-4s %-5s %-5s %-8s %8s", "a", "b", "g", "depth", "view", "model", "kd ms");
  for (int r = 0; r < kUwRegionCount; ++r) std::printf(" %18s", uwRegionName(static_cast<UwRegion>(r)));
  std::printf("\n");
  // The refracted sun ("sun" views), from the scene with --set applied: the same for every case.
  double sun_w[3] = {0, 1, 0};
  if (std::find(cmd.views.begin(), cmd.views.end(), "sun") != cmd.views.end()) {
    std::vector<Override> sun_over;
    for (const std::string& s : cmd.sets) sun_over.push_back(parseSetOption(s));
    const Vec3 d = sunInWater(loadScene(cmd.scene, sun_over));
    sun_w[0] = d.x;
    sun_w[1] = d.y;
    sun_w[2] = d.z;
  }
  for (const std::string& water : cmd.waters) {
    const size_t colon = water.find(':');
    if (colon == std::string::npos) throw RuntimeError("underwater-regions: --waters wants a:b pairs, got '" + water + "'");
    const double a = std::stod(water.substr(0, colon)), b = std::stod(water.substr(colon + 1));
    for (double g : cmd.gs)
      for (double depth : cmd.depths)
        for (const std::string& view : cmd.views) {
          std::vector<Override> base = geometry(depth, view, sun_w);
          base.push_back(set("water.a", "[" + num(a) + ", " + num(a) + "]"));
          base.push_back(set("water.b", "[" + num(b) + ", " + num(b) + "]"));
          base.push_back(set("water.g", num(g)));
          for (const std::string& s : cmd.sets) base.push_back(parseSetOption(s));
          const Scene ref_scene = loadScene(cmd.scene, base);

          // The reference, from the cache or traced (with its per-pixel standard error); with
          // --target-noise, traced again with more paths where a judged region is too noisy.
          const WavelengthGrid grid =
              makeGrid(ref_scene.spectral.count, ref_scene.spectral.min_nm, ref_scene.spectral.max_nm);
          const UnderwaterSetup ref_setup = makeUnderwaterSetup(
              ref_scene, grid,
              makeSensor(ref_scene.spectral.sensor, grid, ref_scene.spectral.white_balance, ref_scene.spectral.camera_dir));
          const std::vector<UwRegion> regions = underwaterRegions(ref_setup);
          Image ref, se;
          const int spp = caseReference(device, cmd, cache, base, ref_setup, regions, ref, se);
          UnderwaterRegionsDump dump;  // --dump: the case's pixels
          if (!cmd.dump_dir.empty()) {
            dump.regions = regions;
            for (const PixelCentreHit& h : pixelCentreHits(ref_setup)) {
              dump.dir_y.push_back(h.dir_y);
              dump.cos_sun.push_back(h.cos_sun);
            }
            dump.reference = ref;
            dump.reference_se = se;
          }

          for (const std::string& model : cmd.models) {
            std::vector<Override> over = base;
            over.push_back(set("underwater.model", "\"" + model + "\""));
            for (const std::string& s : cmd.model_sets) over.push_back(parseSetOption(s));
            const Scene scene = loadScene(cmd.scene, over);
            const FrameResult frame = renderFrame(device, scene, makePlan(scene));
            if (frame.nonfinite != 0) throw RuntimeError("underwater-regions: NaN/Inf in a render");
            double kd_ms = 0.0;
            for (const PassTiming& t : frame.timings)
              if (t.name == kd_pass) kd_ms += t.ms;
            const auto stats = underwaterRegionStats(regions, frame.rgb, ref, se);
            if (!cmd.dump_dir.empty()) {
              dump.fast.emplace_back(model, frame.rgb);
              if (model == "improved")
                dump.ordinates_terms = ordinatesModelTerms(
                    makeUnderwaterSetup(scene, grid,
                                        makeSensor(scene.spectral.sensor, grid, scene.spectral.white_balance,
                                                   scene.spectral.camera_dir)),
                    scene.underwater.multiple_scattering);
            }
            std::vector<CsvCell> row = {a, b, g, depth, view, model, kd_ms, spp};
            std::printf("%-5.3g %-5.3g %-4.3g %-5.3g %-5s %-8s %8.2f", a, b, g, depth, view.c_str(), model.c_str(), kd_ms);
            for (const UwRegionStat& s : stats) {
              row.push_back(s.pixels);
              row.push_back(s.pixels ? CsvCell(s.ratio()) : CsvCell(std::string()));
              row.push_back(s.pixels ? CsvCell(s.relNoise()) : CsvCell(std::string()));
              if (s.pixels) std::printf(" %6.3f ±%5.3f (%4d)", s.ratio(), s.relNoise(), s.pixels);
              else std::printf(" %18s", "-");
            }
            std::printf("\n");
            std::fflush(stdout);
            table.addRow(row);
          }
          if (!cmd.dump_dir.empty())
            writeUnderwaterRegionsDump(cmd.dump_dir + "/" + underwaterRegionsDumpName(a, b, g, depth, view), dump);
        }
  }
  if (!cmd.csv.empty()) table.write(cmd.csv);
  return 0;
}

}  // namespace seasim
