#include "passes/nonfinite_check.h"

#include "device/enqueue.h"
#include "util/error.h"

namespace seasim {

NonfiniteCheck::NonfiniteCheck(Device& device) : device_(device) {
  onDevice("nonfinite_check set-up", [&] {
    kernel_ = cl::Kernel(device.program("check.cl", {}).program, "count_nonfinite");
    counter_ = cl::Buffer(device.context(), CL_MEM_READ_WRITE, sizeof(cl_uint));
  });
}

long long NonfiniteCheck::count(cl::Buffer& buffer, size_t count, double* ms) {
  cl_uint zero = 0, found = 0;
  onDevice("nonfinite_check", [&] {
    device_.queue().enqueueWriteBuffer(counter_, CL_TRUE, 0, sizeof zero, &zero);
    kernel_.setArg(0, buffer);
    kernel_.setArg(1, static_cast<cl_uint>(count));
    kernel_.setArg(2, counter_);
  });
  const size_t local = 64;
  const double kernel_ms =
      runKernel(device_, "nonfinite_check", kernel_, cl::NDRange(roundUp(count, local)), cl::NDRange(local));
  onDevice("nonfinite_check", [&] { device_.queue().enqueueReadBuffer(counter_, CL_TRUE, 0, sizeof found, &found); });
  if (ms) *ms = kernel_ms;
  return found;
}

}  // namespace seasim
