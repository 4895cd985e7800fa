// fault_matrix_test.cpp — the operator's fault matrix through the real `seasim` binary: damaged
// manifests (merge and --resume check the job's files on disk, not the manifest's list), runs of
// different shard layouts at once, empty or garbage locks, outputs the scene cannot give,
// TOML nested past any stack, damaged / read-only / folder-replaced kernel caches, the process's
// own memory limits, NaN input images, a full disk, unreadable folders and files, `validate` on
// scenes that cannot render, and sweeps too large to hold. docs/reliability.md lists each case
// with the message a user sees. Cases that need root (tmpfs mounts, switching to an unprivileged
// user for permission checks) say so when skipped; `make fresh-check` runs them as root.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <fcntl.h>
#include <sys/mount.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <thread>

#include "io/image_io.h"
#include "run_command.h"

namespace fs = std::filesystem;

namespace {

const std::string kBinary = SEASIM_BINARY;
const std::string kRepo = SEASIM_SOURCE_DIR;

using seasim_test::run;
using seasim_test::contains;
using seasim_test::readJson;

using seasim_test::Result;

void writeJson(const fs::path& p, const nlohmann::json& j) { std::ofstream(p) << j.dump(2); }

class FaultMatrix : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = seasim_test::freshTestDir("seasim_faults_"); }
  void TearDown() override {
    for (const auto& m : mounts_) ::umount2(m.c_str(), MNT_DETACH);
    std::error_code ec;
    for (const auto& e : fs::recursive_directory_iterator(dir_, fs::directory_options::skip_permission_denied, ec))
      fs::permissions(e.path(), fs::perms::owner_all, fs::perm_options::add, ec);
    fs::permissions(dir_, fs::perms::owner_all, fs::perm_options::add, ec);
    fs::remove_all(dir_, ec);
  }
  std::string write(const std::string& name, const std::string& text) {
    const fs::path p = dir_ / name;
    fs::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << text;
    return p.string();
  }
  // A [[render]] of the flat sea at 32x18.
  static std::string flatItem(const std::string& name, const std::string& extra = "") {
    return "[[render]]\nname = \"" + name + "\"\nscene = \"" + kRepo + "/scenes/flat_sea.toml\"\n" +
           "overrides = { \"camera.width\" = 32, \"camera.height\" = 18 }\n" + extra;
  }
  bool mountTmpfs(const std::string& where, const std::string& options, std::string& why) {
    fs::create_directories(where);
    if (::geteuid() != 0) {
      why = "needs root to mount a tmpfs";
      return false;
    }
    if (::mount("tmpfs", where.c_str(), "tmpfs", 0, options.c_str()) != 0) {
      why = std::string("mount failed: ") + std::strerror(errno);
      return false;
    }
    mounts_.push_back(where);
    return true;
  }
  // The prefix that runs seasim as an unprivileged user, so that file modes bind (root reads a
  // mode-000 folder). "" when this process is not root: then modes bind for it already.
  static std::string asUnprivileged() { return ::geteuid() == 0 ? "setpriv --reuid=65534 --regid=65534 --clear-groups " : ""; }
  fs::path dir_;
  std::vector<std::string> mounts_;
};

// ---------------------------------------------------------------------------------------------
// Output lost or wrong.

