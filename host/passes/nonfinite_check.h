// nonfinite_check.h — host side of kernels/check.cl: counts NaN/Inf in a float buffer on the device.
#pragma once
#include <CL/opencl.hpp>

#include "device/device.h"

namespace seasim {

class NonfiniteCheck {
 public:
  explicit NonfiniteCheck(Device& device);
  // Number of non-finite floats among the first `count` of `buffer`; *ms gets the kernel time.
  long long count(cl::Buffer& buffer, size_t count, double* ms);

 private:
  Device& device_;
  cl::Kernel kernel_;
  cl::Buffer counter_;
};

}  // namespace seasim
