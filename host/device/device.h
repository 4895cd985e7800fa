// device.h — OpenCL platform/device choice, one context and one in-order profiling queue, and a
// program cache keyed by (kernel file, defines, device) with on-disk binaries.
#pragma once
#include <CL/opencl.hpp>

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace seasim {

struct DeviceInfo {
  int platform_index = 0;
  int device_index = 0;          // within the platform
  std::string platform_name;     // "Portable Computing Language", "NVIDIA CUDA", ...
  std::string name;              // device name
  std::string vendor;
  std::string version;           // CL_DEVICE_VERSION
  std::string driver;            // CL_DRIVER_VERSION
  bool is_gpu = false;
  bool is_pocl = false;
  bool has_fp64 = false;
  unsigned compute_units = 0;
  unsigned long long global_mem_bytes = 0;   // CL_DEVICE_GLOBAL_MEM_SIZE
  unsigned long long max_alloc_bytes = 0;    // CL_DEVICE_MAX_MEM_ALLOC_SIZE (largest one buffer)
  std::string label() const;     // "pocl:0 pthread-AMD EPYC ... (CPU, 2 CU, fp64)"
};

// Every OpenCL device on the machine, platform by platform. Empty when there is no ICD.
std::vector<DeviceInfo> listDevices();

// Picks a device by selector: "" or "auto" (first GPU, else PoCL, else first), "cpu", "gpu",
// "pocl:N", "nvidia:N" (N-th device of the platform whose name contains "pocl"/"nvidia"),
// or a case-insensitive substring of the device name. Throws DeviceError listing the devices.
DeviceInfo chooseDevice(const std::string& selector);

// A compiled program and how long the build took (0 when it came from a cache).
struct BuiltProgram {
  cl::Program program;
  double build_ms = 0.0;
  bool from_cache = false;  // from seasim's cache or the kernel store (kernel_store.h)
  uint64_t cache_key = 0;   // the entry's key in the cache and the store
};

// The one context per run: device, context, in-order queue with profiling, program cache.
class Device {
 public:
  explicit Device(const DeviceInfo& info);
  const DeviceInfo& info() const { return info_; }
  // "<platform>|<device>|<driver>": what keys this device's kernel cache and store entries.
  std::string deviceId() const;
  cl::Context& context() { return context_; }
  cl::CommandQueue& queue() { return queue_; }
  cl::Device& device() { return device_; }

  // Builds (or fetches) kernels/<kernel_file> with `-D` defines (NAME or NAME=VALUE). Includes of
  // "common/x.h" are inlined with #line markers. Sources come from the binary, or from
  // $SEASIM_KERNEL_DIR when set. Binaries are cached in memory and on disk
  // ($SEASIM_CACHE_DIR, else $XDG_CACHE_HOME/seasim, else ~/.cache/seasim).
  // The define SEASIM_FAST_MATH=1 (quality.fast_math, set by the planner) also adds
  // fastMathOptions(info) to the build options.
  // A failed build throws DeviceError with the kernel file and the compiler log.
  const BuiltProgram& program(const std::string& kernel_file, const std::vector<std::string>& defines);

  // Total build milliseconds spent by program() so far (for report.json).
  double totalBuildMs() const { return total_build_ms_; }

  // Writes every program built or loaded so far to `dir` as kernel cache entries (kernel_cache.h), for
  // the kernel store (kernel_store.h). Returns how many; throws RuntimeError naming a file that cannot
  // be written.
  int writeCompiledKernels(const std::string& dir);

  // The options kernels/<kernel_file> is built with for `defines` on this device (what program()
  // passes to the compiler; anything computed by a kernel and cached on disk keys on it).
  std::string buildOptions(const std::vector<std::string>& defines) const;

 private:
  void noteBuildWarnings(const std::string& kernel_file, const cl::Program& program);
  bool loadProgramEntry(const std::string& path, uint64_t key, const std::string& options, BuiltProgram& built,
                        std::string& why);
  void loadFromKernelStore(uint64_t key, const std::string& options, const std::string& kernel_file,
                           BuiltProgram& built);

  DeviceInfo info_;
  cl::Device device_;
  cl::Context context_;
  cl::CommandQueue queue_;
  std::map<std::string, BuiltProgram> programs_;
  double total_build_ms_ = 0.0;
};

// The build options that quality.fast_math's define (SEASIM_FAST_MATH=1) adds on this device:
// -cl-fast-relaxed-math on PoCL, where its error was measured; only -cl-mad-enable and
// -cl-no-signed-zeros on other drivers (device.cpp says why).
std::string fastMathOptions(const DeviceInfo& device);

// Milliseconds between an event's start and end (profiling queue).
double eventMs(const cl::Event& event);

// Throws DeviceError "what: <CL error name> (code)" when err != CL_SUCCESS.
void checkCl(cl_int err, const std::string& what);

// Human name of an OpenCL error code ("CL_OUT_OF_RESOURCES").
const char* clErrorName(cl_int err);

}  // namespace seasim
