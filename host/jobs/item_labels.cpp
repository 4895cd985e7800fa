#include "jobs/item_labels.h"

#include <toml++/toml.h>

#include <cmath>
#include <fstream>
#include <numbers>

#include "io/atomic_file.h"
#include "spectral/jerlov.h"
#include "spectral/wavelength_grid.h"
#include "underwater/underwater_setup.h"
#include "util/paths.h"

namespace seasim {

namespace {

double degrees(double radians) { return radians * 180.0 / std::numbers::pi; }

nlohmann::json vec(const Vec3& v) { return nlohmann::json::array({v.x, v.y, v.z}); }

// A TOML value (an override's text) as JSON: numbers, strings, booleans and arrays of them.
nlohmann::json jsonOf(const toml::node& n) {
  if (auto* i = n.as_integer()) return i->get();
  if (auto* f = n.as_floating_point()) return f->get();
  if (auto* s = n.as_string()) return s->get();
  if (auto* b = n.as_boolean()) return b->get();
  if (auto* a = n.as_array()) {
    nlohmann::json out = nlohmann::json::array();
    for (const toml::node& e : *a) out.push_back(jsonOf(e));
    return out;
  }
  return nullptr;  // tables and dates are never drawn (jobs/job_sampling.cpp)
}

nlohmann::json valueJson(const std::string& value_toml) {
  const toml::table t = toml::parse("v = " + value_toml);
  return jsonOf(*t.get("v"));
}

const char* bottomType(BottomDesc::Type t) {
  switch (t) {
    case BottomDesc::Type::None:
      return "none";
    case BottomDesc::Type::Flat:
      return "flat";
    case BottomDesc::Type::HeightField:
      return "heightfield";
  }
  return "?";
}

}  // namespace

nlohmann::json sampledJson(const RenderItem& item) {
  nlohmann::json sampled = nlohmann::json::object();
  for (const Override& o : item.sampled) sampled[o.key] = valueJson(o.value_toml);
  return sampled;
}

bool labelsRecordOtherDraws(const RenderItem& item, const std::string& dir) {
  std::ifstream in(dir + "/labels.json", std::ios::binary);
  if (!in) return false;  // no labels: the manifest check decides (jobs/farm_items.cpp)
  const nlohmann::json labels = nlohmann::json::parse(in, nullptr, false);
  if (labels.is_discarded() || !labels.is_object() || !labels.contains("sampled")) return true;
  return labels["sampled"] != sampledJson(item) || labels.value("seed", nlohmann::json()) != item.sample_seed;
}

nlohmann::json itemLabels(const Scene& scene, const RenderItem& item) {
  const nlohmann::json sampled = sampledJson(item);

  const SunDesc& sun = scene.sun;
  const Vec3 sun_air{std::sin(sun.zenith) * std::cos(sun.azimuth), std::cos(sun.zenith),
                     std::sin(sun.zenith) * std::sin(sun.azimuth)};
  nlohmann::json labels = {{"format", "seasim-labels-1"},
                           {"item", item.name},
                           {"seed", item.sample_seed},
                           {"index", item.sample_index},
                           {"scene", scene.file},
                           {"sampled", sampled}};

  nlohmann::json water = {{"present", scene.water.present}};
  if (scene.water.present) {
    // The grid and K_d's sun cosine the underwater model resolves the water with (underwater_setup.cpp).
    const WavelengthGrid grid = makeGrid(scene.spectral.count, scene.spectral.min_nm, scene.spectral.max_nm);
    const bool sun_up = sun.enabled && sun.irradiance > 0 && sun_air.y > 1e-6;
    const Vec3 sun_water = sunInWater(scene);
    const double mu_w = sun_up ? sun_water.y : 0.85;
    const BandOptics optics = resolveWater(scene.water, grid, mu_w);
    water["jerlov"] = scene.water.jerlov.empty() ? nlohmann::json(nullptr) : nlohmann::json(scene.water.jerlov);
    water["ior"] = scene.water.ior;
    water["bands_nm"] = grid.centers_nm;
    water["band_width_nm"] = grid.widths_nm.front();
    water["a"] = optics.a;
    water["b"] = optics.b;
    water["c"] = optics.c;
    water["kd"] = optics.kd;
    water["kd_sun_cosine"] = mu_w;
    water["phase"] = {{"name", "henyey_greenstein"}, {"g", scene.water.g}};
    labels["sun"] = {{"direction_water", vec(sun_water)}};
  } else {
    labels["sun"] = nlohmann::json::object();
  }
  labels["water"] = water;
  labels["sun"]["enabled"] = sun.enabled;
  labels["sun"]["zenith_deg"] = degrees(sun.zenith);
  labels["sun"]["azimuth_deg"] = degrees(sun.azimuth);
  labels["sun"]["irradiance"] = sun.irradiance;
  labels["sun"]["direction_air"] = vec(sun_air);

  const CameraDesc& cam = scene.camera;
  const Vec3 d = normalize(cam.look_at - cam.position);
  const double aspect = static_cast<double>(cam.width) / cam.height;
  const std::string& sensor = scene.spectral.sensor;
  const std::string curve =
      sensor == "cie1931" || sensor == "identity" ? "" : cameraFile(sensor, scene.spectral.camera_dir);
  labels["camera"] = {{"position", vec(cam.position)},
                      {"look_at", vec(cam.look_at)},
                      {"up", vec(cam.up)},
                      {"direction", vec(d)},
                      {"depth_m", cam.position.y < 0 ? -cam.position.y : 0.0},
                      {"fov_y_deg", degrees(cam.fov_y)},
                      {"fov_x_deg", degrees(2 * std::atan(std::tan(cam.fov_y / 2) * aspect))},
                      {"width", cam.width},
                      {"height", cam.height},
                      {"exposure_ev", cam.exposure_ev},
                      {"sensor", sensor},
                      {"sensor_file", curve.empty() ? nlohmann::json(nullptr) : nlohmann::json(curve)},
                      {"white_balance", scene.spectral.white_balance}};
  labels["bottom"] = {{"type", bottomType(scene.bottom.type)}, {"depth_m", scene.bottom.depth}};
  labels["underwater_model"] = scene.underwater.model == UnderwaterDesc::Model::DiscreteOrdinates ? "discrete_ordinates" : "thesis";
  return labels;
}

std::string writeItemLabels(const Scene& scene, const RenderItem& item, const std::string& dir) {
  writeTextAtomic(dir + "/labels.json", itemLabels(scene, item).dump(2) + "\n");
  return "labels.json";
}

}  // namespace seasim
