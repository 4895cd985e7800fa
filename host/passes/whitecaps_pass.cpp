#include "passes/whitecaps_pass.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "device/enqueue.h"
#include "geometry/kernel_camera.h"
#include "passes/whitecaps_features.h"
#include "passes/whitecaps_math.h"
#include "sky/sky_light.h"
#include "util/error.h"

namespace seasim {

static_assert(sizeof(WhitecapsParams) == 112, "WhitecapsParams must stay 112 bytes (common/whitecaps_params.h)");
static_assert(offsetof(WhitecapsParams, foam_rgb) == 64);
static_assert(offsetof(WhitecapsParams, tan_half_fov_y) == 80);
static_assert(offsetof(WhitecapsParams, ocean_n) == 96);
static_assert(offsetof(WhitecapsParams, band_count) == 108);

std::vector<double> foamRadianceBands(const Scene& scene, const WavelengthGrid& grid) {
  const SkyLight light = makeSkyLight(scene, grid);
  const std::vector<double> sky = light.horizontalIrradiance();
  const double sun_cos = std::max(light.sun_dir[1], 0.0);
  std::vector<double> out(grid.size());
  for (size_t i = 0; i < grid.size(); ++i) {
    const double e_d = light.sun_irradiance[i] * sun_cos + sky[i];
    out[i] = whitecaps_d::whitecaps_reflectance(grid.centers_nm[i]) * e_d / M_PI;
  }
  return out;
}

WhitecapsPass::WhitecapsPass(Device& device, const Scene& scene, const PassPlan& plan, const WavelengthGrid& grid,
                             const Sensor& sensor, int ocean_n, double ocean_patch)
    : device_(device), spectral_output_(plan.featuresAs<WhitecapsFeatures>().spectral_output) {
  const CameraDesc& cam = scene.camera;
  WhitecapsParams& p = params_;
  setKernelCameraView(p, cam);
  p.aspect = static_cast<float>(cam.width) / static_cast<float>(cam.height);
  p.ocean_patch = static_cast<float>(ocean_patch);
  p.ocean_n = ocean_n;
  p.width = cam.width;
  p.height = cam.height;
  p.band_count = static_cast<int>(grid.size());
  const std::vector<double> foam = foamRadianceBands(scene, grid);
  const std::array<double, 3> foam_rgb = sensor.apply(foam.data());
  for (int c = 0; c < 3; ++c) p.foam_rgb[c] = static_cast<float>(foam_rgb[c]);
  foam_bands_.assign(foam.begin(), foam.end());
  levels_ = whitecaps_d::whitecaps_levels(ocean_n);
  const size_t mip_floats = static_cast<size_t>(whitecaps_d::whitecaps_level_offset(ocean_n, levels_));
  onDevice("whitecaps pass set-up", [&] {
    const cl::Program& program = device.program(plan.kernel_file, plan.defines).program;
    mask_ = cl::Kernel(program, "whitecaps_mask_texels");
    downsample_ = cl::Kernel(program, "whitecaps_downsample");
    over_sea_ = cl::Kernel(program, "whitecaps_over_sea");
    params_buffer_ = cl::Buffer(device.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof p, &p);
    mips_ = cl::Buffer(device.context(), CL_MEM_READ_WRITE, sizeof(float) * mip_floats);
    rank_buffer_ = cl::Buffer(device.context(), CL_MEM_READ_ONLY, sizeof(float) * WHITECAPS_RANK_NODES);
    foam_buffer_ = cl::Buffer(device.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                              sizeof(float) * std::max<size_t>(foam_bands_.size(), 1), foam_bands_.data());
  });
}

void WhitecapsPass::moveCamera(const CameraDesc& cam) {
  if (cam.width != params_.width || cam.height != params_.height) {
    throw RuntimeError("whitecaps pass: the image size changed without a new set-up (camera.width and "
                       "camera.height are among the keys that set this pass up again)");
  }
  setKernelCameraView(params_, cam);
  onDevice("whitecaps pass (moving the camera)", [&] {
    device_.queue().enqueueWriteBuffer(params_buffer_, CL_TRUE, 0, sizeof params_, &params_);
  });
}

double WhitecapsPass::run(const cl::Buffer& jacobian, const WhitecapsFoamLevels& levels, cl::Buffer& rgb,
                          cl::Buffer* spectral) {
  const double ms = updateFoam(jacobian, levels);
  return ms + composite(rgb, spectral);
}

double WhitecapsPass::updateFoam(const cl::Buffer& jacobian, const WhitecapsFoamLevels& levels) {
  const size_t n = static_cast<size_t>(params_.ocean_n);
  double ms = 0;
  onDevice("whitecaps pass", [&] {
    device_.queue().enqueueWriteBuffer(rank_buffer_, CL_TRUE, 0, sizeof(float) * WHITECAPS_RANK_NODES,
                                       levels.rank_j.data());
    mask_.setArg(0, params_buffer_);
    mask_.setArg(1, jacobian);
    mask_.setArg(2, levels.threshold);
    mask_.setArg(3, rank_buffer_);
    mask_.setArg(4, mips_);
  });
  ms += runKernel2d(device_, "whitecaps pass", mask_, n, n);
  for (int level = 0; level + 1 < levels_; ++level) {
    onDevice("whitecaps pass", [&] {
      downsample_.setArg(0, params_buffer_);
      downsample_.setArg(1, mips_);
      downsample_.setArg(2, level);
    });
    const size_t m = n >> (level + 1);
    ms += runKernel2d(device_, "whitecaps pass", downsample_, m, m);
  }
  return ms;
}

double WhitecapsPass::composite(cl::Buffer& rgb, cl::Buffer* spectral) {
  if (spectral_output_ && !spectral)
    throw RuntimeError("whitecaps pass: the plan has spectral output (SEASIM_SPECTRAL_OUTPUT=1) but no spectral image "
                       "was given");
  onDevice("whitecaps pass", [&] {
    over_sea_.setArg(0, params_buffer_);
    over_sea_.setArg(1, mips_);
    over_sea_.setArg(2, foam_buffer_);
    over_sea_.setArg(3, rgb);
    // Without spectral output the kernel does not touch its last argument: the rgb buffer stands in.
    over_sea_.setArg(4, spectral_output_ ? *spectral : rgb);
  });
  return runKernel2d(device_, "whitecaps pass", over_sea_, static_cast<size_t>(params_.width),
                     static_cast<size_t>(params_.height));
}

std::vector<float> WhitecapsPass::readMips() {
  std::vector<float> out(static_cast<size_t>(whitecaps_d::whitecaps_level_offset(params_.ocean_n, levels_)));
  onDevice("whitecaps pass (reading the mask's mips)", [&] {
    device_.queue().enqueueReadBuffer(mips_, CL_TRUE, 0, sizeof(float) * out.size(), out.data());
  });
  return out;
}

}  // namespace seasim