// A hand-edited manifest ("files": {} and the item's folder deleted; one output dropped from the
// list and truncated on disk) made merge report all items intact and --resume skip them.
TEST_F(FaultMatrix, MergeAndResumeCheckTheJobsFilesNotTheManifestsList) {
  const std::string job =
      write("job.toml", "[job]\nname = \"m\"\noutput_dir = \"out\"\n" + flatItem("a") + flatItem("b") + flatItem("c"));
  Result r = run("run " + job + " --device pocl");
  ASSERT_EQ(r.code, 0) << r.output;
  const fs::path out = dir_ / "out";
  ASSERT_EQ(run("farm merge " + job).code, 0);

  nlohmann::json m = readJson(out / "manifest.json");
  for (auto& item : m["items"]) {
    if (item["name"] == "a") item["files"] = nlohmann::json::object();
    if (item["name"] == "b") item["files"].erase("b/image.exr");
  }
  writeJson(out / "manifest.json", m);
  fs::remove_all(out / "a");
  fs::resize_file(out / "b" / "image.exr", fs::file_size(out / "b" / "image.exr") / 2);

  r = run("farm merge " + job);
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_TRUE(contains(r.output, "2 of 3 items are missing")) << r.output;
  EXPECT_TRUE(contains(r.output, "a (damaged: 'a/report.json', an output the job asks for, is not among the manifest's files)"))
      << r.output;
  EXPECT_TRUE(contains(r.output, "b (damaged: 'b/image.exr', an output the job asks for")) << r.output;
  EXPECT_FALSE(contains(r.output, "intact files")) << r.output;

  r = run("run " + job + " --resume --device pocl");
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "2 rendered, 1 finished earlier")) << r.output;
  EXPECT_TRUE(fs::exists(out / "a" / "image.exr"));
  r = run("farm merge " + job);
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "all 3 items present with intact files")) << r.output;
}

// A run without --shard and one with --shard 0/2 rendered the same items at once and left
// checksums that no longer matched; now the second to start is refused.
TEST_F(FaultMatrix, WholeJobAndShardRunsAtOnceTheSecondRefuses) {
  std::string items;
  for (int i = 0; i < 3; ++i)
    items += "[[render]]\nname = \"i" + std::to_string(i) + "\"\nscene = \"" + kRepo +
             "/scenes/flat_sea.toml\"\noverrides = { \"camera.width\" = 480, \"camera.height\" = 270, "
             "\"spectral.count\" = 64 }\n";
  const std::string job = write("job.toml", "[job]\nname = \"x\"\noutput_dir = \"out\"\n" + items);
  const pid_t pid = seasim_test::spawnRun(kBinary, job);
  ASSERT_GT(pid, 0);
  const fs::path lock = dir_ / "out" / "manifest.json.lock";
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (!fs::exists(lock) && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ASSERT_TRUE(fs::exists(lock)) << "the whole-job run took its lock";
  const Result shard = run("run " + job + " --shard 0/2 --device pocl");
  int status = 0;
  waitpid(pid, &status, 0);
  EXPECT_EQ(shard.code, 1) << shard.output;
  EXPECT_TRUE(contains(shard.output, "cannot run shard 0/2: process " + std::to_string(pid))) << shard.output;
  EXPECT_TRUE(contains(shard.output, "is running the whole job in this output folder")) << shard.output;
  EXPECT_FALSE(fs::exists(dir_ / "out" / "manifest-0of2.json")) << "the refused run wrote nothing";
  EXPECT_FALSE(fs::exists(dir_ / "out" / "manifest-0of2.json.lock")) << "and let go of its own lock";
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  const Result merge = run("farm merge " + job);
  EXPECT_EQ(merge.code, 0) << merge.output;
}

// SIGKILL in the middle of an item (after its first output, before report.json): the next run
// takes over the dead run's lock (nobody holds its flock, its PID is gone) and --resume renders the
// killed item and the rest, not the finished one; merge then finds every file.
TEST_F(FaultMatrix, KilledMidItemTheLockIsTakenOverAndResumeRedoesOnlyWhatIsUnfinished) {
  const std::string job =
      write("job.toml", "[job]\nname = \"k\"\noutput_dir = \"out\"\n" + flatItem("a") + flatItem("b") + flatItem("c"));
  const fs::path marker = dir_ / "killed";
  Result r = run("run " + job + " --device pocl", "SEASIM_TEST_KILL_MID_ITEM=b:" + marker.string() + " ");
  ASSERT_TRUE(fs::exists(marker)) << "the run was killed in item b: " << r.output;
  EXPECT_NE(r.code, 0);
  const fs::path out = dir_ / "out";
  ASSERT_TRUE(fs::exists(out / "manifest.json.lock")) << "the killed run's lock is left behind";
  EXPECT_TRUE(fs::exists(out / "b" / "image.exr"));
  EXPECT_FALSE(fs::exists(out / "b" / "report.json"));

  r = run("run " + job + " --resume --device pocl");
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "removing stale lock '" + (out / "manifest.json.lock").string() + "' (process"))
      << r.output;
  EXPECT_TRUE(contains(r.output, "2 rendered, 1 finished earlier")) << r.output;
  EXPECT_FALSE(fs::exists(out / "manifest.json.lock"));
  r = run("farm merge " + job);
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "all 3 items present with intact files")) << r.output;
}

