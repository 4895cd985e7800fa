#include "cli/preview_command.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>

#include "cli/commands.h"
#include "device/device.h"
#include "io/image_io.h"
#include "io/tonemap.h"
#include "io/tonemap_eq18.h"
#include "quality/auto_quality.h"
#include "quality/shafts_method_auto.h"
#include "preview/preview_quality.h"
#include "preview/preview_settings.h"
#include "preview/preview_window.h"
#include "render/renderer.h"
#include "scene/scene_inputs.h"
#include "scene/scene_writer.h"
#include "util/error.h"

namespace seasim {

namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

std::vector<Override> sizeOverrides(const std::string& size) {
  if (size.empty()) return {};
  int w = 0, h = 0;
  char x = 0, extra = 0;
  if (std::sscanf(size.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X') || w < 16 ||
      h < 9 || w > 16384 || h > 16384)
    throw RuntimeError("--size expects WIDTHxHEIGHT from 16x9 to 16384x16384, e.g. --size 640x360; got '" + size + "'");
  const SourceLoc at{"<command line --size " + size + ">", 0};
  return {{"camera.width", std::to_string(w), at}, {"camera.height", std::to_string(h), at}};
}

// The overrides in `next` whose value differs from `applied` (key -> value); updates `applied`.
std::vector<Override> changedOverrides(const std::vector<Override>& next, std::map<std::string, std::string>& applied) {
  std::vector<Override> out;
  for (const Override& o : next) {
    auto it = applied.find(o.key);
    if (it != applied.end() && it->second == o.value_toml) continue;
    applied[o.key] = o.value_toml;
    out.push_back(o);
  }
  return out;
}

// `a` then `b`, one entry per key: a later value replaces an earlier one in its place (--size and a
// quality level both set camera.width; the Renderer keeps the first entry of a key it is given).
std::vector<Override> concat(std::vector<Override> a, const std::vector<Override>& b) {
  for (const Override& o : b) {
    auto it = std::find_if(a.begin(), a.end(), [&](const Override& x) { return x.key == o.key; });
    if (it != a.end())
      *it = o;
    else
      a.push_back(o);
  }
  return a;
}

// quality.shafts_method = "auto": measured once at full quality and then held as given settings (added
// to `base`, `scene` parsed again with them), so the reduced levels scale the chosen method's knobs
// instead of searching again at each level's size.
void holdMeasuredChoices(Device& device, const std::string& scene_file, std::vector<Override>& base, Scene& scene) {
  if (const std::optional<ShaftsMethodCandidate> chosen = measuredShaftsMethod(device, scene)) {
    base = concat(base, shaftsMethodOverrides(*chosen));
    scene = loadScene(scene_file, base);
  }
}

bool hasGlSharing(Device& device) {
  const std::string extensions = device.device().getInfo<CL_DEVICE_EXTENSIONS>();
  return extensions.find("cl_khr_gl_sharing") != std::string::npos;
}

}  // namespace

int cmdPreview(const PreviewCmd& cmd) {
  if (cmd.frames < 0) throw RuntimeError("--frames must be 0 (run until the window closes) or more");
  if (!cmd.screenshot.empty() && cmd.frames == 0) throw RuntimeError("--screenshot needs --frames N (the last frame is saved)");
  if (cmd.budget_ms < 0) throw RuntimeError("--budget-ms must be 0 (always full quality) or more");
  // The command line's settings: --set, then --size. The preview's own settings go on top.
  std::vector<Override> sets;
  for (const std::string& s : cmd.sets) sets.push_back(parseSetOption(s));
  std::vector<Override> base = concat(concat({}, sets), sizeOverrides(cmd.size));
  Scene scene = loadScene(cmd.scene, base);
  checkSceneInputs(scene);
  const std::vector<PreviewInput> script = parseKeyScript(cmd.script);
  if (cmd.frames > 0 && script.size() > static_cast<size_t>(cmd.frames))
    throw RuntimeError("--script has " + std::to_string(script.size()) + " inputs (one per frame) but --frames is " +
                       std::to_string(cmd.frames));
  const std::string save_prefix = cmd.save_prefix.empty() ? scene.name + "_preview" : cmd.save_prefix;

  Device device(chooseDevice(cmd.device));
  holdMeasuredChoices(device, cmd.scene, base, scene);
  PreviewWindow window(scene.camera.width, scene.camera.height, "seasim preview: " + scene.name);
  // CL/GL sharing would let the kernels write the texture; no device this was measured on has it
  // (PoCL does not), so the image is tone-mapped on the host and uploaded (docs/preview.md).
  std::printf("seasim preview: %s on %s; %s; cl_khr_gl_sharing: %s, image uploaded as a texture\n", scene.name.c_str(),
              device.info().label().c_str(), window.info().c_str(), hasGlSharing(device) ? "yes" : "no");
  std::fflush(stdout);

  PreviewSettings settings(scene);
  QualityBudget budget(cmd.budget_ms);
  Scene settings_scene = scene;  // the scene with the preview's settings, at full quality
  int level = budget.next(true);
  std::map<std::string, std::string> applied;
  std::vector<Override> all = concat(base, qualityLevelOverrides(settings_scene, level));
  (void)changedOverrides(all, applied);
  Renderer renderer(device, cmd.scene, all, shippedPasses());

  std::vector<std::uint8_t> bytes;
  int saves = 0;
  auto last_frame = Clock::now();
  for (int frame = 0; cmd.frames == 0 || frame < cmd.frames; ++frame) {
    // Inputs: the script's one for this frame, then the window's.
    bool closed = false;
    std::vector<PreviewInput> inputs = window.poll(closed);
    if (frame < static_cast<int>(script.size())) inputs.insert(inputs.begin(), script[static_cast<size_t>(frame)]);
    if (closed) break;
    bool moving = false, save = false, quit = false;
    for (const PreviewInput& input : inputs) {
      const PreviewEffect effect = settings.apply(input);
      moving |= effect.changed;
      save |= effect.screenshot;
      quit |= effect.quit;
    }
    if (quit) break;
    // A window left alone at full quality (or at its fixed preset): nothing to render, wait for input.
    if (cmd.frames == 0 && frame > 0 && !moving && !save && !settings.playing() &&
        (settings.preset() >= 0 || level == kPreviewFullLevel)) {
      window.waitEvents(0.05);
      continue;
    }
    // Played time: real seconds in a window, 1/30 s per frame in a counted (scripted) run.
    const double dt = cmd.frames > 0 ? 1.0 / 30.0 : std::min(0.1, msSince(last_frame) / 1000.0);
    last_frame = Clock::now();
    moving |= settings.advanceTime(dt);
    if (moving) settings_scene = loadScene(cmd.scene, concat(base, settings.overrides()));

    // Quality: a fixed preset, else the budget's choice; a save shows the full quality it saves.
    level = settings.preset() >= 0 ? settings.preset() : budget.next(moving);
    if (save) level = kPreviewFullLevel;
    const std::vector<Override> next =
        concat(concat(base, settings.overrides()), qualityLevelOverrides(settings_scene, level));
    const auto start = Clock::now();
    if (const std::vector<Override> changed = changedOverrides(next, applied); !changed.empty()) renderer.update(changed);
    const FrameResult result = renderer.render();
    const double frame_ms = msSince(start);
    // The budget learns what a frame at this level costs; a kernel build (or cache load) is paid once.
    if (!renderer.lastExecuted().empty()) budget.record(level, std::max(0.0, frame_ms - result.build_ms));
    if (result.nonfinite) std::fprintf(stderr, "seasim preview: frame %d has %lld NaN/Inf values (shown black)\n", frame, result.nonfinite);
    const Scene& shown = renderer.scene();  // [display]: the PNG's tone map, shown the same way
    if (shown.display.tone_map == DisplayDesc::ToneMap::Eq18)
      toneMapImage8Eq18(result.rgb, shown.camera.exposure_ev, shown.display.eq18, bytes);
    else
      toneMapImage8(result.rgb, shown.camera.exposure_ev, bytes);

    std::string title = "seasim preview: " + scene.name + " | " + levelText(level, moving, settings.preset() >= 0);
    char text[64];
    std::snprintf(text, sizeof text, " | %.1f fps %.1f ms |", frame_ms > 0 ? 1000.0 / frame_ms : 0.0, frame_ms);
    title += text;
    for (const PassTiming& t : result.timings) {
      std::snprintf(text, sizeof text, " %s %.1f", t.name.c_str(), t.ms);
      title += text;
    }
    if (const std::string diff = settings.differences(); !diff.empty()) title += " | " + diff;
    if (settings.playing()) title += " | playing";
    window.setTitle(title);

    const bool last = cmd.frames > 0 && frame + 1 == cmd.frames;
    if (save || (last && !cmd.screenshot.empty())) {
      int w = 0, h = 0;
      const std::vector<std::uint8_t> shot = window.presentAndCapture(bytes, result.rgb.width, result.rgb.height, w, h);
      if (save) {
        ++saves;
        const std::string stem = save_prefix + "_" + std::to_string(saves);
        writePngBytes(stem + ".png", w, h, 3, shot);
        writeSceneWithOverrides(cmd.scene, concat(base, settings.overrides()), stem + ".toml");
        std::printf("saved %s.png and %s.toml (seasim render %s.toml renders this view)\n", stem.c_str(), stem.c_str(),
                    stem.c_str());
      }
      if (last && !cmd.screenshot.empty()) {
        writePngBytes(cmd.screenshot, w, h, 3, shot);
        std::printf("screenshot %s (%dx%d, %s)\n", cmd.screenshot.c_str(), w, h, levelText(level, moving, settings.preset() >= 0).c_str());
      }
    } else {
      window.present(bytes, result.rgb.width, result.rgb.height);
    }
    if (cmd.frames > 0) std::printf("frame %d: %s\n", frame, title.c_str());
    std::fflush(stdout);
  }
  return 0;
}

}  // namespace seasim
