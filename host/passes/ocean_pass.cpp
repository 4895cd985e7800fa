#include "passes/ocean_pass.h"

#include <chrono>
#include <cmath>
#include <cstddef>
#include <string>

#include "device/enqueue.h"
#include "util/error.h"

extern "C" {
#include "common/ocean_params.h"
}

namespace seasim {

static_assert(sizeof(OceanParams) == 16 * 4, "OceanParams layout changed: update ocean_params.h users");
static_assert(offsetof(OceanParams, loop_phase) == 40);
static_assert(offsetof(OceanParams, seed) == 52);
static_assert(offsetof(OceanParams, n) == 56);

OceanConfig oceanConfigFromSurface(const SurfaceDesc& s) {
  OceanConfig c;
  c.grid = s.grid;
  c.patch_size = s.patch_size;
  c.wind_speed = s.wind_speed;
  c.wind_direction = s.wind_direction;
  c.directional_exponent = s.directional_exponent;
  c.small_wave = s.small_wave;
  c.depth = s.depth;
  c.loop_period = s.loop_period;
  c.choppiness = s.choppiness;
  c.seed = s.seed;
  return c;
}

void validateOceanConfig(const OceanConfig& c) {
  auto bad = [](const std::string& what) { throw RuntimeError("ocean: " + what); };
  if (c.grid < 16 || c.grid > 2048 || (c.grid & (c.grid - 1)) != 0)
    bad("grid N = " + std::to_string(c.grid) + " must be a power of two from 16 to 2048");
  if (!(c.patch_size > 0) || !std::isfinite(c.patch_size)) bad("patch_size must be > 0 m");
  if (!(c.wind_speed >= 0) || !std::isfinite(c.wind_speed)) bad("wind_speed must be >= 0 m/s");
  if (!(c.phillips_a >= 0) || !std::isfinite(c.phillips_a)) bad("phillips_a must be >= 0");
  if (!(c.directional_exponent >= 0)) bad("directional_exponent must be >= 0");
  if (!(c.small_wave >= 0)) bad("small_wave must be >= 0 m");
  if (!(c.depth >= 0)) bad("depth must be >= 0 m (0 = deep water)");
  if (!(c.loop_period >= 0)) bad("loop_period must be >= 0 s (0 = no loop)");
  if (!std::isfinite(c.choppiness)) bad("choppiness must be finite");
  if (!(c.gravity > 0)) bad("gravity must be > 0");
}

namespace {

OceanParams makeParams(const OceanConfig& c) {
  OceanParams p{};
  p.patch_size = static_cast<float>(c.patch_size);
  p.wind_speed = static_cast<float>(c.wind_speed);
  p.wind_dir_x = static_cast<float>(std::cos(c.wind_direction));
  p.wind_dir_z = static_cast<float>(std::sin(c.wind_direction));
  p.phillips_a = static_cast<float>(c.phillips_a);
  p.directional_exponent = static_cast<float>(c.directional_exponent);
  p.small_wave = static_cast<float>(c.small_wave);
  p.depth = static_cast<float>(c.depth);
  p.loop_period = static_cast<float>(c.loop_period);
  p.choppiness = static_cast<float>(c.choppiness);
  p.gravity = static_cast<float>(c.gravity);
  p.seed = c.seed;
  p.n = c.grid;
  return p;
}

}  // namespace

OceanPass::OceanPass(Device& device, const OceanConfig& config) : device_(device), config_(config) {
  validateOceanConfig(config_);
  const size_t n = static_cast<size_t>(config_.grid);
  const size_t texels = n * n;
  const OceanParams p = makeParams(config_);
  onDevice("ocean pass set-up", [&] {
    const BuiltProgram& built = device.program("ocean.cl", {});
    init_ = cl::Kernel(built.program, "ocean_init");
    evolve_ = cl::Kernel(built.program, "ocean_evolve_fields");
    spectrum_ = cl::Kernel(built.program, "ocean_height_spectrum");
    maps_ = cl::Kernel(built.program, "ocean_maps");
    cl::Context& ctx = device.context();
    params_ = cl::Buffer(ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof p, const_cast<OceanParams*>(&p));
    h0_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, sizeof(float) * 2 * texels);
    fields_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, sizeof(float) * 2 * 4 * texels);
    height_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, sizeof(float) * texels);
    slope_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, sizeof(float) * 2 * texels);
    displacement_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, sizeof(float) * 4 * texels);
    normal_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, sizeof(float) * 4 * texels);
    jacobian_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, sizeof(float) * texels);
    folding_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, sizeof(float) * 4 * texels);

    init_.setArg(0, params_);
    init_.setArg(1, h0_);
    evolve_.setArg(0, params_);
    evolve_.setArg(1, h0_);
    evolve_.setArg(2, fields_);
    spectrum_.setArg(0, params_);
    spectrum_.setArg(1, h0_);
    maps_.setArg(0, params_);
    maps_.setArg(1, fields_);
    maps_.setArg(2, height_);
    maps_.setArg(3, slope_);
    maps_.setArg(4, displacement_);
    maps_.setArg(5, normal_);
    maps_.setArg(6, jacobian_);
    maps_.setArg(7, folding_);

    device.queue().enqueueNDRangeKernel(init_, cl::NullRange, cl::NDRange(n, n));
    device.queue().finish();
  });
  fft_ = std::make_unique<VkfftPlan>(device, fields_, config_.grid, 4);
}

