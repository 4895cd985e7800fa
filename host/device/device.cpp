#include "device/device.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include "device/crash_hint.h"
#include "device/kernel_cache.h"
#include "device/pocl_cache_check.h"
#include "device/kernel_source.h"
#include "device/kernel_store.h"
#include "util/error.h"
#include "util/hash.h"
#include "util/paths.h"

namespace fs = std::filesystem;

namespace seasim {

namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

std::string trim(std::string s) {
  while (!s.empty() && (s.back() == '\0' || std::isspace(static_cast<unsigned char>(s.back())))) s.pop_back();
  size_t i = 0;
  while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
  return s.substr(i);
}

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

std::string DeviceInfo::label() const {
  std::string plat = is_pocl ? "pocl" : lower(platform_name.substr(0, platform_name.find(' ')));
  std::ostringstream s;
  s << plat << ":" << device_index << " " << name << " (" << (is_gpu ? "GPU" : "CPU") << ", "
    << compute_units << " CU, " << (global_mem_bytes >> 20) << " MiB" << (has_fp64 ? ", fp64" : "")
    << ", " << trim(version) << ")";
  return s.str();
}

std::vector<DeviceInfo> listDevices() {
  usePoclCacheDir();    // before the first OpenCL call, which loads PoCL
  preparePoclCache();   // and PoCL's cache checked: PoCL crashes on a damaged one (pocl_cache_check.h)
  std::vector<DeviceInfo> result;
  std::vector<cl::Platform> platforms;
  cl_int err = CL_SUCCESS;
  try {
    err = cl::Platform::get(&platforms);
  } catch (const cl::Error& e) {  // CL_HPP_ENABLE_EXCEPTIONS: a loader without platforms throws -1001
    err = e.err();
  }
  if (err != CL_SUCCESS && err != CL_PLATFORM_NOT_FOUND_KHR) checkCl(err, "clGetPlatformIDs");
  for (size_t p = 0; p < platforms.size(); ++p) {
    std::vector<cl::Device> devices;
    try {
      platforms[p].getDevices(CL_DEVICE_TYPE_ALL, &devices);
    } catch (const cl::Error&) {
      continue;  // a platform with no devices
    }
    std::string pname = trim(platforms[p].getInfo<CL_PLATFORM_NAME>());
    for (size_t d = 0; d < devices.size(); ++d) {
      DeviceInfo info;
      info.platform_index = static_cast<int>(p);
      info.device_index = static_cast<int>(d);
      info.platform_name = pname;
      info.name = trim(devices[d].getInfo<CL_DEVICE_NAME>());
      info.vendor = trim(devices[d].getInfo<CL_DEVICE_VENDOR>());
      info.version = trim(devices[d].getInfo<CL_DEVICE_VERSION>());
      info.driver = trim(devices[d].getInfo<CL_DRIVER_VERSION>());
      info.is_gpu = (devices[d].getInfo<CL_DEVICE_TYPE>() & CL_DEVICE_TYPE_GPU) != 0;
      info.is_pocl = lower(pname).find("portable computing") != std::string::npos ||
                     lower(pname).find("pocl") != std::string::npos;
      info.has_fp64 = devices[d].getInfo<CL_DEVICE_EXTENSIONS>().find("cl_khr_fp64") != std::string::npos;
      info.compute_units = devices[d].getInfo<CL_DEVICE_MAX_COMPUTE_UNITS>();
      info.global_mem_bytes = devices[d].getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>();
      info.max_alloc_bytes = devices[d].getInfo<CL_DEVICE_MAX_MEM_ALLOC_SIZE>();
      result.push_back(info);
    }
  }
  return result;
}

DeviceInfo chooseDevice(const std::string& selector_in) {
  const std::vector<DeviceInfo> all = listDevices();
  if (all.empty()) {
    // PoCL lists no device when its cache folder cannot be written or created: say so rather
    // than blame the driver.
    const std::string pocl = poclCacheDir();
    if (const std::string problem = pocl.empty() ? "" : outputDirProblem(pocl); !problem.empty())
      throw DeviceError("no OpenCL device found, and PoCL's cache folder '" + pocl + "' is not writable (" + problem +
                        "); PoCL offers no device then: make it writable, or set POCL_CACHE_DIR to a writable folder");
    throw DeviceError("no OpenCL device found: install an OpenCL driver (e.g. apt-get install "
                      "pocl-opencl-icd) and check `clinfo -l`");
  }
  const std::string sel = lower(selector_in);
  auto listing = [&] {
    std::string s;
    for (const auto& d : all) s += "\n  " + d.label();
    return s;
  };
  if (sel.empty() || sel == "auto") {
    for (const auto& d : all)
      if (d.is_gpu) return d;
    for (const auto& d : all)
      if (d.is_pocl) return d;
    return all.front();
  }
  if (sel == "gpu" || sel == "cpu") {
    for (const auto& d : all)
      if (d.is_gpu == (sel == "gpu")) return d;
    throw DeviceError("no " + sel + " OpenCL device; devices here:" + listing());
  }
  if (auto colon = sel.find(':'); colon != std::string::npos) {
    std::string plat = sel.substr(0, colon);
    std::string index_text = sel.substr(colon + 1);
    bool numeric = !index_text.empty() && index_text.find_first_not_of("0123456789") == std::string::npos;
    if (numeric) {
      int want = std::stoi(index_text);
      int seen = 0;
      for (const auto& d : all) {
        bool match = (plat == "pocl") ? d.is_pocl : lower(d.platform_name).find(plat) != std::string::npos;
        if (match && seen++ == want) return d;
      }
      throw DeviceError("no device '" + selector_in + "'; devices here:" + listing());
    }
  }
  for (const auto& d : all) {
    if (lower(d.name).find(sel) != std::string::npos || lower(d.platform_name).find(sel) != std::string::npos ||
        (sel == "pocl" && d.is_pocl))
      return d;
  }
  throw DeviceError("no OpenCL device matches '" + selector_in + "'; devices here:" + listing());
}

Device::Device(const DeviceInfo& info) : info_(info) {
  try {
    std::vector<cl::Platform> platforms;
    cl::Platform::get(&platforms);
    std::vector<cl::Device> devices;
    platforms.at(static_cast<size_t>(info.platform_index)).getDevices(CL_DEVICE_TYPE_ALL, &devices);
    device_ = devices.at(static_cast<size_t>(info.device_index));
    context_ = cl::Context(device_);
    queue_ = cl::CommandQueue(context_, device_, CL_QUEUE_PROFILING_ENABLE);
  } catch (const cl::Error& e) {
    throw DeviceError("cannot open OpenCL device " + info.label() + ": " + e.what() + " " +
                      clErrorName(e.err()));
  } catch (const std::out_of_range&) {
    throw DeviceError("OpenCL device " + info.label() + " disappeared");
  }
}

std::string Device::deviceId() const { return info_.platform_name + "|" + info_.name + "|" + info_.driver; }

// What quality.fast_math asks of the driver. -cl-fast-relaxed-math lets a driver use approximate
// maths functions and assume no NaN/Inf, and drivers differ in how far they go: PoCL's images moved by
// at most 0.0002 of an 8-bit level on every shipped scene where it is on (results/BENCHMARKS.md), but
// Intel's OpenCL CPU runtime under the same flag puts the sea's multiple scattering 0.6 % off its
// double evaluation and the second order over a height field up to 100 % off at some map texels (the
// kernel tests tests/kernels/sea_multiple_kernel_test.cpp, sea_heightfield_test.cpp). So the full flag
// only where its error was measured, PoCL; elsewhere the two relaxations that cannot change which
// branch a kernel takes or how accurate a maths function is: fused multiply-adds and unsigned zeros.
std::string fastMathOptions(const DeviceInfo& device) {
  return device.is_pocl ? " -cl-fast-relaxed-math" : " -cl-mad-enable -cl-no-signed-zeros";
}

std::string Device::buildOptions(const std::vector<std::string>& defines) const {
  std::string options = "-cl-std=CL1.2";
  if (info_.has_fp64) options += " -DSEASIM_HAS_FP64=1";
  for (const auto& d : defines) {
    options += " -D" + d;
    // quality.fast_math (host/plan): the planner marks each pass's build with this define.
    if (d == "SEASIM_FAST_MATH=1") options += fastMathOptions(info_);
  }
  return options;
}

const BuiltProgram& Device::program(const std::string& kernel_file, const std::vector<std::string>& defines) {
  const std::string options = buildOptions(defines);
  const std::string key = kernel_file + "|" + options;
  if (auto it = programs_.find(key); it != programs_.end()) return it->second;

  const auto t0 = std::chrono::steady_clock::now();
  KernelSource source = assembleKernelSource(kernel_file);
  const std::string device_id = deviceId();
  const uint64_t hash = fnv1a64(device_id + "|" + options, fnv1a64(source.text));
  const std::string dir = kernelCacheDir();
  const std::string cache_file = dir.empty() ? std::string() : kernelCachePath(dir, hash);

  // PoCL aborts inside a build when its own cache is damaged: name the folder before dying.
  const CrashHint crash_hint(
      "building kernels/" + kernel_file,
      info_.is_pocl && !poclCacheDir().empty()
          ? "A damaged PoCL kernel cache causes this: clear '" + poclCacheDir() +
                "' (`seasim cache clear` does it when seasim owns that folder) and run again."
          : "If it happens again, clear the driver's kernel cache and seasim's (`seasim cache clear`).",
      info_.is_pocl && !poclCacheDir().empty() ? poclCrashMarker(poclCacheDir()) : "");
  BuiltProgram built;
  if (!cache_file.empty()) {
    std::string why;
    if (!loadProgramEntry(cache_file, hash, options, built, why) && !why.empty()) {
      // A bad entry costs one rebuild, never a failed run.
      std::fprintf(stderr, "seasim: warning: kernel cache entry '%s' for kernels/%s is unusable: %s; rebuilding it\n",
                   cache_file.c_str(), kernel_file.c_str(), why.c_str());
      std::error_code ec;
      fs::remove_all(cache_file, ec);  // a folder put in its place goes too
    }
  }
  if (!built.from_cache) loadFromKernelStore(hash, options, kernel_file, built);
  if (!built.from_cache) {
    // A build that fails on a source that built before is most often a damaged driver cache.
    const std::string pocl_hint =
        info_.is_pocl && !poclCacheDir().empty()
            ? "\nIf this kernel built before, PoCL's own cache may be damaged: clear '" + poclCacheDir() +
                  "' (`seasim cache clear` does it when seasim owns that folder) and run again"
            : "";
    cl::Program p(context_, source.text);
    try {
      p.build({device_}, options.c_str());
    } catch (const cl::BuildError& e) {
      std::string log;
      for (const auto& [dev, text] : e.getBuildLog()) log += text;
      throw DeviceError("kernel build failed: kernels/" + kernel_file + " on " + info_.name +
                        " with options '" + options + "'\n" + log + pocl_hint);
    } catch (const cl::Error& e) {
      std::string log;
      try {
        log = p.getBuildInfo<CL_PROGRAM_BUILD_LOG>(device_);
      } catch (const cl::Error&) {
      }
      throw DeviceError("kernel build failed: kernels/" + kernel_file + " (" + clErrorName(e.err()) + ")\n" + log +
                        pocl_hint);
    }
    built.program = p;
    noteBuildWarnings(kernel_file, p);
    if (!cache_file.empty()) {
      std::vector<std::vector<unsigned char>> bins = p.getInfo<CL_PROGRAM_BINARIES>();
      if (!bins.empty() && !bins[0].empty()) {
        try {
          writeKernelCacheEntry(cache_file, hash, device_id, bins[0]);
        } catch (const RuntimeError& e) {
          // A cache that cannot be written only costs build time next run.
          std::fprintf(stderr, "seasim: warning: kernel cache not updated: %s\n", e.what());
        }
      }
    }
  }
  built.build_ms = msSince(t0);
  built.cache_key = hash;
  total_build_ms_ += built.build_ms;
  return programs_.emplace(key, std::move(built)).first->second;
}

// A program from the kernel entry at `path` (the cache's or the store's): false with `why` set when the
// entry is damaged, foreign or rejected by the driver ("" when there is no file). PoCL files a program
// loaded from a binary under the entry the binary names; when the kernel store has that entry, with the
// work-group functions specialised at the first enqueues (kernel_store.h), it is copied into PoCL's cache
// first (PoCL's cache may lack it even when seasim's has the binary), so nothing is compiled at them.
bool Device::loadProgramEntry(const std::string& path, uint64_t key, const std::string& options, BuiltProgram& built,
                              std::string& why) {
  std::vector<unsigned char> bytes;
  if (!readKernelCacheEntry(path, key, deviceId(), bytes, why)) return false;
  if (info_.is_pocl)
    if (const std::string store = kernelStoreDir(); !store.empty())
      seedPoclEntry(poclStoreDir(store, deviceId()), poclEntryOfBinary(bytes), poclCacheDir());
  try {
    cl::Program::Binaries bins{bytes};
    cl::Program p(context_, {device_}, bins);
    p.build({device_}, options.c_str());
    built.program = p;
    built.from_cache = true;
    return true;
  } catch (const cl::Error& e) {
    why = std::string("the driver rejected it (") + clErrorName(e.err()) + ")";
    return false;
  }
}

// The kernel store (kernel_store.h) is read-only: an entry it lacks or that is unusable is compiled as if
// there were no store (and cached as usual), with a warning naming an unusable one.
void Device::loadFromKernelStore(uint64_t key, const std::string& options, const std::string& kernel_file,
                                 BuiltProgram& built) {
  const std::string store = kernelStoreDir();
  if (store.empty()) return;
  const std::string path = kernelCachePath(store, key);
  std::string why;
  if (!loadProgramEntry(path, key, options, built, why) && !why.empty())
    std::fprintf(stderr, "seasim: warning: kernel store entry '%s' for kernels/%s is unusable: %s; building it\n",
                 path.c_str(), kernel_file.c_str(), why.c_str());
}

int Device::writeCompiledKernels(const std::string& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw RuntimeError("cannot create the kernel folder '" + dir + "': " + ec.message());
  const std::string device_id = deviceId();
  int written = 0;
  for (const auto& [name, built] : programs_) {
    const std::vector<std::vector<unsigned char>> bins = built.program.getInfo<CL_PROGRAM_BINARIES>();
    if (bins.empty() || bins[0].empty()) continue;  // a driver that gives no binary
    writeKernelCacheEntry(kernelCachePath(dir, built.cache_key), built.cache_key, device_id, bins[0]);
    ++written;
  }
  return written;
}

// A kernel must build cleanly on every driver: a warning on one is often an error on another (an
// implicit conversion, an unused variable hiding a typo). The driver's log is printed and counted; the
// cross-runtime test fails on any. Drivers also log progress ("Compilation done", vectorisation
// remarks), so only lines with "warning:" count.
void Device::noteBuildWarnings(const std::string& kernel_file, const cl::Program& program) {
  std::string log;
  try {
    log = program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(device_);
  } catch (const cl::Error&) {
    return;
  }
  std::string lowered = log;
  for (char& c : lowered) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (lowered.find("warning:") == std::string::npos) return;
  std::fprintf(stderr, "seasim: warning: kernels/%s built with warnings on %s:\n%s\n", kernel_file.c_str(),
               info_.name.c_str(), log.c_str());
}

double eventMs(const cl::Event& event) {
  cl_ulong start = event.getProfilingInfo<CL_PROFILING_COMMAND_START>();
  cl_ulong end = event.getProfilingInfo<CL_PROFILING_COMMAND_END>();
  return static_cast<double>(end - start) * 1e-6;
}

void checkCl(cl_int err, const std::string& what) {
  if (err != CL_SUCCESS) {
    throw DeviceError(what + ": " + clErrorName(err) + " (" + std::to_string(err) + ")");
  }
}

const char* clErrorName(cl_int err) {
  switch (err) {
    case CL_SUCCESS: return "CL_SUCCESS";
    case CL_DEVICE_NOT_FOUND: return "CL_DEVICE_NOT_FOUND";
    case CL_DEVICE_NOT_AVAILABLE: return "CL_DEVICE_NOT_AVAILABLE";
    case CL_COMPILER_NOT_AVAILABLE: return "CL_COMPILER_NOT_AVAILABLE";
    case CL_MEM_OBJECT_ALLOCATION_FAILURE: return "CL_MEM_OBJECT_ALLOCATION_FAILURE";
    case CL_OUT_OF_RESOURCES: return "CL_OUT_OF_RESOURCES";
    case CL_OUT_OF_HOST_MEMORY: return "CL_OUT_OF_HOST_MEMORY";
    case CL_BUILD_PROGRAM_FAILURE: return "CL_BUILD_PROGRAM_FAILURE";
    case CL_INVALID_VALUE: return "CL_INVALID_VALUE";
    case CL_INVALID_DEVICE: return "CL_INVALID_DEVICE";
    case CL_INVALID_BINARY: return "CL_INVALID_BINARY";
    case CL_INVALID_BUILD_OPTIONS: return "CL_INVALID_BUILD_OPTIONS";
    case CL_INVALID_PROGRAM: return "CL_INVALID_PROGRAM";
    case CL_INVALID_KERNEL_NAME: return "CL_INVALID_KERNEL_NAME";
    case CL_INVALID_KERNEL_ARGS: return "CL_INVALID_KERNEL_ARGS";
    case CL_INVALID_ARG_INDEX: return "CL_INVALID_ARG_INDEX";
    case CL_INVALID_ARG_VALUE: return "CL_INVALID_ARG_VALUE";
    case CL_INVALID_ARG_SIZE: return "CL_INVALID_ARG_SIZE";
    case CL_INVALID_WORK_GROUP_SIZE: return "CL_INVALID_WORK_GROUP_SIZE";
    case CL_INVALID_WORK_ITEM_SIZE: return "CL_INVALID_WORK_ITEM_SIZE";
    case CL_INVALID_GLOBAL_WORK_SIZE: return "CL_INVALID_GLOBAL_WORK_SIZE";
    case CL_INVALID_BUFFER_SIZE: return "CL_INVALID_BUFFER_SIZE";
    case CL_INVALID_MEM_OBJECT: return "CL_INVALID_MEM_OBJECT";
    case CL_INVALID_COMMAND_QUEUE: return "CL_INVALID_COMMAND_QUEUE";
    case CL_INVALID_CONTEXT: return "CL_INVALID_CONTEXT";
    case CL_PLATFORM_NOT_FOUND_KHR: return "CL_PLATFORM_NOT_FOUND_KHR";
    default: return "CL_ERROR";
  }
}

}  // namespace seasim
