// vkfft_plan.h — a small wrapper over VkFFT's OpenCL backend: batched N x N complex-to-complex FFTs of
// float2 data in a cl::Buffer. The only header that knows VkFFT exists; vkfft_plan.cpp is the only file
// that includes vkFFT.h (a 30 s translation unit, toolchain.md §3.2).
#pragma once
#include <CL/opencl.hpp>

#include <memory>

#include "device/device.h"

namespace seasim {

class VkfftPlan {
 public:
  // Plans `batches` consecutive N x N blocks of float2 (x fastest) in `buffer`, in place, float.
  // Generating and compiling VkFFT's kernels takes 0.2–2 s on PoCL; build once, run many times.
  // Throws DeviceError naming the VkFFT error code.
  VkfftPlan(Device& device, const cl::Buffer& buffer, int n, int batches);
  ~VkfftPlan();
  VkfftPlan(const VkfftPlan&) = delete;
  VkfftPlan& operator=(const VkfftPlan&) = delete;

  // Enqueue on the device's queue (no wait). inverse: f(x) = Σ_k F(k) e^{+ik·x}, unnormalised
  // (004 eq. 19 as written); forward: F(k) = Σ_x f(x) e^{-ik·x} (FFTW_FORWARD's sign).
  void inverse();
  void forward();

  int n() const { return n_; }
  int batches() const { return batches_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int n_, batches_;
};

}  // namespace seasim
