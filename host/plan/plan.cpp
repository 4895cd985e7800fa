#include "plan/plan.h"
#include "plan/shafts_method.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace seasim {

namespace {

// SEASIM_SKY_MODEL (common/sky.h): 0 uniform, 1 analytic (CIE clear sky), 2 lat-long image, 3 Preetham.
int skyModelOf(const SkyDesc& sky) {
  return sky.model == SkyDesc::Model::Analytic   ? 1
         : sky.model == SkyDesc::Model::Image    ? 2
         : sky.model == SkyDesc::Model::Preetham ? 3
                                                 : 0;
}

}  // namespace

bool Plan::hasPass(const std::string& name) const { return find(name) != nullptr; }

const PassPlan* Plan::find(const std::string& name) const {
  for (const auto& p : passes)
    if (p.name == name) return &p;
  return nullptr;
}

std::vector<std::string> Plan::kernelFiles() const {
  std::vector<std::string> files;
  for (const auto& p : passes)
    if (std::find(files.begin(), files.end(), p.kernel_file) == files.end()) files.push_back(p.kernel_file);
  return files;
}

std::string Plan::toText() const {
  std::ostringstream s;
  int i = 1;
  for (const auto& p : passes) {
    s << i++ << ". " << p.name << "  kernels/" << p.kernel_file << " ";
    if (p.defines.empty()) s << " (no defines)";
    for (const auto& d : p.defines) s << " -D" << d;
    s << "  | reads:";
    for (const auto& r : p.reads) s << " " << r;
    s << "  writes:";
    for (const auto& w : p.writes) s << " " << w;
    s << "  | " << p.why;
    if (!p.implemented) s << "  [not implemented yet: " << p.missing << "]";
    s << "\n";
  }
  return s.str();
}

namespace {

std::string flag(const char* name, bool on) { return std::string(name) + "=" + (on ? "1" : "0"); }

}  // namespace

bool fastMathFor(const Scene& scene) {
  const auto fast = scene.quality.find("fast_math");
  if (fast == scene.quality.end()) return false;
  if (!fast->second.automatic) return fast->second.value != 0;
  const bool sea_view = scene.water.present && scene.camera.position.y >= 0.0;
  const bool waves = scene.surface.type == SurfaceDesc::Type::Fft && scene.water.present;
  return !(sea_view && waves);
}

