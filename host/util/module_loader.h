// module_loader.h — finding and loading seasim's plug-in modules (libseasim_oiio.so, image I/O;
// libseasim_preview.so, the GLFW window): where they may be, and how a loaded module is checked.
// Header-only, so that every target using a module (the parser fuzzer too) gets it without a source.
#pragma once
#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

namespace seasim {

// Where module `file` may be, in order: $SEASIM_LIB_DIR, the folder of the running binary (the build
// folder puts the modules beside seasim and the test binaries), <prefix>/lib/seasim beside an
// installed binary (CMakeLists.txt install), then `build_dir`, the build folder CMake configured
// (empty: none).
inline std::vector<std::filesystem::path> moduleCandidates(const std::string& file, const std::string& build_dir) {
  namespace fs = std::filesystem;
  std::vector<fs::path> out;
  if (const char* dir = std::getenv("SEASIM_LIB_DIR"); dir && *dir) out.push_back(fs::path(dir) / file);
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    out.push_back(exe.parent_path() / file);
    out.push_back(exe.parent_path().parent_path() / "lib" / "seasim" / file);
  }
  if (!build_dir.empty()) out.push_back(fs::path(build_dir) / file);
  return out;
}

// The function table of the first candidate that loads and whose `entry` returns a table of this
// binary's `version` (a module built by another configuration is skipped). Never dlclose'd: the
// table's functions are used until exit. nullptr when none does; `tried` then says, per candidate,
// why ("not there", dlerror, or "not a matching seasim <what> module").
template <class Table>
const Table* loadModuleTable(const std::vector<std::filesystem::path>& candidates, const char* entry, int version,
                             const std::string& what, std::string& tried) {
  for (const std::filesystem::path& path : candidates) {
    if (!std::filesystem::exists(path)) {
      tried += "\n  " + path.string() + ": not there";
      continue;
    }
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      tried += "\n  " + path.string() + ": " + dlerror();
      continue;
    }
    using Entry = const Table* (*)();
    auto get_table = reinterpret_cast<Entry>(dlsym(handle, entry));
    const Table* table = get_table ? get_table() : nullptr;
    if (!table || table->version != version) {
      tried += "\n  " + path.string() + ": not a matching seasim " + what + " module (rebuild it with this binary)";
      continue;
    }
    return table;
  }
  return nullptr;
}

}  // namespace seasim
