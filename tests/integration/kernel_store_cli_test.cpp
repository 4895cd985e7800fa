// kernel_store_cli_test.cpp — the kernel store (host/device/kernel_store.h) through the real binary:
// `seasim cache warm --store` on empty caches, then renders with other empty caches that read the
// store build nothing (no seasim entry written, no program compiled by PoCL, VkFFT's included, no depth table
// computed, no work-group function compiled at a first enqueue) and match renders compiled from
// source; a damaged store entry costs its compile and a warning, not the run.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>

#include "run_command.h"

namespace fs = std::filesystem;

namespace {

const std::string kRepo = SEASIM_SOURCE_DIR;
// Small: an FFT ocean (VkFFT's programs) and the sea's second order over a height field (its depth tables).
const std::string kWavy = kRepo + "/scenes/wavy_sea.toml --set camera.width=48 --set camera.height=27 "
                                  "--set spectral.count=4 --set surface.grid=64";
const std::string kShore = kRepo + "/scenes/seashore.toml --set camera.width=48 --set camera.height=27 "
                                   "--set spectral.count=4";

using seasim_test::contains;
using seasim_test::run;

int countFiles(const fs::path& dir, const std::string& extension) {
  int n = 0;
  std::error_code ec;
  for (fs::recursive_directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    n += it->path().extension() == extension;
  return n;
}

std::string readBytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// The names of PoCL's program entries (XX/<hash>) under `pocl` whose bitcode is VkFFT's.
std::set<std::string> vkfftEntries(const fs::path& pocl) {
  std::set<std::string> names;
  std::error_code ec;
  for (fs::recursive_directory_iterator it(pocl, ec), end; !ec && it != end; it.increment(ec))
    if (it->path().filename() == "program.bc" && contains(readBytes(it->path()), "VkFFT_main"))
      names.insert(it->path().parent_path().filename().string());
  return names;
}

class KernelStore : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = seasim_test::freshTestDir("seasim_kernel_store_"); }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  // Environment prefix: caches under dir_/<name>, the store `store` ("" for none).
  std::string env(const std::string& name, const std::string& store) const {
    const fs::path c = dir_ / name;
    return "SEASIM_CACHE_DIR=" + c.string() + " POCL_CACHE_DIR=" + (c / "pocl").string() +
           " SEASIM_KERNEL_STORE=" + store + " ";
  }
  fs::path dir_;
};

