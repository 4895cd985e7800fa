#include "device/kernel_store.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "device/pocl_cache_check.h"
#include "util/error.h"
#include "util/hash.h"
#include "util/paths.h"

namespace fs = std::filesystem;

namespace seasim {

namespace {

// The program entries XX/<hash>/ under a PoCL cache folder.
std::vector<fs::path> poclEntries(const fs::path& root) {
  std::vector<fs::path> entries;
  std::error_code ec;
  for (fs::directory_iterator top(root, ec), end; !ec && top != end; top.increment(ec)) {
    if (!top->is_directory(ec) || top->path().filename().string().size() != 2) continue;
    for (fs::directory_iterator it(top->path(), ec), e2; !ec && it != e2; it.increment(ec))
      if (it->is_directory(ec) && it->path().filename().string()[0] != '.') entries.push_back(it->path());
  }
  return entries;
}

// What is wrong with the first damaged file of an entry, or "".
std::string entryProblem(const fs::path& entry) {
  std::error_code ec;
  for (fs::recursive_directory_iterator it(entry, ec), end; !ec && it != end; it.increment(ec))
    if (std::string problem = poclCacheFileProblem(it->path().string()); !problem.empty())
      return it->path().string() + ": " + problem;
  return "";
}

// Whether the file holds the bytes of `text`.
bool fileContains(const fs::path& file, const std::string& text) {
  std::ifstream in(file, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return bytes.find(text) != std::string::npos;
}

// Copies entry `from` to `to` (absent) through a temporary sibling renamed into place. False when it
// could not (another process may have put it there first: then that one is kept).
bool copyEntry(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  fs::create_directories(to.parent_path(), ec);
  const fs::path temp = to.parent_path() / ("." + to.filename().string() + ".seed-" + std::to_string(::getpid()));
  fs::remove_all(temp, ec);
  fs::copy(from, temp, fs::copy_options::recursive, ec);
  if (!ec) fs::rename(temp, to, ec);
  const bool moved = !ec;
  if (!moved) fs::remove_all(temp, ec);
  return moved;
}

}  // namespace

std::string kernelStoreDir() {
  if (const char* d = std::getenv("SEASIM_KERNEL_STORE")) return d;
  std::error_code ec;
  fs::path dir;
  if (const std::string share = installedShareDir(); !share.empty()) {
    dir = fs::path(share) / "kernel-store";
  } else {
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (ec) return "";
    dir = exe.parent_path() / "kernel-store";
  }
  return fs::is_directory(dir, ec) ? dir.string() : "";
}

std::string poclStoreDir(const std::string& store, const std::string& device_id) {
  return (fs::path(store) / ("pocl-" + hex64(fnv1a64(device_id)))).string();
}

std::string vkfftStoreDir(const std::string& store, const std::string& device_id) {
  return (fs::path(store) / ("vkfft-" + hex64(fnv1a64(device_id)))).string();
}

std::string poclEntryOfBinary(const std::vector<unsigned char>& binary) {
  // PoCL 3.1's binary holds its cache entry's name as text: two letters A-P, a slash and 37 more (the
  // build's hash in letters, as the entry's folders are named); the first such run is it.
  constexpr size_t kLength = 40;
  auto letter = [](unsigned char c) { return c >= 'A' && c <= 'P'; };
  for (size_t i = 0; i + kLength <= binary.size(); ++i) {
    if (binary[i + 2] != '/' || !letter(binary[i]) || !letter(binary[i + 1])) continue;
    size_t k = 3;
    while (k < kLength && letter(binary[i + k])) ++k;
    const bool bounded = (i == 0 || !letter(binary[i - 1])) && (i + kLength == binary.size() || !letter(binary[i + kLength]));
    if (k == kLength && bounded) return std::string(binary.begin() + static_cast<std::ptrdiff_t>(i),
                                                    binary.begin() + static_cast<std::ptrdiff_t>(i + kLength));
  }
  return "";
}

bool seedPoclEntry(const std::string& store_pocl, const std::string& name, const std::string& pocl_cache) {
  std::error_code ec;
  if (store_pocl.empty() || name.empty() || pocl_cache.empty()) return false;
  const fs::path from = fs::path(store_pocl) / name, to = fs::path(pocl_cache) / name;
  if (!fs::is_directory(from, ec) || fs::exists(to, ec)) return false;
  if (const std::string problem = entryProblem(from); !problem.empty()) {
    std::fprintf(stderr, "seasim: warning: kernel store entry '%s' is damaged; PoCL builds it instead\n",
                 problem.c_str());
    return false;
  }
  return copyEntry(from, to);
}

int seedPoclCache(const std::string& store_pocl, const std::string& pocl_cache) {
  int copied = 0;
  for (const fs::path& entry : poclEntries(store_pocl))
    copied += seedPoclEntry(store_pocl, (entry.parent_path().filename() / entry.filename()).string(), pocl_cache);
  return copied;
}

std::string storedDepthTableDir() {
  const std::string store = kernelStoreDir();
  return store.empty() ? "" : (fs::path(store) / "sea_depth_tables").string();
}

int storeDepthTables(const std::string& tables, const std::string& store) {
  std::error_code ec;
  if (tables.empty() || !fs::is_directory(tables, ec)) return 0;
  const fs::path out = fs::path(store) / "sea_depth_tables";
  fs::create_directories(out, ec);
  if (ec) throw RuntimeError("cannot create '" + out.string() + "': " + ec.message());
  int stored = 0;
  for (fs::directory_iterator it(tables, ec), end; !ec && it != end; it.increment(ec)) {
    if (it->path().extension() != ".f32") continue;
    std::error_code copy;
    fs::copy_file(it->path(), out / it->path().filename(), fs::copy_options::overwrite_existing, copy);
    if (copy) throw RuntimeError("cannot copy '" + it->path().string() + "' into '" + out.string() + "': " + copy.message());
    ++stored;
  }
  return stored;
}

int storePoclEntries(const std::string& pocl_cache, const std::string& store, const std::string& device_id) {
  int stored = 0;
  for (const fs::path& entry : poclEntries(pocl_cache)) {
    const fs::path name = entry.parent_path().filename() / entry.filename();
    // VkFFT names its kernels VkFFT_main*; a program whose kernels were never enqueued (a plan's unused
    // direction) has only its bitcode, which still names them, and its build is the costly part.
    const bool vkfft = fileContains(entry / "program.bc", "VkFFT_main");
    const fs::path to = fs::path(vkfft ? vkfftStoreDir(store, device_id) : poclStoreDir(store, device_id)) / name;
    std::error_code ec;
    if (fs::exists(to, ec)) continue;
    if (!copyEntry(entry, to))
      throw RuntimeError("cannot copy PoCL's cache entry '" + entry.string() + "' into the kernel store '" + store + "'");
    ++stored;
  }
  return stored;
}

}  // namespace seasim
