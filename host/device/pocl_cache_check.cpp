#include "device/pocl_cache_check.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

#include "device/kernel_cache.h"
#include "util/paths.h"

namespace fs = std::filesystem;

namespace seasim {

namespace {

// Reads `n` bytes at `offset`; false when the file is shorter.
bool readAt(std::ifstream& in, uint64_t offset, void* out, size_t n) {
  in.clear();
  in.seekg(static_cast<std::streamoff>(offset));
  in.read(static_cast<char*>(out), static_cast<std::streamsize>(n));
  return static_cast<size_t>(in.gcount()) == n;
}

template <class T>
T le(const unsigned char* p) {  // little-endian field (PoCL's CPU objects are native x86-64/aarch64)
  T v{};
  std::memcpy(&v, p, sizeof v);
  return v;
}

std::string beyond(const std::string& what, uint64_t end, uint64_t size) {
  return "truncated: " + what + " end at byte " + std::to_string(end) + " of a " + std::to_string(size) +
         "-byte file";
}

// ELF64 (and ELF32): the header, every program header's segment and every section's bytes lie
// inside the file. A cut file loses its section headers (they come last) first.
std::string elfProblem(std::ifstream& in, uint64_t size) {
  unsigned char h[64];
  if (!readAt(in, 0, h, 52) || std::memcmp(h, "\x7f" "ELF", 4) != 0) return "not an ELF shared object";
  const bool is64 = h[4] == 2;
  if (is64 && !readAt(in, 0, h, 64)) return "truncated ELF header";
  const uint64_t phoff = is64 ? le<uint64_t>(h + 32) : le<uint32_t>(h + 28);
  const uint64_t shoff = is64 ? le<uint64_t>(h + 40) : le<uint32_t>(h + 32);
  const uint16_t phentsize = le<uint16_t>(h + (is64 ? 54 : 42)), phnum = le<uint16_t>(h + (is64 ? 56 : 44));
  const uint16_t shentsize = le<uint16_t>(h + (is64 ? 58 : 46)), shnum = le<uint16_t>(h + (is64 ? 60 : 48));
  if (phoff + uint64_t(phentsize) * phnum > size) return beyond("the program headers", phoff + uint64_t(phentsize) * phnum, size);
  if (shoff + uint64_t(shentsize) * shnum > size) return beyond("the section headers", shoff + uint64_t(shentsize) * shnum, size);
  for (uint16_t i = 0; i < phnum; ++i) {
    unsigned char p[56];
    if (!readAt(in, phoff + uint64_t(i) * phentsize, p, is64 ? 56 : 32)) return "truncated program header";
    const uint64_t off = is64 ? le<uint64_t>(p + 8) : le<uint32_t>(p + 4);
    const uint64_t filesz = is64 ? le<uint64_t>(p + 32) : le<uint32_t>(p + 16);
    if (off + filesz > size) return beyond("a loadable segment's bytes", off + filesz, size);
  }
  for (uint16_t i = 0; i < shnum; ++i) {
    unsigned char s[64];
    if (!readAt(in, shoff + uint64_t(i) * shentsize, s, is64 ? 64 : 40)) return "truncated section header";
    const uint32_t type = le<uint32_t>(s + 4);
    const uint64_t off = is64 ? le<uint64_t>(s + 24) : le<uint32_t>(s + 16);
    const uint64_t sz = is64 ? le<uint64_t>(s + 32) : le<uint32_t>(s + 20);
    if (type != 8 /* SHT_NOBITS */ && off + sz > size) return beyond("a section's bytes", off + sz, size);
  }
  return "";
}

// LLVM bitcode: optionally inside a wrapper header (magic 0x0B17C0DE, offset, size), then 'BC'
// 0xC0DE and top-level blocks, each ENTER_SUBBLOCK (abbrev id 1 in 2 bits), block id (vbr8),
// abbrev width (vbr4), alignment to 32 bits and the block's length in 32-bit words. Walking the
// lengths finds a cut file without parsing the blocks.
class BitReader {
 public:
  BitReader(const std::vector<unsigned char>& bytes, size_t start) : b_(bytes), bit_(start * 8) {}
  bool read(unsigned n, uint64_t& v) {
    v = 0;
    for (unsigned i = 0; i < n; ++i, ++bit_) {
      if (bit_ / 8 >= b_.size()) return false;
      v |= uint64_t((b_[bit_ / 8] >> (bit_ % 8)) & 1u) << i;
    }
    return true;
  }
  bool vbr(unsigned n, uint64_t& v) {
    v = 0;
    for (unsigned shift = 0; shift < 64; shift += n - 1) {
      uint64_t piece = 0;
      if (!read(n, piece)) return false;
      v |= (piece & ((1ull << (n - 1)) - 1)) << shift;
      if (!(piece & (1ull << (n - 1)))) return true;
    }
    return false;
  }
  void align32() { bit_ = (bit_ + 31) / 32 * 32; }
  size_t byte() const { return bit_ / 8; }
  void skipBytes(uint64_t n) { bit_ += n * 8; }

