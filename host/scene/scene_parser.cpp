// scene_parser.cpp — TOML scene files -> Scene. Every table and key is documented in
// scenes/README.md (same order as here); keep the two in step.
#include "scene/scene_parser.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <tuple>

#include "scene/model_keys.h"
#include "scene/toml_reader.h"
#include "scene/water_phase.h"
#include "spectral/jerlov.h"
#include "spectral/sensor.h"
#include "spectral/von_kries.h"
#include "plan/memory_budget.h"
#include "plan/shafts_method.h"
#include "util/error.h"
#include "util/paths.h"

namespace fs = std::filesystem;

namespace seasim {
namespace {

// The path tracer's and quadrature reference's [quality] knobs (host/reference: not a pass, so not in
// a descriptor); the passes' own count knobs are their descriptors' (qualityCountKnobs()).
// scenes/README.md [quality] lists them all.
const KnobDefault kReferenceKnobs[] = {
    {"reference_spp", 64},     // seasim reference under water: paths per pixel (without --steps)
    {"reference_steps", 200},  // seasim reference, sea and shafts: steps per ray (without --steps)
};
constexpr long long kMaxKnob = 1 << 20;  // catches typos such as 1e9 planes

constexpr double kDegToRad = std::numbers::pi / 180.0;

const std::vector<std::string> kTopLevel = {
    "scene",  "camera",  "sun",        "sky",      "water", "air",    "surface",
    "bottom", "objects", "spotlights", "spectral", "sea",   "underwater", "shallow", "quality",
    "display", "outputs"};

// The tables whose keys a model may declare in its descriptor (scene/model_keys.h): each is read
// through SceneParser::finish.
const std::vector<std::string> kModelKeyTables = {"camera", "sun", "sky", "water", "air", "surface", "bottom",
                                                  "spectral", "sea", "underwater", "shallow", "display", "quality"};

std::string fmt(double v) { return formatNumber(v); }

// ---------------------------------------------------------------------------------------------
// The parser

// The discrete-ordinates model's research keys of [underwater] (scenes/README.md, "Research keys"). Each
// is also read under its earlier name, improved_<key>.
void discreteOrdinatesKeys(TableReader& r, UnderwaterDesc& u) {
  const std::string_view diffuse = r.renamed("diffuse", "improved_diffuse");
  u.diffuse = r.choice(diffuse, "discrete_ordinates", {"discrete_ordinates", "two_stream"}) == "two_stream"
                  ? UnderwaterDesc::Diffuse::TwoStream
                  : UnderwaterDesc::Diffuse::DiscreteOrdinates;
  const std::string_view streams = r.renamed("source_streams", "improved_source_streams");
  u.source_streams = static_cast<int>(r.integerIn(streams, u.source_streams, 0, 64));
  r.check(u.source_streams == 0 || (u.source_streams >= 8 && u.source_streams % 2 == 0), streams,
          "must be 0 (the order-3 field's own in-scatter) or an even number of streams in [8, 64], got " +
              std::to_string(u.source_streams));
  for (auto [name, earlier, value] :
       {std::tuple{"mean_cosine_down", "improved_mean_cosine_down", &u.mean_cosine_down},
        std::tuple{"mean_cosine_up", "improved_mean_cosine_up", &u.mean_cosine_up},
        std::tuple{"beam_mean_cosine_down", "improved_beam_mean_cosine_down", &u.beam_mean_cosine_down},
        std::tuple{"beam_mean_cosine_up", "improved_beam_mean_cosine_up", &u.beam_mean_cosine_up}}) {
    const std::string_view key = r.renamed(name, earlier);
    *value = r.number(key, *value);
    r.check(*value == 0 || (*value >= 0.1 && *value <= 1), key,
            "must be 0 (the fitted table) or a mean cosine in [0.1, 1], got " + fmt(*value));
  }
  const std::string closure =
      r.choice(r.renamed("two_stream_closure", "improved_two_stream"), "default", {"default", "quadrature", "asymptotic"});
  u.two_stream_closure = closure == "quadrature"   ? UnderwaterDesc::TwoStream::Quadrature
                         : closure == "asymptotic" ? UnderwaterDesc::TwoStream::Asymptotic
                                                   : UnderwaterDesc::TwoStream::Default;
  const std::string_view share = r.renamed("asymptotic_share", "improved_asymptotic_share");
  u.asymptotic_share = r.number(share, u.asymptotic_share);
  r.check(u.asymptotic_share == -1 || (u.asymptotic_share >= 0 && u.asymptotic_share <= 1), share,
          "must be -1 (the model's own) or a share in [0, 1], got " + fmt(u.asymptotic_share));
  const std::string_view scale = r.renamed("flux_scale", "improved_flux_scale");
  u.flux_scale = r.number(scale, u.flux_scale);
  r.check(u.flux_scale == -1 || (u.flux_scale >= 0 && u.flux_scale <= 3), scale,
          "must be -1 (the model's own) or a scale in [0, 3], got " + fmt(u.flux_scale));
}

class SceneParser {
 public:
  SceneParser(const TomlSource& src, Scene& scene) : src_(src), scene_(scene) {}

