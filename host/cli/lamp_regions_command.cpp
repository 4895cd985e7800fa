#include "cli/lamp_regions_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <sstream>

#include "device/device.h"
#include "io/csv.h"
#include "io/npy.h"
#include "math/kernel_math.h"
#include "plan/pass_descriptor.h"
#include "plan/plan.h"
#include "quality/render_frame.h"
#include "reference/pixel_centre_hits.h"
#include "reference/underwater_reference.h"
#include "scene/scene_parser.h"
#include "scene/set_option.h"
#include "spectral/sensor.h"
#include "spectral/wavelength_grid.h"
#include "underwater/lamps_setup.h"
#include "underwater/underwater_setup.h"
#include "util/error.h"

namespace seasim {

namespace {

namespace fs = std::filesystem;
using kmath_d::real3;

Override set(const std::string& key, const std::string& value) { return {key, value, {"lamp-regions", 0}}; }

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  std::string s = b;
  if (s.find_first_of(".e") == std::string::npos) s += ".0";
  return s;
}

enum LampRegion { kWhole = 0, kLitBottom, kBeam, kOutside, kLampRegionCount };
const char* kRegionNames[kLampRegionCount] = {"whole", "lit_bottom", "beam", "outside"};

// Each pixel's region (lit bottom, beam, outside) from its centre ray, in double with the kernels' geometry.
std::vector<int> lampRegions(const UnderwaterSetup& setup, const UnderwaterLamps& lamps) {
  const UwParams& p = setup.params;
  const UwLamp& L = lamps.lamps[0];
  const real3 o{p.cam_pos[0], p.cam_pos[1], p.cam_pos[2]};
  const real3 lamp{L.position[0], L.position[1], L.position[2]}, axis{L.direction[0], L.direction[1], L.direction[2]};
  const std::vector<PixelCentreHit> hits = pixelCentreHits(setup);
  std::vector<int> out(hits.size(), kOutside);
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x) {
      const size_t i = static_cast<size_t>(y) * p.width + x;
      const real3 d = kmath_d::uw_screen_dir(&p, (x + 0.5) / p.width, (y + 0.5) / p.height);
      const double S = hits[i].distance;
      if (hits[i].material == UW_MAT_BOTTOM) {
        const real3 q = o + S * d - lamp;
        if (kmath_d::dot(q, axis) > L.cos_cone * kmath_d::length(q)) {
          out[i] = kLitBottom;
          continue;
        }
      }
      double ta, tb;
      if (kmath_d::shafts_cone_interval(o, d, lamp, axis, L.cos_cone, &ta, &tb) && ta < std::min(S, 1e29) && tb > 0)
        out[i] = kBeam;
    }
  return out;
}

struct Stat {
  int pixels = 0;
  double fast = 0, ref = 0, var = 0;
};

// The scene text, the overrides and the path count name a reference.
std::string cacheKey(const std::string& scene_file, const std::vector<Override>& over, int spp) {
  std::ifstream in(scene_file, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  text += "|lamps|centre|" + std::to_string(spp);
  for (const Override& o : over) text += "|" + o.key + "=" + o.value_toml;
  char b[32];
  std::snprintf(b, sizeof b, "%016zx", std::hash<std::string>{}(text));
  return b;
}

std::vector<std::string> split(const std::string& s, char c) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, c)) out.push_back(item);
  return out;
}

}  // namespace

