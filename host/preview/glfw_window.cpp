// glfw_window.cpp — the preview window module (preview_window.h): GLFW, an OpenGL 3.3 core context,
// one texture the 8-bit image is uploaded into, and a framebuffer blit that scales it to the window
// (no shaders: glBlitFramebuffer is core since 3.0). Built as libseasim_preview.so, only with GLFW
// and OpenGL; it needs nothing from the seasim binary.
#define GLFW_INCLUDE_GLEXT
#include <GLFW/glfw3.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "preview/preview_window.h"

namespace {

using seasim::PreviewInput;

struct GlFunctions {
  PFNGLGENFRAMEBUFFERSPROC genFramebuffers = nullptr;
  PFNGLDELETEFRAMEBUFFERSPROC deleteFramebuffers = nullptr;
  PFNGLBINDFRAMEBUFFERPROC bindFramebuffer = nullptr;
  PFNGLFRAMEBUFFERTEXTURE2DPROC framebufferTexture2D = nullptr;
  PFNGLBLITFRAMEBUFFERPROC blitFramebuffer = nullptr;
  bool load() {
    genFramebuffers = reinterpret_cast<PFNGLGENFRAMEBUFFERSPROC>(glfwGetProcAddress("glGenFramebuffers"));
    deleteFramebuffers = reinterpret_cast<PFNGLDELETEFRAMEBUFFERSPROC>(glfwGetProcAddress("glDeleteFramebuffers"));
    bindFramebuffer = reinterpret_cast<PFNGLBINDFRAMEBUFFERPROC>(glfwGetProcAddress("glBindFramebuffer"));
    framebufferTexture2D =
        reinterpret_cast<PFNGLFRAMEBUFFERTEXTURE2DPROC>(glfwGetProcAddress("glFramebufferTexture2D"));
    blitFramebuffer = reinterpret_cast<PFNGLBLITFRAMEBUFFERPROC>(glfwGetProcAddress("glBlitFramebuffer"));
    return genFramebuffers && deleteFramebuffers && bindFramebuffer && framebufferTexture2D && blitFramebuffer;
  }
};

struct Window {
  GLFWwindow* glfw = nullptr;
  GlFunctions gl;
  GLuint texture = 0, framebuffer = 0;
  int texture_width = 0, texture_height = 0;
  std::vector<PreviewInput> inputs;
  double mouse_x = 0, mouse_y = 0;
  bool closed = false;
};

std::string keyName(int key) {
  static const std::map<int, std::string> names = {
      {GLFW_KEY_UP, "UP"},           {GLFW_KEY_DOWN, "DOWN"},        {GLFW_KEY_LEFT, "LEFT"},
      {GLFW_KEY_RIGHT, "RIGHT"},     {GLFW_KEY_PAGE_UP, "PAGE_UP"},  {GLFW_KEY_PAGE_DOWN, "PAGE_DOWN"},
      {GLFW_KEY_LEFT_BRACKET, "LEFT_BRACKET"}, {GLFW_KEY_RIGHT_BRACKET, "RIGHT_BRACKET"},
      {GLFW_KEY_MINUS, "MINUS"},     {GLFW_KEY_EQUAL, "EQUAL"},      {GLFW_KEY_SPACE, "SPACE"},
      {GLFW_KEY_ESCAPE, "ESCAPE"},   {GLFW_KEY_KP_ADD, "EQUAL"},     {GLFW_KEY_KP_SUBTRACT, "MINUS"}};
  if (const auto it = names.find(key); it != names.end()) return it->second;
  if (key >= GLFW_KEY_A && key <= GLFW_KEY_Z) return std::string(1, static_cast<char>('A' + key - GLFW_KEY_A));
  if (key >= GLFW_KEY_0 && key <= GLFW_KEY_9) return std::string(1, static_cast<char>('0' + key - GLFW_KEY_0));
  return "";
}

Window* self(GLFWwindow* w) { return static_cast<Window*>(glfwGetWindowUserPointer(w)); }

void onKey(GLFWwindow* w, int key, int, int action, int) {
  if (action == GLFW_RELEASE) return;
  if (std::string name = keyName(key); !name.empty()) self(w)->inputs.push_back({PreviewInput::Kind::Key, name, 0, 0});
}

void onCursor(GLFWwindow* w, double x, double y) {
  Window* win = self(w);
  const double dx = x - win->mouse_x, dy = y - win->mouse_y;
  win->mouse_x = x;
  win->mouse_y = y;
  PreviewInput::Kind kind;
  if (glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS)
    kind = PreviewInput::Kind::Orbit;
  else if (glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS)
    kind = PreviewInput::Kind::Look;
  else
    return;
  // One drag input per frame: motion events between two polls add up.
  if (!win->inputs.empty() && win->inputs.back().kind == kind) {
    win->inputs.back().dx += dx;
    win->inputs.back().dy += dy;
  } else {
    win->inputs.push_back({kind, "", dx, dy});
  }
}

void onScroll(GLFWwindow* w, double, double y) { self(w)->inputs.push_back({PreviewInput::Kind::Zoom, "", 0, y}); }

int glfw_users = 0;  // glfwInit/glfwTerminate around the windows the process has open

// "" when OpenGL reports no error since the last check, else the error and the call before it.
std::string glError(const char* call) {
  std::string text;
  for (GLenum e = glGetError(); e != GL_NO_ERROR; e = glGetError()) {
    char code[16];
    std::snprintf(code, sizeof code, "0x%04x", e);
    text += std::string(text.empty() ? "OpenGL error " : ", ") + code;
  }
  return text.empty() ? text : text + " after " + call;
}

void* openWindow(int width, int height, const std::string& title, std::string& error) {
  glfwSetErrorCallback(nullptr);
  if (glfw_users == 0 && !glfwInit()) {
    const char* why = nullptr;
    glfwGetError(&why);
    error = std::string("GLFW cannot start (no display? set DISPLAY, or run under xvfb-run): ") + (why ? why : "");
    return nullptr;
  }
  ++glfw_users;
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_SCALE_TO_MONITOR, GLFW_FALSE);  // one framebuffer pixel per image pixel
  auto* win = new Window;
  win->glfw = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (!win->glfw) {
    const char* why = nullptr;
    glfwGetError(&why);
    error = std::string("no OpenGL 3.3 core window: ") + (why ? why : "unknown GLFW error");
    delete win;
    if (--glfw_users == 0) glfwTerminate();
    return nullptr;
  }
  glfwMakeContextCurrent(win->glfw);
  glfwSwapInterval(0);  // the renderer sets the pace, not the display's refresh
  if (!win->gl.load()) {
    error = "the OpenGL context lacks framebuffer objects";
    glfwDestroyWindow(win->glfw);
    delete win;
    if (--glfw_users == 0) glfwTerminate();
    return nullptr;
  }
  glfwSetWindowUserPointer(win->glfw, win);
  glfwSetKeyCallback(win->glfw, onKey);
  glfwSetCursorPosCallback(win->glfw, onCursor);
  glfwSetScrollCallback(win->glfw, onScroll);
  glfwGetCursorPos(win->glfw, &win->mouse_x, &win->mouse_y);
  glGenTextures(1, &win->texture);
  win->gl.genFramebuffers(1, &win->framebuffer);
  return win;
}

