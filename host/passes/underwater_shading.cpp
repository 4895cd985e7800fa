#include "passes/underwater_shading.h"

#include "device/enqueue.h"
#include "util/error.h"

namespace seasim {

UnderwaterShading::UnderwaterShading(Device& device, const PassPlan& kd, const UnderwaterSetupBuffers& setup,
                                     const UnderwaterGBuffer& gbuffer)
    : device_(device), width_(setup.setup.params.width), height_(setup.setup.params.height),
      features_(kd.featuresAs<KdFeatures>()), setup_(setup), gbuffer_(gbuffer) {
  const size_t pixels = static_cast<size_t>(width_) * static_cast<size_t>(height_);
  const size_t bands = setup.setup.bands.size();
  onDevice("kd_multiple pass set-up", [&] {
    auto buffer = [&](size_t floats) { return cl::Buffer(device.context(), CL_MEM_READ_WRITE, sizeof(float) * floats); };
    kernel_ = cl::Kernel(device.program(kd.kernel_file, kd.defines).program, "kd_multiple");
    rgb_ = buffer(3 * pixels);
    if (features_.spectral_output) spectral_ = buffer(pixels * bands);
    if (features_.point_spread) {
      // The forward light's moments (common/water_spread_params.h): F and F E per channel, F D and F per pixel.
      forward_.rgb = buffer(pixels * 2 * 3);
      forward_.depth = buffer(pixels * 2);
      if (features_.spectral_output) forward_.spectral = buffer(pixels * 2 * bands);
    }
    // The ground-truth layers kd_multiple.cl writes (its header gives the layout).
    if (features_.formation_layers) {
      formation_ = buffer(pixels * 12);
      forward_layer_ = buffer(pixels * 3);
      lamps_layer_ = buffer(pixels * 3);
    }
    if (features_.veiling_layer) veiling_ = buffer(pixels * 3);
    lamps_split_floats_ = pixels * 3 * static_cast<size_t>(features_.lamps_split_layers);
    if (lamps_split_floats_ > 0) lamps_split_ = buffer(lamps_split_floats_);
    if (features_.band_layers) {
      band_layers_ = buffer(pixels * 5 * bands);
      forward_bands_ = buffer(pixels * bands);
    }
    if (features_.veiling_bands) veiling_bands_ = buffer(pixels * bands);
  });
}

double UnderwaterShading::run(const cl::Buffer* froxel_params, const cl::Buffer* froxel_volume,
                              const UnderwaterSandShare* sand) {
  if (lamps_split_floats_ > 0)  // underwater_lamps adds into it (and leaves it 0 without lamps)
    onDevice("zeroing the lamps' split layers", [&] {
      device_.queue().enqueueFillBuffer(lamps_split_, 0.0f, 0, sizeof(float) * lamps_split_floats_);
    });
  onDevice("kd_multiple arguments", [&] {
    cl_uint arg = 0;
    kernel_.setArg(arg++, setup_.params);
    kernel_.setArg(arg++, setup_.bands);
    kernel_.setArg(arg++, setup_.albedo);
    kernel_.setArg(arg++, setup_.band_table);
    kernel_.setArg(arg++, setup_.objects);
    kernel_.setArg(arg++, gbuffer_.geometry);
    kernel_.setArg(arg++, gbuffer_.material);
    kernel_.setArg(arg++, gbuffer_.visibility);
    kernel_.setArg(arg++, setup_.sky_params);
    kernel_.setArg(arg++, setup_.sky);
    if (froxel_params && froxel_volume) {
      kernel_.setArg(arg++, *froxel_params);
      kernel_.setArg(arg++, *froxel_volume);
    }
    if (features_.sand_map) {
      if (!sand) throw RuntimeError("kd_multiple: planned with the sand's share lattice, run without it");
      kernel_.setArg(arg++, sand->map);
      kernel_.setArg(arg++, static_cast<cl_int>(sand->width));
      kernel_.setArg(arg++, static_cast<cl_int>(sand->height));
      kernel_.setArg(arg++, static_cast<cl_int>(sand->step));
    }
    kernel_.setArg(arg++, rgb_);
    if (features_.spectral_output) kernel_.setArg(arg++, spectral_);
    if (features_.point_spread) {
      kernel_.setArg(arg++, forward_.rgb);
      kernel_.setArg(arg++, forward_.depth);
      if (features_.spectral_output) kernel_.setArg(arg++, forward_.spectral);
    }
    if (features_.formation_layers) {
      kernel_.setArg(arg++, formation_);
      kernel_.setArg(arg++, forward_layer_);
      kernel_.setArg(arg++, lamps_layer_);
    }
    if (features_.veiling_layer) kernel_.setArg(arg++, veiling_);
    if (features_.band_layers) {
      kernel_.setArg(arg++, band_layers_);
      kernel_.setArg(arg++, forward_bands_);
    }
    if (features_.veiling_bands) kernel_.setArg(arg++, veiling_bands_);
  });
  return runKernel2d(device_, "kd_multiple", kernel_, width_, height_);
}

}  // namespace seasim
