#include "jobs/recorded_settings.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "io/atomic_file.h"
#include "util/error.h"

namespace fs = std::filesystem;

namespace seasim {

namespace {

constexpr double kDeg = 180.0 / std::numbers::pi;

std::string surfaceName(const SurfaceDesc& s) {
  if (s.type == SurfaceDesc::Type::Flat) return "flat";
  char buf[96];
  std::snprintf(buf, sizeof buf, "fft, wind %g m/s from %g deg", s.wind_speed, s.wind_direction * kDeg);
  return buf;
}

nlohmann::json readJsonFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw RuntimeError("cannot read '" + path.string() + "'");
  std::stringstream text;
  text << in.rdbuf();
  try {
    return nlohmann::json::parse(text.str());
  } catch (const nlohmann::json::exception& e) {
    throw RuntimeError("'" + path.string() + "' is not JSON (" + e.what() + "); delete it or write it again");
  }
}

bool sameValue(const nlohmann::json& a, const nlohmann::json& b) {
  if (a.is_number() && b.is_number()) {
    const double x = a.get<double>(), y = b.get<double>();
    return std::fabs(x - y) <= 1e-9 * std::max({1.0, std::fabs(x), std::fabs(y)});
  }
  if (a.is_array() && b.is_array() && a.size() == b.size()) {
    for (size_t i = 0; i < a.size(); ++i)
      if (!sameValue(a[i], b[i])) return false;
    return true;
  }
  return a == b;
}

// Numbers to 6 significant digits: 59.99999999999999 (60 through radians and back) reads as 60.
std::string valueText(const nlohmann::json& v) {
  if (v.is_number()) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v.get<double>());
    return buf;
  }
  if (v.is_array()) {
    std::string out = "[";
    for (size_t i = 0; i < v.size(); ++i) out += (i ? ", " : "") + valueText(v[i]);
    return out + "]";
  }
  return v.dump();
}

void diff(const nlohmann::json& a, const nlohmann::json& b, const std::string& prefix, bool knob,
          std::vector<SettingsDifference>& out) {
  std::vector<std::string> keys;
  for (auto it = a.begin(); it != a.end(); ++it) keys.push_back(it.key());
  for (auto it = b.begin(); it != b.end(); ++it)
    if (!a.contains(it.key())) keys.push_back(it.key());
  for (const std::string& k : keys) {
    const std::string name = prefix + k;
    const bool is_knob = knob || k == "wavelength_count" || k == "quality";
    const bool in_a = a.contains(k), in_b = b.contains(k);
    if (in_a && in_b && a[k].is_object() && b[k].is_object()) {
      diff(a[k], b[k], name + ".", is_knob, out);
    } else if (!in_a || !in_b || !sameValue(a[k], b[k])) {
      out.push_back({name, in_a ? valueText(a[k]) : "(none)", in_b ? valueText(b[k]) : "(none)", is_knob});
    }
  }
}

}  // namespace

nlohmann::json settingsJson(const Scene& s) {
  nlohmann::json quality = nlohmann::json::object();
  for (const auto& [key, knob] : s.quality) {
    quality[key] = knob.automatic ? nlohmann::json("auto") : nlohmann::json(knob.value);
  }
  return {{"width", s.camera.width},
          {"height", s.camera.height},
          {"wavelength_count", s.spectral.count},
          {"range_nm", {s.spectral.min_nm, s.spectral.max_nm}},
          {"sensor", s.spectral.sensor},
          {"white_balance", s.spectral.white_balance},
          {"exposure_ev", s.camera.exposure_ev},
          {"sun_zenith_deg", s.sun.zenith * kDeg},
          {"sun_azimuth_deg", s.sun.azimuth * kDeg},
          {"camera_position_m", {s.camera.position.x, s.camera.position.y, s.camera.position.z}},
          {"camera_look_at_m", {s.camera.look_at.x, s.camera.look_at.y, s.camera.look_at.z}},
          {"camera_fov_deg", s.camera.fov_y * kDeg},
          {"water", s.water.present ? (s.water.jerlov.empty() ? "explicit spectra" : "Jerlov " + s.water.jerlov) : "none"},
          {"surface", surfaceName(s.surface)},
          {"quality", quality}};
}

std::string settingsSidecarPath(const std::string& image_path) {
  const fs::path p(image_path);
  return (p.parent_path() / (p.stem().string() + ".settings.json")).string();
}

void writeSettingsSidecar(const std::string& image_path, const Scene& scene, const std::string& made_by) {
  const nlohmann::json j = {{"scene", scene.file}, {"made_by", made_by}, {"settings", settingsJson(scene)}};
  writeTextAtomic(settingsSidecarPath(image_path), j.dump(2) + "\n");
}

nlohmann::json recordedSettings(const std::string& image_path) {
  const fs::path image(image_path);
  const fs::path report = image.parent_path() / "report.json";
  std::error_code ec;
  if (fs::is_regular_file(report, ec)) {
    const nlohmann::json r = readJsonFile(report);
    if (r.contains("outputs") && r["outputs"].is_array() && r.contains("settings"))
      for (const auto& f : r["outputs"])
        if (f.is_string() && (f.get<std::string>() == image.filename().string() ||
                              f.get<std::string>() == image.filename().string() + ".npy"))
          return r["settings"];
  }
  const fs::path sidecar = settingsSidecarPath(image_path);
  if (fs::is_regular_file(sidecar, ec)) {
    const nlohmann::json j = readJsonFile(sidecar);
    if (j.contains("settings")) return j["settings"];
    throw RuntimeError("'" + sidecar.string() + "' has no \"settings\"; delete it or write it again");
  }
  return nullptr;
}

nlohmann::json reportSettings(const std::string& folder) {
  const fs::path report = fs::path(folder) / "report.json";
  std::error_code ec;
  if (!fs::is_regular_file(report, ec)) return nullptr;
  const nlohmann::json r = readJsonFile(report);
  return r.contains("settings") ? r["settings"] : nlohmann::json();
}

std::vector<SettingsDifference> settingsDifferences(const nlohmann::json& test, const nlohmann::json& reference) {
  std::vector<SettingsDifference> out;
  if (test.is_object() && reference.is_object()) diff(test, reference, "", false, out);
  return out;
}

}  // namespace seasim
