// atomic_file.cpp — temp file + fsync + rename (POSIX rename is atomic within one file system).
#include "io/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

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

void writeTextAtomic(const std::string& path, const std::string& text) {
  writeFileAtomic(path, [&](const std::string& temp) {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    if (!out) throw RuntimeError("cannot open '" + temp + "' for writing: " + std::strerror(errno));
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    out.close();
    if (!out) throw RuntimeError("write to '" + temp + "' failed: " + std::strerror(errno));
  });
}

}  // namespace seasim