OceanPass::~OceanPass() = default;

void OceanPass::setTime(double time_s) {
  OceanParams p = makeParams(config_);
  p.time = static_cast<float>(time_s);
  if (config_.loop_period > 0) {
    // τ = frac(t/T) in double, so that t and t + T give the same float (ocean_phase()).
    double tau = std::fmod(time_s, config_.loop_period) / config_.loop_period;
    if (tau < 0) tau += 1.0;
    p.loop_phase = static_cast<float>(tau);
  }
  device_.queue().enqueueWriteBuffer(params_, CL_TRUE, 0, sizeof p, &p);
}

double OceanPass::run(double time_s) {
  const auto start = std::chrono::steady_clock::now();
  const size_t n = static_cast<size_t>(config_.grid);
  onDevice("ocean pass run", [&] {
    setTime(time_s);
    device_.queue().enqueueNDRangeKernel(evolve_, cl::NullRange, cl::NDRange(n, n));
    fft_->inverse();
    device_.queue().enqueueNDRangeKernel(maps_, cl::NullRange, cl::NDRange(n, n));
    device_.queue().finish();
  });
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

std::vector<float> OceanPass::read(const cl::Buffer& buffer, size_t floats) {
  std::vector<float> out(floats);
  onDevice("ocean pass read-back", [&] {
    device_.queue().enqueueReadBuffer(buffer, CL_TRUE, 0, sizeof(float) * floats, out.data());
  });
  return out;
}

static size_t texelsOf(const OceanConfig& c) { return static_cast<size_t>(c.grid) * static_cast<size_t>(c.grid); }

std::vector<float> OceanPass::readHeight() { return read(height_, texelsOf(config_)); }
std::vector<float> OceanPass::readSlope() { return read(slope_, 2 * texelsOf(config_)); }
std::vector<float> OceanPass::readDisplacement() { return read(displacement_, 4 * texelsOf(config_)); }
std::vector<float> OceanPass::readNormal() { return read(normal_, 4 * texelsOf(config_)); }
std::vector<float> OceanPass::readJacobian() { return read(jacobian_, texelsOf(config_)); }

std::vector<float> readJacobian(Device& device, const OceanMaps& maps) {
  std::vector<float> out(texelsOf(maps.config));
  onDevice("ocean Jacobian read-back", [&] {
    device.queue().enqueueReadBuffer(maps.jacobian, CL_TRUE, 0, sizeof(float) * out.size(), out.data());
  });
  return out;
}
std::vector<float> OceanPass::readFolding() { return read(folding_, 4 * texelsOf(config_)); }
std::vector<float> OceanPass::readFields() { return read(fields_, 8 * texelsOf(config_)); }

static std::vector<std::complex<float>> toComplex(const std::vector<float>& v) {
  std::vector<std::complex<float>> out(v.size() / 2);
  for (size_t i = 0; i < out.size(); ++i) out[i] = {v[2 * i], v[2 * i + 1]};
  return out;
}

std::vector<std::complex<float>> OceanPass::readH0() { return toComplex(read(h0_, 2 * texelsOf(config_))); }

std::vector<std::complex<float>> OceanPass::heightSpectrum(double time_s) {
  const size_t n = static_cast<size_t>(config_.grid);
  onDevice("ocean pass height spectrum", [&] {
    if (!scratch_()) scratch_ = cl::Buffer(device_.context(), CL_MEM_READ_WRITE, sizeof(float) * 2 * n * n);
    setTime(time_s);
    spectrum_.setArg(2, scratch_);
    device_.queue().enqueueNDRangeKernel(spectrum_, cl::NullRange, cl::NDRange(n, n));
    device_.queue().finish();
  });
  return toComplex(read(scratch_, 2 * n * n));
}

std::vector<std::complex<float>> OceanPass::heightComplex(double time_s) {
  heightSpectrum(time_s);
  if (!scratch_fft_) scratch_fft_ = std::make_unique<VkfftPlan>(device_, scratch_, config_.grid, 1);
  onDevice("ocean pass height FFT", [&] {
    scratch_fft_->inverse();
    device_.queue().finish();
  });
  return toComplex(read(scratch_, 2 * texelsOf(config_)));
}

}  // namespace seasim