  void parse(const toml::table& root_table) {
    TableReader root(src_, root_table, "");
    for (const auto& name : kTopLevel) root.has(name);
    root.finish();
    // Every key the models declare, at its default until its table says otherwise.
    for (const ModelKey& k : modelSceneKeys()) {
      if (std::find(kModelKeyTables.begin(), kModelKeyTables.end(), k.table) == kModelKeyTables.end())
        throw RuntimeError("the scene key " + k.dotted() + " is declared in a table whose model keys the parser "
                           "does not read (scene_parser.cpp, kModelKeyTables)");
      scene_.model_keys[k.dotted()] = k.default_value;
    }

    scene_.name = fs::path(scene_.file).stem().string();
    if (auto* t = root.subtable("scene")) {
      TableReader r(src_, *t, "scene");
      scene_.name = r.string("name", scene_.name);
      r.check(!scene_.name.empty(), "name", "must not be empty");
      r.finish();
    }
    camera(section(root, "camera"));
    sun(section(root, "sun"));
    sky(section(root, "sky"));

    scene_.water.present = root.has("water");
    scene_.air.present = root.has("air");
    // The surface is the air-water boundary and the bottom lies under water: both need [water].
    for (const char* needs_water : {"surface", "bottom"}) {
      if (root.has(needs_water) && !scene_.water.present)
        root.fail(needs_water, std::string("needs a [water] table (the ") + needs_water +
                                   " belongs to the water body); add [water] or remove [" +
                                   needs_water + "]");
    }
    if (scene_.water.present) water(section(root, "water"));
    if (scene_.air.present) air(section(root, "air"));
    surface(section(root, "surface"));
    bottom(section(root, "bottom"), root.has("bottom"));
    // Counts are capped (plan/memory_budget.h): each light costs a shadow map and every pixel's
    // shaft integral, each object a test per pixel per light; thousands aborted inside the driver.
    for (const auto& [i, t] : root.arrayOfTables("objects")) {
      if (i >= static_cast<size_t>(kMaxObjects))
        src_.fail(t, "objects[" + std::to_string(i) + "]",
                  "too many objects: at most " + std::to_string(kMaxObjects) + " per scene");
      object(*t, i);
    }
    for (const auto& [i, t] : root.arrayOfTables("spotlights")) {
      if (i >= static_cast<size_t>(kMaxSpotlights))
        src_.fail(t, "spotlights[" + std::to_string(i) + "]",
                  "too many spotlights: at most " + std::to_string(kMaxSpotlights) + " per scene");
      spotlight(*t, i);
    }
    spectral(section(root, "spectral"));
    sea(section(root, "sea"));
    underwater(section(root, "underwater"));
    if (root.subtable("shallow")) {
      // [shallow] needs water seen from above a flat surface: errors at the [shallow] header.
      root.check(scene_.water.present, "shallow", "needs a [water] table (the four-flow model's water)");
      root.check(scene_.camera.position.y > 0, "shallow",
                 "the four-flow model renders water seen from above: camera.position y must be > 0");
      shallow(section(root, "shallow"));
    }
    quality(section(root, "quality"));
    display(section(root, "display"));
    TableReader outputs(src_, section(root, "outputs"), "outputs");
    parseOutputs(outputs, scene_.outputs);
  }

 private:
  const TomlSource& src_;
  Scene& scene_;
  toml::table empty_;

  // Reads the keys the models declare for `table` (scene/model_keys.h), then reports every key
  // still unread as unknown.
  void finish(TableReader& r, const std::string& table) {
    for (const ModelKey& k : modelSceneKeys()) {
      if (k.table != table) continue;
      double v = k.default_value;
      if (k.type == ModelKey::Type::Boolean) {
        v = r.boolean(k.name, k.default_value != 0) ? 1.0 : 0.0;
      } else if (k.type == ModelKey::Type::Integer) {
        v = static_cast<double>(r.integerIn(k.name, static_cast<long long>(k.default_value),
                                            static_cast<long long>(k.min), static_cast<long long>(k.max)));
      } else {
        v = r.number(k.name, k.default_value);
        r.check((k.min_open ? v > k.min : v >= k.min) && v <= k.max, k.name,
                "must be in " + std::string(k.min_open ? "(" : "[") + fmt(k.min) + ", " + fmt(k.max) + "]" +
                    (k.unit.empty() ? "" : " " + k.unit) + ", got " + fmt(v));
      }
      scene_.model_keys[k.dotted()] = v;
    }
    r.finish();
  }

  const toml::table& section(TableReader& root, const char* name) {
    const toml::table* t = root.subtable(name);
    return t ? *t : empty_;
  }


  // A texture path, resolved against the scene file's folder; it must exist.
  std::string texture(TableReader& r, const char* key, bool required) {
    if (!r.has(key)) {
      if (required) r.fail(key, "missing: this type needs an image file");
      return "";
    }
    std::string p = r.string(key, "");
    r.check(!p.empty(), key, "must not be empty");
    std::string abs = resolveRelativeTo(scene_.file, p);
    const std::string problem = inputFileProblem(abs);
    r.check(problem.empty(), key, problem);
    scene_.images.push_back(ImageInputRef{r.path(key), abs, src_.locOf(r.get(key))});
    return abs;
  }

  // Wavelengths: non-empty, positive, strictly increasing.
  void checkWavelengths(TableReader& r, const char* key, const std::vector<double>& wl) {
    r.check(!wl.empty(), key, "must not be empty");
    for (size_t i = 0; i < wl.size(); ++i) {
      r.check(wl[i] > 0, key, "wavelengths must be positive, got " + fmt(wl[i]));
      if (i > 0)
        r.check(wl[i] > wl[i - 1], key,
                "wavelengths must be strictly increasing (" + fmt(wl[i - 1]) + " then " +
                    fmt(wl[i]) + ")");
    }
  }

  // An array of values at the table's wavelengths: same length, each in [lo, hi].
  Spectrum spectrumValues(TableReader& r, const char* key, const std::vector<double>& wl, double lo,
                          double hi, const std::string& range_text) {
    std::vector<double> v = r.numbers(key);
    r.check(v.size() == wl.size(), key,
            "has " + std::to_string(v.size()) + " values but wavelengths_nm has " +
                std::to_string(wl.size()));
    for (double x : v)
      r.check(x >= lo && x <= hi, key, "values must be " + range_text + ", got " + fmt(x));
    return Spectrum{wl, v};
  }

  // albedo = 0.3 or albedo = { wavelengths_nm = [...], values = [...] }, each in [0, 1].
  Spectrum albedo(TableReader& r, const Spectrum& def) {
    const toml::node* n = r.get("albedo");
    if (!n) return def;
    if (n->is_number()) {
      double v = r.number("albedo", 0);
      r.check(v >= 0 && v <= 1, "albedo", "must be in [0, 1], got " + fmt(v));
      return Spectrum::constant(v);
    }
    const toml::table* t = n->as_table();
    if (!t)
      r.fail("albedo",
             "expected a number in [0, 1] or { wavelengths_nm = [...], values = [...] }, got " +
                 typeName(*n));
    TableReader s(src_, *t, r.path("albedo"));
    for (const char* k : {"wavelengths_nm", "values"}) s.has(k);
    s.finish();
    std::vector<double> wl = s.numbers("wavelengths_nm");
    checkWavelengths(s, "wavelengths_nm", wl);
    Spectrum out = spectrumValues(s, "values", wl, 0, 1, "in [0, 1]");
    s.finish();
    return out;
  }

