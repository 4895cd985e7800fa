// kernel_source_test.cpp — kernel files are embedded, includes are inlined once each with #line
// markers naming the real file, and SEASIM_KERNEL_DIR overrides the embedded copy.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <unistd.h>

#include "device/kernel_source.h"
#include "util/error.h"

namespace fs = std::filesystem;

namespace {

TEST(KernelSource, EmbeddedKernelInlinesCommonHeadersOnce) {
  unsetenv("SEASIM_KERNEL_DIR");
  const seasim::KernelSource src = seasim::assembleKernelSource("sea_single.cl");
  EXPECT_EQ(src.files.front(), "sea_single.cl");
  EXPECT_NE(std::find(src.files.begin(), src.files.end(), "common/optics.h"), src.files.end());
  // compat.h is included by the kernel; inlined exactly once.
  EXPECT_EQ(std::count(src.files.begin(), src.files.end(), "common/compat.h"), 1);
  // No include directive is left for the OpenCL compiler (comments may still mention them).
  EXPECT_FALSE(std::regex_search(src.text, std::regex(R"((^|\n)[ \t]*#[ \t]*include[ \t]*\")")));
  EXPECT_NE(src.text.find("#line 1 \"kernels/common/optics.h\""), std::string::npos);
  EXPECT_NE(src.text.find("__kernel void sea_single"), std::string::npos);
}

TEST(KernelSource, MissingKernelIsAClearError) {
  unsetenv("SEASIM_KERNEL_DIR");
  try {
    seasim::readKernelFile("no_such_kernel.cl");
    FAIL() << "expected DeviceError";
  } catch (const seasim::DeviceError& e) {
    EXPECT_NE(std::string(e.what()).find("kernels/no_such_kernel.cl"), std::string::npos);
  }
}

TEST(KernelSource, KernelDirOverridesEmbeddedSources) {
  const fs::path dir = fs::temp_directory_path() / ("seasim_kernel_dir_test_" + std::to_string(::getpid()));
  fs::create_directories(dir / "common");
  std::ofstream(dir / "k.cl") << "#include \"common/a.h\"\n#include \"common/a.h\"\nkernel void k() {}\n";
  std::ofstream(dir / "common" / "a.h") << "#define A 1\n";
  setenv("SEASIM_KERNEL_DIR", dir.c_str(), 1);
  const seasim::KernelSource src = seasim::assembleKernelSource("k.cl");
  unsetenv("SEASIM_KERNEL_DIR");
  EXPECT_EQ(src.files, (std::vector<std::string>{"k.cl", "common/a.h"}));
  EXPECT_NE(src.text.find("#define A 1"), std::string::npos);
  // After the include, the marker returns to the including file's next line.
  EXPECT_NE(src.text.find("#line 2 \"kernels/k.cl\""), std::string::npos);
  fs::remove_all(dir);
}

}  // namespace
