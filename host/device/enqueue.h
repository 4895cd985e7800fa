// enqueue.h — the one way a pass launches a kernel, after the OpenCL-SDK samples' single error
// wrapper: the global size rounded up to whole work-groups (the kernels return early past the
// image), the launch waited for and timed on the profiling queue, and any OpenCL error rethrown as a
// DeviceError that names the pass and the kernel.
#pragma once
#include <CL/opencl.hpp>

#include <cstddef>
#include <string>
#include <utility>

#include "device/device.h"
#include "util/error.h"

namespace seasim {

// n rounded up to a multiple of `local`.
size_t roundUp(size_t n, size_t local);

// `local` when this device can run `kernel` in groups of that size (CL_KERNEL_WORK_GROUP_SIZE and
// CL_DEVICE_MAX_WORK_ITEM_SIZES), else NullRange: the driver chooses. OpenCL sets no minimum group
// size, so an explicit 8 x 8 is a request, not a requirement; global sizes are whole groups anyway.
cl::NDRange workGroupFor(Device& device, const cl::Kernel& kernel, const cl::NDRange& local);

// Launches `kernel` over width x height in local x local work-groups and waits; returns its ms.
double runKernel2d(Device& device, const std::string& pass, const cl::Kernel& kernel, size_t width, size_t height,
                   size_t local = 8);

// Launches `kernel` over `global` (`local`: NullRange lets the driver choose) and waits; returns its ms.
double runKernel(Device& device, const std::string& pass, const cl::Kernel& kernel, const cl::NDRange& global,
                 const cl::NDRange& local = cl::NullRange);

// The DeviceError for an OpenCL error made in `where` ("sea_single pass", "froxel pass set-up"):
// "sea_single pass, kernel sea_single: clEnqueueNDRangeKernel CL_INVALID_WORK_GROUP_SIZE", with the
// kernel's name when one is given.
DeviceError deviceError(const std::string& where, const cl::Error& e, const cl::Kernel* kernel = nullptr);

// Runs `calls` (buffers, arguments, reads and writes), rethrowing an OpenCL error as deviceError(where).
template <class F>
decltype(auto) onDevice(const std::string& where, F&& calls) {
  try {
    return std::forward<F>(calls)();
  } catch (const cl::Error& e) {
    throw deviceError(where, e);
  }
}

}  // namespace seasim
