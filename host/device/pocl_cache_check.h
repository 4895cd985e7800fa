// pocl_cache_check.h — PoCL's own kernel cache checked before PoCL loads. PoCL maps the shared
// objects and reads the LLVM bitcode it cached without checking them: with every cached .so cut
// in half, 31 of 47 renders died by SIGABRT or SIGBUS inside PoCL, and every later run did too. A
// read-only cache folder made PoCL offer no device at all. Neither can be caught once PoCL runs,
// so both are found here, on the files, and repaired or bypassed so that the run goes on.
#pragma once
#include <string>

namespace seasim {

// What a file of PoCL's cache shows: "" when it looks whole, else why not ("truncated: the section
// headers end at byte 12345 of a 6000-byte file"). Shared objects (.so) are checked as ELF (every
// header and segment inside the file), LLVM bitcode (.bc) by its top-level blocks' lengths; other
// files are not checked. A folder where a file belongs is damage too.
std::string poclCacheFileProblem(const std::string& path);

// The file a crash inside PoCL's kernel build leaves in its cache folder (device/crash_hint.h):
// "<dir>/.seasim-crashed". checkPoclCache then clears the folder, since a damaged entry the
// structural checks pass (a flipped byte) is the likely cause, and removes the marker.
std::string poclCrashMarker(const std::string& dir);

struct PoclCacheRepair {
  int removed = 0;             // damaged program entries removed (PoCL rebuilds them)
  std::string bypass_reason;   // not empty: the folder could not be used or repaired
};

// Checks the cache folder `dir`: removes the program entry (XX/<hash>/) of every damaged
// file, with a warning on stderr naming the file and the damage. When `dir` is read-only, or not a
// folder, or a damaged entry cannot be removed, returns why in bypass_reason (nothing changed).
PoclCacheRepair checkPoclCache(const std::string& dir);

// Before the first OpenCL call (device.cpp listDevices): checkPoclCache on POCL_CACHE_DIR, and when
// it must be bypassed, points POCL_CACHE_DIR at a fresh private folder for this run (removed at exit)
// with a warning that says why (read-only: its own message; damaged and unremovable: which file).
void preparePoclCache();

}  // namespace seasim