// A lock left empty (created, then killed before it was written) or holding garbage blocked its
// shard until deleted by hand. Nobody holds it: it is taken over.
TEST_F(FaultMatrix, EmptyOrGarbageLockNobodyHoldsIsTakenOver) {
  const std::string job = write("job.toml", "[job]\nname = \"l\"\noutput_dir = \"out\"\n" + flatItem("a"));
  for (const std::string content : {std::string(""), std::string("\x01garbage{")}) {
    write("out/manifest.json.lock", content);
    const Result r = run("run " + job + " --device pocl");
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_TRUE(contains(r.output, "removing stale lock '" + (dir_ / "out" / "manifest.json.lock").string() +
                                       "' (empty or not a lock, and nobody holds it)"))
        << r.output;
    EXPECT_FALSE(fs::exists(dir_ / "out" / "manifest.json.lock"));
  }
}

// `--set spectral.spectral_exr=true --output exr,spectral_exr` on a scene without a spectral pass
// failed after image.exr was written, without report.json.
TEST_F(FaultMatrix, SpectralOutputTheSceneCannotGiveFailsBeforeAnyFile) {
  const fs::path out = dir_ / "o";
  Result r = run("render " + kRepo + "/scenes/spot_sphere.toml -o " + out.string() +
                 " --set camera.width=32 --set camera.height=18 --set spectral.spectral_exr=true"
                 " --output exr,spectral_exr --device pocl");
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_TRUE(contains(r.output, "output 'spectral_exr': scene 'spot_sphere' has no spectral image")) << r.output;
  EXPECT_FALSE(contains(r.output, "needs spectral.spectral_exr = true")) << "it is set: " << r.output;
  EXPECT_FALSE(fs::exists(out / "image.exr"));
  EXPECT_FALSE(fs::exists(out / "report.json"));
  // Not set: said so, also before anything is written.
  r = run("render " + kRepo + "/scenes/flat_sea.toml -o " + out.string() +
          " --set camera.width=32 --set camera.height=18 --output exr,spectral_exr --device pocl");
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_TRUE(contains(r.output, "needs spectral.spectral_exr = true")) << r.output;
  EXPECT_FALSE(fs::exists(out / "image.exr"));
}

// ---------------------------------------------------------------------------------------------
// Crashes.

// A dotted key of 40,000 parts crashed toml++ (SIGSEGV); 5,000 under `ulimit -s 1024`.
TEST_F(FaultMatrix, DeepTomlIsRefusedByALimitBeforeTheParserRecurses) {
  std::string dotted, header, nested;
  for (int i = 0; i < 40000; ++i) dotted += i ? ".a" : "a";
  const std::string k = write("k.toml", "# deep\n" + dotted + " = 1\n");
  const std::string h = write("h.toml", "[" + dotted + "]\n");
  nested = "v = " + std::string(100000, '[') + std::string(100000, ']') + "\n";
  const std::string n = write("n.toml", nested);
  const std::string j = write("j.toml", "[[render]]\nscene = \"" + kRepo + "/scenes/flat_sea.toml\"\n" + dotted + " = 1\n");
  for (const auto& [file, line] : {std::pair{k, 2}, std::pair{h, 1}, std::pair{n, 1}, std::pair{j, 3}}) {
    const Result r = seasim_test::runCommand("ulimit -s 1024; " + kBinary + " validate " + file);
    EXPECT_EQ(r.code, 1) << file << ": " << r.output.substr(0, 2000);
    EXPECT_TRUE(contains(r.output, file + ":" + std::to_string(line) + ": ")) << r.output.substr(0, 2000);
    EXPECT_TRUE(contains(r.output, "refused before parsing")) << r.output.substr(0, 2000);
  }
  // --set: a key of 5,000 parts, and a value nested 100,000 deep.
  std::string key;
  for (int i = 0; i < 5000; ++i) key += i ? ".a" : "a";
  Result r = seasim_test::runCommand("ulimit -s 1024; " + kBinary + " plan " + kRepo + "/scenes/flat_sea.toml --set " +
                                     key + "=1");
  EXPECT_EQ(r.code, 1) << r.output.substr(0, 2000);
  EXPECT_TRUE(contains(r.output, "more than 64 parts")) << r.output.substr(0, 2000);
  r = seasim_test::runCommand("ulimit -s 1024; " + kBinary + " plan " + kRepo + "/scenes/flat_sea.toml --set 'sun.zenith_deg=" +
                              std::string(100000, '[') + "'");
  EXPECT_EQ(r.code, 1) << r.output.substr(0, 2000);
  EXPECT_TRUE(contains(r.output, "nested more than 64 deep")) << r.output.substr(0, 2000);
}

