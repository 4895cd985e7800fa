// py_scene.h — seasim.Scene: a validated scene with the TOML text and overrides it came from, so a
// Renderer can parse it again with more overrides (Renderer::update) whether it was a file or a dict.
#pragma once
#include <nanobind/nanobind.h>

#include <string>
#include <vector>

#include "scene/scene.h"
#include "scene/scene_parser.h"

namespace seasim::py {

struct PyScene {
  std::string path;  // the scene file, or kDictFile
  std::string text;  // its TOML
  std::vector<Override> overrides;
  Scene scene;       // parseScene(text, path, overrides)
  bool fromDict() const;
};

void bindScene(nanobind::module_& m);

}  // namespace seasim::py
