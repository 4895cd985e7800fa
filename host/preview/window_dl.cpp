// window_dl.cpp — loads the GLFW window module (preview_window.h) the first time a window opens.
#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <mutex>

#include "preview/preview_window.h"
#include "util/error.h"

namespace seasim {

namespace {

namespace fs = std::filesystem;

// As the image module (io/image_io_dl.cpp): $SEASIM_LIB_DIR, beside the binary, <prefix>/lib/seasim,
// the build folder.
std::vector<fs::path> moduleCandidates() {
  std::vector<fs::path> out;
  if (const char* dir = std::getenv("SEASIM_LIB_DIR"); dir && *dir) out.push_back(fs::path(dir) / SEASIM_PREVIEW_MODULE_FILE);
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    out.push_back(exe.parent_path() / SEASIM_PREVIEW_MODULE_FILE);
    out.push_back(exe.parent_path().parent_path() / "lib" / "seasim" / SEASIM_PREVIEW_MODULE_FILE);
  }
#ifdef SEASIM_PREVIEW_MODULE_DIR
  out.push_back(fs::path(SEASIM_PREVIEW_MODULE_DIR) / SEASIM_PREVIEW_MODULE_FILE);
#endif
  return out;
}

const PreviewWindowModule& module() {
  if (!previewBuilt())
    throw RuntimeError("seasim preview: not built: CMake found no GLFW or OpenGL when this binary was configured "
                       "(install libglfw3-dev and libgl-dev, e.g. `make deps`, and configure again)");
  static const PreviewWindowModule* table = nullptr;
  static std::string failure;
  static std::once_flag once;
  std::call_once(once, [] {
    std::string tried;
    for (const fs::path& path : moduleCandidates()) {
      if (!fs::exists(path)) {
        tried += "\n  " + path.string() + ": not there";
        continue;
      }
      void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);  // never closed: used until exit
      if (!handle) {
        tried += "\n  " + path.string() + ": " + dlerror();
        continue;
      }
      using Entry = const PreviewWindowModule* (*)();
      auto entry = reinterpret_cast<Entry>(dlsym(handle, SEASIM_PREVIEW_MODULE_ENTRY));
      const PreviewWindowModule* t = entry ? entry() : nullptr;
      if (!t || t->version != kPreviewModuleVersion) {
        tried += "\n  " + path.string() + ": not a matching seasim preview module (rebuild it with this binary)";
        continue;
      }
      table = t;
      return;
    }
    failure = "cannot load the preview module " SEASIM_PREVIEW_MODULE_FILE ":" + tried;
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