  Vec3 direction(TableReader& r, const char* key, Vec3 def) {
    Vec3 d = r.vec3(key, def);
    r.check(length(d) > 0, key, "must not be the zero vector");
    return normalize(d);
  }

  void camera(const toml::table& t) {
    TableReader r(src_, t, "camera");
    CameraDesc& c = scene_.camera;
    c.position = r.vec3("position", c.position);
    c.look_at = r.vec3("look_at", c.look_at);
    c.up = r.vec3("up", c.up);
    double fov = r.number("fov_deg", 60.0);
    r.check(fov > 0 && fov < 180, "fov_deg", "must be in (0, 180) degrees, got " + fmt(fov));
    c.fov_y = fov * kDegToRad;
    c.width = static_cast<int>(r.integerIn("width", c.width, 1, 16384));
    c.height = static_cast<int>(r.integerIn("height", c.height, 1, 16384));
    c.exposure_ev = r.number("exposure_ev", c.exposure_ev);

    Vec3 view = c.look_at - c.position;
    // Point at whichever of the two an override wrote, so a job's bad position is found there.
    const char* at = src_.isOverride(t.get("position")) ? "position" : "look_at";
    r.check(length(view) > 0, at, "camera.position and camera.look_at are the same point");
    r.check(length(c.up) > 0, "up", "must not be the zero vector");
    r.check(length(cross(view, c.up)) > 1e-9 * length(view) * length(c.up), "up",
            "is parallel to the view direction (look_at - position)");
    c.up = normalize(c.up);
    finish(r, "camera");
  }

  void sun(const toml::table& t) {
    TableReader r(src_, t, "sun");
    SunDesc& s = scene_.sun;
    s.enabled = r.boolean("enabled", s.enabled);
    double zenith = r.number("zenith_deg", 45.0);
    // Zenith up to 180: a sun below the horizon (dusk, night) is allowed.
    r.check(zenith >= 0 && zenith <= 180, "zenith_deg",
            "must be in [0, 180] degrees, got " + fmt(zenith));
    s.zenith = zenith * kDegToRad;
    s.azimuth = r.number("azimuth_deg", 0.0) * kDegToRad;
    s.irradiance = r.number("irradiance", s.irradiance);
    r.check(s.irradiance >= 0, "irradiance", "must be >= 0, got " + fmt(s.irradiance));
    double radius = r.number("angular_radius_deg", 0.2667);
    r.check(radius >= 0 && radius <= 45, "angular_radius_deg",
            "must be in [0, 45] degrees, got " + fmt(radius));
    s.angular_radius = radius * kDegToRad;
    finish(r, "sun");
  }

  void sky(const toml::table& t) {
    TableReader probe(src_, t, "sky");
    std::string model = probe.choice("model", "uniform", {"uniform", "analytic", "image", "preetham"});
    TableReader r(src_, t, "sky", "not used with model = '" + model + "'");
    r.has("model");
    SkyDesc& s = scene_.sky;
    s.model = model == "uniform"    ? SkyDesc::Model::Uniform
              : model == "analytic" ? SkyDesc::Model::Analytic
              : model == "preetham" ? SkyDesc::Model::Preetham
                                    : SkyDesc::Model::Image;
    s.radiance = r.number("radiance", s.radiance);
    r.check(s.radiance >= 0, "radiance", "must be >= 0, got " + fmt(s.radiance));
    if (s.model == SkyDesc::Model::Image) s.image = texture(r, "image", true);
    if (s.model == SkyDesc::Model::Preetham) {
      s.turbidity = r.number("turbidity", s.turbidity);
      // Preetham et al. 1999 fitted T in [2, 10]; 1.7 (the clearest skies) is the usual lower limit.
      r.check(s.turbidity >= 1.7 && s.turbidity <= 10, "turbidity", "must be in [1.7, 10], got " + fmt(s.turbidity));
      s.chromaticity_on_daylight_locus = r.choice("chromaticity", "preetham", {"preetham", "daylight_locus"}) == "daylight_locus";
    }
    finish(r, "sky");
  }

