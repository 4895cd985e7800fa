// scene_inputs.h — checks of the files a scene reads (sky, height field, light map images) that
// parsing alone does not do: each must open as an image within the pixel limit and decode. Run by
// `seasim validate`, at job start and before a render, so a bad texture fails before any kernel
// runs and the message points at the key that named it.
#pragma once
#include <set>
#include <string>

#include "scene/scene.h"

namespace seasim {

// Throws InputError (file:line: key 'sky.image': ...) for the first image that cannot be read.
// Paths in `already_checked` are skipped and every path checked is added (a job's frames share
// their textures).
void checkSceneInputs(const Scene& scene, std::set<std::string>* already_checked = nullptr);

}  // namespace seasim
