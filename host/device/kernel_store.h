// kernel_store.h — kernels compiled ahead of a node's first frame and shipped with an installation.
//
// A render with empty caches spent 1–10 s compiling before its first frame (results/BENCHMARKS.md, "Cold
// against warm first frame"). The store holds what those builds make, compiled by `seasim cache warm
// --store DIR` (`make kernel-store`, installed under share/seasim/kernel-store):
//   <store>/<key>.bin         seasim's programs as kernel cache entries (kernel_cache.h: the key hashes
//                             device, driver, options and source), read when the cache lacks the entry;
//   <store>/pocl-<device>/    PoCL's cache entries (XX/<hash>/) of those programs, with the work-group
//                             functions PoCL specialises at a kernel's first enqueue (a program binary
//                             carries only the generic one; compiling the specialised ones took seabed's
//                             first frame 1.5 s). A binary names its entry, which is copied into PoCL's
//                             cache folder just before the program is loaded from it;
//   <store>/vkfft-<device>/   PoCL's entries of the programs VkFFT builds from its own generated source,
//                             copied before an FFT plan is made (PoCL finds them by their source's hash);
//   <store>/sea_depth_tables/ the sea's second-order depth tables of the shipped scenes (000 §5.4: a
//                             kernel computes them once per floor and camera, 1.3 s for seashore),
//                             read when the cache lacks them (passes/sea_heightfield.h).
// All are keyed by the device and driver, so a node of another CPU or driver finds nothing and compiles
// as before. The store is only read: a missing or damaged piece costs its compile, never a run.
#pragma once
#include <string>
#include <vector>

namespace seasim {

// The store's folder: $SEASIM_KERNEL_STORE when set ("" for none), else <prefix>/share/seasim/kernel-store
// beside an installed binary, else kernel-store beside the binary (a build tree); "" when absent.
std::string kernelStoreDir();

// For device_id "<platform>|<device>|<driver>" (Device::deviceId): "<store>/pocl-<16 hex digits of its
// hash>" and "<store>/vkfft-<the same>".
std::string poclStoreDir(const std::string& store, const std::string& device_id);
std::string vkfftStoreDir(const std::string& store, const std::string& device_id);

// The PoCL cache entry ("XX/<37 letters A-P>") a PoCL program binary names, or "" (another driver's binary).
std::string poclEntryOfBinary(const std::vector<unsigned char>& binary);

// Copies the entry `name` of `store_pocl` into `pocl_cache` when that lacks it: into a temporary sibling,
// renamed into place, so that PoCL never sees half an entry; a damaged one (pocl_cache_check.h) is skipped
// with a warning. Whether it was copied.
bool seedPoclEntry(const std::string& store_pocl, const std::string& name, const std::string& pocl_cache);

// seedPoclEntry for every entry of `store_pocl`. Returns how many were copied.
int seedPoclCache(const std::string& store_pocl, const std::string& pocl_cache);

// The store's depth tables: "<kernelStoreDir()>/sea_depth_tables", or "" without a store.
std::string storedDepthTableDir();

// Writes the store's parts from the caches a warm-up filled: the `.f32` depth tables of `tables`, and
// every entry of `pocl_cache`, VkFFT's (their bitcode names VkFFT_main) into vkfftStoreDir and the rest
// into poclStoreDir. Each returns how many; throws RuntimeError naming what cannot be copied.
int storeDepthTables(const std::string& tables, const std::string& store);
int storePoclEntries(const std::string& pocl_cache, const std::string& store, const std::string& device_id);

}  // namespace seasim