 private:
  const std::vector<unsigned char>& b_;
  uint64_t bit_;
};

std::string bitcodeProblem(std::ifstream& in, uint64_t size) {
  if (size > (uint64_t(1) << 31)) return "";  // not a cached kernel: leave it to PoCL
  std::vector<unsigned char> bytes(size);
  if (!readAt(in, 0, bytes.data(), size)) return "cannot be read";
  size_t start = 0, end = size;
  if (size >= 20 && le<uint32_t>(bytes.data()) == 0x0B17C0DE) {
    const uint64_t off = le<uint32_t>(bytes.data() + 8), len = le<uint32_t>(bytes.data() + 12);
    if (off + len > size) return beyond("the wrapped bitcode", off + len, size);
    start = off;
    end = off + len;
  }
  if (end - start < 4 || std::memcmp(bytes.data() + start, "BC\xC0\xDE", 4) != 0) return "not LLVM bitcode";
  BitReader r(bytes, start + 4);
  while (r.byte() + 4 <= end) {
    uint64_t abbrev = 0, id = 0, width = 0, words = 0;
    if (!r.read(2, abbrev)) break;
    if (abbrev == 0) break;  // padding at the end of the stream
    if (abbrev != 1) return "damaged: a top-level record that is not a block";
    if (!r.vbr(8, id) || !r.vbr(4, width)) return "truncated block header";
    r.align32();
    if (!r.read(32, words)) return "truncated block header";
    const uint64_t block_end = r.byte() + words * 4;
    if (block_end > end) return beyond("block " + std::to_string(id) + "'s bytes", block_end, end);
    r.skipBytes(words * 4);
  }
  return "";
}

// The program entry a file belongs to: <dir>/XX/<hash> (PoCL 3: program.bc and a folder per
// kernel under it) or <dir>/kcache/XX/<hash> (older PoCL); a file outside such an entry is its own.
fs::path entryOf(const fs::path& dir, const fs::path& file) {
  const fs::path rel = file.lexically_relative(dir);
  auto it = rel.begin();
  if (it == rel.end()) return file;
  const int depth = *it == "kcache" ? 3 : 2;
  fs::path entry = dir;
  for (int i = 0; i < depth && it != rel.end(); ++i, ++it) entry /= *it;
  return it == rel.end() ? file : entry;
}

// Why PoCL cannot write `dir` ("" when it can), as the sentence the warning uses: "is read-only
// (...)" for a read-only file system or missing permission, else "cannot be used (...)".
std::string writableProblem(const std::string& dir) {
  const auto why = [](int err, const std::string& what) {
    const bool read_only = err == EROFS || err == EACCES || err == EPERM;
    return std::string(read_only ? "is read-only (" : "cannot be used (") + what + ")";
  };
  std::error_code ec;
  if (!fs::exists(dir, ec)) {
    fs::create_directories(dir, ec);  // as PoCL would; where it cannot, PoCL offered no device at all
    if (ec) return why(ec.value(), "it cannot be created: " + ec.message());
  }
  if (!fs::is_directory(dir, ec)) return why(ENOTDIR, "it is not a folder");
  // access(2) ignores read-only mounts for root and ACL subtleties: a real file says it all.
  const std::string probe = dir + "/.seasim-write-test-" + std::to_string(::getpid());
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0) {
    const int err = errno;
    return why(err, std::strerror(err));
  }
  ::close(fd);
  ::unlink(probe.c_str());
  return "";
}

std::string g_private_dir;  // the bypass folder of this process, removed at exit
void removePrivateDir() {
  std::error_code ec;
  if (!g_private_dir.empty()) fs::remove_all(g_private_dir, ec);
}

}  // namespace

std::string poclCacheFileProblem(const std::string& path) {
  std::error_code ec;
  const fs::path p(path);
  const std::string ext = p.extension().string();
  if (ext != ".so" && ext != ".bc") return "";
  if (fs::is_directory(p, ec)) return "a folder where PoCL keeps a file";
  const uint64_t size = fs::file_size(p, ec);
  if (ec) return "cannot be read: " + ec.message();
  std::ifstream in(path, std::ios::binary);
  if (!in) return "cannot be read";
  return ext == ".so" ? elfProblem(in, size) : bitcodeProblem(in, size);
}

static const char* const kPoclLockName = ".seasim-lock";

