// atomic_file.cpp — temp file + fsync + rename (POSIX rename is atomic within one file system).
#include "io/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "util/error.h"

namespace seasim {

namespace fs = std::filesystem;

std::string atomicTempPath(const std::string& path) {
  const fs::path p(path);
  const std::string temp_name = "." + p.filename().string() + ".tmp-" + std::to_string(::getpid());
  return (p.parent_path() / temp_name).string();
}

namespace {

// Flushes the file's data to disk so that the rename cannot land before the contents (a crash
// right after the rename must not leave an empty file under the final name).
void syncFile(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) throw RuntimeError("cannot reopen '" + path + "' to flush it: " + std::strerror(errno));
  const int rc = ::fsync(fd);
  const int err = errno;
  ::close(fd);
  if (rc != 0) throw RuntimeError("cannot flush '" + path + "' to disk: " + std::strerror(err));
}

}  // namespace

void writeFileAtomic(const std::string& path,
                     const std::function<void(const std::string& temp_path)>& write) {
  if (path.empty()) throw RuntimeError("cannot write a file with an empty path");
  const fs::path target(path);
  if (target.filename().empty())
    throw RuntimeError("cannot write '" + path + "': the path names a folder, not a file");
  const std::string temp = atomicTempPath(path);
  try {
    const fs::path parent = target.parent_path();
    if (!parent.empty()) {
      std::error_code ec;
      fs::create_directories(parent, ec);
      if (ec) throw RuntimeError("cannot create folder '" + parent.string() + "': " + ec.message());
    }
    write(temp);
    if (!fs::is_regular_file(temp)) throw RuntimeError("the writer produced no file");
    syncFile(temp);
    std::error_code ec;
    fs::rename(temp, target, ec);
    if (ec) throw RuntimeError("cannot rename the temporary file onto it: " + ec.message());
  } catch (const std::exception& e) {
    std::error_code ignored;
    fs::remove(temp, ignored);
    throw RuntimeError("cannot write '" + path + "': " + e.what());
  }
}

void writeBytes(const std::string& path, const std::vector<ByteSpan>& pieces) {
  std::size_t total = 0, written = 0;
  for (const ByteSpan& piece : pieces) total += piece.size;
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw RuntimeError("cannot create '" + path + "': " + std::strerror(errno));
  for (const ByteSpan& piece : pieces) {
    const char* p = static_cast<const char*>(piece.data);
    std::size_t left = piece.size;
    while (left > 0) {
      const ssize_t n = ::write(fd, p, left);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        // n == 0 with bytes left is a short write the kernel gave no reason for: treat as full.
        const int err = n < 0 ? errno : ENOSPC;
        ::close(fd);
        throw RuntimeError("cannot write '" + path + "' (" + std::to_string(written) + " of " +
                           std::to_string(total) + " bytes written): " + std::strerror(err));
      }
      p += n;
      left -= static_cast<std::size_t>(n);
      written += static_cast<std::size_t>(n);
    }
  }
  // NFS and some quota set-ups report ENOSPC/EDQUOT only at close.
  if (::close(fd) != 0) throw RuntimeError("cannot write '" + path + "': " + std::strerror(errno));
}

void writeBytes(const std::string& path, const void* data, std::size_t size) {
  writeBytes(path, std::vector<ByteSpan>{{data, size}});
}

namespace {

// True for ".<target>.tmp-<digits>"; sets `target`.
bool isTempName(const std::string& name, std::string& target) {
  const size_t mark = name.rfind(".tmp-");
  if (name.size() < 2 || name[0] != '.' || mark == std::string::npos || mark < 2) return false;
  const std::string pid = name.substr(mark + 5);
  if (pid.empty() || pid.find_first_not_of("0123456789") != std::string::npos) return false;
  target = name.substr(1, mark - 1);
  return true;
}

int removeTemps(const fs::path& dir, const std::string& only_target) {
  int removed = 0;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return 0;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    std::string target;
    if (!entry.is_regular_file(ec) || !isTempName(entry.path().filename().string(), target)) continue;
    if (!only_target.empty() && target != only_target) continue;
    if (fs::remove(entry.path(), ec)) ++removed;
  }
  return removed;
}

}  // namespace

int removeTempFiles(const std::string& dir) { return removeTemps(dir, ""); }

int removeTempFilesFor(const std::string& path) {
  const fs::path p(path);
  return removeTemps(p.parent_path(), p.filename().string());
}

void writeTextAtomic(const std::string& path, const std::string& text) {
  writeFileAtomic(path, [&](const std::string& temp) { writeBytes(temp, text.data(), text.size()); });
}

}  // namespace seasim
