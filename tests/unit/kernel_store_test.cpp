// kernel_store_test.cpp — the kernel store's pieces without a device (host/device/kernel_store.h): the
// PoCL entry a binary names, one entry seeded into a PoCL cache (whole, once, never half, a damaged one
// refused), and where the store is looked for. The store end to end: tests/integration/kernel_store_cli_test.cpp.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "device/kernel_store.h"

namespace fs = std::filesystem;
using namespace seasim;

namespace {

std::vector<unsigned char> bytes(const std::string& s) { return {s.begin(), s.end()}; }

const std::string kName = "KI/DIHEMIBBLFOGPHEFKHKDKHPDOKONMFOBCKCGF";  // as PoCL 3.1 writes it

class KernelStoreFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("seasim_kernel_store_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
            std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  // An entry of `root` named `name` with a whole bitcode file (the magic and no block) and one other file.
  void writeEntry(const fs::path& root, const std::string& name, const std::string& bitcode = "BC\xC0\xDE") {
    fs::create_directories(root / name / "kernel" / "0-0-0");
    std::ofstream(root / name / "program.bc", std::ios::binary) << bitcode;
    std::ofstream(root / name / "last_accessed") << "";
  }
  fs::path dir_;
};

}  // namespace

TEST(KernelStoreBinary, NamesTheEntryPoclWroteIntoIt) {
  EXPECT_EQ(poclEntryOfBinary(bytes(std::string("poclbin\0\x0c{", 10) + kName + std::string("\0C", 2))), kName);
  EXPECT_EQ(poclEntryOfBinary(bytes(kName)), kName);  // at both ends of the bytes
  // Not a name: one letter too few or too many, a letter past P, no slash, nothing at all.
  EXPECT_EQ(poclEntryOfBinary(bytes("x" + kName.substr(0, kName.size() - 1) + "\n")), "");
  EXPECT_EQ(poclEntryOfBinary(bytes(kName + "A")), "");
  EXPECT_EQ(poclEntryOfBinary(bytes("A" + kName)), "");
  std::string off = kName;
  off[10] = 'Q';
  EXPECT_EQ(poclEntryOfBinary(bytes(off)), "");
  std::string no_slash = kName;
  no_slash[2] = 'A';
  EXPECT_EQ(poclEntryOfBinary(bytes(no_slash)), "");
  EXPECT_EQ(poclEntryOfBinary({}), "");
}

TEST_F(KernelStoreFiles, SeedsAnEntryWholeAndOnceAndRefusesADamagedOne) {
  const fs::path store = dir_ / "store", cache = dir_ / "cache";
  writeEntry(store, kName);
  ASSERT_TRUE(seedPoclEntry(store.string(), kName, cache.string()));
  EXPECT_TRUE(fs::exists(cache / kName / "program.bc"));
  EXPECT_TRUE(fs::is_directory(cache / kName / "kernel" / "0-0-0"));
  EXPECT_FALSE(seedPoclEntry(store.string(), kName, cache.string())) << "an entry the cache has is left alone";
  // No temporary sibling left behind.
  for (const auto& e : fs::directory_iterator(cache / kName.substr(0, 2)))
    EXPECT_EQ(e.path().filename().string(), kName.substr(3));
  // An entry the store lacks, and an empty name, copy nothing.
  EXPECT_FALSE(seedPoclEntry(store.string(), "AA/" + kName.substr(3), cache.string()));
  EXPECT_FALSE(seedPoclEntry(store.string(), "", cache.string()));
  // A bitcode file cut inside a block is damage (pocl_cache_check.h): not copied, PoCL builds it instead.
  const std::string other = "AB/" + kName.substr(3);
  writeEntry(store, other, std::string("BC\xC0\xDE\x35\x14\x00\x00\x05\x00\x00\x00", 12));
  EXPECT_FALSE(seedPoclEntry(store.string(), other, cache.string()));
  EXPECT_FALSE(fs::exists(cache / other));
  EXPECT_EQ(seedPoclCache(store.string(), (dir_ / "second").string()), 1) << "all but the damaged entry";
}

TEST(KernelStoreDir, TheEnvironmentNamesItAndAnEmptyValueMeansNone) {
  const char* old = std::getenv("SEASIM_KERNEL_STORE");
  const std::string kept = old ? old : "";
  ::setenv("SEASIM_KERNEL_STORE", "/some/store", 1);
  EXPECT_EQ(kernelStoreDir(), "/some/store");
  ::setenv("SEASIM_KERNEL_STORE", "", 1);
  EXPECT_EQ(kernelStoreDir(), "");
  if (old) ::setenv("SEASIM_KERNEL_STORE", kept.c_str(), 1); else ::unsetenv("SEASIM_KERNEL_STORE");
  EXPECT_NE(poclStoreDir("/s", "a|b|c"), poclStoreDir("/s", "a|b|d")) << "keyed by the device and driver";
  EXPECT_NE(poclStoreDir("/s", "a|b|c"), vkfftStoreDir("/s", "a|b|c"));
}