  // Water: a Jerlov type or explicit spectra. With explicit spectra, c may be given instead of b
  // (b = c - a), or with both, and then must equal a + b; kd left out stays empty and
  // resolveWater (spectral/jerlov.h) derives it from a and b.
  void water(const toml::table& t) {
    TableReader r(src_, t, "water");
    // Unknown keys first: a typo'd "jerlv" should read as a typo, not as "jerlov missing".
    for (const char* k : {"jerlov", "wavelengths_nm", "a", "b", "c", "kd", "g", "ior", "phase", "phase_file", "bb_ratio"})
      r.has(k);
    finish(r, "water");
    WaterDesc& w = scene_.water;
    const char* explicit_keys[] = {"wavelengths_nm", "a", "b", "c", "kd"};
    const char* first_explicit = nullptr;
    for (const char* k : explicit_keys)
      if (r.has(k) && !first_explicit) first_explicit = k;

    if (r.has("jerlov")) {
      if (first_explicit)
        r.fail(first_explicit,
               "give either jerlov or explicit spectra (wavelengths_nm, a, b), not both");
      std::string type = r.string("jerlov", "");
      std::string canon = type;
      for (char& ch : canon) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
      const std::vector<std::string>& types = jerlovTypes();
      if (std::find(types.begin(), types.end(), canon) == types.end()) {
        std::string list;
        for (size_t i = 0; i < types.size(); ++i) list += (i ? ", " : "") + types[i];
        r.fail("jerlov", "unknown Jerlov water type '" + type + "'; valid: " + list);
      }
      // The tables' spectra (spectral/jerlov.h: a, b from Solonenko & Mobley 2015 with its gaps
      // filled, Kd from Jerlov 1976), so every consumer sees the same water.
      WaterSpectra js = jerlovWater(canon);
      w.jerlov = canon;
      w.a = js.a;
      w.b = js.b;
      w.kd = js.kd;
    } else if (first_explicit) {
      r.check(r.has("wavelengths_nm"), first_explicit, "explicit spectra need wavelengths_nm");
      r.check(r.has("a"), "wavelengths_nm", "explicit spectra need a (absorption, 1/m)");
      r.check(r.has("b") || r.has("c"), "wavelengths_nm",
              "explicit spectra need b (scattering, 1/m) or c (attenuation, 1/m)");
      std::vector<double> wl = r.numbers("wavelengths_nm");
      checkWavelengths(r, "wavelengths_nm", wl);
      const double inf = INFINITY;
      w.a = spectrumValues(r, "a", wl, 0, inf, ">= 0");
      if (r.has("b")) w.b = spectrumValues(r, "b", wl, 0, inf, ">= 0");
      if (r.has("c")) {
        Spectrum c = spectrumValues(r, "c", wl, 0, inf, ">= 0");
        if (!r.has("b")) w.b = Spectrum{wl, std::vector<double>(wl.size())};
        for (size_t i = 0; i < wl.size(); ++i) {
          double b_from_c = c.values[i] - w.a.values[i];
          if (!r.has("b")) {
            r.check(b_from_c >= -1e-9, "c",
                    "c must be >= a (b = c - a), but at " + fmt(wl[i]) +
                        " nm c = " + fmt(c.values[i]) + " < a = " + fmt(w.a.values[i]));
            w.b.values[i] = std::max(b_from_c, 0.0);
          } else {
            double sum = w.a.values[i] + w.b.values[i];
            r.check(std::abs(c.values[i] - sum) <= 0.005 * sum + 1e-6, "c",
                    "c must equal a + b (within 0.5 %), but at " + fmt(wl[i]) +
                        " nm c = " + fmt(c.values[i]) + " and a + b = " + fmt(sum));
          }
        }
      }
      if (r.has("kd")) w.kd = spectrumValues(r, "kd", wl, 0, inf, ">= 0");
    } else {
      r.fail("jerlov",
             "missing: [water] needs jerlov = \"IB\" (a Jerlov type) or explicit spectra "
             "wavelengths_nm, a and b");
    }
    w.g = r.number("g", w.g);
    r.check(std::abs(w.g) < 1, "g", "must satisfy |g| < 1, got " + fmt(w.g));
    readWaterPhase(r, scene_.file, w);
    w.ior = r.number("ior", w.ior);
    r.check(w.ior > 1 && w.ior < 3, "ior",
            "must be in (1, 3) (water is denser than air), got " + fmt(w.ior));
    r.finish();
  }

  void air(const toml::table& t) {
    TableReader probe(src_, t, "air");
    std::string phase = probe.choice("phase", "shafts", {"shafts", "hg"});
    TableReader r(src_, t, "air", "not used with phase = '" + phase + "'");
    r.has("phase");
    AirDesc& a = scene_.air;
    a.phase = phase == "hg" ? AirDesc::Phase::HenyeyGreenstein : AirDesc::Phase::Shafts;
    a.density = r.number("density", a.density);
    r.check(a.density >= 0, "density", "must be >= 0, got " + fmt(a.density));
    a.extinction = r.number("extinction", a.extinction);
    r.check(a.extinction >= 0, "extinction", "must be >= 0 (1/m), got " + fmt(a.extinction));
    if (a.phase == AirDesc::Phase::HenyeyGreenstein) {
      a.g = r.number("g", a.g);
      r.check(std::abs(a.g) < 1, "g", "must satisfy |g| < 1, got " + fmt(a.g));
    }
    finish(r, "air");
  }

  // The wave keys are read (and ignored) for a flat surface too, so a scene can switch type by
  // an override, and a job's frames (surface.time) apply to any sea.
  void surface(const toml::table& t) {
    TableReader r(src_, t, "surface");
    SurfaceDesc& s = scene_.surface;
    std::string type = r.choice("type", "flat", {"flat", "fft"});
    s.type = type == "fft" ? SurfaceDesc::Type::Fft : SurfaceDesc::Type::Flat;
    auto nonNegative = [&](const char* key, double& v, const char* unit) {
      v = r.number(key, v);
      r.check(v >= 0, key, std::string("must be >= 0") + unit + ", got " + fmt(v));
    };
    nonNegative("wind_speed", s.wind_speed, " m/s");
    s.wind_direction = r.number("wind_direction_deg", 0.0) * kDegToRad;
    s.patch_size = r.number("patch_size", s.patch_size);
    r.check(s.patch_size > 0, "patch_size", "must be > 0 m, got " + fmt(s.patch_size));
    long long grid = r.integer("grid", s.grid);
    r.check(grid >= 16 && grid <= 2048 && (grid & (grid - 1)) == 0, "grid",
            "must be a power of two in [16, 2048], got " + std::to_string(grid));
    s.grid = static_cast<int>(grid);
    nonNegative("choppiness", s.choppiness, "");
    nonNegative("directional_exponent", s.directional_exponent, "");
    nonNegative("small_wave", s.small_wave, " m");
    nonNegative("depth", s.depth, " m");
    nonNegative("loop_period", s.loop_period, " s");
    s.time = r.number("time", s.time);
    s.seed = static_cast<unsigned>(r.integerIn("seed", s.seed, 0, 4294967295LL));
    finish(r, "surface");
  }

