// preview_command.h — `seasim preview SCENE`: the live window (docs/preview.md). Each frame
// runs the scene's Renderer (render/renderer.h: only passes whose keys changed run again) on the
// chosen OpenCL device and shows the linear image through the tone map of image.png (io/tonemap.h).
#pragma once
#include <string>
#include <vector>

#include "preview/preview_quality.h"

namespace seasim {

struct PreviewCmd {
  std::string scene;
  std::string device;              // selector as elsewhere ("" = auto)
  std::vector<std::string> sets;   // key=value scene overrides
  std::string size;                // "WxH": window and camera.width/height; "" = the scene's size
  int frames = 0;                  // > 0: stop after this many frames (headless runs, tests)
  std::string screenshot;          // PNG of the last frame's framebuffer (glReadPixels), written atomically
  std::string script;              // key script, one input per frame (preview/preview_settings.h)
  double budget_ms = kPreviewMovingBudgetMs;  // frame-time budget while the view moves; 0 = always full quality
  std::string save_prefix;         // `S` writes <prefix>_<n>.png and <prefix>_<n>.toml; "" = ./<scene name>_preview
};

// Returns 0; throws RuntimeError (no window module, no display, bad script) or InputError (scene).
int cmdPreview(const PreviewCmd& cmd);

}  // namespace seasim