Plan makePlan(const Scene& scene) {
  Plan plan;
  const bool underwater = scene.water.present && scene.camera.position.y < 0.0;
  const bool sea_view = scene.water.present && !underwater;
  const bool waves = scene.surface.type == SurfaceDesc::Type::Fft && scene.water.present;
  // The air shafts pass: spotlights in a scene without water (under water: underwater_lamps, below).
  const bool lights = !scene.spotlights.empty() && scene.air.present && !scene.water.present;
  const bool objects = !scene.objects.empty();
  const bool spectral_out = scene.spectral.spectral_exr;

  const bool sun_up = scene.sun.enabled && scene.sun.irradiance > 0 && scene.sun.zenith < M_PI / 2;
  const UnderwaterDesc& uw = scene.underwater;
  const bool froxels = underwater && uw.single_scattering && sun_up;
  const int caustics = !sun_up ? 0
                       : uw.caustics == UnderwaterDesc::Caustics::Texture ? 1
                       : uw.caustics == UnderwaterDesc::Caustics::Map     ? 2
                                                                          : 0;
  if (objects && lights && !underwater) {  // issue 4: shafts.cl ray casts its analytic objects per pixel
    plan.passes.push_back({"raycast", "shafts.cl", {}, {"scene"}, {"gbuffer"}, "scene has objects", true, ""});
  }
  // Shafts feature defines (issue 4), shared by the shadow_maps and shafts passes (one build).
  bool light_map = false;
  for (const auto& l : scene.spotlights) light_map = light_map || !l.light_map.empty();
  const auto exact = scene.quality.find("shafts_exact");
  const bool intervals = shaftsUseIntervals(scene);  // plan/shafts_method.h (issue 14)
  const std::vector<std::string> shafts_defines = {
      flag("SEASIM_SHAFTS_INTERVALS", intervals),
      flag("SEASIM_SHAFTS_EXACT", exact != scene.quality.end() && exact->second.value != 0),
      flag("SEASIM_SHAFTS_HG", scene.air.phase == AirDesc::Phase::HenyeyGreenstein),
      flag("SEASIM_HAS_OBJECTS", objects), flag("SEASIM_HAS_LIGHT_MAP", light_map)};
  // The FFT ocean runs for the sea view's wave normals and for the caustic maps under water (under
  // water the model's surface is otherwise flat, so texture caustics or none need no ocean).
  const bool ocean_for_caustics = underwater && waves && caustics == 2;
  // sea_single's wave normals (SEASIM_HAS_WAVES); [shallow] averages its waves on the host (003 eq. 10).
  const bool ocean_for_sea = waves && sea_view && !scene.shallow.present;
  if (ocean_for_sea || ocean_for_caustics) {
    plan.passes.push_back({"ocean_fft", "ocean.cl", {flag("SEASIM_HAS_CHOPPY", scene.surface.choppiness > 0)},
                           {"scene"}, {"ocean_maps"}, "surface.type = \"fft\"", true, ""});
  }
  if (lights && objects && !intervals) {  // the intervals method casts exact shadow volumes instead
    plan.passes.push_back({"shadow_maps", "shafts.cl", shafts_defines, {"scene"}, {"shadow_maps"},
                           "spotlights and objects that cast shadows", true, ""});
  }
  if (ocean_for_caustics) {
    plan.passes.push_back({"caustics", "caustics.cl", {}, {"ocean_maps"}, {"caustic_map"},
                           "camera below an FFT surface, underwater.caustics = \"map\" (004 §5.2.1)", true, ""});
  }
  // The sea seen from above: the ocean's caustics on a bottom the sun reaches (sea.bottom_caustics).
  const bool sea_bottom = scene.bottom.type != BottomDesc::Type::None;
  const bool bottom_caustics = ocean_for_sea && sea_bottom && sun_up && scene.sea.bottom_caustics;
  if (bottom_caustics) {
    plan.passes.push_back({"caustics", "caustics.cl", {}, {"ocean_maps"}, {"caustic_map"},
                           "FFT surface over a bottom, sea.bottom_caustics = true (004 §5.2.1)", true, ""});
  }
  if (underwater) {
    // 002 §4.3.2: the deferred pipeline's G-buffer (hit distance, normal, material, sun visibility);
    // with caustic maps, after the caustics pass: the sun visibility reads them.
    std::vector<std::string> reads = {"scene"};
    if (ocean_for_caustics) reads.push_back("caustic_map");
    PassPlan pass{"raycast", "raycast.cl",
                  {flag("SEASIM_HAS_OBJECTS", objects), flag("SEASIM_HAS_SUN", sun_up),
                   "SEASIM_CAUSTICS=" + std::to_string(caustics)},
                  reads, {"gbuffer"}, "camera below the surface: per-pixel hit, normal, material", true, ""};
    plan.passes.push_back(pass);
  }
  if (froxels) {
    std::vector<std::string> froxel_reads = {"scene", "gbuffer"};  // gbuffer: which froxels are read
    if (ocean_for_caustics) froxel_reads.push_back("caustic_map");
    plan.passes.push_back({"froxel", "froxel.cl",
                           {flag("SEASIM_HAS_OBJECTS", objects), "SEASIM_CAUSTICS=" + std::to_string(caustics),
                            flag("SEASIM_SPECTRAL_INJECTION", uw.injection == UnderwaterDesc::Injection::Spectral)},
                           froxel_reads, {"froxel_volume"},
                           "camera below the surface, sun up, underwater.single_scattering", true, ""});
  }
  // Shallow water with a visible bottom (paper 003): the four-flow pass takes the place of the sea
  // model for the view from above; its tables are built only on the table path.
  const bool shallow = sea_view && scene.shallow.present;
  if (shallow) {
    const bool table = scene.shallow.path != ShallowDesc::Path::Exact;
    const bool eq24 = scene.shallow.path == ShallowDesc::Path::TableEq24;
    plan.passes.push_back({"fourflow", "fourflow.cl",
                           {std::string("SEASIM_FF_TABLES=") + (eq24 ? "2" : table ? "1" : "0"),
                            flag("SEASIM_FF_HEIGHTFIELD", scene.shallow.slope ||
                                                              scene.bottom.type == BottomDesc::Type::HeightField),
                            flag("SEASIM_SPECTRAL_OUTPUT", spectral_out),
                            "SEASIM_SKY_MODEL=" + std::to_string(skyModelOf(scene.sky))},
                           {"scene"}, {"rgb"},
                           std::string("[shallow]: four-flow light field over a visible bottom (003 eq. 4-20), ") +
                               (eq24 ? "(l, h) tables + pre-converted blend (eq. 24)"
                                       : table ? "(l, h) tables + blend (eq. 22-23)" : "exact spectral path (eq. 20)"),
                           true, ""});
  }
  if (sea_view && !shallow) {
    const bool sun = scene.sun.enabled && scene.sun.irradiance > 0;
    const bool height_field = scene.bottom.type == BottomDesc::Type::HeightField;
    const bool bottom = scene.bottom.type == BottomDesc::Type::Flat || height_field;
    const bool multiple = scene.sea.model == SeaDesc::Model::Multiple;
    const int sky_model = skyModelOf(scene.sky);
    std::vector<std::string> defines = {
        flag("SEASIM_HAS_REFLECTION", scene.sea.reflection),
        // "multiple"'s column also holds the skylight scattered in the water, which a sun that is off
        // does not remove; paper 000's single scattering is the sun's alone.
        flag("SEASIM_HAS_SINGLE_SCATTERING", scene.sea.single_scattering && (sun || multiple)),
        flag("SEASIM_HAS_BOTTOM", bottom),
        flag("SEASIM_HAS_SUN", sun),
        flag("SEASIM_SPECTRAL_OUTPUT", spectral_out),
        flag("SEASIM_HAS_WAVES", waves),  // local normals from the ocean's normal map (common/sea_waves.h)
        "SEASIM_SKY_MODEL=" + std::to_string(sky_model),
        flag("SEASIM_BOTTOM_CAUSTICS", bottom_caustics),
        // sea.model: 0 paper 000's eq. 5 and 9, 1 "multiple" (all orders in closed form, no second order)
        std::string("SEASIM_SEA_MODEL=") + (multiple ? "1" : "0")};
    // 000 §5.4: the bottom is a height field (z_Q per pixel, depth tables for the second order).
    if (height_field) defines.push_back("SEASIM_BOTTOM_HEIGHTFIELD=1");
    // Issue 19: wave normals filtered over the pixel's footprint (common/sea_lean.h), unless turned
    // off or replaced by its reference, n x n rays per pixel over the unfiltered normals.
    const auto knob = [&](const char* name, double fallback) {
      const auto it = scene.quality.find(name);
      return it == scene.quality.end() ? fallback : it->second.value;
    };
    const int supersample = static_cast<int>(knob("sea_supersample", 1));
    if (waves) defines.push_back(flag("SEASIM_WAVE_FILTER", knob("wave_filter", 1) != 0 && supersample == 1));
    if (supersample > 1) defines.push_back("SEASIM_SUPERSAMPLE=" + std::to_string(supersample));
    std::vector<std::string> reads = {"scene"};
    if (waves) reads.push_back("ocean_maps");
    if (bottom_caustics) reads.push_back("caustic_map");
    PassPlan pass{"sea_single", "sea_single.cl", defines, reads, {"rgb"},
                  multiple ? "camera above water (reflection; sea.model = \"multiple\": all orders of the water and "
                             "the bottom in closed form)"
                           : "camera above water (reflection, single scattering, bottom)",
                  true, ""};
    plan.passes.push_back(pass);
    // With "multiple" the second order is inside the closed form: its pass would count it twice.
    if (scene.sea.second_order && !multiple) {
      std::vector<std::string> second_defines = {flag("SEASIM_HAS_BOTTOM", bottom),
                                                 flag("SEASIM_SPECTRAL_OUTPUT", spectral_out)};
      if (height_field) second_defines.push_back("SEASIM_BOTTOM_HEIGHTFIELD=1");
      plan.passes.push_back({"sea_second", "sea_second.cl", second_defines, {"scene", "rgb"}, {"rgb"},
                             "sea.second_order = true", pass.implemented, pass.missing});
    }
  }
  if (lights) {
    std::vector<std::string> shafts_reads = {"scene"};
    if (objects && !intervals) shafts_reads.push_back("shadow_maps");
    plan.passes.push_back({"shafts", "shafts.cl", shafts_defines, shafts_reads, {"rgb"},
                           intervals ? std::string("spotlights in air; method intervals: exact lit stretches, "
                                                   "analytic shadow volumes, no shadow maps (quality.shafts_method)")
                                     : std::string("spotlights in air; method planes (001's sampling planes)") +
                               ((scene.quality.count("shafts_planes") && scene.quality.at("shafts_planes").automatic) ||
                                        (scene.quality.count("shafts_subplanes") && scene.quality.at("shafts_subplanes").automatic)
                                    ? "; n, m \"auto\": the cheapest under quality.shafts_error_budget (searched once, cached)"
                                    : ""),
                           true, ""});
  }
  if (underwater) {
    const bool improved_uw = uw.model == UnderwaterDesc::Model::Improved;
    const bool spread = improved_uw && uw.point_spread && scene.water.g > 0;
    std::vector<std::string> reads = {"gbuffer"};
    if (froxels) reads.push_back("froxel_volume");
    plan.passes.push_back({"kd_multiple", "kd_multiple.cl",
                           {flag("SEASIM_HAS_MULTIPLE", uw.multiple_scattering), flag("SEASIM_HAS_FROXEL", froxels),
                            flag("SEASIM_SPECTRAL_OUTPUT", spectral_out),
                            "SEASIM_SKY_MODEL=" + std::to_string(skyModelOf(scene.sky)),  // Snell's window
                            // underwater.model: 0 thesis (002 eq. 4.7), 1 improved (common/underwater_improved.h)
                            "SEASIM_UNDERWATER_MODEL=" + std::string(improved_uw ? "1" : "0"),
                            flag("SEASIM_UWI_SPREAD", spread)},
                           reads, {"rgb"},
                           improved_uw ? "camera below the surface: T L_s + L_MS per band, model \"improved\" (delta-M, "
                                         "the diffuse field over the bottom by discrete ordinates or a two-stream, "
                                         "its in-scatter by direction)"
                                       : "camera below the surface: T L_s + L_MS per band (002 eq. 4.7)",
                           true, ""});
    // The light delta-M counts as unscattered was scattered by small angles: put back blurred (issue 13
    // s11). Only the improved model scales by delta-M, and only a forward phase (g > 0) has a peak.
    if (spread)
      plan.passes.push_back({"water_spread", "water_spread.cl", {}, {"gbuffer", "rgb"}, {"rgb"},
                             "underwater.model \"improved\", water.g > 0, underwater.point_spread: the light delta-M "
                             "counts as unscattered, blurred by the phase's small angles (common/water_spread.h)",
                             true, ""});
  }
  // Spotlights under water (divers' torches, ROV lamps): the sampling planes in the water's spectral
  // medium, added into the frame kd_multiple wrote (it reads "rgb" so that it runs after).
  if (underwater && !scene.spotlights.empty()) {
    plan.passes.push_back({"underwater_lamps", "underwater_lamps.cl",
                           {flag("SEASIM_HAS_OBJECTS", objects), flag("SEASIM_SPECTRAL_OUTPUT", spectral_out)},
                           {"gbuffer", "rgb"}, {"rgb"},
                           "[[spotlights]] under water: 001's sampling planes with the water's sigma_s, sigma_t, HG",
                           true, ""});
  }
  // Spotlights over the sea seen from above need the lamp's light through the surface, which is not
  // modelled: a planned pass that is not implemented stops the render before anything is written,
  // naming the lamp's table.
  if (sea_view && !scene.spotlights.empty()) {
    const SourceLoc& at = scene.spotlights.front().loc;
    plan.passes.push_back({"shafts", "shafts.cl", {}, {"scene"}, {"rgb"},
                           "[[spotlights]] at " + at.file + ":" + std::to_string(at.line) +
                               " with the camera above [water]",
                           false,
                           "spotlights are composed with the underwater view (camera below y = 0), not with the sea "
                           "seen from above; move the camera below the surface or remove the [[spotlights]] tables"});
  }
  // quality.fast_math: the light-transport passes are built with -cl-fast-relaxed-math (the define
  // tells Device::program and the kernels). Not the NaN/Inf check below (finite-only maths may assume
  // away the very values it counts), nor the FFT ocean and its caustics, which build without the
  // plan's defines (their error was not measured under relaxed maths).
  if (fastMathFor(scene)) {
    for (PassPlan& p : plan.passes)
      if (p.name != "ocean_fft" && p.name != "caustics" && p.name != "fourflow")  // fourflow: not measured
        p.defines.push_back("SEASIM_FAST_MATH=1");
  }
  plan.passes.push_back({"nonfinite_check", "check.cl", {}, {"rgb"}, {"status"},
                         "always: kernels must never emit NaN/Inf", true, ""});
  return plan;
}

}  // namespace seasim
