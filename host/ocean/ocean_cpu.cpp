#include "ocean/ocean_cpu.h"

#include <fftw3.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <numbers>

#include "math/kernel_math.h"
#include "util/error.h"

namespace seasim {

namespace {

// The shared math by precision (kmath_f / kmath_d).
inline void h0At(int i, int j, const OceanConfig& c, float* re, float* im) {
  kmath_f::ocean_h0(i, j, c.grid, static_cast<float>(c.patch_size), static_cast<float>(std::cos(c.wind_direction)),
                    static_cast<float>(std::sin(c.wind_direction)), static_cast<float>(c.wind_speed),
                    static_cast<float>(c.gravity), static_cast<float>(c.phillips_a),
                    static_cast<float>(c.directional_exponent), static_cast<float>(c.small_wave), c.seed, re, im);
}
inline void h0At(int i, int j, const OceanConfig& c, double* re, double* im) {
  kmath_d::ocean_h0(i, j, c.grid, c.patch_size, std::cos(c.wind_direction), std::sin(c.wind_direction), c.wind_speed,
                    c.gravity, c.phillips_a, c.directional_exponent, c.small_wave, c.seed, re, im);
}
inline float omegaOf(float k, float g, float d) { return kmath_f::ocean_omega(k, g, d); }
inline double omegaOf(double k, double g, double d) { return kmath_d::ocean_omega(k, g, d); }
inline float phaseOf(float w, float t, float T, float tau) { return kmath_f::ocean_phase(w, t, T, tau); }
inline double phaseOf(double w, double t, double T, double tau) { return kmath_d::ocean_phase(w, t, T, tau); }
inline void evolveOf(float a, float b, float c, float d, float ph, float* r, float* i) {
  kmath_f::ocean_evolve(a, b, c, d, ph, r, i);
}
inline void evolveOf(double a, double b, double c, double d, double ph, double* r, double* i) {
  kmath_d::ocean_evolve(a, b, c, d, ph, r, i);
}
inline void eigenOf(float a, float b, float c, float* m, float* p, float* x, float* z) {
  kmath_f::ocean_jacobian_eigen(a, b, c, m, p, x, z);
}
inline void eigenOf(double a, double b, double c, double* m, double* p, double* x, double* z) {
  kmath_d::ocean_jacobian_eigen(a, b, c, m, p, x, z);
}

// FFTW by precision: 4 batched N x N in-place inverse (e^{+ik·x}) transforms.
struct FftwPlanD {
  fftw_plan plan = nullptr;
  FftwPlanD(int n, std::complex<double>* data) {
    int dims[2] = {n, n};
    auto* p = reinterpret_cast<fftw_complex*>(data);
    plan = fftw_plan_many_dft(2, dims, 4, p, nullptr, 1, n * n, p, nullptr, 1, n * n, FFTW_BACKWARD, FFTW_ESTIMATE);
  }
  ~FftwPlanD() { if (plan) fftw_destroy_plan(plan); }
  void execute() { fftw_execute(plan); }
};
struct FftwPlanF {
  fftwf_plan plan = nullptr;
  FftwPlanF(int n, std::complex<float>* data) {
    int dims[2] = {n, n};
    auto* p = reinterpret_cast<fftwf_complex*>(data);
    plan = fftwf_plan_many_dft(2, dims, 4, p, nullptr, 1, n * n, p, nullptr, 1, n * n, FFTW_BACKWARD, FFTW_ESTIMATE);
  }
  ~FftwPlanF() { if (plan) fftwf_destroy_plan(plan); }
  void execute() { fftwf_execute(plan); }
};
template <class T> struct FftwFor;
template <> struct FftwFor<double> { using type = FftwPlanD; };
template <> struct FftwFor<float> { using type = FftwPlanF; };

}  // namespace

struct OceanCpuImpl {
  virtual ~OceanCpuImpl() = default;
  virtual void run(double time_s) = 0;
  virtual std::vector<std::complex<double>> h0() const = 0;
  // which: 0 height, 1 slope, 2 displacement, 3 normal, 4 jacobian, 5 folding, 6 fields
  virtual std::vector<double> get(int which) const = 0;
};

namespace {

template <class T>
struct Core : OceanCpuImpl {
  using C = std::complex<T>;
  OceanConfig cfg;
  int n;
  bool direct;
  std::vector<C> h0v, fields;  // fields: 4 slots of N²
  std::vector<T> height, slope, displacement, normal, jacobian, folding;
  std::unique_ptr<typename FftwFor<T>::type> fftw;
  std::vector<std::complex<double>> twiddle;  // e^{+2πi m/N}, direct DFT

