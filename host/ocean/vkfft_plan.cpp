// vkfft_plan.cpp — the one translation unit that includes vkFFT.h (Debian's single-header 1.2.26: the
// configuration takes pointers to cl_device_id / cl_context / cl_mem, sizes are uint64_t).
// Own header first: CL/opencl.hpp sets CL_TARGET_OPENCL_VERSION before vkFFT.h pulls in CL/cl.h.
#include "ocean/vkfft_plan.h"

#define VKFFT_BACKEND 3
#include <vkFFT.h>

#include <string>

#include "device/kernel_cache.h"
#include "device/kernel_store.h"
#include "util/error.h"

namespace seasim {

struct VkfftPlan::Impl {
  VkFFTApplication app{};
  cl_device_id device = nullptr;
  cl_context context = nullptr;
  cl_platform_id platform = nullptr;
  cl_command_queue queue = nullptr;
  cl_mem buffer = nullptr;
  uint64_t buffer_bytes = 0;
  bool initialised = false;

  void run(int direction) {
    VkFFTLaunchParams launch{};
    launch.commandQueue = &queue;
    launch.buffer = &buffer;
    const VkFFTResult r = VkFFTAppend(&app, direction, &launch);
    if (r != VKFFT_SUCCESS)
      throw DeviceError("VkFFTAppend (" + std::string(direction < 0 ? "forward" : "inverse") +
                        ") failed with VkFFT error " + std::to_string(static_cast<int>(r)));
  }
};

VkfftPlan::VkfftPlan(Device& device, const cl::Buffer& buffer, int n, int batches)
    : impl_(std::make_unique<Impl>()), n_(n), batches_(batches) {
  if (n < 2 || (n & (n - 1)) != 0) throw RuntimeError("VkfftPlan: N = " + std::to_string(n) + " is not a power of two");
  if (batches < 1) throw RuntimeError("VkfftPlan: batches must be >= 1");
  Impl& m = *impl_;
  m.device = device.device()();
  m.context = device.context()();
  m.queue = device.queue()();
  m.buffer = buffer();
  // VkFFT builds its programs from generated source, past Device::program: PoCL finds them compiled in its
  // cache when the kernel store has them (device/kernel_store.h).
  if (device.info().is_pocl)
    if (const std::string store = kernelStoreDir(); !store.empty())
      seedPoclCache(vkfftStoreDir(store, device.deviceId()), poclCacheDir());
  checkCl(clGetDeviceInfo(m.device, CL_DEVICE_PLATFORM, sizeof m.platform, &m.platform, nullptr),
          "clGetDeviceInfo(CL_DEVICE_PLATFORM) for VkFFT");
  m.buffer_bytes = static_cast<uint64_t>(n) * static_cast<uint64_t>(n) * static_cast<uint64_t>(batches) * 8u;

  VkFFTConfiguration cfg{};
  cfg.FFTdim = 2;
  cfg.size[0] = static_cast<uint64_t>(n);
  cfg.size[1] = static_cast<uint64_t>(n);
  cfg.numberBatches = static_cast<uint64_t>(batches);
  cfg.device = &m.device;
  cfg.context = &m.context;
  cfg.platform = &m.platform;
  cfg.buffer = &m.buffer;
  cfg.bufferSize = &m.buffer_bytes;
  const VkFFTResult r = initializeVkFFT(&m.app, cfg);
  if (r != VKFFT_SUCCESS)
    throw DeviceError("initializeVkFFT (" + std::to_string(n) + "x" + std::to_string(n) + " x " +
                      std::to_string(batches) + ") failed with VkFFT error " + std::to_string(static_cast<int>(r)) +
                      " on " + device.info().name);
  m.initialised = true;
}

VkfftPlan::~VkfftPlan() {
  if (impl_ && impl_->initialised) deleteVkFFT(&impl_->app);
}

void VkfftPlan::inverse() { impl_->run(1); }
void VkfftPlan::forward() { impl_->run(-1); }

}  // namespace seasim
