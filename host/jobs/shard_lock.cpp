#include "jobs/shard_lock.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>

#include "io/atomic_file.h"
#include "util/error.h"

namespace fs = std::filesystem;

namespace seasim {

namespace {

std::string hostName() {
  char buf[256] = {};
  if (::gethostname(buf, sizeof buf - 1) != 0) return "unknown-host";
  return buf;
}

std::string nowText() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

struct Owner {
  std::string host, started;
  long pid = 0;
  bool readable = false;
};

Owner readOwner(const std::string& path) {
  Owner o;
  try {
    std::ifstream in(path);
    const nlohmann::json j = nlohmann::json::parse(in);
    o.host = j.at("host").get<std::string>();
    o.pid = j.at("pid").get<long>();
    o.started = j.at("started").get<std::string>();
    o.readable = true;
  } catch (const std::exception&) {
  }
  return o;
}

// True when the lock's owner is certainly gone: same host and no process with its PID. A lock
// that cannot be read (its owner died between creating and filling it) is stale after a minute.
bool isStale(const std::string& path, const Owner& o) {
  if (!o.readable) {
    std::error_code ec;
    const auto age = fs::file_time_type::clock::now() - fs::last_write_time(path, ec);
    return !ec && age > std::chrono::minutes(1);
  }
  if (o.host != hostName()) return false;
  return ::kill(static_cast<pid_t>(o.pid), 0) != 0 && errno == ESRCH;
}

}  // namespace

std::string shardLockPath(const std::string& manifest_path) { return manifest_path + ".lock"; }

ShardLock::ShardLock(std::string path) : path_(std::move(path)) {
  const std::string content = nlohmann::json{{"host", hostName()}, {"pid", static_cast<long>(::getpid())},
                                             {"started", nowText()}}.dump() + "\n";
  for (int attempt = 0; attempt < 2; ++attempt) {
    const int fd = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd >= 0) {
      ::close(fd);
      try {
        writeBytes(path_, content.data(), content.size());
      } catch (...) {
        ::unlink(path_.c_str());
        throw;
      }
      return;
    }
    if (errno != EEXIST)
      throw RuntimeError("cannot create the shard lock '" + path_ + "': " + std::strerror(errno));
    const Owner owner = readOwner(path_);
    if (attempt == 0 && isStale(path_, owner)) {
      std::fprintf(stderr, "seasim: warning: removing stale lock '%s' (%s)\n", path_.c_str(),
                   owner.readable ? ("process " + std::to_string(owner.pid) + " on " + owner.host +
                                     " is no longer running").c_str()
                                  : "unreadable and over a minute old");
      ::unlink(path_.c_str());
      continue;
    }
    std::string who = owner.readable ? "process " + std::to_string(owner.pid) + " on host " + owner.host +
                                           ", started " + owner.started
                                     : "an unknown process (the lock file is empty or unreadable)";
    throw RuntimeError("this shard is already being run by " + who + " (lock '" + path_ +
                       "'); wait for it to finish, or run another shard. If that run is dead, delete the lock file "
                       "and run again with --resume");
  }
  throw RuntimeError("cannot take the shard lock '" + path_ + "'");
}

ShardLock::~ShardLock() { ::unlink(path_.c_str()); }

}  // namespace seasim
