// version.h — seasim's version (CMake project version) and the git commit it was built from
// (generated at build time by cmake/git_version.cmake; "unknown" outside a checkout or archive).
#pragma once

namespace seasim {

const char* version();
const char* gitCommit();

}  // namespace seasim
