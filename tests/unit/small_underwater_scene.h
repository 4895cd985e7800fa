// small_underwater_scene.h — the scene text the output tests plan against (output_layers_test,
// scene_profile_test): a camera 4 m down in Jerlov IB over a flat bottom at 6 m, nothing else; and the
// message parseScene gives for a text, for the tests of bad [outputs] keys.
#ifndef SEASIM_TESTS_SMALL_UNDERWATER_SCENE_H
#define SEASIM_TESTS_SMALL_UNDERWATER_SCENE_H

#include <string>

#include "scene/scene_parser.h"
#include "util/error.h"

namespace seasim {

inline const char* kSmallUnderwaterScene = R"([camera]
position = [0, -4, 0]
look_at = [0, -5, -8]
[water]
jerlov = "IB"
[bottom]
type = "flat"
depth = 6
)";

// The InputError's message parsing `text` as file `file` gives; "" when it parses.
inline std::string parseErrorOf(const std::string& text, const std::string& file) {
  try {
    parseScene(text, file);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace seasim

#endif
