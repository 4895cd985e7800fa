// preview_settings.h — what the preview's keys and mouse change, without a window (unit-tested in
// tests/unit/preview_settings_test.cpp): the key script's syntax, the key -> setting table, the
// camera's orbit and fly moves, and the settings as scene-key overrides (what `S` saves and what the
// window title lists as differing from the scene file).
//
// Keys (docs/preview.md has the same table):
//   left-drag / ORBIT:dx,dy     orbit the camera around camera.look_at; wheel / ZOOM:n  dolly
//   right-drag / LOOK:dx,dy     turn the camera where it stands (fly look)
//   I K J L U O                 fly forward / back / left / right / up / down
//   PAGE_UP PAGE_DOWN           camera depth: camera and target 0.5 m up / down
//   UP DOWN                     sun zenith -5 / +5 degrees (0..89);  LEFT RIGHT  sun azimuth -5 / +5
//   LEFT_BRACKET RIGHT_BRACKET  water type previous / next (Jerlov types, scenes with water.jerlov)
//   MINUS EQUAL                 wavelength count halved / doubled (1..1000)
//   Q                           quality preset: auto (frame-time budget) -> level 0 -> 1 -> 2 -> 3 -> auto
//   T or SPACE                  time play / pause (surface.time: waves, caustics)
//   1..9                        pass switches the scene has (sea reflection, single, second order,
//                               bottom caustics; underwater multiple, single scattering, caustics)
//   S                           save a screenshot and the settings as a scene file
//   ESCAPE                      quit
#pragma once
#include <map>
#include <string>
#include <vector>

#include "preview/preview_input.h"
#include "scene/scene.h"
#include "scene/scene_parser.h"

namespace seasim {

// "UP*3 RIGHT ORBIT:40,0 WAIT*2 S": whitespace-separated tokens, one input per frame; `*n` repeats a
// token n times (one per frame); WAIT is a frame without input. Key names are case-insensitive.
// Throws RuntimeError naming the token for an unknown key or a malformed token.
std::vector<PreviewInput> parseKeyScript(const std::string& script);

// True for the key names the preview acts on.
bool isPreviewKey(const std::string& name);

struct PreviewEffect {
  bool changed = false;     // a setting or the view changed: render again (reduced quality while moving)
  bool screenshot = false;  // S
  bool quit = false;        // ESCAPE
};

// One pass switch: a bool scene key (or underwater.caustics, "none" when off) and its state.
struct PassSwitch {
  std::string key;
  bool on = true;
  std::string on_value;  // TOML value text when on ("true", "\"texture\"")
};

class PreviewSettings {
 public:
  // `scene` as loaded with the command line's --set; the settings start from it.
  explicit PreviewSettings(const Scene& scene);

  PreviewEffect apply(const PreviewInput& input);
  // While playing, surface.time moves on by `seconds`; returns whether it did.
  bool advanceTime(double seconds);
  bool playing() const { return playing_; }
  // -1: automatic (the frame-time budget chooses); else the fixed quality level.
  int preset() const { return preset_; }
  const std::vector<PassSwitch>& switches() const { return switches_; }

  // Every key changed so far with its current value (a key set back to the scene's value stays
  // listed, so the renderer is told), in the order first changed.
  std::vector<Override> overrides() const;
  // "key=value ..." for the keys whose value differs from the scene's, for the window title.
  std::string differences() const;

 private:
  void set(const std::string& key, const std::string& value_toml);
  void setCamera();
  PreviewEffect moveCamera(const PreviewInput& input);

  std::map<std::string, std::string> original_;  // key -> the scene's value text, for differences()
  std::vector<std::string> order_;               // keys in the order first changed
  std::map<std::string, std::string> current_;
  Vec3 position_, look_at_;
  double sun_zenith_deg_, sun_azimuth_deg_;
  int band_count_;
  std::string jerlov_;  // empty: the scene has no Jerlov water, [ and ] do nothing
  double time_;
  bool time_applies_;
  bool playing_ = false;
  int preset_ = -1;
  std::vector<PassSwitch> switches_;
};

// TOML value text of a number (shortest that reads back the same) and of a 3-vector.
std::string tomlNumber(double v);
std::string tomlVec3(const Vec3& v);

}  // namespace seasim