  // Without [bottom] the water is deep (type "none"); a [bottom] table defaults to a flat one.
  void bottom(const toml::table& t, bool present) {
    TableReader probe(src_, t, "bottom");
    std::string type =
        probe.choice("type", present ? "flat" : "none", {"none", "flat", "heightfield"});
    // The underwater models have no height-field floor (their set-up takes a flat bottom or none).
    probe.check(type != "heightfield" || !scene_.water.present || !(scene_.camera.position.y < 0), "type",
                "\"heightfield\" is drawn from above the water (the sea and shallow water); with the camera under "
                "the surface use type = \"flat\" or \"none\"");
    TableReader r(src_, t, "bottom", "not used with type = '" + type + "'");
    r.has("type");
    BottomDesc& b = scene_.bottom;
    if (type == "flat") {
      b.type = BottomDesc::Type::Flat;
      b.depth = r.number("depth", b.depth);
      r.check(b.depth >= 0, "depth", "must be >= 0 m, got " + fmt(b.depth));
      b.albedo = albedo(r, b.albedo);
    } else if (type == "heightfield") {
      b.type = BottomDesc::Type::HeightField;
      b.heightfield = texture(r, "heightfield", true);
      b.min_depth = r.number("min_depth", b.min_depth);
      r.check(b.min_depth >= 0, "min_depth", "must be >= 0 m, got " + fmt(b.min_depth));
      b.max_depth = r.number("max_depth", b.max_depth);
      r.check(b.max_depth > b.min_depth, "max_depth",
              "must be > min_depth (" + fmt(b.min_depth) + " m), got " + fmt(b.max_depth));
      b.extent = r.number("extent", b.extent);
      r.check(b.extent > 0, "extent", "must be > 0 m, got " + fmt(b.extent));
      b.albedo = albedo(r, b.albedo);
    } else {
      b.type = BottomDesc::Type::None;
    }
    finish(r, "bottom");
  }

  void object(const toml::table& t, size_t index) {
    std::string path = "objects[" + std::to_string(index) + "]";
    TableReader probe(src_, t, path);
    probe.check(probe.has("type"), "type",
                "missing: one of 'sphere', 'box', 'plane', 'heightfield'");
    std::string type = probe.choice("type", "", {"sphere", "box", "plane", "heightfield"});
    TableReader r(src_, t, path, "not used with type = '" + type + "'");
    r.has("type");
    ObjectDesc o;
    o.loc = src_.locOf(&t);
    if (type == "sphere") {
      o.type = ObjectDesc::Type::Sphere;
      o.center = r.vec3("center", o.center);
      o.radius = r.number("radius", o.radius);
      r.check(o.radius > 0, "radius", "must be > 0 m, got " + fmt(o.radius));
    } else if (type == "box") {
      o.type = ObjectDesc::Type::Box;
      r.check(r.has("min") && r.has("max"), r.has("min") ? "max" : "min",
              "missing: a box needs min and max");
      o.box_min = r.vec3("min", o.box_min);
      o.box_max = r.vec3("max", o.box_max);
      r.check(o.box_min.x < o.box_max.x && o.box_min.y < o.box_max.y && o.box_min.z < o.box_max.z,
              "max", "every component of max must be greater than min's");
    } else if (type == "plane") {
      o.type = ObjectDesc::Type::Plane;
      o.point = r.vec3("point", o.point);
      o.normal = direction(r, "normal", o.normal);
    } else {
      o.type = ObjectDesc::Type::HeightField;
      o.heightfield = texture(r, "heightfield", true);
      o.point = r.vec3("point", o.point);
      o.extent = r.number("extent", o.extent);
      r.check(o.extent > 0, "extent", "must be > 0 m, got " + fmt(o.extent));
      o.height = r.number("height", o.height);
      r.check(o.height > 0, "height", "must be > 0 m, got " + fmt(o.height));
    }
    o.albedo = albedo(r, o.albedo);
    r.finish();
    scene_.objects.push_back(o);
  }

  void spotlight(const toml::table& t, size_t index) {
    TableReader r(src_, t, "spotlights[" + std::to_string(index) + "]");
    SpotlightDesc s;
    s.loc = src_.locOf(&t);
    s.position = r.vec3("position", s.position);
    s.direction = direction(r, "direction", s.direction);
    double cone = r.number("cone_deg", 20.0);
    r.check(cone > 0 && cone < 90, "cone_deg", "must be in (0, 90) degrees, got " + fmt(cone));
    double falloff = r.number("falloff_deg", std::min(5.0, cone));
    r.check(falloff >= 0 && falloff <= cone, "falloff_deg",
            "must be in [0, cone_deg = " + fmt(cone) + "] degrees, got " + fmt(falloff));
    s.cone = cone * kDegToRad;
    s.falloff = falloff * kDegToRad;
    s.intensity = r.number("intensity", s.intensity);
    r.check(s.intensity >= 0, "intensity", "must be >= 0 W/sr, got " + fmt(s.intensity));
    s.color = r.vec3("color", s.color);
    r.check(s.color.x >= 0 && s.color.y >= 0 && s.color.z >= 0, "color", "components must be >= 0");
    s.has_color = r.has("color");
    s.light_map = texture(r, "light_map", false);
    if (r.has("temperature_k")) {
      s.temperature_k = r.number("temperature_k", 0.0);
      r.check(s.temperature_k >= 500 && s.temperature_k <= 50000, "temperature_k",
              "must be in [500, 50000] K, got " + fmt(s.temperature_k));
    }
    if (r.has("spectrum")) {
      r.check(s.temperature_k == 0, "spectrum", "give either spectrum or temperature_k, not both");
      const std::string p = r.string("spectrum", "");
      r.check(!p.empty(), "spectrum", "must not be empty");
      s.spectrum = resolveRelativeTo(scene_.file, p);
      const std::string problem = inputFileProblem(s.spectrum);
      r.check(problem.empty(), "spectrum", problem);
    }
    const bool spectral_lamp = s.temperature_k > 0 || !s.spectrum.empty();
    r.check(!(spectral_lamp && s.has_color), "color",
            "a lamp with temperature_k or spectrum takes its colour from that spectrum; remove color");
    // Under water the lamp shines in the water's spectral medium (passes/underwater_lamps_pass.h):
    // its colour is a spectrum, and it must be in the water (a lamp in air would light the water
    // through the refracting surface, which is not modelled).
    if (scene_.water.present && scene_.camera.position.y < 0) {
      r.check(s.position.y < 0, "position",
              "a lamp at or above the water surface (y = " + fmt(s.position.y) +
                  " >= 0) is not modelled under water (its light would refract through the surface); put it "
                  "below y = 0");
      r.check(!s.has_color, "color", "under water a lamp is spectral: give temperature_k or spectrum instead of color");
      r.check(s.light_map.empty(), "light_map", "light maps are not supported for lamps under water yet");
    }
    r.finish();
    scene_.spotlights.push_back(s);
  }

