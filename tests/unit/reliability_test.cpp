// reliability_test.cpp — the faults that need no device: full disks for every writer
// (a real tmpfs, root only), decompression-bomb images, damaged kernel cache entries, manifests of
// the wrong shape, the shard lock, orphan temporary files, memory budgets and count limits, and
// the input messages (huge override index, float overflow, NUL bytes, bad output folders,
// reserved item names).
#include <gtest/gtest.h>
#include <sys/mount.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <functional>
#include <set>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "device/kernel_cache.h"
#include "io/atomic_file.h"
#include "io/image_io.h"
#include "io/npy.h"
#include "jobs/farm_items.h"
#include "jobs/job.h"
#include "jobs/manifest.h"
#include "jobs/shard_lock.h"
#include "plan/memory_budget.h"
#include "plan/plan.h"
#include "scene/scene_inputs.h"
#include "scene/scene_parser.h"
#include "util/error.h"
#include "util/hash.h"

namespace seasim {
namespace {

namespace fs = std::filesystem;

class Reliability : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("seasim_rel_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    if (mounted_) ::umount2(mounted_dir_.c_str(), MNT_DETACH);
    fs::remove_all(dir_);
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string write(const std::string& name, const std::string& bytes) const {
    std::ofstream(dir_ / name, std::ios::binary) << bytes;
    return path(name);
  }
  // A 64 KiB tmpfs at <dir>/full, filled to the last byte; false when that is not possible here.
  bool mountFullTmpfs(std::string& why) {
    mounted_dir_ = path("full");
    fs::create_directories(mounted_dir_);
    if (::geteuid() != 0) {
      why = "needs root to mount a tmpfs";
      return false;
    }
    if (::mount("tmpfs", mounted_dir_.c_str(), "tmpfs", 0, "size=64k") != 0) {
      why = std::string("mount of a tmpfs failed: ") + std::strerror(errno);
      return false;
    }
    mounted_ = true;
    std::ofstream fill(mounted_dir_ + "/filler", std::ios::binary);
    const std::string block(4096, 'x');
    for (int i = 0; i < 64 && fill; ++i) fill.write(block.data(), block.size());
    fill.close();
    return true;
  }
  // Every file under `d`, recursively.
  static std::vector<std::string> files(const std::string& d) {
    std::vector<std::string> out;
    for (const auto& e : fs::recursive_directory_iterator(d))
      if (e.is_regular_file()) out.push_back(e.path().filename().string());
    return out;
  }
  fs::path dir_;
  std::string mounted_dir_;
  bool mounted_ = false;
};

Image testImage(int w, int h) {
  Image img;
  img.resize(w, h, 3);
  for (size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = static_cast<float>((i * 7919) % 1000) / 1000.0f;
  return img;
}

template <class F>
std::string errorOf(F&& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

// ---------------------------------------------------------------------------------------------
// Full disk: every writer fails naming the file, leaves no temporary file and no partial result.

TEST_F(Reliability, EveryWriterReportsAFullDiskNamingTheFileAndLeavesNothing) {
  std::string why;
  if (!mountFullTmpfs(why)) GTEST_SKIP() << "full-disk test skipped: " << why;
  const Image img = testImage(256, 256);  // far more than the few bytes left
  struct Case {
    const char* file;
    std::function<void(const std::string&)> write;
  };
  const std::vector<Case> cases = {
      {"image.png", [&](const std::string& p) { writePng(p, img, 0.0); }},
      {"image.exr", [&](const std::string& p) { writeExr(p, img); }},
      {"image.npy", [&](const std::string& p) { writeNpy(p, img); }},
      {"report.json", [&](const std::string& p) { writeTextAtomic(p, std::string(200000, 'j')); }},
  };
  for (const Case& c : cases) {
    const std::string target = mounted_dir_ + "/" + c.file;
    const std::string msg = errorOf([&] { c.write(target); });
    EXPECT_NE(msg.find(target), std::string::npos) << c.file << ": the error must name the file: " << msg;
    EXPECT_FALSE(fs::exists(target)) << c.file << ": no partial file under the final name";
    EXPECT_EQ(files(mounted_dir_), std::vector<std::string>{"filler"}) << c.file << ": temporary file left";
  }
  // The PNG error says why (the system's reason, not a report.json failure later).
  const std::string msg = errorOf([&] { writePng(mounted_dir_ + "/image.png", img, 0.0); });
  EXPECT_NE(msg.find("No space left on device"), std::string::npos) << msg;
}

// ---------------------------------------------------------------------------------------------
// Decompression bombs: a tiny file whose header claims 60000 x 60000 is refused before decoding.

uint32_t crc32(const std::string& bytes) {
  uint32_t c = 0xffffffffu;
  for (unsigned char b : bytes) {
    c ^= b;
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
  }
  return c ^ 0xffffffffu;
}

std::string be32(uint32_t v) {
  return {static_cast<char>(v >> 24), static_cast<char>(v >> 16), static_cast<char>(v >> 8), static_cast<char>(v)};
}

std::string chunk(const std::string& type, const std::string& data) {
  return be32(static_cast<uint32_t>(data.size())) + type + data + be32(crc32(type + data));
}

// A valid PNG signature and IHDR for width x height RGB 8-bit, a small IDAT of zeros, IEND.
std::string bombPng(uint32_t width, uint32_t height) {
  std::string ihdr = be32(width) + be32(height) + std::string("\x08\x02\x00\x00\x00", 5);
  // zlib stream of a few stored zero bytes: enough for a decoder to start, nowhere near the size.
  std::string idat("\x78\x01\x01\x10\x00\xef\xff", 7);
  idat += std::string(16, '\0');
  idat += std::string("\x00\x00\x00\x01", 4);
  return std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", ihdr) + chunk("IDAT", idat) + chunk("IEND", "");
}

TEST_F(Reliability, DecompressionBombPngIsRefusedFromItsHeader) {
  const std::string bomb = write("bomb.png", bombPng(60000, 60000));
  ASSERT_LT(fs::file_size(bomb), 1000u);
  for (auto read : {+[](const std::string& p) { (void)readImageHeader(p); },
                    +[](const std::string& p) { (void)readImage(p); }}) {
    const std::string msg = errorOf([&] { read(bomb); });
    EXPECT_NE(msg.find("60000x60000"), std::string::npos) << msg;
    EXPECT_NE(msg.find("limit"), std::string::npos) << msg;
    EXPECT_NE(msg.find(bomb), std::string::npos) << msg;
  }
  // A small image in the same form is fine (the check is the size, not the format).
  writePng(path("small.png"), testImage(8, 4), 0.0);
  const ImageHeader h = readImageHeader(path("small.png"));
  EXPECT_EQ(h.width, 8);
  EXPECT_EQ(h.height, 4);
}

TEST_F(Reliability, BombUsedAsSkyHeightFieldOrLightMapFailsAtItsKey) {
  write("bomb.png", bombPng(60000, 60000));
  struct Case {
    std::string toml, key;
    int line;
  };
  const std::vector<Case> cases = {
      {"[sky]\nmodel = \"image\"\nimage = \"bomb.png\"\n", "sky.image", 3},
      {"[water]\njerlov = \"IB\"\n[bottom]\ntype = \"heightfield\"\nheightfield = \"bomb.png\"\n", "bottom.heightfield", 5},
      {"[air]\ndensity = 0.04\n[[spotlights]]\nposition = [0, 5, 0]\nlight_map = \"bomb.png\"\n",
       "spotlights[0].light_map", 5},
  };
  for (const Case& c : cases) {
    const Scene scene = parseScene(c.toml, path("s.toml"));
    const std::string msg = errorOf([&] { checkSceneInputs(scene); });
    const std::string where = path("s.toml") + ":" + std::to_string(c.line) + ": key '" + c.key + "'";
    EXPECT_NE(msg.find(where), std::string::npos) << msg;
    EXPECT_NE(msg.find("60000x60000"), std::string::npos) << msg;
  }
  // Not an image at all: the same key, a clear reason.
  write("text.png", "this is not a png");
  const Scene scene = parseScene("[sky]\nmodel = \"image\"\nimage = \"text.png\"\n", path("s.toml"));
  const std::string msg = errorOf([&] { checkSceneInputs(scene); });
  EXPECT_NE(msg.find("key 'sky.image'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("not an image"), std::string::npos) << msg;
}

TEST_F(Reliability, NpyHeaderClaimingMoreThanTheFileHoldsIsRefused) {
  writeNpy(path("ok.npy"), testImage(4, 4));
  std::string bytes;
  {
    std::ifstream in(path("ok.npy"), std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  const size_t shape = bytes.find("(4, 4, 3)");
  ASSERT_NE(shape, std::string::npos);
  std::string big = bytes;
  big.replace(shape, 9, "(9, 9, 3)");  // same length: the header stays well-formed
  write("big.npy", big);
  std::string msg = errorOf([&] { (void)readImage(path("big.npy")); });
  EXPECT_NE(msg.find("file holds"), std::string::npos) << msg;
  std::string bomb = bytes;
  bomb.replace(shape, 9, "(60000, 60000, 3)");
  write("bomb.npy", bomb);
  msg = errorOf([&] { (void)readImage(path("bomb.npy")); });
  EXPECT_NE(msg.find("limit"), std::string::npos) << msg;
}

// ---------------------------------------------------------------------------------------------
// Kernel cache entries: any damage is detected before the driver sees the bytes.

TEST_F(Reliability, KernelCacheEntryDetectsTruncationCorruptionAndSwaps) {
  const std::vector<unsigned char> payload(5000, 0xab);
  const uint64_t key_a = 0x1111, key_b = 0x2222;
  const std::string a = kernelCachePath(dir_.string(), key_a), b = kernelCachePath(dir_.string(), key_b);
  writeKernelCacheEntry(a, key_a, "pocl|cpu|6.0", payload);
  std::vector<unsigned char> got;
  std::string why;
  ASSERT_TRUE(readKernelCacheEntry(a, key_a, "pocl|cpu|6.0", got, why)) << why;
  EXPECT_EQ(got, payload);
  EXPECT_EQ(verifyKernelCacheEntry(a), "");

  // Another device or driver version: not used.
  EXPECT_FALSE(readKernelCacheEntry(a, key_a, "pocl|cpu|7.0", got, why));
  EXPECT_NE(why.find("built for"), std::string::npos) << why;

  // Copied over another entry's name.
  fs::copy_file(a, b);
  EXPECT_FALSE(readKernelCacheEntry(b, key_b, "pocl|cpu|6.0", got, why));
  EXPECT_NE(why.find("copied over another"), std::string::npos) << why;
  EXPECT_NE(verifyKernelCacheEntry(b), "");

  // Cut in half.
  fs::resize_file(a, fs::file_size(a) / 2);
  EXPECT_FALSE(readKernelCacheEntry(a, key_a, "pocl|cpu|6.0", got, why));
  EXPECT_NE(why.find("truncated"), std::string::npos) << why;
  EXPECT_NE(verifyKernelCacheEntry(a), "");

  // One flipped byte in the payload.
  writeKernelCacheEntry(a, key_a, "pocl|cpu|6.0", payload);
  {
    std::fstream f(a, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(-10, std::ios::end);
    f.put('\x00');
  }
  EXPECT_FALSE(readKernelCacheEntry(a, key_a, "pocl|cpu|6.0", got, why));
  EXPECT_NE(why.find("checksum"), std::string::npos) << why;

  // A raw binary from an older seasim (no header).
  write("3333333333333333.bin", std::string(100, 'z'));
  EXPECT_NE(verifyKernelCacheEntry(path("3333333333333333.bin")).find("not a seasim kernel cache entry"),
            std::string::npos);
  // No temporary files left by the atomic writes.
  for (const auto& f : files(dir_.string())) EXPECT_EQ(f.find(".tmp-"), std::string::npos) << f;
}

// ---------------------------------------------------------------------------------------------
// Manifests, locks and orphan temporary files.

TEST_F(Reliability, ManifestOfTheWrongShapeIsAClearError) {
  for (const std::string& text : {std::string("[1, 2, 3]"), std::string("{\"items\": 5}"),
                                  std::string("{\"items\": [{\"name\": 3}]}"),
                                  std::string("{\"items\": [{\"name\": \"a\", \"files\": {\"x\": 1}}]}"),
                                  std::string("not json at all")}) {
    const std::string p = write("manifest.json", text);
    const std::string msg = errorOf([&] { (void)Manifest::load(p, "job.toml"); });
    EXPECT_NE(msg.find(p), std::string::npos) << text << " -> " << msg;
    EXPECT_NE(msg.find("is not a seasim job manifest"), std::string::npos) << text << " -> " << msg;
    EXPECT_NE(msg.find("delete it"), std::string::npos) << msg;
    EXPECT_NE(errorOf([&] { (void)finishedItems(Job{}, dir_.string()); }), "") << text;
  }
}

// A job of two items whose only output is report.json (outputs = {}), for the manifest tests.
Job reportOnlyJob(const std::vector<std::string>& names) {
  Job job;
  for (const std::string& name : names) job.items.push_back(RenderItem{name, "", {}, {}, "", {}, "", {}});
  return job;
}

TEST_F(Reliability, ManifestRecordsFailedItemsAndResumeSkipsOnlyDoneOnes) {
  fs::create_directories(dir_ / "good");
  fs::create_directories(dir_ / "bad");
  write("good/report.json", "{}");
  write("bad/report.json", "{}");
  const Job job = reportOnlyJob({"good", "bad"});
  Manifest m("job.toml");
  m.recordDone("good", {{"good/report.json", fileChecksum(path("good/report.json"))}}, 1.5);
  m.recordFailed("bad", "scene.toml:3: key 'x': broken");
  m.save(path("manifest.json"));
  const Manifest back = Manifest::load(path("manifest.json"), "job.toml");
  ASSERT_EQ(back.entries().size(), 2u);
  EXPECT_FALSE(back.entries()[1].done);
  EXPECT_EQ(back.entries()[1].error, "scene.toml:3: key 'x': broken");
  EXPECT_EQ(finishedItems(job, dir_.string()), std::set<std::string>{"good"});
  // Recording the item again replaces its entry.
  m.recordDone("bad", {{"bad/report.json", fileChecksum(path("bad/report.json"))}}, 2.0);
  m.save(path("manifest.json"));
  EXPECT_EQ(finishedItems(job, dir_.string()), (std::set<std::string>{"bad", "good"}));
}

// The manifest's own list is not trusted: an item whose list leaves out a file the job expects
// (edited to {} by hand, or one output dropped) is not finished, whatever the listed checksums say.
TEST_F(Reliability, FinishedItemsNeedEveryFileTheJobExpectsNotJustTheManifestsList) {
  fs::create_directories(dir_ / "a");
  write("a/report.json", "{}");
  write("a/image.png", "png");
  Job job = reportOnlyJob({"a"});
  job.items[0].outputs = {"exr", "png"};
  Manifest m("job.toml");
  m.recordDone("a", nlohmann::json::object(), 1.0);
  m.save(path("manifest.json"));
  EXPECT_TRUE(finishedItems(job, dir_.string()).empty()) << "an empty list of files";
  m.recordDone("a", {{"a/report.json", fileChecksum(path("a/report.json"))},
                     {"a/image.png", fileChecksum(path("a/image.png"))}}, 1.0);
  m.save(path("manifest.json"));
  EXPECT_TRUE(finishedItems(job, dir_.string()).empty()) << "image.exr left out of the list";
  const std::vector<ItemState> states = readItemStates(job, dir_.string(), true);
  ASSERT_EQ(states.size(), 1u);
  EXPECT_EQ(states[0].status, ItemState::Status::Damaged);
  EXPECT_NE(states[0].detail.find("'a/image.exr', an output the job asks for, is not among the manifest's files"),
            std::string::npos) << states[0].detail;
  write("a/image.exr", "exr");
  m.recordDone("a", {{"a/report.json", fileChecksum(path("a/report.json"))},
                     {"a/image.png", fileChecksum(path("a/image.png"))},
                     {"a/image.exr", fileChecksum(path("a/image.exr"))}}, 1.0);
  m.save(path("manifest.json"));
  EXPECT_EQ(finishedItems(job, dir_.string()), std::set<std::string>{"a"});
  write("a/image.exr", "ex");  // truncated on disk
  EXPECT_TRUE(finishedItems(job, dir_.string()).empty()) << "a listed file that no longer matches";
}

TEST_F(Reliability, ShardLockRefusesASecondRunAndTakesOverStaleLocks) {
  const std::string lock_path = path("manifest.json.lock");
  {
    ShardLock first(lock_path);
    const std::string msg = errorOf([&] { ShardLock second(lock_path); });
    EXPECT_NE(msg.find("already being run by process " + std::to_string(::getpid())), std::string::npos) << msg;
    EXPECT_NE(msg.find(lock_path), std::string::npos) << msg;
  }
  EXPECT_FALSE(fs::exists(lock_path)) << "the lock is removed when its run ends";

  // A lock left by a process of this host that no longer runs: stale, taken over.
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ::waitpid(child, nullptr, 0);
  char host[256] = {};
  ::gethostname(host, sizeof host - 1);
  write("manifest.json.lock", "{\"host\": \"" + std::string(host) + "\", \"pid\": " + std::to_string(child) +
                                  ", \"started\": \"2026-01-01T00:00:00Z\"}");
  { ShardLock taken(lock_path); }

  // A lock from another host is never taken over: that run may be alive.
  write("manifest.json.lock", "{\"host\": \"other-node-17\", \"pid\": 1, \"started\": \"2026-01-01T00:00:00Z\"}");
  const std::string msg = errorOf([&] { ShardLock other(lock_path); });
  EXPECT_NE(msg.find("other-node-17"), std::string::npos) << msg;
  EXPECT_NE(msg.find("delete the lock file"), std::string::npos) << msg;
}

TEST_F(Reliability, OrphanTemporaryFilesAreFoundAndRemoved) {
  write(".image.exr.tmp-12345", "partial");
  write(".report.json.tmp-999", "partial");
  write(".manifest.json.tmp-77", "partial");
  write(".manifest-1of2.json.tmp-78", "another shard's");
  write("image.exr", "finished");
  write(".hidden", "not a temp");
  EXPECT_EQ(removeTempFilesFor(path("manifest.json")), 1);
  EXPECT_TRUE(fs::exists(path(".manifest-1of2.json.tmp-78")));
  EXPECT_EQ(removeTempFiles(dir_.string()), 3);
  EXPECT_TRUE(fs::exists(path("image.exr")));
  EXPECT_TRUE(fs::exists(path(".hidden")));
}

// ---------------------------------------------------------------------------------------------
// Memory budgets and counts.

TEST_F(Reliability, MemoryBudgetNamesTheSettingsAndWhatFits) {
  const Scene seabed =
      loadScene(std::string(SEASIM_SOURCE_DIR) + "/scenes/seabed.toml",
                {{"camera.width", "16384", {"t", 1}}, {"camera.height", "16384", {"t", 1}},
                 {"underwater.model", "\"thesis\"", {"t", 1}}});  // the buffers below are the thesis's
  const auto buffers = estimateBuffers(seabed, makePlan(seabed));
  // 16384^2 float4 G-buffer hits alone are 4 GiB.
  const unsigned long long gib = 1ull << 30;
  std::string msg = errorOf([&] { checkMemoryBudget(buffers, 64 * gib, 2 * gib, "test device"); });
  EXPECT_NE(msg.find("CL_DEVICE_MAX_MEM_ALLOC_SIZE"), std::string::npos) << msg;
  EXPECT_NE(msg.find("camera.width = 16384, camera.height = 16384"), std::string::npos) << msg;
  // The largest float4 image in 2 GiB: 8192 wide at full height, or 11585 x 11585 (2^31 / 16 = 11585.2^2).
  EXPECT_NE(msg.find("at most camera.width = 8192 or camera.height = 8192"), std::string::npos) << msg;
  EXPECT_NE(msg.find("or 11585 x 11585 at this aspect ratio"), std::string::npos) << msg;
  msg = errorOf([&] { checkMemoryBudget(buffers, 8 * gib, 8 * gib, "test device"); });
  EXPECT_NE(msg.find("CL_DEVICE_GLOBAL_MEM_SIZE"), std::string::npos) << msg;
  // All device per-pixel buffers (12 + 16 + 4 + 4 = 36 bytes a pixel) shrink with the image; the
  // froxel volume (80 x 45 x 32 froxels at any image size), caustic and sun shadow maps (a few MiB)
  // stay: 0.9 x 8 GiB minus those over 36 bytes is 214.5M pixels, 14647^2 at this aspect ratio.
  EXPECT_NE(msg.find("or 14647 x 14647 at this aspect ratio"), std::string::npos) << msg;
  EXPECT_EQ(errorOf([&] { checkMemoryBudget(buffers, 64 * gib, 8 * gib, "test device"); }), "");
  // On a CPU device the host copies of the frame share the same memory and count too.
  EXPECT_EQ(errorOf([&] { checkMemoryBudget(buffers, 12 * gib, 8 * gib, "gpu", false); }), "");
  EXPECT_NE(errorOf([&] { checkMemoryBudget(buffers, 12 * gib, 8 * gib, "cpu", true); }), "");

  // Quality knobs: the message names the knob.
  const Scene spot = loadScene(std::string(SEASIM_SOURCE_DIR) + "/scenes/spot_sphere.toml",
                               {{"quality.shadow_map_size", "200000", {"t", 1}},
                                {"quality.shafts_method", "\"planes\"", {"t", 1}}});  // intervals: no shadow maps
  msg = errorOf([&] { checkMemoryBudget(estimateBuffers(spot, makePlan(spot)), 64 * gib, 2 * gib, "d"); });
  EXPECT_NE(msg.find("quality.shadow_map_size = 200000"), std::string::npos) << msg;
  // 2 GiB of floats for one light: 23170^2 texels.
  EXPECT_NE(msg.find("at most quality.shadow_map_size = 23170"), std::string::npos) << msg;
  const Scene table = loadScene(std::string(SEASIM_SOURCE_DIR) + "/scenes/spot_sphere.toml",
                                {{"quality.shafts_table_size", "1000000", {"t", 1}},
                                 {"quality.shafts_method", "\"planes\"", {"t", 1}}});
  msg = errorOf([&] { checkMemoryBudget(estimateBuffers(table, makePlan(table)), 64 * gib, 2 * gib, "d"); });
  EXPECT_NE(msg.find("quality.shafts_table_size = 1000000"), std::string::npos) << msg;
}

TEST_F(Reliability, SpotlightAndObjectCountsAreLimited) {
  std::ostringstream lights, objects;
  lights << "[air]\ndensity = 0.04\n";
  for (int i = 0; i < 4000; ++i) lights << "[[spotlights]]\nposition = [0, 5, 0]\n";
  std::string msg = errorOf([&] { parseScene(lights.str(), path("s.toml")); });
  EXPECT_NE(msg.find("key 'spotlights[" + std::to_string(kMaxSpotlights) + "]'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("too many spotlights: at most " + std::to_string(kMaxSpotlights)), std::string::npos) << msg;
  for (int i = 0; i <= kMaxObjects; ++i) objects << "[[objects]]\ntype = \"sphere\"\n";
  msg = errorOf([&] { parseScene(objects.str(), path("s.toml")); });
  EXPECT_NE(msg.find("too many objects"), std::string::npos) << msg;
}

// ---------------------------------------------------------------------------------------------
// Input messages.

TEST_F(Reliability, HugeOverrideIndexIsAnInputError) {
  const std::string msg = errorOf([&] {
    parseScene("[[objects]]\ntype = \"sphere\"\n", path("s.toml"),
               {{"objects[99999999999999999999].radius", "1", {"job.toml", 7}}});
  });
  EXPECT_NE(msg.find("job.toml:7: key 'objects[99999999999999999999].radius'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("too large"), std::string::npos) << msg;
}

TEST_F(Reliability, ValuesThatOverflowSinglePrecisionAreInputErrors) {
  struct Case {
    std::string toml, where;
  };
  const std::vector<Case> cases = {
      {"[sun]\nirradiance = 1e38\n", ":2: key 'sun.irradiance'"},
      {"[water]\na = [0.1, 0.1]\nb = [1e300, 0.1]\nwavelengths_nm = [400, 700]\n", ":3: key 'water.b[0]'"},
      {"[sun]\nirradiance = 1e-300\n", ":2: key 'sun.irradiance'"},
  };
  for (const Case& c : cases) {
    const std::string msg = errorOf([&] { parseScene(c.toml, path("s.toml")); });
    EXPECT_NE(msg.find(path("s.toml") + c.where), std::string::npos) << msg;
    EXPECT_NE(msg.find("single-precision"), std::string::npos) << msg;
    EXPECT_EQ(msg.find("bug"), std::string::npos) << msg;
  }
  EXPECT_NO_THROW(parseScene("[sun]\nirradiance = 1e15\n", path("s.toml")));
}

class JobDir : public Reliability {
 protected:
  std::string jobWith(const std::string& job_table, const std::string& render_extra = "") {
    write("s.toml", "[camera]\nwidth = 16\nheight = 8\n");
    return write("job.toml", "[job]\n" + job_table + "[[render]]\nscene = \"s.toml\"\n" + render_extra);
  }
};

TEST_F(JobDir, OutputDirThatIsAFileOrDevNullOrHasNulIsRefusedAtItsKey) {
  write("afile", "x");
  for (const std::string& dir : {std::string("afile"), std::string("/dev/null"), std::string("afile/sub")}) {
    const std::string job = jobWith("output_dir = \"" + dir + "\"\n");
    const std::string msg = errorOf([&] { loadJob(job); });
    EXPECT_NE(msg.find(job + ":2: key 'job.output_dir'"), std::string::npos) << dir << ": " << msg;
  }
  std::string job = jobWith("output_dir = \"out\\u0000evil\"\n");
  std::string msg = errorOf([&] { loadJob(job); });
  EXPECT_NE(msg.find(job + ":2: key 'job.output_dir'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("NUL"), std::string::npos) << msg;
  job = jobWith("output_dir = \"" + std::string(300, 'n') + "\"\n");
  msg = errorOf([&] { loadJob(job); });
  EXPECT_NE(msg.find("255"), std::string::npos) << msg;
}

// Found by the fuzzer: a path part over 255 bytes made std::filesystem throw out of the parser.
TEST_F(JobDir, OverlongInputPathsAreInputErrors) {
  const std::string long_part(300, 'n');
  std::string job = write("job.toml", "[[render]]\nscene = \"" + long_part + "/s.toml\"\n");
  std::string msg = errorOf([&] { loadJob(job); });
  EXPECT_NE(msg.find(job + ":2: key 'render[0].scene'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("File name too long"), std::string::npos) << msg;
  msg = errorOf([&] { parseScene("[sky]\nmodel = \"image\"\nimage = \"" + long_part + ".png\"\n", path("s.toml")); });
  EXPECT_NE(msg.find("key 'sky.image'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("File name too long"), std::string::npos) << msg;
  msg = errorOf([&] { parseScene("[spectral]\nsensor = \"" + long_part + "\"\n", path("s.toml")); });
  EXPECT_NE(msg.find("key 'spectral.sensor'"), std::string::npos) << msg;
}

TEST_F(JobDir, ItemNamedLikeAManifestIsRefused) {
  for (const std::string& name : {"manifest.json", "manifest-0of2.json", "Manifest.JSON"}) {
    const std::string job = jobWith("output_dir = \"out\"\n", "name = \"" + name + "\"\n");
    const std::string msg = errorOf([&] { loadJob(job); });
    EXPECT_NE(msg.find("key 'render[0].name'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("reserved"), std::string::npos) << msg;
  }
}

}  // namespace
}  // namespace seasim
