#include "passes/nonfinite_check.h"

#include "util/error.h"

namespace seasim {

NonfiniteCheck::NonfiniteCheck(Device& device) : device_(device) {
  try {
    kernel_ = cl::Kernel(device.program("check.cl", {}).program, "count_nonfinite");
    counter_ = cl::Buffer(device.context(), CL_MEM_READ_WRITE, sizeof(cl_uint));
  } catch (const cl::Error& e) {
    throw DeviceError(std::string("nonfinite_check set-up: ") + e.what() + " " + clErrorName(e.err()));
  }
}

long long NonfiniteCheck::count(cl::Buffer& buffer, size_t count, double* ms) {
  cl_uint zero = 0, found = 0;
  cl::Event done;
  try {
    device_.queue().enqueueWriteBuffer(counter_, CL_TRUE, 0, sizeof zero, &zero);
    kernel_.setArg(0, buffer);
    kernel_.setArg(1, static_cast<cl_uint>(count));
    kernel_.setArg(2, counter_);
    const size_t local = 64;
    device_.queue().enqueueNDRangeKernel(kernel_, cl::NullRange, cl::NDRange((count + local - 1) / local * local),
                                         cl::NDRange(local), nullptr, &done);
    device_.queue().enqueueReadBuffer(counter_, CL_TRUE, 0, sizeof found, &found);
  } catch (const cl::Error& e) {
    throw DeviceError(std::string("nonfinite_check: ") + e.what() + " " + clErrorName(e.err()));
  }
  if (ms) *ms = eventMs(done);
  return found;
}

}  // namespace seasim