  void spectral(const toml::table& t) {
    TableReader r(src_, t, "spectral");
    SpectralDesc& s = scene_.spectral;
    s.count = static_cast<int>(r.integerIn("count", s.count, 1, 1000));
    if (r.has("range_nm")) {
      std::vector<double> range = r.numbers("range_nm");
      r.check(range.size() == 2, "range_nm",
              "expected [min, max] in nm, got " + std::to_string(range.size()) + " numbers");
      r.check(range[0] < range[1], "range_nm",
              "min must be < max, got [" + fmt(range[0]) + ", " + fmt(range[1]) + "]");
      r.check(range[0] >= 300 && range[1] <= 1000, "range_nm",
              "must lie within [300, 1000] nm, got [" + fmt(range[0]) + ", " + fmt(range[1]) + "]");
      s.min_nm = range[0];
      s.max_nm = range[1];
    }
    if (r.has("camera_dir")) {
      const std::string dir = r.string("camera_dir", "");
      r.check(!dir.empty(), "camera_dir", "must not be empty");
      s.camera_dir = resolveRelativeTo(scene_.file, dir);
      std::error_code ec;
      r.check(std::filesystem::is_directory(s.camera_dir, ec), "camera_dir",
              "no such folder: " + s.camera_dir + " (a folder of <camera>.csv files with the header nm,r,g,b)");
    }
    s.sensor = r.string("sensor", s.sensor);
    double white_kelvin = 0;  // "vonkries[:<kelvin>]": 003 eq. 15-17 (spectral/von_kries.h)
    bool von_kries = false;
    try {
      von_kries = parseVonKriesSensor(s.sensor, &white_kelvin);
    } catch (const std::exception& e) {
      r.fail("sensor", e.what());
    }
    if (s.sensor != "cie1931" && s.sensor != "identity" && !von_kries && cameraFile(s.sensor, s.camera_dir).empty()) {
      std::vector<std::string> names = cameraNames(s.camera_dir);
      names.insert(names.begin(), {"cie1931", "identity", "vonkries"});
      r.fail("sensor", unknownCameraMessage(s.sensor, s.camera_dir) + suggestion(s.sensor, names, 6));
    }
    if (s.sensor != "cie1931" && s.sensor != "identity" && !von_kries) {
      // Read now, not at the first frame: an unreadable or malformed camera CSV passed `validate`
      // and failed the render.
      try {
        (void)loadCamera(s.sensor, s.camera_dir);
      } catch (const std::exception& e) {
        r.fail("sensor", e.what());
      }
    }
    s.white_balance = r.boolean("white_balance", s.white_balance);
    s.spectral_exr = r.boolean("spectral_exr", s.spectral_exr);
    if (s.sensor == "identity") {  // its output is the bands themselves
      r.check(!r.has("spectral_exr") || s.spectral_exr, "spectral_exr",
              "must be true with sensor = \"identity\" (its image.exr is the raw bands)");
      s.spectral_exr = true;
    }
    finish(r, "spectral");
  }

  void sea(const toml::table& t) {
    TableReader r(src_, t, "sea");
    SeaDesc& s = scene_.sea;
    s.model = r.choice("model", "multiple", {"paper", "multiple"}) == "multiple" ? SeaDesc::Model::Multiple
                                                                             : SeaDesc::Model::Paper;
    s.single_scattering = r.boolean("single_scattering", s.single_scattering);
    s.second_order = r.boolean("second_order", s.second_order);
    s.bottom_caustics = r.boolean("bottom_caustics", s.bottom_caustics);
    s.reflection = r.boolean("reflection", s.reflection);
    finish(r, "sea");
  }

  void underwater(const toml::table& t) {
    TableReader r(src_, t, "underwater");
    UnderwaterDesc& u = scene_.underwater;
    // "improved" is the discrete-ordinates model's earlier name, still read as it (and not offered in
    // the messages).
    const toml::node* model = r.get("model");
    const bool earlier_name = model && model->value<std::string>() == "improved";
    u.model = !earlier_name && r.choice("model", "discrete_ordinates", {"thesis", "discrete_ordinates"}) == "thesis"
                  ? UnderwaterDesc::Model::Thesis
                  : UnderwaterDesc::Model::DiscreteOrdinates;
    u.multiple_scattering = r.boolean("multiple_scattering", u.multiple_scattering);
    u.single_scattering = r.boolean("single_scattering", u.single_scattering);
    const std::string caustics = r.choice("caustics", "texture", {"none", "texture", "map"});
    u.caustics = caustics == "none"      ? UnderwaterDesc::Caustics::None
                 : caustics == "texture" ? UnderwaterDesc::Caustics::Texture
                                         : UnderwaterDesc::Caustics::Map;
    if (u.caustics == UnderwaterDesc::Caustics::Map && scene_.surface.type != SurfaceDesc::Type::Fft)
      r.fail("caustics", "\"map\" needs a wavy surface ([surface] type = \"fft\"); use \"texture\" or \"none\"");
    u.caustic_period = r.number("caustic_period_m", u.caustic_period);
    r.check(u.caustic_period > 0, "caustic_period_m", "must be > 0 m, got " + fmt(u.caustic_period));
    u.caustic_speed = r.number("caustic_speed_mps", u.caustic_speed);
    r.check(u.caustic_speed >= 0, "caustic_speed_mps", "must be >= 0 m/s, got " + fmt(u.caustic_speed));
    u.injection = r.choice("froxel_injection", "spectral", {"spectral", "rgb"}) == "rgb"
                      ? UnderwaterDesc::Injection::Rgb
                      : UnderwaterDesc::Injection::Spectral;
    u.froxel_near = r.number("froxel_near_m", u.froxel_near);
    r.check(u.froxel_near > 0, "froxel_near_m", "must be > 0 m, got " + fmt(u.froxel_near));
    u.froxel_far = r.number("froxel_far_m", u.froxel_far);
    r.check(u.froxel_far > u.froxel_near && u.froxel_far <= 1e4, "froxel_far_m",
            "must be > froxel_near_m (" + fmt(u.froxel_near) + ") and <= 10000 m, got " + fmt(u.froxel_far));
    u.point_spread = r.boolean("point_spread", u.point_spread);
    discreteOrdinatesKeys(r, u);
    finish(r, "underwater");
  }

