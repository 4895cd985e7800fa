// preview_input.h — one input to the preview: a key, or a mouse drag/scroll, as the window reports it
// and as a --script names it. Shared by the window module (host/preview/glfw_window.cpp) and the pure
// settings (preview_settings.h), so real keys and scripted keys take one path.
#pragma once
#include <string>

namespace seasim {

struct PreviewInput {
  enum class Kind { Key, Orbit, Look, Zoom, Wait };
  Kind kind = Kind::Key;
  std::string key;        // Key: GLFW's name without "GLFW_KEY_": "LEFT", "PAGE_UP", "S", "1", "LEFT_BRACKET"
  double dx = 0, dy = 0;  // Orbit / Look: mouse motion in pixels (left / right button held); Zoom: dy wheel clicks
};

}  // namespace seasim