  Core(const OceanConfig& c, bool use_direct) : cfg(c), n(c.grid), direct(use_direct) {
    const size_t nn = static_cast<size_t>(n) * n;
    h0v.resize(nn);
    fields.resize(4 * nn);
    height.resize(nn);
    slope.resize(2 * nn);
    displacement.resize(4 * nn);
    normal.resize(4 * nn);
    jacobian.resize(nn);
    folding.resize(4 * nn);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        T re, im;
        h0At(i, j, cfg, &re, &im);
        h0v[static_cast<size_t>(j) * n + i] = C(re, im);
      }
    if (direct) {
      twiddle.resize(n);
      for (int m = 0; m < n; ++m) twiddle[m] = std::polar(1.0, 2.0 * std::numbers::pi * m / n);
    } else {
      fftw = std::make_unique<typename FftwFor<T>::type>(n, fields.data());
      if (!fftw->plan) throw RuntimeError("ocean CPU reference: FFTW could not plan " + std::to_string(n) + "²");
    }
  }

  void run(double time_s) override {
    const size_t nn = static_cast<size_t>(n) * n;
    double tau = 0.0;
    if (cfg.loop_period > 0) {
      tau = std::fmod(time_s, cfg.loop_period) / cfg.loop_period;
      if (tau < 0) tau += 1.0;
    }
    const T dk = static_cast<T>(2.0 * std::numbers::pi / cfg.patch_size);
    const T t = static_cast<T>(time_s), T_loop = static_cast<T>(cfg.loop_period), tau_t = static_cast<T>(tau);
    const T g = static_cast<T>(cfg.gravity), depth = static_cast<T>(cfg.depth);
    // Evolution and packing, exactly as ocean_evolve_fields in ocean.cl.
    tbb::parallel_for(tbb::blocked_range<int>(0, n), [&](const tbb::blocked_range<int>& rows) {
      for (int j = rows.begin(); j < rows.end(); ++j)
        for (int i = 0; i < n; ++i) {
          const T kx = dk * static_cast<T>(kmath_d::ocean_wave_index(i, n));
          const T kz = dk * static_cast<T>(kmath_d::ocean_wave_index(j, n));
          const T k = std::sqrt(kx * kx + kz * kz);
          const C a = h0v[static_cast<size_t>(j) * n + i];
          const C b = h0v[static_cast<size_t>((n - j) & (n - 1)) * n + ((n - i) & (n - 1))];
          const T phase = phaseOf(omegaOf(k, g, depth), t, T_loop, tau_t);
          T hr, hi;
          evolveOf(a.real(), a.imag(), b.real(), b.imag(), phase, &hr, &hi);
          const C h(hr, hi), ih(-hi, hr), I(0, 1);
          const T inv_k = k > 0 ? T(1) / k : T(0);
          const C slope_x = kx * ih, slope_z = kz * ih;
          const C disp_x = (kx * inv_k) * ih, disp_z = (kz * inv_k) * ih;
          const C dxx = -(kx * kx * inv_k) * h, dzz = -(kz * kz * inv_k) * h, dxz = -(kx * kz * inv_k) * h;
          const size_t at = static_cast<size_t>(j) * n + i;
          fields[at] = h + I * slope_x;
          fields[nn + at] = slope_z + I * disp_x;
          fields[2 * nn + at] = disp_z + I * dxx;
          fields[3 * nn + at] = dzz + I * dxz;
        }
    });
    if (direct) directInverse(); else fftw->execute();
    maps();
  }

  // Separable direct DFT in double: rows then columns, f(x) = Σ F(k) e^{+2πi k x/N}.
  void directInverse() {
    const size_t nn = static_cast<size_t>(n) * n;
    std::vector<std::complex<double>> line(n), out(n);
    for (int s = 0; s < 4; ++s) {
      C* f = fields.data() + s * nn;
      for (int pass = 0; pass < 2; ++pass)
        for (int r = 0; r < n; ++r) {
          auto idx = [&](int q) { return pass == 0 ? static_cast<size_t>(r) * n + q : static_cast<size_t>(q) * n + r; };
          for (int q = 0; q < n; ++q) line[q] = std::complex<double>(f[idx(q)]);
          for (int x = 0; x < n; ++x) {
            std::complex<double> acc = 0;
            for (int q = 0; q < n; ++q) acc += line[q] * twiddle[(static_cast<size_t>(q) * x) % n];
            out[x] = acc;
          }
          for (int x = 0; x < n; ++x) f[idx(x)] = C(static_cast<T>(out[x].real()), static_cast<T>(out[x].imag()));
        }
    }
  }