int cmdLampRegions(const LampRegionsCmd& cmd) {
  Device device(chooseDevice(cmd.device));
  std::printf("device: %s\n", device.info().label().c_str());
  std::string cache = cmd.cache_dir;
  if (cache.empty()) {
    const char* env = std::getenv("SEASIM_CACHE_DIR");
    cache = (env && *env ? std::string(env) : std::string("build")) + "/lamp_regions";
  }
  fs::create_directories(cache);
  std::vector<std::string> header = {"a", "b", "g", "cone_deg", "height_m", "model", "lamps_ms", "reference_spp"};
  for (const char* r : kRegionNames)
    for (const char* col : {"_pixels", "_ratio", "_ref_rel_se"}) header.push_back(std::string(r) + col);
  CsvWriter table(header);
  std::printf("%-5s %-5s %-5s %-5s %-5s %-8s %9s", "a", "b", "g", "cone", "h", "model", "lamps ms");
  for (const char* r : kRegionNames) std::printf(" %22s", r);
  std::printf("\n");
  for (const std::string& c : cmd.cases) {
    const std::vector<std::string> f = split(c, ':');
    if (f.size() != 5) throw RuntimeError("lamp-regions: --cases wants a:b:g:cone:height, got '" + c + "'");
    const double a = std::stod(f[0]), b = std::stod(f[1]), g = std::stod(f[2]), cone = std::stod(f[3]),
                 height = std::stod(f[4]);
    std::vector<Override> base = {set("water.a", "[" + num(a) + ", " + num(a) + "]"),
                                  set("water.b", "[" + num(b) + ", " + num(b) + "]"), set("water.g", num(g)),
                                  set("spotlights[0].cone_deg", num(cone))};
    // The lamp (and camera) sit at y = -4 in lamp_glow.toml: the bottom `height` below them.
    const Scene probe = loadScene(cmd.scene);
    base.push_back(set("bottom.depth", num(-probe.spotlights.at(0).position.y + height)));
    for (const std::string& s : cmd.sets) base.push_back(parseSetOption(s));
    const Scene ref_scene = loadScene(cmd.scene, base);
    const WavelengthGrid grid = makeGrid(ref_scene.spectral.count, ref_scene.spectral.min_nm, ref_scene.spectral.max_nm);
    const UnderwaterSetup setup = makeUnderwaterSetup(
        ref_scene, grid,
        makeSensor(ref_scene.spectral.sensor, grid, ref_scene.spectral.white_balance, ref_scene.spectral.camera_dir));
    const UnderwaterLamps lamps = makeUnderwaterLamps(ref_scene, grid);
    const std::vector<int> regions = lampRegions(setup, lamps);

    std::string stem = cache + "/" + cacheKey(cmd.scene, base, cmd.spp);
    if (cmd.max_bounces > 0) stem += ".bounces" + std::to_string(cmd.max_bounces);
    Image ref, se;
    if (fs::exists(stem + ".rgb.npy") && fs::exists(stem + ".se.npy")) {
      ref = readNpy(stem + ".rgb.npy");
      se = readNpy(stem + ".se.npy");
    } else {
      UnderwaterReferenceSettings settings;
      settings.samples_per_pixel = cmd.spp;
      settings.jitter = false;
      settings.lamps = &lamps;
      if (cmd.max_bounces > 0) settings.max_bounces = cmd.max_bounces;
      const UnderwaterReferenceResult r = renderUnderwaterReference(device, setup, settings);
      ref = r.rgb;
      se = r.std_error;
      writeNpy(stem + ".se.npy", se);
      writeNpy(stem + ".rgb.npy", ref);
    }

    // The fast models, rendered in interleaved rounds (the machine's load falls on each alike).
    std::vector<Image> images(cmd.models.size());
    std::vector<std::vector<double>> ms(cmd.models.size());
    const std::string& lamps_pass = descriptorFor(PassRole::UnderwaterLamps).name;
    for (int round = 0; round < std::max(1, cmd.rounds); ++round)
      for (size_t m = 0; m < cmd.models.size(); ++m) {
        std::vector<Override> over = base;
        over.push_back(set("quality.lamps_model", "\"" + cmd.models[m] + "\""));
        for (const std::string& s : cmd.model_sets) over.push_back(parseSetOption(s));
        const Scene scene = loadScene(cmd.scene, over);
        const FrameResult frame = renderFrame(device, scene, makePlan(scene));
        if (frame.nonfinite != 0) throw RuntimeError("lamp-regions: NaN/Inf in a render");
        double t = 0;
        for (const PassTiming& pt : frame.timings)
          if (pt.name.rfind(lamps_pass, 0) == 0) t += pt.ms;  // and its lattice, underwater_lamps_lattice
        ms[m].push_back(t);
        images[m] = frame.rgb;
      }
    for (size_t m = 0; m < cmd.models.size(); ++m) {
      std::array<Stat, kLampRegionCount> st{};
      const size_t n = regions.size();
      for (size_t i = 0; i < n; ++i)
        for (int r : {int(kWhole), regions[i]}) {
          st[r].pixels++;
          for (int ch = 0; ch < 3; ++ch) {
            st[r].fast += images[m].pixels[3 * i + ch];
            st[r].ref += ref.pixels[3 * i + ch];
          }
          // The channels of one pixel share its paths: their errors add.
          const double e = se.pixels[3 * i] + se.pixels[3 * i + 1] + se.pixels[3 * i + 2];
          st[r].var += e * e;
        }
      std::vector<double> t = ms[m];
      std::sort(t.begin(), t.end());
      const double med = t[t.size() / 2];
      std::vector<CsvCell> row = {a, b, g, cone, height, cmd.models[m], med, cmd.spp};
      std::printf("%-5.3g %-5.3g %-5.3g %-5.3g %-5.3g %-8s %9.2f", a, b, g, cone, height, cmd.models[m].c_str(), med);
      for (const Stat& s : st) {
        const double ratio = s.ref > 0 ? s.fast / s.ref : 0.0, noise = s.ref > 0 ? std::sqrt(s.var) / s.ref : 0.0;
        row.push_back(s.pixels);
        row.push_back(s.pixels ? CsvCell(ratio) : CsvCell(std::string()));
        row.push_back(s.pixels ? CsvCell(noise) : CsvCell(std::string()));
        if (s.pixels) std::printf(" %6.3f ±%5.3f (%5d)", ratio, noise, s.pixels);
        else std::printf(" %22s", "-");
      }
      std::printf("\n");
      if (cmd.means) {
        std::printf("%-45s", "  mean radiance per pixel, fast / reference");
        for (const Stat& s : st)
          if (s.pixels) std::printf(" %10.4g / %9.4g", s.fast / s.pixels, s.ref / s.pixels);
          else std::printf(" %22s", "-");
        std::printf("\n");
      }
      std::fflush(stdout);
      table.addRow(row);
    }
  }
  if (!cmd.csv.empty()) table.write(cmd.csv);
  return 0;
}

}  // namespace seasim