// Every cached PoCL .so and .bc cut in half: renders died by SIGABRT/SIGBUS, every time after.
TEST_F(FaultMatrix, DamagedPoclCacheIsFoundRemovedAndTheRenderGoesOn) {
  const std::string pocl = (dir_ / "pocl").string(), cache = (dir_ / "cache").string();
  const std::string env = "POCL_CACHE_DIR=" + pocl + " SEASIM_CACHE_DIR=" + cache + " ";
  const std::string render = "render " + kRepo + "/scenes/flat_sea.toml --set camera.width=32 --set camera.height=16 "
                             "--device pocl -o ";
  Result r = run(render + (dir_ / "a").string(), env);
  ASSERT_EQ(r.code, 0) << r.output;
  int damaged = 0;
  for (const auto& e : fs::recursive_directory_iterator(pocl))
    if (e.is_regular_file() && (e.path().extension() == ".so" || e.path().extension() == ".bc")) {
      fs::resize_file(e.path(), fs::file_size(e.path()) / 2);
      ++damaged;
    }
  ASSERT_GT(damaged, 0);
  for (int run_index = 0; run_index < 2; ++run_index) {  // with seasim's cache, then without
    r = run(render + (dir_ / ("b" + std::to_string(run_index))).string(), env);
    EXPECT_EQ(r.code, 0) << r.output;
    if (run_index == 0) {
      EXPECT_TRUE(contains(r.output, "seasim: warning: PoCL's cache entry '" + pocl)) << r.output;
      EXPECT_TRUE(contains(r.output, "truncated")) << r.output;
    } else {
      EXPECT_FALSE(contains(r.output, "damaged")) << "repaired for good: " << r.output;
    }
    EXPECT_TRUE(fs::exists(dir_ / ("b" + std::to_string(run_index)) / "image.png"));
    fs::remove_all(cache);
  }
}

// A read-only PoCL cache was blamed on a damaged cache (or PoCL offered no device at all).
TEST_F(FaultMatrix, ReadOnlyPoclCacheGetsItsOwnMessageAndTheRenderGoesOn) {
  const std::string ro = (dir_ / "ro").string();
  std::string why;
  if (!mountTmpfs(ro, "size=64k,ro", why)) GTEST_SKIP() << "read-only PoCL cache (a read-only tmpfs) skipped: " << why;
  const std::string pocl = ro + "/pocl";
  const Result r = run("render " + kRepo + "/scenes/flat_sea.toml --set camera.width=32 --set camera.height=16 -o " +
                           (dir_ / "o").string() + " --device pocl",
                       "POCL_CACHE_DIR=" + pocl + " ");
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "PoCL's cache folder '" + pocl + "' is read-only (it cannot be created: Read-only file system)"))
      << r.output;
  EXPECT_TRUE(contains(r.output, "PoCL builds this run's kernels in the private folder")) << r.output;
  EXPECT_FALSE(contains(r.output, "damaged")) << r.output;
  EXPECT_TRUE(fs::exists(dir_ / "o" / "image.png"));
}

