// shard_lock.h — one run per shard at a time. Two runs of the same shard would both render and
// overwrite each other's manifest, so resume then redid items at random. The lock is a file
// created with O_CREAT|O_EXCL (atomic on local disks and on NFSv3+ shared folders) beside the
// manifest, holding the host, PID and start time of its owner.
#pragma once
#include <string>

namespace seasim {

// "<manifest>.lock", e.g. results/x/manifest-0of4.json.lock.
std::string shardLockPath(const std::string& manifest_path);

class ShardLock {
 public:
  // Takes the lock or throws RuntimeError naming the owner (host, PID, start time) and the file.
  // A lock left by a dead process of this host (its PID no longer runs) is stale: it is removed
  // with a warning and taken. A lock from another host is never taken over automatically: that
  // run may be alive; the message says to delete the file if it is not.
  explicit ShardLock(std::string path);
  ~ShardLock();  // removes the file
  ShardLock(const ShardLock&) = delete;
  ShardLock& operator=(const ShardLock&) = delete;

 private:
  std::string path_;
};

}  // namespace seasim
