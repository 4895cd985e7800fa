// window_dl.cpp — loads the GLFW window module (preview_window.h) the first time a window opens.
#include <mutex>

#include "preview/preview_window.h"
#include "util/error.h"
#include "util/module_loader.h"

namespace seasim {

namespace {

const PreviewWindowModule& module() {
  if (!previewBuilt())
    throw RuntimeError("seasim preview: not built: CMake found no GLFW or OpenGL when this binary was configured "
                       "(install libglfw3-dev and libgl-dev, e.g. `make deps`, and configure again)");
  static const PreviewWindowModule* table = nullptr;
  static std::string failure;
  static std::once_flag once;
  std::call_once(once, [] {
#ifdef SEASIM_PREVIEW_MODULE_DIR
    const std::string build_dir = SEASIM_PREVIEW_MODULE_DIR;
#else
    const std::string build_dir;
#endif
    std::string tried;
    table = loadModuleTable<PreviewWindowModule>(moduleCandidates(SEASIM_PREVIEW_MODULE_FILE, build_dir),
                                                 SEASIM_PREVIEW_MODULE_ENTRY, kPreviewModuleVersion, "preview", tried);
    if (!table) failure = "cannot load the preview module " SEASIM_PREVIEW_MODULE_FILE ":" + tried;
  });
  if (!table) throw RuntimeError(failure);
  return *table;
}

}  // namespace

bool previewBuilt() { return SEASIM_PREVIEW != 0; }

PreviewWindow::PreviewWindow(int width, int height, const std::string& title) : module_(&module()) {
  std::string error;
  handle_ = module_->open(width, height, title, error);
  if (!handle_) throw RuntimeError("seasim preview: cannot open a window: " + error);
}

PreviewWindow::~PreviewWindow() { module_->close(handle_); }

void PreviewWindow::check(const std::string& gl_error) {
  if (!gl_error.empty()) throw RuntimeError("seasim preview: " + gl_error);
}

}  // namespace seasim
