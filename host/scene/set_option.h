// set_option.h — the command line's `--set key=value` as an Override. Here, beside the scene
// parser, rather than in the CLI, so the parser fuzzer (tests/fuzz) runs the very code the
// command line does.
#pragma once
#include <string>

#include "scene/scene_parser.h"

namespace seasim {

// "key=value" from --set; a value that is not valid TOML is taken as a string. Throws InputError
// for a text without '=' and for a value nested past the TOML limits (scene/toml_limits.h).
Override parseSetOption(const std::string& text);

}  // namespace seasim
