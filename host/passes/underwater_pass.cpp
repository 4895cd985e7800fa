#include "passes/underwater_pass.h"

#include <algorithm>
#include <string>

#include "device/enqueue.h"
#include "passes/caustic_stack.h"
#include "passes/underwater_features.h"
#include "underwater/underwater_band_table.h"

#include "util/error.h"

namespace seasim {

UnderwaterPass::UnderwaterPass(Device& device, const UnderwaterSetup& setup, const PassPlan& raycast,
                               const PassPlan& kd, bool spectral_output)
    : device_(device), width_(setup.params.width), height_(setup.params.height), spectral_output_(spectral_output),
      band_count_(setup.bands.size()), object_count_(setup.objects.size()), albedo_count_(setup.albedo.size()),
      sky_count_(setup.sky_buffer.size()) {
  const size_t pixels = static_cast<size_t>(width_) * static_cast<size_t>(height_);
  const cl_mem_flags in = CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR;
  onDevice("underwater pass set-up", [&] {
    raycast_ = cl::Kernel(device.program(raycast.kernel_file, raycast.defines).program, "raycast");
    shade_ = cl::Kernel(device.program(kd.kernel_file, kd.defines).program, "kd_multiple");
    params_ = cl::Buffer(device.context(), in, sizeof(UwParams), const_cast<UwParams*>(&setup.params));
    bands_ = cl::Buffer(device.context(), in, sizeof(UwBand) * setup.bands.size(),
                        const_cast<UwBand*>(setup.bands.data()));
    objects_ = cl::Buffer(device.context(), in, sizeof(UwObject) * setup.objects.size(),
                          const_cast<UwObject*>(setup.objects.data()));
    albedo_ = cl::Buffer(device.context(), in, sizeof(float) * setup.albedo.size(),
                         const_cast<float*>(setup.albedo.data()));
    std::vector<float> band_table = underwaterBandTable(setup);
    band_table_count_ = band_table.size();
    band_table_ = cl::Buffer(device.context(), in, sizeof(float) * band_table.size(), band_table.data());
    sky_params_ = cl::Buffer(device.context(), in, sizeof(SkyParams), const_cast<SkyParams*>(&setup.sky_params));
    sky_ = cl::Buffer(device.context(), in, sizeof(float) * setup.sky_buffer.size(),
                      const_cast<float*>(setup.sky_buffer.data()));
    has_improved_ = !setup.improved.empty();  // its values are the band table's improved rows
    geom_ = cl::Buffer(device.context(), CL_MEM_READ_WRITE, sizeof(cl_float4) * pixels);
    material_ = cl::Buffer(device.context(), CL_MEM_READ_WRITE, sizeof(cl_int) * pixels);
    vis_ = cl::Buffer(device.context(), CL_MEM_READ_WRITE, sizeof(float) * pixels);
    no_caustics_ = noCausticMap(device);
    rgb_ = cl::Buffer(device.context(), CL_MEM_READ_WRITE, sizeof(float) * 3 * pixels);
    if (spectral_output)
      spectral_ = cl::Buffer(device.context(), CL_MEM_READ_WRITE, sizeof(float) * pixels * setup.bands.size());
    spread_ = kd.featuresAs<KdFeatures>().point_spread;
    if (spread_) {
      // The forward light's moments (common/water_spread_params.h): F and F E per channel, F D and F per pixel.
      forward_rgb_ = cl::Buffer(device.context(), CL_MEM_READ_WRITE, sizeof(float) * pixels * 2 * 3);
      forward_depth_ = cl::Buffer(device.context(), CL_MEM_READ_WRITE, sizeof(float) * pixels * 2);
      if (spectral_output)
        forward_spectral_ =
            cl::Buffer(device.context(), CL_MEM_READ_WRITE, sizeof(float) * pixels * 2 * setup.bands.size());
    }
    const KdFeatures& kd_features = kd.featuresAs<KdFeatures>();
    // The ground-truth layers kd_multiple.cl writes (its header gives the layout).
    if (kd_features.formation_layers) {
      formation_ = cl::Buffer(device.context(), CL_MEM_READ_WRITE, sizeof(float) * pixels * 12);
      forward_layer_ = cl::Buffer(device.context(), CL_MEM_READ_WRITE, sizeof(float) * pixels * 3);
      lamps_layer_ = cl::Buffer(device.context(), CL_MEM_READ_WRITE, sizeof(float) * pixels * 3);
    }
    if (kd_features.veiling_layer)
      veiling_ = cl::Buffer(device.context(), CL_MEM_READ_WRITE, sizeof(float) * pixels * 3);
    if (kd_features.band_layers) {
      band_layers_ = cl::Buffer(device.context(), CL_MEM_READ_WRITE, sizeof(float) * pixels * 5 * setup.bands.size());
      forward_bands_ = cl::Buffer(device.context(), CL_MEM_READ_WRITE, sizeof(float) * pixels * setup.bands.size());
    }
    if (kd_features.veiling_bands)
      veiling_bands_ = cl::Buffer(device.context(), CL_MEM_READ_WRITE, sizeof(float) * pixels * setup.bands.size());
    raycast_.setArg(0, params_);
    raycast_.setArg(1, objects_);
    raycast_.setArg(2, no_caustics_);
    raycast_.setArg(3, geom_);
    raycast_.setArg(4, material_);
    raycast_.setArg(5, vis_);
  });
}

void UnderwaterPass::update(const UnderwaterSetup& setup) {
  if (setup.bands.size() != band_count_ || setup.objects.size() != object_count_ ||
      setup.albedo.size() != albedo_count_ || setup.sky_buffer.size() != sky_count_ || setup.params.width != width_ ||
      setup.params.height != height_ || !setup.improved.empty() != has_improved_) {
    throw RuntimeError("underwater pass: the new set-up has other sizes (bands, objects, sky or image); make a new pass");
  }
  onDevice("underwater pass update", [&] {
    cl::CommandQueue& q = device_.queue();
    q.enqueueWriteBuffer(params_, CL_FALSE, 0, sizeof(UwParams), &setup.params);
    q.enqueueWriteBuffer(bands_, CL_FALSE, 0, sizeof(UwBand) * band_count_, setup.bands.data());
    q.enqueueWriteBuffer(objects_, CL_FALSE, 0, sizeof(UwObject) * object_count_, setup.objects.data());
    q.enqueueWriteBuffer(albedo_, CL_FALSE, 0, sizeof(float) * albedo_count_, setup.albedo.data());
    // Same size: same band and object counts, and the improved rows or not.
    const std::vector<float> band_table = underwaterBandTable(setup);
    q.enqueueWriteBuffer(band_table_, CL_FALSE, 0, sizeof(float) * band_table_count_, band_table.data());
    q.enqueueWriteBuffer(sky_params_, CL_FALSE, 0, sizeof(SkyParams), &setup.sky_params);
    q.enqueueWriteBuffer(sky_, CL_FALSE, 0, sizeof(float) * sky_count_, setup.sky_buffer.data());
    q.finish();  // the host vectors may go away after this call
  });
}

double UnderwaterPass::enqueue(cl::Kernel& kernel, const char* what) {
  return runKernel2d(device_, what, kernel, width_, height_);
}

double UnderwaterPass::runRaycast(const cl::Buffer* caustic_maps) {
  onDevice("raycast arguments", [&] {
    raycast_.setArg(2, caustic_maps ? *caustic_maps : no_caustics_);
  });
  return enqueue(raycast_, "raycast");
}

double UnderwaterPass::runShading(const cl::Buffer* froxel_params, const cl::Buffer* froxel_volume) {
  onDevice("kd_multiple arguments", [&] {
    cl_uint arg = 0;
    shade_.setArg(arg++, params_);
    shade_.setArg(arg++, bands_);
    shade_.setArg(arg++, albedo_);
    shade_.setArg(arg++, band_table_);
    shade_.setArg(arg++, objects_);
    shade_.setArg(arg++, geom_);
    shade_.setArg(arg++, material_);
    shade_.setArg(arg++, vis_);
    shade_.setArg(arg++, sky_params_);
    shade_.setArg(arg++, sky_);
    if (froxel_params && froxel_volume) {
      shade_.setArg(arg++, *froxel_params);
      shade_.setArg(arg++, *froxel_volume);
    }
    shade_.setArg(arg++, rgb_);
    if (spectral_output_) shade_.setArg(arg++, spectral_);
    if (spread_) {
      shade_.setArg(arg++, forward_rgb_);
      shade_.setArg(arg++, forward_depth_);
      if (spectral_output_) shade_.setArg(arg++, forward_spectral_);
    }
    if (formation_() != nullptr) {
      shade_.setArg(arg++, formation_);
      shade_.setArg(arg++, forward_layer_);
      shade_.setArg(arg++, lamps_layer_);
    }
    if (veiling_() != nullptr) shade_.setArg(arg++, veiling_);
    if (band_layers_() != nullptr) {
      shade_.setArg(arg++, band_layers_);
      shade_.setArg(arg++, forward_bands_);
    }
    if (veiling_bands_() != nullptr) shade_.setArg(arg++, veiling_bands_);
  });
  return enqueue(shade_, "kd_multiple");
}

}  // namespace seasim