// Seasim's own cache entries replaced by folders (and a PoCL program entry replaced by a folder).
TEST_F(FaultMatrix, KernelCacheEntriesReplacedByFoldersAreRebuilt) {
  const std::string pocl = (dir_ / "pocl").string(), cache = (dir_ / "cache").string();
  const std::string env = "POCL_CACHE_DIR=" + pocl + " SEASIM_CACHE_DIR=" + cache + " ";
  const std::string render = "render " + kRepo + "/scenes/flat_sea.toml --set camera.width=32 --set camera.height=16 "
                             "--device pocl -o ";
  ASSERT_EQ(run(render + (dir_ / "a").string(), env).code, 0);
  int replaced = 0;
  for (const auto& e : fs::directory_iterator(cache))
    if (e.path().extension() == ".bin") {
      fs::remove(e.path());
      fs::create_directories(e.path() / "inside");
      ++replaced;
    }
  ASSERT_GT(replaced, 0);
  std::vector<fs::path> so;
  for (const auto& e : fs::recursive_directory_iterator(pocl))
    if (e.is_regular_file() && e.path().extension() == ".so") so.push_back(e.path());
  ASSERT_FALSE(so.empty());
  fs::remove(so[0]);
  fs::create_directories(so[0] / "inside");
  const Result r = run(render + (dir_ / "b").string(), env);
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "is unusable: it is a folder, not a cache file; rebuilding it")) << r.output;
  EXPECT_TRUE(contains(r.output, "a folder where PoCL keeps a file")) << r.output;
  EXPECT_TRUE(fs::exists(dir_ / "b" / "image.png"));
  for (const auto& e : fs::directory_iterator(cache))
    if (e.path().extension() == ".bin") EXPECT_TRUE(fs::is_regular_file(e.path())) << e.path();
}

// Under `ulimit -v 4 GiB` a 16384² render passed the device check and aborted inside PoCL (or threw
// std::bad_alloc after 100 s); the process's own limit is now in the budget.
TEST_F(FaultMatrix, AddressSpaceLimitIsInTheMemoryBudget) {
  for (const char* scene : {"seabed.toml", "spot_sphere.toml"}) {
    const auto t0 = std::chrono::steady_clock::now();
    const Result r = seasim_test::runCommand("ulimit -v 4194304; " + kBinary + " render " + kRepo + "/scenes/" + scene +
                                             " --set camera.width=16384 --set camera.height=16384 --device pocl -o " +
                                             (dir_ / "o").string());
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_EQ(r.code, 1) << scene << ": " << r.output;
    EXPECT_TRUE(contains(r.output, "not enough device memory")) << r.output;
    EXPECT_TRUE(contains(r.output, "the process's address-space limit (RLIMIT_AS, ulimit -v) of 4096 MiB")) << r.output;
    EXPECT_TRUE(contains(r.output, "camera.width = 16384")) << r.output;
    EXPECT_TRUE(contains(r.output, "nothing was allocated")) << r.output;
    EXPECT_FALSE(contains(r.output, "bad_alloc")) << r.output;
    EXPECT_LT(s, 60.0) << "refused before rendering";
    EXPECT_FALSE(fs::exists(dir_ / "o" / "image.exr"));
  }
}

// ---------------------------------------------------------------------------------------------
// Messages.

// The froxel pass's sun shadow map was not in the budget: raw CL_INVALID_BUFFER_SIZE.
TEST_F(FaultMatrix, UnderwaterShadowMapIsInTheBudget) {
  const Result r = run("render " + kRepo + "/scenes/seabed.toml --set camera.width=64 --set camera.height=36 "
                       "--set quality.shadow_map_size=65536 --device pocl -o " + (dir_ / "o").string(),
                       "SEASIM_DEVICE_MEMORY_MB=4096 ");
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_TRUE(contains(r.output, "sun shadow map over the objects")) << r.output;
  EXPECT_TRUE(contains(r.output, "quality.shadow_map_size = 65536")) << r.output;
  EXPECT_TRUE(contains(r.output, "to fit, at most quality.shadow_map_size = ")) << r.output;
  EXPECT_FALSE(contains(r.output, "CL_INVALID_BUFFER_SIZE")) << r.output;
}

