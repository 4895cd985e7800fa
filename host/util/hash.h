// hash.h — FNV-1a 64: a stable hash (the same in every build) for cache names and output checksums.
#pragma once
#include <cstdint>
#include <string>

namespace seasim {

inline uint64_t fnv1a64(const void* data, size_t size, uint64_t h = 1469598103934665603ull) {
  const unsigned char* p = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < size; ++i) {
    h ^= p[i];
    h *= 1099511628211ull;
  }
  return h;
}

inline uint64_t fnv1a64(const std::string& s, uint64_t h = 1469598103934665603ull) {
  return fnv1a64(s.data(), s.size(), h);
}

std::string hex64(uint64_t v);

// Checksum of a file's bytes ("fnv1a64:0123abcd..."); "" when it cannot be read.
std::string fileChecksum(const std::string& path);

}  // namespace seasim
