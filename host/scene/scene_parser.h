// scene_parser.h — TOML scene files -> Scene, with validation (STYLE.md 6): every key read with an
// explicit default, units converted, every unknown key / wrong type / out-of-range value an
// InputError naming file:line and the dotted key.
#pragma once
#include <string>
#include <vector>

#include "scene/scene.h"

namespace seasim {

// One "dotted.key = value" override applied to a scene before validation (from a job file or
// `--set` on the command line). value_toml is TOML value text ("40", "\"IB\"", "[1, 2]");
// loc is where the override was written, so errors point there.
struct Override {
  std::string key;
  std::string value_toml;
  SourceLoc loc;
};

// Reads, overrides and validates a scene file. Relative texture paths resolve against the scene
// file's folder. Throws InputError.
Scene loadScene(const std::string& path, const std::vector<Override>& overrides = {});

// Same, from TOML text (tests); `path` names it in messages and anchors relative paths.
// `ignored_keys` (dotted, as errors name them) are read as absent: `validate` parses again without
// the key that failed to find the file's next error.
Scene parseScene(const std::string& toml_text, const std::string& path,
                 const std::vector<Override>& overrides = {}, const std::vector<std::string>& ignored_keys = {});
Scene loadScene(const std::string& path, const std::vector<Override>& overrides,
                const std::vector<std::string>& ignored_keys);

}  // namespace seasim
