// memory_limits.h — how much more memory this process may take, from the limits the system puts on
// it rather than the device: the address-space limit (RLIMIT_AS, `ulimit -v`, `prlimit --as`) less
// what the process has mapped, and the memory cgroup's limit (v2 memory.max, v1
// memory.limit_in_bytes, for this cgroup and every parent) less what the cgroup uses. On a CPU
// device (PoCL) the "device" buffers are this process's memory: under `prlimit --as=4G` a 16384²
// render passed the device check and then aborted inside PoCL or threw std::bad_alloc after 100 s.
#pragma once
#include <string>

namespace seasim {

struct ProcessMemoryLimit {
  unsigned long long available_bytes = 0;  // 0: no limit found
  std::string source;                      // "the address-space limit (RLIMIT_AS) of 4096 MiB, 312 MiB in use"
};

// The tightest of the limits below (available_bytes 0 when none applies).
ProcessMemoryLimit processMemoryLimit();

// The parts, with the files they read passed in, so tests can give them a made-up system.
// RLIMIT_AS: `limit_bytes` (RLIM_INFINITY as ~0ull: none) less `mapped_bytes`.
ProcessMemoryLimit addressSpaceLimit(unsigned long long limit_bytes, unsigned long long mapped_bytes);
// The cgroup of `proc_self_cgroup` (the text of /proc/self/cgroup) under `cgroup_root` (normally
// /sys/fs/cgroup): v2 ("0::/path", <root>/<path>/memory.max and memory.current) or v1 (the
// "memory" controller's line, <root>/memory/<path>/memory.limit_in_bytes and memory.usage_in_bytes);
// each level from the process's cgroup up to the root counts, its use less the inactive page cache
// of its memory.stat (the kernel drops that first). A path that is not there (a
// container that shows its own cgroup as the root) falls back to the mount's root.
ProcessMemoryLimit cgroupMemoryLimit(const std::string& cgroup_root, const std::string& proc_self_cgroup);

}  // namespace seasim
