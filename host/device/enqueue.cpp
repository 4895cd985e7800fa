#include "device/enqueue.h"

#include <vector>

namespace seasim {

size_t roundUp(size_t n, size_t local) { return (n + local - 1) / local * local; }

DeviceError deviceError(const std::string& where_made, const cl::Error& e, const cl::Kernel* kernel) {
  std::string where = where_made;
  if (kernel && (*kernel)()) {
    try {
      where += ", kernel " + kernel->getInfo<CL_KERNEL_FUNCTION_NAME>();
    } catch (const cl::Error&) {
      // The kernel object itself is broken: the pass's name and the error code still say enough.
    }
  }
  return DeviceError(where + ": " + e.what() + " " + clErrorName(e.err()));
}

// OpenCL guarantees no minimum: a GPU may allow a register-heavy kernel fewer work-items per group
// than the 8 x 8 the passes ask for, and then an explicit size fails with CL_INVALID_WORK_GROUP_SIZE.
cl::NDRange workGroupFor(Device& device, const cl::Kernel& kernel, const cl::NDRange& local) {
  if (local.dimensions() == 0) return local;
  const size_t kernel_max = kernel.getWorkGroupInfo<CL_KERNEL_WORK_GROUP_SIZE>(device.device());
  const std::vector<size_t> item_max = device.device().getInfo<CL_DEVICE_MAX_WORK_ITEM_SIZES>();
  size_t items = 1;
  for (size_t d = 0; d < local.dimensions(); ++d) {
    if (d < item_max.size() && local[d] > item_max[d]) return cl::NullRange;
    items *= local[d];
  }
  return items <= kernel_max ? local : cl::NullRange;
}

double runKernel(Device& device, const std::string& pass, const cl::Kernel& kernel, const cl::NDRange& global,
                 const cl::NDRange& local) {
  cl::Event done;
  try {
    device.queue().enqueueNDRangeKernel(kernel, cl::NullRange, global, workGroupFor(device, kernel, local), nullptr,
                                        &done);
    done.wait();
  } catch (const cl::Error& e) {
    throw deviceError(pass + " pass", e, &kernel);
  }
  return eventMs(done);
}

double runKernel2d(Device& device, const std::string& pass, const cl::Kernel& kernel, size_t width, size_t height,
                   size_t local) {
  return runKernel(device, pass, kernel, cl::NDRange(roundUp(width, local), roundUp(height, local)),
                   cl::NDRange(local, local));
}

}  // namespace seasim
