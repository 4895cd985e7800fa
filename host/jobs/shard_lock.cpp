#include "jobs/shard_lock.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <regex>

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

std::string describe(const Owner& o) {
  return o.readable ? "process " + std::to_string(o.pid) + " on host " + o.host + ", started " + o.started
                    : "an unknown process (the lock file is empty or unreadable)";
}

// A lock file opened and flock-ed by us to look at it: `held` when its owner (or another process
// looking at it) holds the flock, so it is alive.
struct Probe {
  int fd = -1;
  bool held = false;
  ~Probe() {
    if (fd >= 0) ::close(fd);
  }
};

// True when the lock at `path` was left by an owner that is gone; then `probe` holds its flock, so
// no other process can decide the same at once, and the caller may remove it.
bool isStale(const std::string& path, const Owner& o, Probe& probe) {
  probe.fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (probe.fd < 0) return false;  // gone meanwhile: the next attempt creates it
  bool flock_known = true;
  if (::flock(probe.fd, LOCK_EX | LOCK_NB) != 0) {
    if (errno == EWOULDBLOCK) {
      probe.held = true;
      return false;
    }
    flock_known = false;  // a file system without flock (NFS without lockd): age and PID decide
  }
  if (!o.readable) {
    if (flock_known) return true;  // seasim writes locks complete: an empty or garbage one is left over
    std::error_code ec;
    const auto age = fs::file_time_type::clock::now() - fs::last_write_time(path, ec);
    return !ec && age > std::chrono::minutes(1);
  }
  if (o.host != hostName()) return false;
  return ::kill(static_cast<pid_t>(o.pid), 0) != 0 && errno == ESRCH;
}

// Removes `path` if it is still the file `probe` opened (not a fresh lock another run made after
// it was decided stale).
void removeIfSame(const std::string& path, const Probe& probe) {
  struct stat a {}, b {};
  if (::fstat(probe.fd, &a) == 0 && ::stat(path.c_str(), &b) == 0 && a.st_ino == b.st_ino && a.st_dev == b.st_dev)
    ::unlink(path.c_str());
}

// The shard count a lock's name says: 1 for manifest.json.lock, N for manifest-<i>of<N>.json.lock,
// 0 for any other file.
int shardCountOf(const std::string& name) {
  static const std::regex sharded(R"(^manifest-[0-9]+of([0-9]+)\.json\.lock$)");
  if (name == "manifest.json.lock") return 1;
  std::smatch m;
  if (!std::regex_match(name, m, sharded)) return 0;
  try {
    return std::stoi(m[1].str());
  } catch (const std::exception&) {
    return 0;
  }
}

}  // namespace

std::string shardLockPath(const std::string& manifest_path) { return manifest_path + ".lock"; }

ShardLock::ShardLock(std::string path) : path_(std::move(path)) { acquire(); }

ShardLock::ShardLock(const std::string& output_dir, int shard_index, int shard_count)
    : path_(output_dir + "/" +
            (shard_count <= 1 ? std::string("manifest.json")
                              : "manifest-" + std::to_string(shard_index) + "of" + std::to_string(shard_count) +
                                    ".json") +
            ".lock") {
  acquire();
  std::error_code ec;
  for (fs::directory_iterator it(output_dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    const int count = shardCountOf(name);
    if (count == 0 || count == std::max(shard_count, 1)) continue;
    const std::string other = it->path().string();
    const Owner owner = readOwner(other);
    Probe probe;
    if (isStale(other, owner, probe)) {
      std::fprintf(stderr, "seasim: warning: removing stale lock '%s' (%s)\n", other.c_str(),
                   owner.readable ? ("process " + std::to_string(owner.pid) + " is no longer running").c_str()
                                  : "empty or not a lock, and nobody holds it");
      removeIfSame(other, probe);
      continue;
    }
    if (probe.fd < 0) continue;  // removed meanwhile: that run has finished
    const std::string mine = shard_count <= 1 ? "the whole job" : "shard " + std::to_string(shard_index) + "/" +
                                                                        std::to_string(shard_count);
    const std::string theirs = count == 1 ? "the whole job" : "shards of " + std::to_string(count);
    ::unlink(path_.c_str());
    ::close(fd_);
    fd_ = -1;
    throw RuntimeError("cannot run " + mine + ": " + describe(owner) + " is running " + theirs +
                       " in this output folder (lock '" + other +
                       "'), and runs with another --shard count (or none) render some of the same items. Wait "
                       "for it, or use the same --shard count. If that run is dead, delete the lock file and "
                       "run again with --resume");
  }
}

void ShardLock::acquire() {
  const std::string content = nlohmann::json{{"host", hostName()}, {"pid", static_cast<long>(::getpid())},
                                             {"started", nowText()}}.dump() + "\n";
  // The complete lock under a temporary name, flock-ed, then linked onto its name: the name never
  // shows an empty lock, and the flock says "alive" for as long as this process runs.
  const std::string temp = atomicTempPath(path_);
  ::unlink(temp.c_str());
  writeBytes(temp, content.data(), content.size());
  fd_ = ::open(temp.c_str(), O_RDONLY | O_CLOEXEC);
  // Where the file system has no flock (ENOLCK, EOPNOTSUPP), the lock still excludes by its name;
  // only telling a dead owner's empty lock from a live one falls back to its age.
  if (fd_ < 0 || (::flock(fd_, LOCK_EX | LOCK_NB) != 0 && errno == EWOULDBLOCK)) {
    const std::string why = std::strerror(errno);
    ::unlink(temp.c_str());
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
    throw RuntimeError("cannot create the shard lock '" + path_ + "': " + why);
  }
  for (int attempt = 0; attempt < 2; ++attempt) {
    if (::link(temp.c_str(), path_.c_str()) == 0) {
      ::unlink(temp.c_str());
      return;
    }
    const int err = errno;
    if (err != EEXIST) {
      ::unlink(temp.c_str());
      ::close(fd_);
      fd_ = -1;
      throw RuntimeError("cannot create the shard lock '" + path_ + "': " + std::strerror(err));
    }
    const Owner owner = readOwner(path_);
    Probe probe;
    if (attempt == 0 && isStale(path_, owner, probe)) {
      std::fprintf(stderr, "seasim: warning: removing stale lock '%s' (%s)\n", path_.c_str(),
                   owner.readable ? ("process " + std::to_string(owner.pid) + " on " + owner.host +
                                     " is no longer running").c_str()
                                  : "empty or not a lock, and nobody holds it");
      removeIfSame(path_, probe);
      continue;
    }
    if (probe.fd < 0 && attempt == 0) continue;  // the owner finished meanwhile
    ::unlink(temp.c_str());
    ::close(fd_);
    fd_ = -1;
    throw RuntimeError("this shard is already being run by " + describe(owner) + " (lock '" + path_ +
                       "'); wait for it to finish, or run another shard. If that run is dead, delete the lock file "
                       "and run again with --resume");
  }
  ::unlink(temp.c_str());
  ::close(fd_);
  fd_ = -1;
  throw RuntimeError("cannot take the shard lock '" + path_ + "'");
}

ShardLock::~ShardLock() {
  ::unlink(path_.c_str());
  if (fd_ >= 0) ::close(fd_);
}

}  // namespace seasim
