#include "cli/cache_command.h"

#include <cstdio>
#include <filesystem>
#include <string>

#include "device/kernel_cache.h"
#include "device/kernel_store.h"
#include "util/error.h"
#include "util/paths.h"

namespace fs = std::filesystem;

namespace seasim {

namespace {

// Sub-folders of the cache folder that seasim writes (util/paths cacheDir users). Only these and
// the kernel entries are removed: the cache folder may be one the user shares with other files.
const char* const kCacheSubfolders[] = {"pocl", "sea_depth_tables", "sea_auto", "shafts_auto"};

bool isKernelEntryOrTemp(const fs::path& p) {
  const std::string name = p.filename().string();
  return p.extension() == ".bin" || name.find(".bin.tmp-") != std::string::npos;
}

}  // namespace

int cmdCacheClear() {
  const std::string dir = kernelCacheDir();
  if (dir.empty() || !fs::is_directory(dir)) {
    std::printf("no cache folder (%s): nothing to clear\n", dir.empty() ? "HOME and SEASIM_CACHE_DIR unset" : dir.c_str());
    return 0;
  }
  std::uintmax_t removed = 0;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.is_regular_file() && isKernelEntryOrTemp(entry.path())) {
      if (!fs::remove(entry.path(), ec))
        throw RuntimeError("cannot remove '" + entry.path().string() + "': " + ec.message());
      ++removed;
    }
  }
  for (const char* sub : kCacheSubfolders) {
    const fs::path p = fs::path(dir) / sub;
    if (!fs::exists(p)) continue;
    const std::uintmax_t n = fs::remove_all(p, ec);
    if (ec) throw RuntimeError("cannot remove '" + p.string() + "': " + ec.message());
    removed += n;
  }
  std::printf("cleared %s (%ju files and folders removed)\n", dir.c_str(), removed);
  const std::string pocl = poclCacheDir();
  if (!pocl.empty() && fs::path(pocl).lexically_normal() != (fs::path(dir) / "pocl").lexically_normal())
    std::printf("PoCL's cache is '%s' (POCL_CACHE_DIR, set outside seasim): not cleared; delete it yourself if a "
                "kernel build fails on it\n", pocl.c_str());
  return 0;
}

namespace {

// Verifies the kernel entries of `dir`, printing each damaged one and a summary line; the damaged count.
int verifyFolder(const std::string& dir, const char* what, const char* damaged_then) {
  int good = 0, bad = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (!entry.is_regular_file() || entry.path().extension() != ".bin") continue;
    const std::string why = verifyKernelCacheEntry(entry.path().string());
    if (why.empty()) {
      ++good;
    } else {
      ++bad;
      std::printf("damaged: %s: %s\n", entry.path().string().c_str(), why.c_str());
    }
  }
  std::printf("%s %s: %d kernel entries good, %d damaged%s\n", what, dir.c_str(), good, bad, bad ? damaged_then : "");
  return bad;
}

}  // namespace

int cmdCacheVerify() {
  int bad = 0;
  const std::string dir = kernelCacheDir();
  if (dir.empty() || !fs::is_directory(dir))
    std::printf("no cache folder: nothing to verify\n");
  else
    bad += verifyFolder(dir, "cache", " (each is rebuilt on its next use; `seasim cache clear` removes them now)");
  // The kernel store (device/kernel_store.h) is read-only: a damaged entry is compiled instead, each run.
  if (const std::string store = kernelStoreDir(); !store.empty() && fs::is_directory(store))
    bad += verifyFolder(store, "kernel store", " (each is compiled instead on every use: make the store again)");
  return bad == 0 ? 0 : 1;
}

}  // namespace seasim
