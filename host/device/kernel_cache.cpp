#include "device/kernel_cache.h"

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "io/atomic_file.h"
#include "util/error.h"
#include "util/hash.h"
#include "util/paths.h"

namespace fs = std::filesystem;

namespace seasim {

namespace {

constexpr char kMagic[8] = {'S', 'E', 'A', 'S', 'I', 'M', 'K', 'C'};
constexpr uint32_t kVersion = 1;

struct Header {
  uint64_t key = 0, length = 0, checksum = 0;
  std::string device_id;
  size_t payload_offset = 0;
};

void put(std::string& out, const void* p, size_t n) { out.append(static_cast<const char*>(p), n); }

template <class T>
bool get(const std::vector<unsigned char>& in, size_t& pos, T& v) {
  if (in.size() - pos < sizeof v) return false;
  std::memcpy(&v, in.data() + pos, sizeof v);
  pos += sizeof v;
  return true;
}

std::vector<unsigned char> readAll(const std::string& path, bool& exists) {
  std::ifstream in(path, std::ios::binary);
  exists = static_cast<bool>(in);
  if (!in) return {};
  return std::vector<unsigned char>(std::istreambuf_iterator<char>(in), {});
}

// Parses and checks the header and payload; "" when good.
std::string parse(const std::vector<unsigned char>& bytes, Header& h) {
  size_t pos = 0;
  if (bytes.size() < sizeof kMagic || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0)
    return "not a seasim kernel cache entry (no header; written by an older seasim or damaged)";
  pos = sizeof kMagic;
  uint32_t version = 0, zero = 0, id_len = 0;
  if (!get(bytes, pos, version) || !get(bytes, pos, zero)) return "truncated header";
  if (version != kVersion) return "cache format version " + std::to_string(version) + ", expected " + std::to_string(kVersion);
  if (!get(bytes, pos, h.key) || !get(bytes, pos, h.length) || !get(bytes, pos, h.checksum) || !get(bytes, pos, id_len))
    return "truncated header";
  if (id_len > 4096 || bytes.size() - pos < id_len) return "truncated header";
  h.device_id.assign(reinterpret_cast<const char*>(bytes.data() + pos), id_len);
  pos += id_len;
  h.payload_offset = pos;
  const uint64_t have = bytes.size() - pos;
  if (have != h.length)
    return "payload is " + std::to_string(have) + " bytes, the header says " + std::to_string(h.length) +
           " (truncated or padded)";
  if (fnv1a64(bytes.data() + pos, have) != h.checksum) return "payload checksum mismatch (corrupt)";
  return "";
}

}  // namespace

std::string kernelCacheDir() { return cacheDir(""); }

std::string kernelCachePath(const std::string& dir, uint64_t key) { return dir + "/" + hex64(key) + ".bin"; }

bool readKernelCacheEntry(const std::string& path, uint64_t key, const std::string& device_id,
                          std::vector<unsigned char>& payload, std::string& why) {
  why.clear();
  if (std::error_code ec; fs::is_directory(path, ec)) {
    why = "it is a folder, not a cache file";
    return false;
  }
  bool exists = false;
  const std::vector<unsigned char> bytes = readAll(path, exists);
  if (!exists) return false;
  Header h;
  why = parse(bytes, h);
  if (!why.empty()) return false;
  // A binary copied over another entry's name: its key says what it really is.
  if (h.key != key) {
    why = "holds the entry " + hex64(h.key) + ", not " + hex64(key) + " (a file copied over another)";
    return false;
  }
  if (h.device_id != device_id) {
    why = "built for '" + h.device_id + "', not '" + device_id + "'";
    return false;
  }
  payload.assign(bytes.begin() + static_cast<std::ptrdiff_t>(h.payload_offset), bytes.end());
  return true;
}

void writeKernelCacheEntry(const std::string& path, uint64_t key, const std::string& device_id,
                           const std::vector<unsigned char>& payload) {
  std::string header;
  put(header, kMagic, sizeof kMagic);
  const uint32_t version = kVersion, zero = 0, id_len = static_cast<uint32_t>(device_id.size());
  const uint64_t length = payload.size(), checksum = fnv1a64(payload.data(), payload.size());
  put(header, &version, 4);
  put(header, &zero, 4);
  put(header, &key, 8);
  put(header, &length, 8);
  put(header, &checksum, 8);
  put(header, &id_len, 4);
  header += device_id;
  writeFileAtomic(path, [&](const std::string& temp) {
    writeBytes(temp, {{header.data(), header.size()}, {payload.data(), payload.size()}});
  });
}

std::string verifyKernelCacheEntry(const std::string& path) {
  bool exists = false;
  const std::vector<unsigned char> bytes = readAll(path, exists);
  if (!exists) return "cannot be read";
  Header h;
  if (std::string why = parse(bytes, h); !why.empty()) return why;
  if (fs::path(path).filename().string() != hex64(h.key) + ".bin")
    return "holds the entry " + hex64(h.key) + ", not the one its name says (a file copied over another)";
  return "";
}

std::string poclCacheDir() {
  if (const char* d = std::getenv("POCL_CACHE_DIR"); d && *d) return d;
  return cacheDir("pocl");
}

void usePoclCacheDir() {
  if (const char* d = std::getenv("POCL_CACHE_DIR"); d && *d) return;
  const std::string dir = cacheDir("pocl");
  if (dir.empty()) return;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) return;  // PoCL falls back to its own default folder
  ::setenv("POCL_CACHE_DIR", dir.c_str(), 0);
}

}  // namespace seasim
