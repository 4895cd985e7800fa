// recorded_settings.h — the settings an image was made with, written beside it, so `seasim compare`
// can use the scene's exposure and warn when a render and its reference were made differently
// (e.g. a render at sun.zenith_deg = 60 against a reference at the scene's 40).
//
// Where they are recorded:
//   a render's image.exr / image.png   <folder>/report.json, its "settings" (jobs/render_item.h)
//   a reference OUT.exr                OUT.settings.json beside it: {"scene": ..., "settings": ...}
//                                      (`seasim reference`, and `seasim sweep` when it makes one)
#pragma once
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "scene/scene.h"

namespace seasim {

// The settings of a scene that decide what an image shows and how it is displayed: size, spectral
// grid, sensor, exposure, sun, camera, water, surface, and the [quality] knobs.
nlohmann::json settingsJson(const Scene& scene);

// "ref.exr" -> "ref.settings.json".
std::string settingsSidecarPath(const std::string& image_path);

// Writes settingsSidecarPath(image_path) atomically: {"scene": scene.file, "settings": settingsJson}.
void writeSettingsSidecar(const std::string& image_path, const Scene& scene, const std::string& made_by);

// The settings recorded for an image: report.json's "settings" when the image is one of the outputs
// that report lists, else the sidecar's; null when neither exists. A file that is there but is not
// JSON is a RuntimeError naming it.
nlohmann::json recordedSettings(const std::string& image_path);

// The "settings" of FOLDER/report.json (a render's folder); null when the report has none. A report
// that is not JSON is a RuntimeError naming it.
nlohmann::json reportSettings(const std::string& folder);

struct SettingsDifference {
  std::string key;          // "sun_zenith_deg", "quality.sea_nz"
  std::string test, reference;  // the values as JSON text ("(none)" when one side lacks the key)
  bool knob = false;        // a quality knob or the wavelength count: what error-vs-time varies on purpose
};

// Keys whose values differ between two recorded settings (numbers within 1e-9 relative are equal).
std::vector<SettingsDifference> settingsDifferences(const nlohmann::json& test, const nlohmann::json& reference);

}  // namespace seasim
