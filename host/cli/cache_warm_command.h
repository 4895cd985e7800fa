// cache_warm_command.h — `seasim cache warm SCENE|JOB`: compile, before the first frame, every kernel
// program and every PoCL work-group function the scene's or job's plans will need, so that a farm node
// pays the compile once (into $SEASIM_CACHE_DIR and $POCL_CACHE_DIR) instead of in its first frame;
// with --store DIR, also a kernel store (device/kernel_store.h) to ship with an install.
#pragma once
#include <string>
#include <vector>

namespace seasim {

struct CacheWarmCmd {
  std::vector<std::string> files;  // scene or job TOML files
  std::string device;              // device selector ("" = auto)
  std::vector<std::string> sets;   // key=value overrides, applied to every scene (after a job's own)
  std::string store;               // "" or a folder to write the kernel store into
};

// Renders one frame of each distinct (plan, image size, quality) among the files' renders, writing
// nothing but the caches; with a store, into fresh private caches instead (removed after), which are
// then written into the store folder. Prints what it built and how long it took. Returns 0; throws
// InputError/RuntimeError/DeviceError like `seasim render` (main prints them).
int cmdCacheWarm(const CacheWarmCmd& cmd);

}  // namespace seasim
