// file_errors.h — every error `seasim validate` can find in a scene or job file, not just the first.
//
// The parsers stop at the first bad key (an InputError naming file:line and key). To find the next,
// the file is parsed again with that key read as absent (its default, never "unknown"), until it
// parses or an error cannot be stepped past (a TOML syntax error, a missing file, an error that
// names no key, or the same key again after its parent table was dropped too). So every error is
// one the parser itself reports, with its own file:line, and a later error that only the first one
// caused is not invented: dropping a key gives the default, which is valid by construction.
#pragma once
#include <string>
#include <vector>

#include "scene/scene_parser.h"

namespace seasim {

// The messages (InputError::what(), "FILE:LINE: key 'KEY': ...") of a scene file with overrides,
// in the order found; empty when it is valid.
std::vector<std::string> sceneFileErrors(const std::string& path, const std::vector<Override>& overrides = {});

// A job file's own errors, then each item's scene errors with that item's overrides (each distinct
// message once). Image inputs are not read here (jobs/job_inputs.h checks them).
std::vector<std::string> jobFileErrors(const std::string& path);

}  // namespace seasim
