// kernel_cache.h — compiled kernel binaries on disk, in a form that cannot poison later runs.
// A cache file cut in half used to make every later run segfault inside the driver, and a binary
// copied over another's name failed every run with CL_INVALID_KERNEL_NAME. Each entry now carries
// a header checked before the driver sees a byte:
//   "SEASIMKC"  magic, 8 bytes
//   u32 format version (1), u32 zero
//   u64 key: the hash of (device, driver, options, source) that also names the file
//   u64 payload length, u64 payload checksum (FNV-1a 64)
//   u32 length + bytes: "platform|device|driver" of the device that built it
//   the payload: the driver's program binary
// Entries are written atomically (temporary file, fsync, rename: io/atomic_file.h).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace seasim {

// The folder of kernel entries ("" when no cache folder can be found: then nothing is cached).
std::string kernelCacheDir();

// "<dir>/<16 hex digits of key>.bin".
std::string kernelCachePath(const std::string& dir, uint64_t key);

// The payload of a good entry for (key, device_id); false and `why` set when the file is missing
// ("" then), or damaged, foreign or for another device (a sentence).
bool readKernelCacheEntry(const std::string& path, uint64_t key, const std::string& device_id,
                          std::vector<unsigned char>& payload, std::string& why);

// Writes an entry atomically; throws RuntimeError naming the file on failure.
void writeKernelCacheEntry(const std::string& path, uint64_t key, const std::string& device_id,
                           const std::vector<unsigned char>& payload);

// "" when the file is a well-formed entry whose name matches its key and whose payload matches
// its length and checksum; else what is wrong. For `seasim cache verify` (no device needed).
std::string verifyKernelCacheEntry(const std::string& path);

// The folder PoCL keeps its own compiled kernels in: $POCL_CACHE_DIR when set, else seasim's
// cache folder "pocl" (set by usePoclCacheDir). "" when neither is known.
std::string poclCacheDir();

// Points PoCL at <seasim cache>/pocl by setting POCL_CACHE_DIR, unless the user set it. Must run
// before the first OpenCL call (PoCL reads it when it loads). So `seasim cache clear` can clear
// PoCL's entries too, and a failure can name the folder.
void usePoclCacheDir();

}  // namespace seasim
