// scene_writer.h — a scene file with overrides folded in, as a new scene file that `seasim render`
// reads to the same scene (the preview's `S` key saves the settings it shows this way).
#pragma once
#include <string>
#include <vector>

#include "scene/scene_parser.h"

namespace seasim {

// The TOML text of `scene_file` with `overrides` applied (as loadScene applies them), every image
// path and camera_dir made absolute so the text reads the same from any folder, and a first comment
// naming where it came from. Comments of the original are not kept. Throws InputError as loadScene.
std::string sceneTextWithOverrides(const std::string& scene_file, const std::vector<Override>& overrides);

// Writes that text to `out_path` atomically (io/atomic_file.h) after checking that it parses back
// to a valid scene. Returns out_path.
std::string writeSceneWithOverrides(const std::string& scene_file, const std::vector<Override>& overrides,
                                    const std::string& out_path);

}  // namespace seasim