  // As ocean_maps in ocean.cl.
  void maps() {
    const size_t nn = static_cast<size_t>(n) * n;
    const T lambda = static_cast<T>(cfg.choppiness);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, nn), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t at = r.begin(); at < r.end(); ++at) {
        const C f0 = fields[at], f1 = fields[nn + at], f2 = fields[2 * nn + at], f3 = fields[3 * nn + at];
        const T h = f0.real(), hx = f0.imag(), hz = f1.real(), dx = f1.imag(), dz = f2.real();
        const T jxx = 1 + lambda * f2.imag(), jzz = 1 + lambda * f3.real(), jxz = lambda * f3.imag();
        height[at] = h;
        slope[2 * at] = hx;
        slope[2 * at + 1] = hz;
        displacement[4 * at] = lambda * dx;
        displacement[4 * at + 1] = h;
        displacement[4 * at + 2] = lambda * dz;
        displacement[4 * at + 3] = 0;
        // ∂P/∂z × ∂P/∂x with ∂P/∂x = (jxx, hx, jxz), ∂P/∂z = (jxz, hz, jzz).
        T cx = hz * jxz - jzz * hx, cy = jzz * jxx - jxz * jxz, cz = jxz * hx - hz * jxx;
        const T len = std::sqrt(cx * cx + cy * cy + cz * cz);
        if (len > 0) { cx /= len; cy /= len; cz /= len; } else { cx = 0; cy = 1; cz = 0; }
        normal[4 * at] = cx;
        normal[4 * at + 1] = cy;
        normal[4 * at + 2] = cz;
        normal[4 * at + 3] = 0;
        jacobian[at] = jxx * jzz - jxz * jxz;
        eigenOf(jxx, jzz, jxz, &folding[4 * at], &folding[4 * at + 1], &folding[4 * at + 2], &folding[4 * at + 3]);
      }
    });
  }

  std::vector<std::complex<double>> h0() const override { return {h0v.begin(), h0v.end()}; }

  std::vector<double> get(int which) const override {
    switch (which) {
      case 0: return {height.begin(), height.end()};
      case 1: return {slope.begin(), slope.end()};
      case 2: return {displacement.begin(), displacement.end()};
      case 3: return {normal.begin(), normal.end()};
      case 4: return {jacobian.begin(), jacobian.end()};
      case 5: return {folding.begin(), folding.end()};
      default: {
        std::vector<double> out(2 * fields.size());
        for (size_t i = 0; i < fields.size(); ++i) {
          out[2 * i] = fields[i].real();
          out[2 * i + 1] = fields[i].imag();
        }
        return out;
      }
    }
  }
};

}  // namespace

OceanCpu::OceanCpu(const OceanConfig& config, Precision precision, Transform transform) : config_(config) {
  validateOceanConfig(config_);
  const bool direct = transform == Transform::DirectDft || (transform == Transform::Auto && config_.grid <= 64);
  if (precision == Precision::Double) impl_ = std::make_unique<Core<double>>(config_, direct);
  else impl_ = std::make_unique<Core<float>>(config_, direct);
}

OceanCpu::~OceanCpu() = default;

void OceanCpu::run(double time_s) { impl_->run(time_s); }
std::vector<std::complex<double>> OceanCpu::h0() const { return impl_->h0(); }
std::vector<double> OceanCpu::height() const { return impl_->get(0); }
std::vector<double> OceanCpu::slope() const { return impl_->get(1); }
std::vector<double> OceanCpu::displacement() const { return impl_->get(2); }
std::vector<double> OceanCpu::normal() const { return impl_->get(3); }
std::vector<double> OceanCpu::jacobian() const { return impl_->get(4); }
std::vector<double> OceanCpu::folding() const { return impl_->get(5); }
std::vector<double> OceanCpu::fields() const { return impl_->get(6); }

}  // namespace seasim
