// preview_window.h — the preview's window: GLFW and OpenGL 3.3 core live in a module the binary
// dlopens when `seasim preview` opens a window (libseasim_preview.so beside the binary, built from
// host/preview/glfw_window.cpp when CMake finds GLFW and OpenGL), so no other command loads GL, X11
// or GLFW (start-up: image_io_module.h). The module knows nothing of scenes: it shows 8-bit
// sRGB images, reports inputs and reads its framebuffer back.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "preview/preview_input.h"

namespace seasim {

constexpr int kPreviewModuleVersion = 1;
#define SEASIM_PREVIEW_MODULE_ENTRY "seasim_preview_module_v1"
#define SEASIM_PREVIEW_MODULE_FILE "libseasim_preview.so"

// The module's table (same compiler and CMake run on both sides, so C++ types cross unchanged).
struct PreviewWindowModule {
  int version;
  // A window whose framebuffer is width x height; null and `error` set when none can be opened.
  void* (*open)(int width, int height, const std::string& title, std::string& error);
  void (*close)(void* window);
  void (*setTitle)(void* window, const std::string& title);
  // Inputs since the last call (keys pressed or repeated, mouse drags, wheel); `closed` when the
  // window's close button was pressed.
  std::vector<PreviewInput> (*poll)(void* window, bool& closed);
  // Draws the RGB image (8-bit sRGB, top row first) scaled to the framebuffer and shows it. With
  // `capture`, first reads the drawn framebuffer back (glReadPixels, top row first, RGB). Returns ""
  // or the OpenGL error met, naming the call.
  std::string (*present)(void* window, const std::uint8_t* rgb, int width, int height, std::vector<std::uint8_t>* capture,
                  int* capture_width, int* capture_height);
  // Sleeps until an input arrives or `seconds` pass (the window idle at full quality).
  void (*wait)(void* window, double seconds);
  // "OpenGL 4.5 (Core Profile) Mesa 22.3.6, llvmpipe ...".
  std::string (*info)(void* window);
};

// True when this build has the module (CMake found GLFW and OpenGL).
bool previewBuilt();

// An open window; the constructor loads the module and throws RuntimeError when it is missing or no
// window can be opened (no display).
class PreviewWindow {
 public:
  PreviewWindow(int width, int height, const std::string& title);
  ~PreviewWindow();
  PreviewWindow(const PreviewWindow&) = delete;
  PreviewWindow& operator=(const PreviewWindow&) = delete;

  void setTitle(const std::string& title) { module_->setTitle(handle_, title); }
  std::vector<PreviewInput> poll(bool& closed) { return module_->poll(handle_, closed); }
  void present(const std::vector<std::uint8_t>& rgb, int width, int height) {
    check(module_->present(handle_, rgb.data(), width, height, nullptr, nullptr, nullptr));
  }
  // present() and the framebuffer read back as an 8-bit RGB image.
  std::vector<std::uint8_t> presentAndCapture(const std::vector<std::uint8_t>& rgb, int width, int height,
                                              int& capture_width, int& capture_height) {
    std::vector<std::uint8_t> out;
    check(module_->present(handle_, rgb.data(), width, height, &out, &capture_width, &capture_height));
    return out;
  }
  void waitEvents(double seconds) { module_->wait(handle_, seconds); }
  std::string info() { return module_->info(handle_); }

 private:
  static void check(const std::string& gl_error);  // throws RuntimeError when not empty
  const PreviewWindowModule* module_;
  void* handle_;
};

}  // namespace seasim