void closeWindow(void* handle) {
  auto* win = static_cast<Window*>(handle);
  glfwMakeContextCurrent(win->glfw);
  win->gl.deleteFramebuffers(1, &win->framebuffer);
  glDeleteTextures(1, &win->texture);
  glfwDestroyWindow(win->glfw);
  delete win;
  if (--glfw_users == 0) glfwTerminate();
}

void setTitle(void* handle, const std::string& title) { glfwSetWindowTitle(static_cast<Window*>(handle)->glfw, title.c_str()); }

std::vector<PreviewInput> poll(void* handle, bool& closed) {
  auto* win = static_cast<Window*>(handle);
  glfwPollEvents();
  closed = glfwWindowShouldClose(win->glfw);
  std::vector<PreviewInput> out;
  out.swap(win->inputs);
  return out;
}

std::string present(void* handle, const std::uint8_t* rgb, int width, int height, std::vector<std::uint8_t>* capture,
                    int* capture_width, int* capture_height) {
  auto* win = static_cast<Window*>(handle);
  glfwMakeContextCurrent(win->glfw);
  (void)glError("");  // errors from before this frame are not this frame's
  // Upload: a plain texture upload (the image is already tone-mapped to 8-bit sRGB on the host by
  // io/tonemap.h, the function image.png uses). Rows go in top row first, so the blit flips them.
  glBindTexture(GL_TEXTURE_2D, win->texture);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  if (width != win->texture_width || height != win->texture_height) {
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB8, width, height, 0, GL_RGB, GL_UNSIGNED_BYTE, rgb);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
    win->texture_width = width;
    win->texture_height = height;
    win->gl.bindFramebuffer(GL_READ_FRAMEBUFFER, win->framebuffer);
    win->gl.framebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, win->texture, 0);
  } else {
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, rgb);
  }
  if (std::string e = glError("the texture upload (glTexImage2D/glTexSubImage2D)"); !e.empty()) return e;
  int fb_width = 0, fb_height = 0;
  glfwGetFramebufferSize(win->glfw, &fb_width, &fb_height);
  win->gl.bindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  glViewport(0, 0, fb_width, fb_height);
  glClearColor(0, 0, 0, 1);
  glClear(GL_COLOR_BUFFER_BIT);
  win->gl.bindFramebuffer(GL_READ_FRAMEBUFFER, win->framebuffer);
  // Same size: every pixel copied as it is (NEAREST); else scaled with linear filtering.
  const bool same = fb_width == width && fb_height == height;
  win->gl.blitFramebuffer(0, height, width, 0, 0, 0, fb_width, fb_height, GL_COLOR_BUFFER_BIT,
                          same ? GL_NEAREST : GL_LINEAR);
  if (std::string e = glError("glBlitFramebuffer"); !e.empty()) return e;
  if (capture) {
    win->gl.bindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    std::vector<std::uint8_t> bottom_up(static_cast<size_t>(fb_width) * fb_height * 3);
    glFinish();
    glReadPixels(0, 0, fb_width, fb_height, GL_RGB, GL_UNSIGNED_BYTE, bottom_up.data());
    if (std::string e = glError("glReadPixels"); !e.empty()) return e;
    capture->resize(bottom_up.size());
    const size_t row = static_cast<size_t>(fb_width) * 3;
    for (int y = 0; y < fb_height; ++y)
      std::memcpy(capture->data() + static_cast<size_t>(y) * row,
                  bottom_up.data() + static_cast<size_t>(fb_height - 1 - y) * row, row);
    *capture_width = fb_width;
    *capture_height = fb_height;
  }
  glfwSwapBuffers(win->glfw);
  return "";
}

void waitEvents(void*, double seconds) { glfwWaitEventsTimeout(seconds); }

std::string info(void* handle) {
  glfwMakeContextCurrent(static_cast<Window*>(handle)->glfw);
  const auto* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  return std::string("OpenGL ") + (version ? version : "?") + ", " + (renderer ? renderer : "?");
}

}  // namespace

// The module's one entry point (preview_window.h).
extern "C" __attribute__((visibility("default"))) const seasim::PreviewWindowModule* seasim_preview_module_v1() {
  static const seasim::PreviewWindowModule table{seasim::kPreviewModuleVersion, &openWindow, &closeWindow, &setTitle,
                                                 &poll, &present, &waitEvents, &info};
  return &table;
}
