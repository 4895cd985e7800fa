#include "plan/memory_limits.h"

#include <sys/resource.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace seasim {

namespace {

std::string mib(unsigned long long bytes) { return std::to_string(bytes >> 20) + " MiB"; }

// The first token of a one-value file such as memory.max ("max" or a number); false when absent.
bool readValue(const fs::path& file, std::string& value) {
  std::ifstream in(file);
  return static_cast<bool>(in >> value);
}

// cgroup v1 reports "no limit" as a huge number rounded to the page (9223372036854771712).
constexpr unsigned long long kNoLimitAbove = 1ull << 60;

// One cgroup level: its limit less its use, or nothing when it has no limit.
// `inactive_key`: the memory.stat line of the inactive page cache under this level (v2
// "inactive_file", v1 "total_inactive_file": its usage_in_bytes counts the children too).
void tighten(ProcessMemoryLimit& best, const fs::path& dir, const char* limit_file, const char* usage_file,
             const char* inactive_key) {
  std::string limit_text, usage_text;
  if (!readValue(dir / limit_file, limit_text) || limit_text == "max") return;
  unsigned long long limit = 0, usage = 0;
  try {
    limit = std::stoull(limit_text);
    if (readValue(dir / usage_file, usage_text)) usage = std::stoull(usage_text);
  } catch (const std::exception&) {
    return;
  }
  if (limit >= kNoLimitAbove) return;
  // The page cache counts in the use but the kernel gives it back under pressure: what a new
  // allocation competes with is the working set, use less inactive file pages (as `docker stats`).
  std::ifstream stat(dir / "memory.stat");
  std::string key;
  unsigned long long value = 0;
  while (stat >> key >> value)
    if (key == inactive_key) {
      usage = value < usage ? usage - value : 0;
      break;
    }
  const unsigned long long available = usage < limit ? limit - usage : 0;
  if (best.available_bytes != 0 && available >= best.available_bytes) return;
  best.available_bytes = available == 0 ? 1 : available;  // 1: a limit already reached still counts
  best.source = "the memory cgroup's limit (" + (dir / limit_file).string() + ") of " + mib(limit) + ", " +
                mib(usage) + " in use (page cache it can drop left out)";
}

// Every level from `path` (relative to `mount`) up to `mount` itself.
void walkUp(ProcessMemoryLimit& best, const fs::path& mount, std::string path, const char* limit_file,
            const char* usage_file, const char* inactive_key) {
  while (!path.empty() && path.front() == '/') path.erase(0, 1);
  fs::path dir = mount / path;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) dir = mount;  // a container's own cgroup mounted as the root
  for (;;) {
    tighten(best, dir, limit_file, usage_file, inactive_key);
    if (dir == mount || !dir.has_parent_path() || dir.parent_path() == dir) break;
    dir = dir.parent_path();
    if (dir.string().size() < mount.string().size()) break;
  }
}

}  // namespace

ProcessMemoryLimit addressSpaceLimit(unsigned long long limit_bytes, unsigned long long mapped_bytes) {
  ProcessMemoryLimit out;
  if (limit_bytes == ~0ull || limit_bytes >= kNoLimitAbove) return out;
  const unsigned long long available = mapped_bytes < limit_bytes ? limit_bytes - mapped_bytes : 0;
  out.available_bytes = available == 0 ? 1 : available;
  out.source = "the process's address-space limit (RLIMIT_AS, ulimit -v) of " + mib(limit_bytes) + ", " +
               mib(mapped_bytes) + " of it mapped";
  return out;
}

ProcessMemoryLimit cgroupMemoryLimit(const std::string& cgroup_root, const std::string& proc_self_cgroup) {
  ProcessMemoryLimit best;
  std::istringstream lines(proc_self_cgroup);
  std::string line;
  while (std::getline(lines, line)) {
    // "hierarchy-id:controllers:path"; the path may itself hold ':'.
    const size_t a = line.find(':'), b = a == std::string::npos ? a : line.find(':', a + 1);
    if (b == std::string::npos) continue;
    const std::string id = line.substr(0, a), controllers = line.substr(a + 1, b - a - 1), path = line.substr(b + 1);
    if (id == "0" && controllers.empty()) {
      const fs::path unified = fs::exists(fs::path(cgroup_root) / "cgroup.controllers")
                                   ? fs::path(cgroup_root)
                                   : fs::path(cgroup_root) / "unified";
      walkUp(best, unified, path, "memory.max", "memory.current", "inactive_file");
    } else {
      std::istringstream names(controllers);
      std::string name;
      while (std::getline(names, name, ','))
        if (name == "memory")
          walkUp(best, fs::path(cgroup_root) / "memory", path, "memory.limit_in_bytes", "memory.usage_in_bytes",
                 "total_inactive_file");
    }
  }
  return best;
}

ProcessMemoryLimit processMemoryLimit() {
  ProcessMemoryLimit best;
  rlimit as{};
  if (::getrlimit(RLIMIT_AS, &as) == 0 && as.rlim_cur != RLIM_INFINITY) {
    unsigned long long pages = 0;
    if (std::FILE* f = std::fopen("/proc/self/statm", "r")) {
      if (std::fscanf(f, "%llu", &pages) != 1) pages = 0;
      std::fclose(f);
    }
    best = addressSpaceLimit(as.rlim_cur, pages * static_cast<unsigned long long>(::sysconf(_SC_PAGESIZE)));
  }
  std::ifstream in("/proc/self/cgroup");
  std::stringstream text;
  text << in.rdbuf();
  const ProcessMemoryLimit cgroup = cgroupMemoryLimit("/sys/fs/cgroup", text.str());
  if (cgroup.available_bytes != 0 && (best.available_bytes == 0 || cgroup.available_bytes < best.available_bytes))
    best = cgroup;
  return best;
}

}  // namespace seasim
