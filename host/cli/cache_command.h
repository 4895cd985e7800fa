// cache_command.h — `seasim cache <action>`: the on-disk caches (kernel binaries, PoCL's own
// kernels when seasim owns its folder, depth tables, auto-quality searches). One function per
// action; main.cpp adds one CLI11 subcommand under `cache` for each, so a new action (e.g.
// `cache warm`) is one more function here and one more line there.
#pragma once

namespace seasim {

// Removes every cache seasim owns under its cache folder (util/paths cacheDir): kernel entries,
// their temporary files and the sub-folders in kCacheSubfolders. A PoCL folder the user chose
// (POCL_CACHE_DIR set outside seasim) is named, not removed. Returns 0.
int cmdCacheClear();

// Checks every kernel entry's header, length and checksum (device/kernel_cache.h) without a
// device. Prints one line per damaged entry and a count; returns 1 when any is damaged.
int cmdCacheVerify();

}  // namespace seasim
