// device_test.cpp — the OpenCL device layer on PoCL: listing and selection by every selector form,
// the program cache (memory and disk), a failed build reported with the kernel file and the log,
// and fp64 defines only where the device has fp64.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "device/device.h"
#include "util/error.h"

namespace fs = std::filesystem;

namespace {

TEST(Device, ListsPoclAndChoosesBySelector) {
  const auto all = seasim::listDevices();
  ASSERT_FALSE(all.empty());
  const seasim::DeviceInfo pocl = seasim::chooseDevice("pocl:0");
  EXPECT_TRUE(pocl.is_pocl);
  EXPECT_EQ(seasim::chooseDevice("cpu").name, seasim::chooseDevice("cpu").name);
  EXPECT_FALSE(seasim::chooseDevice("cpu").is_gpu);
  // A name substring, any case.
  std::string part = pocl.name.substr(0, 6);
  for (char& c : part) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  EXPECT_EQ(seasim::chooseDevice(part).name, pocl.name);
  // Default: the first GPU, else PoCL.
  bool any_gpu = false;
  for (const auto& d : all) any_gpu |= d.is_gpu;
  EXPECT_EQ(seasim::chooseDevice("").is_gpu, any_gpu);
  EXPECT_NE(pocl.label().find("pocl:0"), std::string::npos);
}

TEST(Device, UnknownSelectorListsTheDevices) {
  try {
    seasim::chooseDevice("no-such-device-xyz");
    FAIL() << "expected DeviceError";
  } catch (const seasim::DeviceError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("no-such-device-xyz"), std::string::npos);
    EXPECT_NE(msg.find("pocl:0"), std::string::npos) << msg;
  }
  EXPECT_THROW(seasim::chooseDevice("pocl:7"), seasim::DeviceError);
}

class DeviceCache : public ::testing::Test {
 protected:
  void SetUp() override {
    // One folder per test and process: ctest runs tests in parallel processes.
    cache_ = fs::temp_directory_path() /
             ("seasim_device_cache_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) +
              "_" + std::to_string(::getpid()));
    fs::remove_all(cache_);
    old_ = std::getenv("SEASIM_CACHE_DIR") ? std::getenv("SEASIM_CACHE_DIR") : "";
    setenv("SEASIM_CACHE_DIR", cache_.c_str(), 1);
  }
  void TearDown() override {
    if (old_.empty()) unsetenv("SEASIM_CACHE_DIR"); else setenv("SEASIM_CACHE_DIR", old_.c_str(), 1);
    unsetenv("SEASIM_KERNEL_DIR");
    fs::remove_all(cache_);
  }
  fs::path cache_;
  std::string old_;
};

TEST_F(DeviceCache, ProgramsAreCachedInMemoryAndOnDisk) {
  seasim::Device first(seasim::chooseDevice("pocl"));
  const seasim::BuiltProgram& a = first.program("check.cl", {"SEASIM_TEST_DEFINE=1"});
  EXPECT_FALSE(a.from_cache);
  const seasim::BuiltProgram& again = first.program("check.cl", {"SEASIM_TEST_DEFINE=1"});
  EXPECT_EQ(&a, &again) << "same (file, defines, device) -> the same program object";
  const seasim::BuiltProgram& other = first.program("check.cl", {"SEASIM_TEST_DEFINE=2"});
  EXPECT_NE(&a, &other) << "different defines -> a different program";
  size_t binaries = 0;
  for (const auto& e : fs::directory_iterator(cache_)) binaries += e.path().extension() == ".bin";
  EXPECT_EQ(binaries, 2u);

  seasim::Device second(seasim::chooseDevice("pocl"));
  const seasim::BuiltProgram& cached = second.program("check.cl", {"SEASIM_TEST_DEFINE=1"});
  EXPECT_TRUE(cached.from_cache);
  cl::Kernel k(cached.program, "count_nonfinite");  // the cached binary has the kernel
  EXPECT_EQ(k.getInfo<CL_KERNEL_FUNCTION_NAME>(), std::string("count_nonfinite"));
}

TEST_F(DeviceCache, FailedBuildNamesTheKernelFileAndShowsTheLog) {
  const fs::path kdir = fs::temp_directory_path() / ("seasim_bad_kernels_" + std::to_string(::getpid()));
  fs::create_directories(kdir / "common");
  std::ofstream(kdir / "broken.cl") << "// line 1\n__kernel void broken(__global float* x) {\n  x[0] = undeclared_symbol;\n}\n";
  setenv("SEASIM_KERNEL_DIR", kdir.c_str(), 1);
  seasim::Device dev(seasim::chooseDevice("pocl"));
  try {
    dev.program("broken.cl", {});
    FAIL() << "expected DeviceError";
  } catch (const seasim::DeviceError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("kernels/broken.cl"), std::string::npos) << msg;
    EXPECT_NE(msg.find("undeclared_symbol"), std::string::npos) << msg;
    EXPECT_NE(msg.find("kernels/broken.cl:3"), std::string::npos) << "the log points at the real line: " << msg;
  }
  fs::remove_all(kdir);
}

TEST_F(DeviceCache, Fp64DefineFollowsTheDevice) {
  const fs::path kdir = fs::temp_directory_path() / ("seasim_fp64_kernels_" + std::to_string(::getpid()));
  fs::create_directories(kdir);
  std::ofstream(kdir / "fp64.cl") << "__kernel void has_fp64(__global int* out) {\n"
                                     "#ifdef SEASIM_HAS_FP64\n  out[0] = 1;\n#else\n  out[0] = 0;\n#endif\n}\n";
  setenv("SEASIM_KERNEL_DIR", kdir.c_str(), 1);
  seasim::Device dev(seasim::chooseDevice("pocl"));
  cl::Kernel k(dev.program("fp64.cl", {}).program, "has_fp64");
  cl::Buffer out(dev.context(), CL_MEM_WRITE_ONLY, sizeof(int));
  k.setArg(0, out);
  dev.queue().enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(1));
  int value = -1;
  dev.queue().enqueueReadBuffer(out, CL_TRUE, 0, sizeof value, &value);
  EXPECT_EQ(value, dev.info().has_fp64 ? 1 : 0);
  fs::remove_all(kdir);
}

}  // namespace