std::string poclCrashMarker(const std::string& dir) { return dir + "/.seasim-crashed"; }

PoclCacheRepair checkPoclCache(const std::string& dir) {
  PoclCacheRepair out;
  if (const std::string problem = writableProblem(dir); !problem.empty()) {
    out.bypass_reason = "PoCL's cache folder '" + dir + "' " + problem;
    return out;
  }
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return out;
  if (fs::exists(poclCrashMarker(dir), ec)) {
    std::vector<fs::path> entries;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
      if (it->path().filename() != kPoclLockName) entries.push_back(it->path());  // held by this process
    int removed = 0;
    for (const fs::path& entry : entries) {
      std::error_code rm;
      fs::remove_all(entry, rm);
      if (rm) {
        out.bypass_reason = "PoCL's cache folder '" + dir + "' held a crashed build and cannot be cleared (" +
                            rm.message() + ")";
        return out;
      }
      ++removed;
    }
    std::fprintf(stderr,
                 "seasim: warning: the last run crashed inside PoCL while building kernels; cleared PoCL's cache "
                 "'%s' (%d entries), which may have caused it\n",
                 dir.c_str(), removed - 1);
    out.removed += removed - 1;  // the marker is not an entry
  }
  std::vector<std::pair<fs::path, std::string>> damaged;
  for (fs::recursive_directory_iterator it(dir, fs::directory_options::skip_permission_denied, ec), end;
       !ec && it != end; it.increment(ec)) {
    const std::string problem = poclCacheFileProblem(it->path().string());
    if (problem.empty()) continue;
    damaged.emplace_back(entryOf(dir, it->path()), it->path().string() + ": " + problem);
    if (it->is_directory(ec)) it.disable_recursion_pending();
  }
  for (const auto& [entry, why] : damaged) {
    if (!fs::exists(entry, ec)) continue;  // two damaged files of one entry
    fs::remove_all(entry, ec);
    if (ec) {
      out.bypass_reason = "PoCL's cache entry '" + why + "' is damaged and cannot be removed (" + ec.message() + ")";
      return out;
    }
    std::fprintf(stderr, "seasim: warning: PoCL's cache entry '%s' is damaged; removed '%s' (PoCL rebuilds it)\n",
                 why.c_str(), entry.string().c_str());
    ++out.removed;
  }
  return out;
}

// Several seasim processes may share PoCL's cache (a farm node's jobs, ctest -j 2). While one builds
// a kernel its files are half-written, which the check would take for damage and remove under it
// (PoCL then aborts: "Final linking of kernel ... failed"). So every process holds a shared flock on
// <cache>/.seasim-lock for its lifetime, and only a process that gets it exclusively, i.e. the only
// seasim using the cache, checks and repairs it, before sharing it. Returns whether it was alone.
static int g_pocl_lock_fd = -1;
static bool lockPoclCacheAlone(const std::string& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);  // so that the first process's lock covers its own first build
  g_pocl_lock_fd = ::open((fs::path(dir) / kPoclLockName).c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
  if (g_pocl_lock_fd < 0) return true;  // no lock to take (a read-only folder): the check says why
  if (::flock(g_pocl_lock_fd, LOCK_EX | LOCK_NB) == 0) return true;
  ::flock(g_pocl_lock_fd, LOCK_SH);  // waits while another process checks the cache, then shares it
  return false;
}

void preparePoclCache() {
  const std::string dir = poclCacheDir();
  if (dir.empty() || !g_private_dir.empty() || g_pocl_lock_fd >= 0) return;
  if (!lockPoclCacheAlone(dir)) return;  // in use by another seasim: its files may be half-written
  const PoclCacheRepair repair = checkPoclCache(dir);
  if (g_pocl_lock_fd >= 0) ::flock(g_pocl_lock_fd, LOCK_SH);  // checked: now shared with later processes
  if (repair.bypass_reason.empty()) return;
  const std::string private_dir = makeTempFolder("seasim-pocl");
  if (private_dir.empty()) {
    std::fprintf(stderr, "seasim: warning: %s, and no private folder could be made instead (%s)\n",
                 repair.bypass_reason.c_str(), std::strerror(errno));
    return;
  }
  g_private_dir = private_dir;
  std::atexit(removePrivateDir);
  ::setenv("POCL_CACHE_DIR", g_private_dir.c_str(), 1);
  std::fprintf(stderr,
               "seasim: warning: %s; PoCL builds this run's kernels in the private folder '%s' instead (removed at "
               "exit; slower: fix or clear the folder to keep its kernels)\n",
               repair.bypass_reason.c_str(), g_private_dir.c_str());
}

}  // namespace seasim