  void shallow(const toml::table& t) {
    TableReader r(src_, t, "shallow");
    ShallowDesc& s = scene_.shallow;
    s.present = true;
    const std::string path = r.choice("path", "table", {"table", "table_eq24", "exact"});
    s.path = path == "exact"        ? ShallowDesc::Path::Exact
             : path == "table_eq24" ? ShallowDesc::Path::TableEq24
                                    : ShallowDesc::Path::Table;
    s.gamma = r.number("gamma", s.gamma);
    r.check(s.gamma > 0 && s.gamma <= 100, "gamma", "must be in (0, 100], got " + fmt(s.gamma));
    s.texture_scale = r.number("texture_scale_m", s.texture_scale);
    r.check(s.texture_scale > 0, "texture_scale_m", "must be > 0 m, got " + fmt(s.texture_scale));
    s.dark_albedo = r.number("dark_albedo", s.dark_albedo);
    r.check(s.dark_albedo >= 0 && s.dark_albedo <= 1, "dark_albedo", "must be in [0, 1], got " + fmt(s.dark_albedo));
    s.dark_fraction = r.number("dark_fraction", s.dark_fraction);
    r.check(s.dark_fraction >= 0 && s.dark_fraction <= 1, "dark_fraction",
            "must be in [0, 1], got " + fmt(s.dark_fraction));
    if (r.has("slope_depths_m")) {
      const std::vector<double> d = r.numbers("slope_depths_m");
      r.check(d.size() == 2 && d[0] >= 0 && d[1] > d[0] && d[1] <= 1e4, "slope_depths_m",
              "expected [shallow, deep] in m with 0 <= shallow < deep <= 10000");
      s.slope = true;
      s.slope_shallow = d[0];
      s.slope_deep = d[1];
      s.slope_extent = r.number("slope_extent_m", s.slope_extent);
      r.check(s.slope_extent > 0 && s.slope_extent <= 1e5, "slope_extent_m",
              "must be in (0, 100000] m, got " + fmt(s.slope_extent));
    } else {
      r.check(scene_.bottom.type != BottomDesc::Type::None, "slope_depths_m",
              "missing: [shallow] needs a bottom: [bottom] type = \"flat\" or \"heightfield\", or slope_depths_m");
    }
    finish(r, "shallow");
  }

  // [display] (io/tonemap_eq18.h): the default curve, or 003 eq. 18 with its constants.
  void display(const toml::table& t) {
    TableReader probe(src_, t, "display");
    const std::string mode = probe.choice("tone_map", "default", {"default", "eq18"});
    TableReader r(src_, t, "display", "not used with tone_map = '" + mode + "'");
    r.has("tone_map");
    DisplayDesc& d = scene_.display;
    if (mode == "eq18") {
      d.tone_map = DisplayDesc::ToneMap::Eq18;
      Eq18Params& p = d.eq18;
      if (const toml::node* n = r.get("adaptation_luminance")) {
        if (auto* s = n->as_string()) {
          r.check(s->get() == "mean" || s->get() == "log_mean", "adaptation_luminance",
                  "expected \"log_mean\", \"mean\" or a number > 0, got \"" + s->get() + "\"");
          p.adaptation = s->get() == "mean" ? Eq18Params::Adaptation::Mean : Eq18Params::Adaptation::LogMean;
        } else {
          p.adaptation = Eq18Params::Adaptation::Given;
          p.world_adaptation = r.number("adaptation_luminance", p.world_adaptation);
          r.check(p.world_adaptation > 0 && std::isfinite(p.world_adaptation), "adaptation_luminance",
                  "must be > 0, got " + fmt(p.world_adaptation));
        }
      }
      const auto positive = [&](const char* key, double& v) {
        v = r.number(key, v);
        r.check(v > 0 && v <= 1e6, key, "must be in (0, 1e6], got " + fmt(v));
      };
      positive("display_adaptation", p.display_adaptation);
      positive("gamma_world", p.gamma_world);
      positive("gamma_display", p.gamma_display);
      positive("contrast_scale", p.contrast_scale);
      if (const toml::node* n = r.get("white")) {
        if (auto* s = n->as_string()) {
          r.check(s->get() == "max", "white", "expected \"max\" or a number > 0, got \"" + s->get() + "\"");
        } else {
          p.white_from_image = false;
          positive("white", p.white);
        }
      }
    }
    finish(r, "display");
  }