TEST_F(KernelStore, RendersFromTheStoreBuildNothingAndMatchRendersCompiledFromSource) {
  const fs::path store = dir_ / "store";
  const auto warm = run("cache warm " + kWavy + " --device pocl --store " + store.string(), env("warm", ""));
  ASSERT_EQ(warm.code, 0) << warm.output;
  const auto shore = run("cache warm " + kShore + " --device pocl --store " + store.string(), env("warm", ""));
  ASSERT_EQ(shore.code, 0) << shore.output;
  EXPECT_TRUE(contains(warm.output, "kernel store")) << warm.output;
  EXPECT_GE(countFiles(store, ".bin"), 3);
  EXPECT_GE(countFiles(store / "sea_depth_tables", ".f32"), 1);
  ASSERT_FALSE(vkfftEntries(store).empty()) << "no VkFFT program in the store";

  for (const std::string& scene : {kWavy, kShore}) {
    const std::string tag = scene == kWavy ? "wavy" : "shore";
    const fs::path fed = dir_ / ("fed_" + tag), compiled = dir_ / ("compiled_" + tag);
    // POCL_DEBUG=llvm: PoCL logs "Writing program.bc" for each program it compiles from source (VkFFT's
    // included) and "Generating an object file" for each work-group function it compiles at a kernel's
    // first enqueue; nothing of the kind for what it finds in its cache.
    const std::string debug = "POCL_DEBUG=llvm ";
    const auto a = run("render " + scene + " --device pocl --output npy -o " + fed.string(),
                       debug + env("fed_" + tag, store.string()));
    ASSERT_EQ(a.code, 0) << a.output;
    const auto b = run("render " + scene + " --device pocl --output npy -o " + compiled.string(),
                       debug + env("compiled_" + tag, ""));
    ASSERT_EQ(b.code, 0) << b.output;
    const fs::path caches = dir_ / ("fed_" + tag);
    // Nothing compiled: seasim writes an entry for every program it builds from source, PoCL compiles
    // VkFFT's programs and a specialised work-group function at a first enqueue, and the second order
    // writes the depth tables it computes.
    EXPECT_EQ(countFiles(caches, ".bin"), 0) << tag << ": a program was compiled despite the store";
    EXPECT_FALSE(contains(a.output, "Writing program.bc")) << tag << ": PoCL compiled a program despite the store";
    EXPECT_FALSE(contains(a.output, "Generating an object file")) << tag << ": PoCL compiled a work-group function";
    EXPECT_EQ(countFiles(caches / "sea_depth_tables", ".f32"), 0) << tag << ": depth tables computed despite the store";
    // The compiled-from-source run did build (so the checks above can fail), and the images agree.
    EXPECT_GE(countFiles(dir_ / ("compiled_" + tag), ".bin"), 1) << tag;
    EXPECT_TRUE(contains(b.output, "Writing program.bc") && contains(b.output, "Generating an object file"))
        << tag << ": PoCL's log no longer says when it compiles";
    EXPECT_EQ(readBytes(fed / "image.npy"), readBytes(compiled / "image.npy")) << tag;
    // seasim's cache kept, PoCL's emptied (its own clean-up, another POCL_CACHE_DIR): the programs come
    // from seasim's cache and their work-group functions, again, from the store.
    fs::remove_all(dir_ / ("compiled_" + tag) / "pocl");
    const auto c = run("render " + scene + " --device pocl --output npy -o " + (dir_ / ("again_" + tag)).string(),
                       debug + env("compiled_" + tag, store.string()));
    ASSERT_EQ(c.code, 0) << c.output;
    EXPECT_FALSE(contains(c.output, "Generating an object file")) << tag << ": PoCL compiled a work-group function";
  }
}

TEST_F(KernelStore, DamagedStoreEntryIsCompiledWithAWarning) {
  const fs::path store = dir_ / "store";
  ASSERT_EQ(run("cache warm " + kWavy + " --device pocl --store " + store.string(), env("warm", "")).code, 0);
  fs::path damaged;
  for (const auto& e : fs::directory_iterator(store))
    if (e.path().extension() == ".bin") damaged = e.path();
  ASSERT_FALSE(damaged.empty());
  fs::resize_file(damaged, fs::file_size(damaged) / 2);
  const auto r = run("render " + kWavy + " --device pocl --output npy -o " + (dir_ / "out").string(),
                     env("fed", store.string()));
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "kernel store entry")) << r.output;
  EXPECT_TRUE(contains(r.output, damaged.filename().string())) << r.output;
  EXPECT_EQ(countFiles(dir_ / "fed", ".bin"), 1) << "exactly the damaged entry is compiled and cached";
}

// A store folder that cannot be written is a clear error naming it, with a non-zero exit, before anything is
// compiled: no private caches are made.
TEST_F(KernelStore, UnwritableStoreFolderIsAClearError) {
  const fs::path file = dir_ / "a_file";
  std::ofstream(file) << "not a folder";
  const fs::path tmp = dir_ / "tmp";
  fs::create_directories(tmp);
  const auto r = run("cache warm " + kWavy + " --device pocl --store " + (file / "store").string(),
                     "TMPDIR=" + tmp.string() + " " + env("warm", ""));
  EXPECT_NE(r.code, 0) << r.output;
  EXPECT_TRUE(contains(r.output, (file / "store").string())) << r.output;
  EXPECT_FALSE(contains(r.output, "device: ")) << "it opened the device before checking the folder: " << r.output;
  EXPECT_TRUE(fs::is_empty(tmp)) << "private caches were made or left behind";
}

}  // namespace
