#include "device/enqueue.h"

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

double runKernel(Device& device, const std::string& pass, const cl::Kernel& kernel, const cl::NDRange& global,
                 const cl::NDRange& local) {
  cl::Event done;
  try {
    device.queue().enqueueNDRangeKernel(kernel, cl::NullRange, global, local, nullptr, &done);
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