  void quality(const toml::table& t) {
    TableReader r(src_, t, "quality");
    std::vector<KnobDefault> counts(std::begin(kReferenceKnobs), std::end(kReferenceKnobs));
    for (const KnobDefault& k : qualityCountKnobs()) counts.push_back(k);
    for (const KnobDefault& k : counts) {
      Knob knob{k.automatic, k.value};
      if (const toml::node* n = r.get(k.name)) {
        knob.given = true;
        if (auto* s = n->as_string()) {
          r.check(s->get() == "auto", k.name,
                  "expected a positive integer or \"auto\", got '" + s->get() + "'");
          knob.automatic = true;
        } else {
          r.check(n->is_integer(), k.name,
                  "expected a positive integer or \"auto\", got " + typeName(*n));
          knob.value = static_cast<double>(r.integerIn(k.name, static_cast<long long>(k.value), 1, kMaxKnob));
          knob.automatic = false;
        }
      }
      scene_.quality[k.name] = knob;
    }
    // Exact phase function in the shafts integral instead of its table: a switch, stored as a
    // knob of value 0 or 1 so the planner reads every setting from one map.
    scene_.quality["shafts_exact"] = Knob{false, r.boolean("shafts_exact", false) ? 1.0 : 0.0};
    // Wave normals filtered over each pixel's footprint (kernels/common/sea_lean.h): on by default.
    scene_.quality["wave_filter"] = Knob{false, r.boolean("wave_filter", true) ? 1.0 : 0.0};
    // Spotlights under water: the model (passes/underwater_lamps_pass.h), stored as a knob 0 "single"
    // (001's single scattering in the water as it is), 1 "delta_m" (the water delta-M scaled), 2
    // "orders" (single scattering plus the orders of common/underwater_lamps_ms.h; the default, the most
    // accurate of the three against all orders: results/BENCHMARKS.md). The older switch lamps_delta_m
    // (true: "delta_m", false: "single") stays, but not beside lamps_model.
    r.check(!(r.has("lamps_model") && r.has("lamps_delta_m")), "lamps_model",
            "give lamps_model or the older lamps_delta_m, not both");
    const std::string older = r.has("lamps_delta_m") ? (r.boolean("lamps_delta_m", true) ? "delta_m" : "single") : "orders";
    const std::string lamps_model = r.choice("lamps_model", older, {"single", "delta_m", "orders"});
    const double lamps_model_id = lamps_model == "single" ? 0.0 : lamps_model == "delta_m" ? 1.0 : 2.0;
    scene_.quality["lamps_model"] = Knob{false, lamps_model_id};
    scene_.quality["lamps_delta_m"] = Knob{false, lamps_model_id == 1.0 ? 1.0 : 0.0};
    // Kernels built with -cl-fast-relaxed-math: true, false or "auto" (the default), which the planner
    // turns on where the shipped scenes were measured within 0.05 of an 8-bit level of the exact-maths
    // image (fastMathFor in host/plan; results/BENCHMARKS.md has the table).
    Knob fast{true, 0.0};
    if (const toml::node* n = r.get("fast_math")) {
      if (auto* s = n->as_string()) {
        r.check(s->get() == "auto", "fast_math", "expected true, false or \"auto\", got '" + s->get() + "'");
      } else {
        fast = Knob{false, r.boolean("fast_math", false) ? 1.0 : 0.0};
      }
    }
    scene_.quality["fast_math"] = fast;
    // The shafts method: "intervals" (exact lit stretches, kernels/common/shafts_intervals.h),
    // "planes" (paper 001's sampling planes, which suit GPU texture units) or "march" (steps in the
    // lamp's angle with exact shadow rays). Absent: the planner's rule (plan/shafts_method.h: intervals
    // while the objects fit its per-pixel stretch list, else planes). "auto": measured on the device at
    // quality.shafts_error_budget before the first render (host/quality/shafts_method_auto.h), the rule
    // until then. Stored as a knob holding ShaftsMethod, automatic for both, given for "auto".
    const std::string method = r.choice("shafts_method", "auto", {"planes", "intervals", "march", "auto"});
    if (method != "auto") {
      r.check(method != "intervals" || static_cast<int>(scene_.objects.size()) <= kShaftsIntervalsMaxObjects,
              "shafts_method",
              "\"intervals\" handles at most " + std::to_string(kShaftsIntervalsMaxObjects) + " objects, the scene has " +
                  std::to_string(scene_.objects.size()) + "; use \"planes\" or \"march\"");
      const ShaftsMethod chosen = method == "intervals" ? ShaftsMethod::Intervals
                                  : method == "march"   ? ShaftsMethod::March
                                                        : ShaftsMethod::Planes;
      scene_.quality["shafts_method"] = Knob{false, static_cast<double>(static_cast<int>(chosen)), true};
    } else {
      scene_.quality["shafts_method"] = Knob{true, 1.0, r.has("shafts_method")};
    }
    // Intervals method: the widest quadrature panel in degrees of the lamp's angle, and over a light
    // map in its texels (the error-time knobs of `seasim sweep`).
    const double panel_deg = r.number("shafts_panel_deg", kShaftsPanelDegDefault);
    r.check(panel_deg >= 0.05 && panel_deg <= 90, "shafts_panel_deg", "must be in [0.05, 90] degrees, got " + fmt(panel_deg));
    scene_.quality["shafts_panel_deg"] = Knob{false, panel_deg};
    const double panel_texels = r.number("shafts_panel_texels", kShaftsPanelTexelsDefault);
    r.check(panel_texels >= 0.05 && panel_texels <= 64, "shafts_panel_texels",
            "must be in [0.05, 64] light-map texels, got " + fmt(panel_texels));
    scene_.quality["shafts_panel_texels"] = Knob{false, panel_texels};
    // RMS error budget of the shafts `auto` quality, 8-bit levels (host/quality/shafts_auto.h): a number, not a knob.
    const double budget = r.number("shafts_error_budget", 1.0);
    r.check(budget > 0 && budget <= 255, "shafts_error_budget", "must be in (0, 255] levels, got " + fmt(budget));
    scene_.quality["shafts_error_budget"] = Knob{false, budget};
    finish(r, "quality");
  }
};

}  // namespace

Scene parseScene(const std::string& toml_text, const std::string& path, const std::vector<Override>& overrides,
                 const std::vector<std::string>& ignored_keys) {
  toml::table root = parseTomlText(toml_text, path);
  TomlSource src(path);
  for (const std::string& key : ignored_keys) src.ignore(key);
  for (const Override& o : overrides) applyOverride(root, o, src);
  Scene scene;
  scene.file = fs::absolute(path).lexically_normal().string();
  SceneParser(src, scene).parse(root);
  return scene;
}

Scene loadScene(const std::string& path, const std::vector<Override>& overrides) {
  return loadScene(path, overrides, {});
}

Scene loadScene(const std::string& path, const std::vector<Override>& overrides,
                const std::vector<std::string>& ignored_keys) {
  std::ifstream in(path, std::ios::binary);
  if (std::error_code ec; !in || fs::is_directory(path, ec)) throw InputError(path, 1, "", "cannot open scene file");
  std::stringstream text;
  text << in.rdbuf();
  return parseScene(text.str(), path, overrides, ignored_keys);
}

}  // namespace seasim
