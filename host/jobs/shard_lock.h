// shard_lock.h — one run per set of items at a time. Two runs rendering the same items would both
// write them and overwrite each other's manifests, so resume and merge then trusted checksums of
// files the other run had replaced. The lock is a file beside the manifest holding the host, PID
// and start time of its owner, written complete under a temporary name and linked onto its name
// (link(2) fails if the name exists: atomic on local disks and NFS, and never an empty lock), and
// flock(2)-held by its owner while it runs, so a lock nobody holds is known to be left over (on a
// file system without flock, an unreadable lock is taken over once it is a minute old).
//
// Runs exclude each other by the items they render: shards of one layout (--shard i/N, same N)
// render disjoint items and run side by side; a run of another layout (no --shard, or another N)
// renders some of the same items, so it is refused while any lock of another layout is held.
#pragma once
#include <string>

namespace seasim {

// "<manifest>.lock", e.g. results/x/manifest-0of4.json.lock.
std::string shardLockPath(const std::string& manifest_path);

class ShardLock {
 public:
  // Takes the lock file `path` or throws RuntimeError naming the owner (host, PID, start time) and
  // the file. A lock is taken over, with a warning, when its owner is certainly gone: nobody holds
  // its flock and either it is empty or not a lock (a run of an older seasim killed between
  // creating and writing it, or a damaged file), or its PID no longer runs on this host. A lock
  // from another host with a readable owner is never taken over: that run may be alive; the
  // message says to delete the file if it is not.
  explicit ShardLock(std::string path);
  // The lock of shard `shard_index` of `shard_count` over the manifests in `output_dir`
  // (manifest.json.lock when shard_count is 1, else manifest-<i>of<N>.json.lock), then refuses,
  // releasing it, while a live lock of another shard count is in the folder. Both sides take their
  // own lock before looking for the other's, so of two runs started together at least one sees
  // the other.
  ShardLock(const std::string& output_dir, int shard_index, int shard_count);
  ~ShardLock();  // removes the file
  ShardLock(const ShardLock&) = delete;
  ShardLock& operator=(const ShardLock&) = delete;

 private:
  void acquire();
  std::string path_;
  int fd_ = -1;  // holds the flock while the lock is ours
};

}  // namespace seasim