// A light map holding NaN gave "the kernels produced 156 NaN/Inf values", naming no file.
TEST_F(FaultMatrix, NanInAnInputImageIsNamedAtItsKey) {
  seasim::Image img;
  img.resize(8, 8, 3);
  img.at(3, 2, 1) = std::numeric_limits<float>::quiet_NaN();
  img.at(5, 5, 0) = std::numeric_limits<float>::infinity();
  const std::string map = (dir_ / "nan_map.exr").string();
  seasim::writeExr(map, img);
  std::ifstream in(kRepo + "/scenes/spot_sphere.toml");
  std::string scene((std::istreambuf_iterator<char>(in)), {});
  const size_t at = scene.find("intensity = 60.0");
  ASSERT_NE(at, std::string::npos);
  scene.insert(at, "light_map = \"" + map + "\"\n");
  const std::string file = write("s.toml", scene);
  const int line = static_cast<int>(std::count(scene.begin(), scene.begin() + static_cast<long>(at), '\n')) + 1;
  const std::string expected = file + ":" + std::to_string(line) + ": key 'spotlights[0].light_map': the image '" +
                               map + "' holds 2 NaN/Inf values (the first at pixel x = 3, y = 2, channel 1)";
  Result r = run("validate " + file);
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_TRUE(contains(r.output, expected)) << r.output;
  r = run("render " + file + " --set camera.width=32 --set camera.height=18 --device pocl -o " + (dir_ / "o").string());
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_TRUE(contains(r.output, expected)) << r.output;
  EXPECT_FALSE(fs::exists(dir_ / "o" / "image.exr"));
}

// An EXR on a full disk said "File output failed" without the reason.
TEST_F(FaultMatrix, ExrOnAFullDiskSaysNoSpaceLeftOnDevice) {
  const std::string full = (dir_ / "full").string();
  std::string why;
  if (!mountTmpfs(full, "size=64k", why)) GTEST_SKIP() << "full-disk EXR (a 64 KiB tmpfs) skipped: " << why;
  fs::create_directories(full + "/o");
  {  // filled to the last byte by unbuffered writes (a stream's buffer can leave room behind)
    const int fd = ::open((full + "/filler").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ASSERT_GE(fd, 0);
    const std::string block(4096, 'x');
    while (::write(fd, block.data(), block.size()) > 0) {
    }
    ::close(fd);
  }
  const Result r = run("render " + kRepo + "/scenes/flat_sea.toml --set camera.width=64 --set camera.height=36 "
                       "--output exr --device pocl -o " + full + "/o");
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_TRUE(contains(r.output, "No space left on device")) << r.output;
  EXPECT_TRUE(contains(r.output, full + "/o/image.exr")) << r.output;
  EXPECT_FALSE(fs::exists(full + "/o/image.exr"));
  for (const auto& e : fs::directory_iterator(full + "/o")) ADD_FAILURE() << "left behind: " << e.path();
}

// Mode-000 folders: the data folder gave a raw "filesystem error", a scene folder "File does not
// exist". Both now name the path and the system's reason.
TEST_F(FaultMatrix, UnreadableDataAndSceneFoldersSayPermissionDeniedWithThePath) {
  if (::geteuid() == 0 && seasim_test::runCommand("setpriv --reuid=65534 --regid=65534 --clear-groups true").code != 0)
    GTEST_SKIP() << "needs setpriv to drop root (root reads mode-000 folders)";
  fs::permissions(dir_, fs::perms::all, fs::perm_options::add);  // the unprivileged user reaches inside
  const fs::path data = dir_ / "data";
  fs::copy(kRepo + "/data", data, fs::copy_options::recursive);
  fs::permissions(data, fs::perms::none);
  const fs::path scenes = dir_ / "scenes";
  fs::create_directories(scenes);
  fs::copy_file(kRepo + "/scenes/flat_sea.toml", scenes / "flat_sea.toml");
  fs::permissions(scenes, fs::perms::none);
  const std::string user = asUnprivileged();
  Result r = seasim_test::runCommand("SEASIM_DATA_DIR=" + data.string() + " " + user + kBinary + " validate " + kRepo +
                                     "/scenes/flat_sea.toml");
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_TRUE(contains(r.output, "cannot read the data folder '" + data.string() + "' (SEASIM_DATA_DIR): Permission denied"))
      << r.output;
  EXPECT_FALSE(contains(r.output, "filesystem error")) << r.output;
  r = seasim_test::runCommand(user + kBinary + " validate " + (scenes / "flat_sea.toml").string());
  EXPECT_NE(r.code, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "cannot use the path '" + (scenes / "flat_sea.toml").string() + "': Permission denied"))
      << r.output;
  EXPECT_FALSE(contains(r.output, "File does not exist")) << r.output;
}

