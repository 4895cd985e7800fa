// ocean_cpu.h — the FFT ocean of kernels/ocean.cl on the CPU: the reference the kernel tests compare
// against (double, direct DFT for small N, FFTW for large) and the benchmark's CPU baseline (float or
// double FFTW, TBB loops). It runs the same shared math (kernels/common/ocean_spectrum.h through
// host/math/kernel_math.h) and the same packing of eight real fields into four complex FFTs, and
// produces the same maps in the same layouts as OceanPass (passes/ocean_pass.h).
#pragma once
#include <complex>
#include <memory>
#include <vector>

#include "passes/ocean_pass.h"

namespace seasim {

struct OceanCpuImpl;  // ocean_cpu.cpp

class OceanCpu {
 public:
  enum class Precision { Double, Float };
  // Auto: direct (separable) DFT for N <= 64, FFTW above.
  enum class Transform { Auto, DirectDft, Fftw };

  explicit OceanCpu(const OceanConfig& config, Precision precision = Precision::Double,
                    Transform transform = Transform::Auto);
  ~OceanCpu();
  OceanCpu(const OceanCpu&) = delete;
  OceanCpu& operator=(const OceanCpu&) = delete;

  // Evolves to time t, transforms and computes all maps (as OceanPass::run).
  void run(double time_s);

  int n() const { return config_.grid; }
  const OceanConfig& config() const { return config_; }

  // h̃0 in FFT order; the maps of the last run(), layouts as OceanPass::read*().
  std::vector<std::complex<double>> h0() const;
  std::vector<double> height() const;
  std::vector<double> slope() const;
  std::vector<double> displacement() const;
  std::vector<double> normal() const;
  std::vector<double> jacobian() const;
  std::vector<double> folding() const;
  // The eight real fields, slot-major as OceanPass::readFields().
  std::vector<double> fields() const;

 private:
  OceanConfig config_;
  std::unique_ptr<OceanCpuImpl> impl_;
};

}  // namespace seasim
