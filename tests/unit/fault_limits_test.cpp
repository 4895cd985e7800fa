// fault_limits_test.cpp — the fault matrix's pieces that need no device: TOML nesting limits, the
// process's memory limits (address space, cgroup v1 and v2 on a made-up /sys/fs/cgroup), shard
// locks of different layouts, and PoCL cache files cut short. The same cases through the real
// binary are in tests/integration/fault_matrix_test.cpp.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <fcntl.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>

#include "device/crash_hint.h"
#include "device/pocl_cache_check.h"
#include "jobs/shard_lock.h"
#include "plan/memory_budget.h"
#include "plan/memory_limits.h"
#include "plan/plan.h"
#include "scene/scene_parser.h"
#include "scene/toml_limits.h"
#include "util/error.h"

namespace seasim {
namespace {

namespace fs = std::filesystem;

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

class FaultLimits : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("seasim_limits_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string write(const std::string& name, const std::string& bytes) const {
    fs::create_directories((dir_ / name).parent_path());
    std::ofstream(dir_ / name, std::ios::binary) << bytes;
    return path(name);
  }
  fs::path dir_;
};

std::string parts(int n, const std::string& sep = ".") {
  std::string s;
  for (int i = 0; i < n; ++i) s += (i ? sep : "") + "a";
  return s;
}

TEST_F(FaultLimits, TomlKeysAndNestingAreLimitedAtTheirLine) {
  EXPECT_EQ(errorOf([] { checkTomlLimits(parts(64) + " = 1\n", "f.toml"); }), "") << "64 parts are allowed";
  std::string msg = errorOf([] { checkTomlLimits("x = 1\n\n" + parts(65) + " = 1\n", "f.toml"); });
  EXPECT_EQ(msg.rfind("f.toml:3: a dotted key or table header with more than 64 parts", 0), 0u) << msg;
  msg = errorOf([] { checkTomlLimits("[" + parts(40000) + "]\n", "f.toml"); });
  EXPECT_EQ(msg.rfind("f.toml:1: a dotted key or table header", 0), 0u) << msg;
  msg = errorOf([] { checkTomlLimits("v = " + std::string(65, '[') + std::string(65, ']'), "f.toml", 7); });
  EXPECT_EQ(msg.rfind("f.toml:7: arrays or inline tables nested more than 64 deep", 0), 0u) << msg;
  EXPECT_EQ(errorOf([] { checkTomlLimits("v = " + std::string(64, '[') + std::string(64, ']'), "f.toml"); }), "");
  // Dots and brackets inside strings and comments are not structure; floats have one dot each.
  const std::string quoted = "\"" + parts(100) + "\" = 1\nb = '" + std::string(100, '[') + "'\n# " + parts(100) +
                             "\nc = \"\"\"\n" + std::string(100, '{') + "\n\"\"\"\nd = [" + parts(100, "1.5, 1") + "]\n";
  EXPECT_EQ(errorOf([&] { checkTomlLimits(quoted, "f.toml"); }), "");
  // The scene parser applies it (and to --set/override keys).
  msg = errorOf([] { (void)parseScene(parts(5000) + " = 1\n", "s.toml"); });
  EXPECT_EQ(msg.rfind("s.toml:1: a dotted key", 0), 0u) << msg;
  msg = errorOf([] { (void)parseScene("", "s.toml", {Override{parts(5000), "1", {"job.toml", 4}}}); });
  EXPECT_NE(msg.find("job.toml:4: "), std::string::npos) << msg;
  EXPECT_NE(msg.find("more than 64 parts"), std::string::npos) << msg;
  EXPECT_LT(msg.size(), 400u) << "the key is shown by its start";
}

TEST_F(FaultLimits, AddressSpaceLimitLeavesWhatIsNotMapped) {
  EXPECT_EQ(addressSpaceLimit(~0ull, 1ull << 30).available_bytes, 0u) << "unlimited";
  const ProcessMemoryLimit l = addressSpaceLimit(4ull << 30, 1ull << 30);
  EXPECT_EQ(l.available_bytes, 3ull << 30);
  EXPECT_EQ(l.source, "the process's address-space limit (RLIMIT_AS, ulimit -v) of 4096 MiB, 1024 MiB of it mapped");
  EXPECT_EQ(addressSpaceLimit(1ull << 30, 2ull << 30).available_bytes, 1u) << "already over: nothing left";
}

// On a GPU the device's buffers are its own, but the host copies of the frame are this process's:
// under RLIMIT_AS they are checked against what the process may still map (in a child, so the
// limit does not stay on the test runner).
TEST_F(FaultLimits, OnAGpuTheHostCopiesMeetTheProcesssLimit) {
  const std::string out = path("message");
  const pid_t child = ::fork();
  if (child == 0) {
    rlimit as{};
    as.rlim_cur = as.rlim_max = 8ull << 30;
    ::setrlimit(RLIMIT_AS, &as);
    const double big = 12.0 * 16384 * 16384;  // 3 GiB each
    const std::vector<BufferEstimate> buffers = {
        {"frame", "RGB image", big, {"camera.width", "camera.height"}, {16384, 16384}, false},
        {"frame", "RGB image read back to the host", big, {"camera.width", "camera.height"}, {16384, 16384}, true},
        {"frame", "another host copy", big, {"camera.width", "camera.height"}, {16384, 16384}, true},
        {"frame", "a third host copy", big, {"camera.width", "camera.height"}, {16384, 16384}, true}};
    std::string msg = errorOf([&] { checkRenderMemory(buffers, 80ull << 30, 20ull << 30, "gpu:0 test", false); });
    std::ofstream(out) << msg;
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  std::ifstream in(out);
  const std::string msg((std::istreambuf_iterator<char>(in)), {});
  EXPECT_NE(msg.find("more than 90% of the host side of this process's"), std::string::npos) << msg;
  EXPECT_NE(msg.find("the process's address-space limit (RLIMIT_AS, ulimit -v) of 8192 MiB"), std::string::npos) << msg;
  EXPECT_EQ(msg.find("RGB image 3072"), std::string::npos) << "the device's own buffer is not a host copy: " << msg;
}

TEST_F(FaultLimits, CgroupLimitsAreReadForV1AndV2AndTheTightestLevelWins) {
  // v2: the process's cgroup has no limit, its parent 2 GiB with 512 MiB used.
  write("v2/cgroup.controllers", "memory\n");
  write("v2/jobs/memory.max", "2147483648\n");
  write("v2/jobs/memory.current", "536870912\n");
  write("v2/jobs/task7/memory.max", "max\n");
  write("v2/jobs/task7/memory.current", "1000\n");
  ProcessMemoryLimit l = cgroupMemoryLimit(path("v2"), "0::/jobs/task7\n");
  EXPECT_EQ(l.available_bytes, 1536ull << 20);
  EXPECT_NE(l.source.find("memory cgroup's limit (" + path("v2/jobs/memory.max") + ") of 2048 MiB, 512 MiB in use"
                          " (page cache it can drop left out)"),
            std::string::npos)
      << l.source;
  // v1: the memory controller's line; "no limit" is a huge page-rounded number.
  write("v1/memory/memory.limit_in_bytes", "9223372036854771712\n");
  write("v1/memory/box/memory.limit_in_bytes", "1073741824\n");
  write("v1/memory/box/memory.usage_in_bytes", "536870912\n");
  // Of its 512 MiB in use, 256 MiB are page cache the kernel drops first.
  write("v1/memory/box/memory.stat", "cache 300000000\ninactive_file 1\ntotal_inactive_file 268435456\n");
  l = cgroupMemoryLimit(path("v1"), "5:cpu,cpuacct:/\n4:memory:/box\n0::/\n");
  EXPECT_EQ(l.available_bytes, 768ull << 20);
  // A container that shows its own cgroup as the mount's root: the path is not there, the root counts.
  l = cgroupMemoryLimit(path("v1"), "4:memory:/process_api/abc\n");
  EXPECT_EQ(l.available_bytes, 0u) << "the root has no limit";
  EXPECT_EQ(cgroupMemoryLimit(path("none"), "0::/\n").available_bytes, 0u);
}

// The buffers the froxel pass (sun shadow map over spheres and boxes) and kd_multiple (the forward
// light's moments under underwater.point_spread) allocate per setting are in the estimate.
TEST_F(FaultLimits, UnderwaterShadowMapAndForwardMomentsAreInTheBudget) {
  const Scene seabed = loadScene(std::string(SEASIM_SOURCE_DIR) + "/scenes/seabed.toml",
                                 {{"quality.shadow_map_size", "4096", {"t", 1}},
                                  {"underwater.model", "\"discrete_ordinates\"", {"t", 2}},
                                  {"underwater.point_spread", "true", {"t", 3}},
                                  {"camera.width", "100", {"t", 4}},
                                  {"camera.height", "50", {"t", 5}}});
  double shadow = 0, moments = 0;
  for (const BufferEstimate& b : estimateBuffers(seabed, makePlan(seabed))) {
    if (b.pass == "froxel" && b.what == "sun shadow map over the objects") shadow = b.bytes;
    if (b.pass == "kd_multiple" && b.what == "forward light moments (underwater.point_spread)") moments = b.bytes;
  }
  EXPECT_EQ(shadow, 4.0 * 4096 * 4096);  // one float per texel (froxel_pass.cpp)
  EXPECT_EQ(moments, 4.0 * 8 * 100 * 50);  // 2 x 3 channel moments + 2 per pixel (underwater_shading.cpp)
}

TEST_F(FaultLimits, ShardLocksOfDifferentLayoutsExcludeEachOther) {
  const std::string out = dir_.string();
  {
    ShardLock whole(out, 0, 1);
    const std::string msg = errorOf([&] { ShardLock shard(out, 0, 2); });
    EXPECT_NE(msg.find("cannot run shard 0/2: process " + std::to_string(::getpid())), std::string::npos) << msg;
    EXPECT_NE(msg.find("is running the whole job"), std::string::npos) << msg;
    EXPECT_FALSE(fs::exists(out + "/manifest-0of2.json.lock")) << "the refused run let go of its own lock";
  }
  {
    ShardLock s0(out, 0, 2);
    ShardLock s1(out, 1, 2);  // one layout: side by side
    std::string msg = errorOf([&] { ShardLock whole(out, 0, 1); });
    EXPECT_NE(msg.find("cannot run the whole job"), std::string::npos) << msg;
    EXPECT_NE(msg.find("is running shards of 2"), std::string::npos) << msg;
    msg = errorOf([&] { ShardLock other(out, 2, 3); });
    EXPECT_NE(msg.find("cannot run shard 2/3"), std::string::npos) << msg;
    EXPECT_FALSE(fs::exists(out + "/manifest.json.lock"));
  }
  // A lock of another layout nobody holds and that is not a lock: stale, taken over.
  write("manifest-1of4.json.lock", "");
  { ShardLock whole(out, 0, 1); }
  EXPECT_FALSE(fs::exists(out + "/manifest-1of4.json.lock"));
}

TEST_F(FaultLimits, LockFilesAreNeverEmptyAndAGarbageOneIsTakenOnlyWhenNobodyHoldsIt) {
  const std::string lock = path("manifest.json.lock");
  {
    ShardLock mine(lock);
    std::ifstream in(lock);
    const std::string text((std::istreambuf_iterator<char>(in)), {});
    EXPECT_NE(text.find("\"pid\":" + std::to_string(::getpid())), std::string::npos) << text;
    for (const auto& e : fs::directory_iterator(dir_))
      EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << "no temporary left: " << e.path();
  }
  write("manifest.json.lock", "garbage");
  { ShardLock taken(lock); }
  // Garbage that a live process holds (flock): not taken.
  write("manifest.json.lock", "");
  const int fd = ::open(lock.c_str(), O_RDONLY);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::flock(fd, LOCK_EX), 0);
  const std::string msg = errorOf([&] { ShardLock second(lock); });
  EXPECT_NE(msg.find("an unknown process (the lock file is empty or unreadable)"), std::string::npos) << msg;
  ::close(fd);
}

// A crash while a CrashHint is alive leaves its marker and still dies by the same signal.
TEST_F(FaultLimits, CrashInsideTheDriverLeavesTheMarkerAndDiesAsBefore) {
  const std::string marker = poclCrashMarker(dir_.string());
  const pid_t child = ::fork();
  if (child == 0) {
    const CrashHint hint("building kernels/test.cl", "a hint", marker);
    ::raise(SIGABRT);
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGABRT) << status;
  EXPECT_TRUE(fs::exists(marker));
}

TEST_F(FaultLimits, PoclCacheFilesCutShortAreFound) {
  // A real shared object of this system, whole and halved.
  std::string so;
  for (const char* candidate : {"/lib/x86_64-linux-gnu/libm.so.6", "/lib/aarch64-linux-gnu/libm.so.6", "/lib64/libm.so.6"})
    if (fs::exists(candidate)) so = candidate;
  if (so.empty()) GTEST_SKIP() << "no libm.so.6 to copy";
  fs::create_directories(dir_ / "AB" / "CDEF" / "kernel");
  const fs::path whole = dir_ / "AB" / "CDEF" / "kernel" / "whole.so";
  fs::copy_file(so, whole);
  EXPECT_EQ(poclCacheFileProblem(whole.string()), "");
  fs::copy_file(so, dir_ / "half.so");
  fs::resize_file(dir_ / "half.so", fs::file_size(so) / 2);
  EXPECT_EQ(poclCacheFileProblem(path("half.so")).rfind("truncated: ", 0), 0u) << poclCacheFileProblem(path("half.so"));
  write("text.so", "not elf");
  EXPECT_EQ(poclCacheFileProblem(path("text.so")), "not an ELF shared object");
  // Bitcode: magic, one block of 2 words that the file holds, then one it does not.
  const std::string block = std::string("BC\xC0\xDE", 4) + std::string("\x35\x14\x00\x00", 4) +
                            std::string("\x02\x00\x00\x00", 4) + std::string(8, '\0');
  write("ok.bc", block);
  EXPECT_EQ(poclCacheFileProblem(path("ok.bc")), "");
  write("cut.bc", block.substr(0, 16));
  EXPECT_EQ(poclCacheFileProblem(path("cut.bc")).rfind("truncated: block 13's bytes end at byte 20", 0), 0u)
      << poclCacheFileProblem(path("cut.bc"));
  fs::create_directories(dir_ / "program.bc");
  EXPECT_EQ(poclCacheFileProblem(path("program.bc")), "a folder where PoCL keeps a file");

  // The check removes the damaged file's whole program entry and leaves the rest.
  fs::copy_file(dir_ / "half.so", dir_ / "AB" / "CDEF" / "kernel" / "half.so");
  fs::create_directories(dir_ / "AB" / "GOOD");
  fs::copy_file(so, dir_ / "AB" / "GOOD" / "k.so");
  fs::remove(dir_ / "half.so");
  fs::remove(dir_ / "text.so");
  fs::remove(dir_ / "cut.bc");
  fs::remove(dir_ / "program.bc");
  const PoclCacheRepair repair = checkPoclCache(dir_.string());
  EXPECT_EQ(repair.bypass_reason, "");
  EXPECT_EQ(repair.removed, 1);
  EXPECT_FALSE(fs::exists(dir_ / "AB" / "CDEF"));
  EXPECT_TRUE(fs::exists(dir_ / "AB" / "GOOD" / "k.so"));

  // A build that crashed inside PoCL left its marker (device/crash_hint.h): the whole cache goes,
  // whole-looking entries too (a flipped byte passes the structural checks).
  write(".seasim-crashed", "");
  const PoclCacheRepair cleared = checkPoclCache(dir_.string());
  EXPECT_EQ(cleared.bypass_reason, "");
  EXPECT_EQ(cleared.removed, 2) << "AB and ok.bc";
  EXPECT_TRUE(fs::is_empty(dir_));
}

}  // namespace
}  // namespace seasim