// `validate` said "ok" for an empty scene and for an unreadable sensor CSV; render then failed.
TEST_F(FaultMatrix, ValidateRefusesAnEmptySceneAndAnUnreadableSensorCsv) {
  const std::string empty = write("empty.toml", "");
  Result r = run("validate " + empty);
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_TRUE(contains(r.output, empty + ":1: the scene renders nothing")) << r.output;

  const fs::path cams = dir_ / "cams";
  fs::create_directories(cams);
  write("cams/broken.csv", "nm,r,g,b\n400,not,a,number\n");
  const std::string scene = write("s.toml", "[camera]\nwidth = 32\nheight = 18\n[water]\njerlov = \"IB\"\n"
                                            "[spectral]\ncamera_dir = \"cams\"\nsensor = \"broken\"\n");
  r = run("validate " + scene);
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_TRUE(contains(r.output, scene + ":8: key 'spectral.sensor': ")) << r.output;
  EXPECT_TRUE(contains(r.output, "broken.csv:2: column 'r': 'not' is not a finite number")) << r.output;
  // A well-formed CSV that cannot be read (mode 000, as an unprivileged user).
  write("cams/broken.csv", "nm,r,g,b\n400,1,1,1\n700,1,1,1\n");
  fs::permissions(cams / "broken.csv", fs::perms::none);
  if (::geteuid() == 0 && seasim_test::runCommand("setpriv --reuid=65534 --regid=65534 --clear-groups true").code != 0)
    GTEST_SKIP() << "the mode-000 CSV needs setpriv to drop root";
  r = seasim_test::runCommand(asUnprivileged() + kBinary + " validate " + scene);
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_TRUE(contains(r.output, scene + ":8: key 'spectral.sensor': " + (cams / "broken.csv").string() +
                                     ": cannot open for reading: Permission denied"))
      << r.output;
}

// A sweep of 10^6 values made `validate` take 3.1 GB and 16 s; it is refused before it is expanded.
TEST_F(FaultMatrix, HugeSweepIsRefusedBeforeItIsExpanded) {
  std::string values;
  values.reserve(9000000);
  for (int i = 0; i < 1000000; ++i) values += (i ? ", " : "") + std::to_string(i % 90) + ".5";
  const std::string job = write("job.toml", "[[sweep]]\nscene = \"" + kRepo +
                                                "/scenes/flat_sea.toml\"\nparam = \"sun.zenith_deg\"\nvalues = [" +
                                                values + "]\n");
  const auto t0 = std::chrono::steady_clock::now();
  const Result r = run("validate " + job);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  rusage usage{};
  ::getrusage(RUSAGE_CHILDREN, &usage);
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_TRUE(contains(r.output, job + ":4: key 'sweep[0].values': 1000000 items (0 before it) are more than a job "
                                       "may hold (100000)"))
      << r.output;
  // Most of the time is toml++ reading the 8 MB array (5.7 s on the shared 2-core VM, was 16 s).
  EXPECT_LT(s, 30.0);
  EXPECT_LT(usage.ru_maxrss, 1024L * 1024L) << "KiB of the largest child: under 1 GiB (was 3.1 GB)";
  std::printf("validate of a 10^6-value sweep: %.2f s, max RSS %ld MiB\n", s, usage.ru_maxrss / 1024);
}

}  // namespace
