#include "quality/expected_error.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>

#include "plan/scene_facts.h"
#include "scene/model_keys.h"
#include "spectral/csv_table.h"
#include "util/error.h"
#include "util/paths.h"

namespace seasim {

namespace {

// SEASIM_SKY_* (common/sky.h) of a scene's sky, as the measured cases' `sky` column.
int skyCode(const SkyDesc& sky) {
  switch (sky.model) {
    case SkyDesc::Model::Uniform: return 0;
    case SkyDesc::Model::Analytic: return 1;
    case SkyDesc::Model::Image: return 2;
    case SkyDesc::Model::Preetham: return 3;
  }
  return 0;
}

const char* skyName(int code) {
  static const char* names[] = {"uniform", "CIE clear", "image", "Preetham"};
  return code >= 0 && code < 4 ? names[code] : "unknown";
}

// Share of the water column the view sees before the bottom: 1 - e^{-c depth}, 1 with no bottom.
double columnSeen(const MeasuredCase& c) {
  return c.bottom_m < 0 ? 1.0 : -std::expm1(-(c.a + c.b) * c.bottom_m);
}

// The bottom's depth as a regime sees it: a flat bottom's, a height field's mean; -1 with none.
double bottomDepth(const Scene& scene) {
  switch (scene.bottom.type) {
    case BottomDesc::Type::Flat: return scene.bottom.depth;
    case BottomDesc::Type::HeightField: return 0.5 * (scene.bottom.min_depth + scene.bottom.max_depth);
    default: return -1.0;
  }
}

// A regime's water (a and b at 550 nm, g) and its floor's kind, which the daylight and the lamps' share.
MeasuredCase waterRegime(const Scene& scene) {
  MeasuredCase r;
  r.a = scene.water.a.at(550.0);
  r.b = scene.water.b.at(550.0);
  r.g = scene.water.g;
  r.floor = scene.bottom.type == BottomDesc::Type::HeightField ? 1 : 0;
  return r;
}

// Share of a lamp's light the water takes before its axis meets the bottom: 1 - e^{-c l}, 1 with none.
double beamSeen(const MeasuredCase& c) {
  return c.lamp_bottom_m < 0 ? 1.0 : -std::expm1(-(c.a + c.b) * c.lamp_bottom_m);
}

// The scene's features that no measured daylight case has (the studies: no caustics or foam, and spotlights
// only under water, in their own entry; the sky, the floor's kind and the surface's are the cases' own
// columns, lookupExpectedError).
std::vector<std::string> unmeasuredFeatures(const Scene& scene, bool underwater) {
  std::vector<std::string> f;
  if (!scene.spotlights.empty() && !underwater) f.push_back("spotlights");
  if (underwater && scene.underwater.caustics != UnderwaterDesc::Caustics::None) f.push_back("caustics");
  if (!underwater && scene.sea.bottom_caustics) f.push_back("caustics");
  if (modelKey(scene, "surface.whitecaps") != 0) f.push_back("whitecaps");  // foam: no path-traced counterpart
  return f;
}

// Which cases a regime is looked up in: those measured under its sky, when there are any, among them
// those over its kind of floor, among those its kind of surface, and among those with or without objects
// as it has them, each when there are any. What no case has is added to `features`, by name.
struct CaseFilter {
  const MeasuredCase& regime;
  bool sky = false, floor = false, surface = false, objects = false;  // restrict to the regime's kind
  bool fits(const MeasuredCase& c) const {
    return (!sky || c.sky == regime.sky) && (!floor || c.floor == regime.floor) &&
           (!surface || c.surface == regime.surface) && (!objects || c.objects == regime.objects);
  }
};

CaseFilter caseFilter(const MeasuredCase& regime, const std::vector<MeasuredCase>& cases,
                      std::vector<std::string>& features) {
  CaseFilter f{regime};
  if (cases.empty()) return f;
  f.sky = std::any_of(cases.begin(), cases.end(), [&](const MeasuredCase& c) { return c.sky == regime.sky; });
  if (!f.sky) features.push_back(std::string("the sky (") + skyName(regime.sky) + ")");
  f.floor = std::any_of(cases.begin(), cases.end(), [&](const MeasuredCase& c) {
    return (!f.sky || c.sky == regime.sky) && c.floor == regime.floor;
  });
  if (!f.floor && regime.floor != 0) features.push_back("a height-field bottom");
  f.surface = std::any_of(cases.begin(), cases.end(), [&](const MeasuredCase& c) {
    return (!f.sky || c.sky == regime.sky) && (!f.floor || c.floor == regime.floor) && c.surface == regime.surface;
  });
  if (!f.surface && regime.surface != 0) features.push_back("waves");
  CaseFilter before = f;
  before.objects = false;
  f.objects = std::any_of(cases.begin(), cases.end(),
                          [&](const MeasuredCase& c) { return before.fits(c) && c.objects == regime.objects; });
  if (!f.objects && regime.objects != 0) features.push_back("objects in the lamps' light");
  return f;
}

}  // namespace

double regimeDistance(const MeasuredCase& s, const MeasuredCase& c) {
  const double ln2 = std::log(2.0);
  auto logStep = [&](double x, double y) {
    return std::log(std::max(x, 1e-6) / std::max(y, 1e-6)) / ln2;
  };
  const double da = logStep(s.a, c.a), db = logStep(s.b, c.b), dg = (s.g - c.g) / 0.1;
  const double df = (columnSeen(s) - columnSeen(c)) / 0.25, ds = (s.sun_zenith_deg - c.sun_zenith_deg) / 15.0;
  double lamp2 = 0;  // a lamp's cone and beam, when both are lamps' regimes
  if (s.cone_deg > 0 && c.cone_deg > 0) {
    const double dc = logStep(s.cone_deg, c.cone_deg), dl = (beamSeen(s) - beamSeen(c)) / 0.25;
    lamp2 = dc * dc + dl * dl;
  }
  return std::sqrt(da * da + db * db + dg * dg + df * df + ds * ds + lamp2);
}

std::string measuredTable(const std::string& view, const std::string& model, int source) {
  // <view>_<model>.tables beside the cases: the study tables in `source` order, one per line
  // (tests/perf/expected_error_table.py writes both).
  std::ifstream in(std::filesystem::path(dataDir()) / "expected_error" / (view + "_" + model + ".tables"));
  std::string line;
  for (int i = 0; std::getline(in, line); ++i)
    if (i == source) return line;
  return "unknown";
}

std::vector<MeasuredCase> loadMeasuredCases(const std::string& view, const std::string& model) {
  const std::string path = (std::filesystem::path(dataDir()) / "expected_error" / (view + "_" + model + ".csv")).string();
  const CsvTable t = loadCsv(path);
  if (!t.empty_cells.empty())
    throw RuntimeError(path + ":" + std::to_string(t.empty_cells[0].line) + ": an empty cell in a measured case");
  std::vector<MeasuredCase> cases(t.rows());
  const auto &a = t.column("a"), &b = t.column("b"), &g = t.column("g"), &bottom = t.column("bottom_m"),
             &sun = t.column("sun_zenith_deg"), &sky = t.column("sky"), &floor = t.column("floor"),
             &surface = t.column("surface"), &objects = t.column("objects"), &cone = t.column("cone_deg"), &lamp_bottom = t.column("lamp_bottom_m"),
             &err = t.column("max_abs_error"), &worst = t.column("worst_ratio"), &se = t.column("reference_rel_se"),
             &source = t.column("source");
  for (size_t i = 0; i < cases.size(); ++i)
    cases[i] = MeasuredCase{a[i], b[i], g[i], bottom[i], sun[i],
                            static_cast<int>(sky[i]), static_cast<int>(floor[i]), static_cast<int>(surface[i]),
                            static_cast<int>(objects[i]), cone[i], lamp_bottom[i], err[i], worst[i], se[i],
                            static_cast<int>(source[i])};
  return cases;
}

ExpectedError lookupExpectedError(const MeasuredCase& regime, const std::string& view, const std::string& model,
                                  const std::vector<MeasuredCase>& cases, std::vector<std::string> features) {
  ExpectedError e;
  e.view = view;
  e.model = model;
  e.unmeasured_features = std::move(features);
  e.distance = std::numeric_limits<double>::infinity();
  const CaseFilter eligible = caseFilter(regime, cases, e.unmeasured_features);
  for (const MeasuredCase& c : cases) {
    if (!eligible.fits(c)) continue;
    const double d = regimeDistance(regime, c);
    // Equally near (within 1e-9): the larger error, so a tie never hides the worse case.
    if (d < e.distance - 1e-9 || (std::fabs(d - e.distance) <= 1e-9 && c.max_abs_error > e.nearest.max_abs_error)) {
      e.distance = d;
      e.nearest = c;
    }
  }
  if (cases.empty()) return e;
  e.max_abs_error = e.nearest.max_abs_error;
  e.worst_ratio = e.nearest.worst_ratio;
  e.table = measuredTable(view, model, e.nearest.source);
  e.measured = e.distance <= kExpectedErrorMaxDistance && e.unmeasured_features.empty();
  return e;
}

namespace {

// One lamp's regime: the water, the lamp's cone and the distance along its axis to the bottom (a height
// field's mean plane), and whether objects stand in the lamps' light (the glow and the blur ignore them).
// A lamp out of the water or with a light map never gets here: the parser refuses both under water.
MeasuredCase lampRegime(const Scene& scene, const SpotlightDesc& lamp) {
  MeasuredCase r = waterRegime(scene);
  r.cone_deg = lamp.cone * 180.0 / M_PI;
  const double depth = bottomDepth(scene);
  const double height = lamp.position.y + depth;  // the bottom lies at y = -depth
  if (depth > 0 && height > 0 && lamp.direction.y < 0) r.lamp_bottom_m = height / -lamp.direction.y;
  r.objects = scene.objects.empty() ? 0 : 1;
  return r;
}

// The lamps' entry: each lamp looked up, the worst kept (one not measured before a measured one, then the
// larger error), since each lamp's light carries its own error and the image's is at most the worst.
ExpectedError lampsExpectedError(const Scene& scene) {
  const std::string model = underwaterLampsModel(scene);
  const std::vector<MeasuredCase> cases = loadMeasuredCases("lamps", model);
  ExpectedError worst;
  for (size_t i = 0; i < scene.spotlights.size(); ++i) {
    ExpectedError e = lookupExpectedError(lampRegime(scene, scene.spotlights[i]), "lamps", model, cases, {});
    e.subject = "spotlights[" + std::to_string(i) + "]";
    const bool worse = i == 0 || (worst.measured && !e.measured) ||
                       (worst.measured == e.measured && e.max_abs_error > worst.max_abs_error);
    if (worse) worst = std::move(e);
  }
  return worst;
}

}  // namespace

std::vector<ExpectedError> expectedErrors(const Scene& scene) {
  const bool underwater = cameraUnderwater(scene);
  const bool sea = !underwater && seaSeenFromAbove(scene) && !scene.shallow.present;
  if (!scene.water.present || (!underwater && !sea)) return {};
  MeasuredCase regime = waterRegime(scene);
  regime.bottom_m = bottomDepth(scene);
  regime.sun_zenith_deg = scene.sun.zenith * 180.0 / M_PI;
  regime.sky = skyCode(scene.sky);
  regime.surface = scene.surface.type == SurfaceDesc::Type::Fft ? 1 : 0;
  const std::string view = underwater ? "underwater" : "sea";
  const std::string model = underwater ? (scene.underwater.model == UnderwaterDesc::Model::DiscreteOrdinates ? "discrete_ordinates" : "thesis")
                                       : (scene.sea.model == SeaDesc::Model::Multiple ? "multiple" : "paper");
  std::vector<ExpectedError> out = {
      lookupExpectedError(regime, view, model, loadMeasuredCases(view, model), unmeasuredFeatures(scene, underwater))};
  if (underwater && !scene.spotlights.empty()) out.push_back(lampsExpectedError(scene));
  return out;
}

nlohmann::json expectedErrorJson(const std::vector<ExpectedError>& errors) {
  nlohmann::json out = nlohmann::json::array();
  for (const ExpectedError& e : errors) {
    const MeasuredCase& c = e.nearest;
    nlohmann::json nearest = {{"a", c.a}, {"b", c.b}, {"g", c.g}, {"bottom_m", c.bottom_m},
                              {"sun_zenith_deg", c.sun_zenith_deg}, {"sky", skyName(c.sky)},
                              {"floor", c.floor ? "height field" : "flat or none"},
                              {"surface", c.surface ? "FFT waves" : "flat"}, {"reference_rel_se", c.reference_rel_se}};
    if (c.cone_deg > 0) {
      nearest["cone_deg"] = c.cone_deg;
      nearest["lamp_bottom_m"] = c.lamp_bottom_m;
    }
    out.push_back({{"view", e.view},
                   {"model", e.model},
                   {"measured", e.measured},
                   {"status", e.measured ? "measured" : "unmeasured here"},
                   {"expected_max_abs_error", e.max_abs_error},
                   {"worst_ratio", e.worst_ratio},
                   {"distance", e.distance},
                   {"max_distance", kExpectedErrorMaxDistance},
                   {"unmeasured_features", e.unmeasured_features},
                   {"table", e.table},
                   {"nearest_case", nearest}});
    if (!e.subject.empty()) out.back()["subject"] = e.subject;
  }
  return out;
}

std::string expectedErrorText(const std::vector<ExpectedError>& errors) {
  std::string out;
  char line[512];
  for (const ExpectedError& e : errors) {
    const MeasuredCase& c = e.nearest;
    std::string why;
    if (e.distance > kExpectedErrorMaxDistance) why = "; distance > " + std::to_string(kExpectedErrorMaxDistance).substr(0, 3);
    for (const std::string& f : e.unmeasured_features) why += "; " + f;
    if (c.cone_deg > 0) {
      std::snprintf(line, sizeof line,
                    "expected error (%s %s, %s, against all orders): %s%.1f %% (worst ratio %.3f), the nearest measured "
                    "case a %.3g b %.3g g %.2g cone %.0f deg, %s to the bottom along the axis, distance %.2f, in %s%s\n",
                    e.view.c_str(), e.model.c_str(), e.subject.c_str(), e.measured ? "" : "UNMEASURED HERE; for orientation ",
                    100 * e.max_abs_error, e.worst_ratio, c.a, c.b, c.g, c.cone_deg,
                    c.lamp_bottom_m < 0 ? "no bottom" : (std::to_string(c.lamp_bottom_m).substr(0, 4) + " m").c_str(),
                    e.distance, e.table.c_str(), why.c_str());
      out += line;
      continue;
    }
    std::snprintf(line, sizeof line,
                  "expected error (%s %s, against all orders): %s%.1f %% (worst ratio %.3f), the nearest measured "
                  "case a %.3g b %.3g g %.2g bottom %s sun %.0f deg %s sky%s, distance %.2f, in %s%s\n",
                  e.view.c_str(), e.model.c_str(), e.measured ? "" : "UNMEASURED HERE; for orientation ", 100 * e.max_abs_error,
                  e.worst_ratio, c.a, c.b, c.g, c.bottom_m < 0 ? "none" : (std::to_string(c.bottom_m).substr(0, 4) + " m").c_str(),
                  c.sun_zenith_deg, skyName(c.sky), c.surface ? ", FFT waves" : "", e.distance, e.table.c_str(),
                  why.c_str());
    out += line;
  }
  return out;
}

}  // namespace seasim
