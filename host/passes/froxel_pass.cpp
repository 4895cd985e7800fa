#include "passes/froxel_pass.h"

#include "device/enqueue.h"
#include "passes/caustic_stack.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>

#include "math/kernel_math.h"
#include "util/error.h"

namespace seasim {

// The kernels read this struct with OpenCL C layout; float/int are 4 bytes on both sides.
static_assert(sizeof(FroxelParams) == 6 * 16 + 8 * 4 + 8 * 4, "FroxelParams layout changed: update froxel.h users");
static_assert(offsetof(FroxelParams, sigma_t_rgb) == 48);
static_assert(offsetof(FroxelParams, z_near) == 96);
static_assert(offsetof(FroxelParams, shadow_bias) == 112);
static_assert(offsetof(FroxelParams, nx) == 128);
static_assert(offsetof(FroxelParams, injection) == 144);

namespace {

// Makes `defines` hold NAME=value: adds it when missing, throws when the caller set another value.
void requireDefine(std::vector<std::string>& defines, const std::string& name, int value) {
  const std::string want = name + "=" + std::to_string(value);
  for (const std::string& d : defines) {
    if (d == want) return;
    if (d == name || d.rfind(name + "=", 0) == 0) {
      throw RuntimeError("froxel pass: define " + d + " disagrees with the scene (" + want +
                         "); the plan and the scene must come from the same file");
    }
  }
  defines.push_back(want);
}


// What froxel_shadow_map reads, as bytes: the sun's direction in the water and the object count
// (UwParams), the map's frame, extent, bias and size (FroxelParams), and the objects.
std::string shadowMapInputs(const UnderwaterSetup& setup, const FroxelParams& fp) {
  std::string key;
  const auto put = [&](const void* data, size_t bytes) { key.append(static_cast<const char*>(data), bytes); };
  put(setup.params.sun_dir_water, sizeof(setup.params.sun_dir_water));
  put(&setup.params.object_count, sizeof(setup.params.object_count));
  put(fp.shadow_origin, sizeof(fp.shadow_origin));
  put(fp.shadow_right, sizeof(fp.shadow_right));
  put(fp.shadow_up, sizeof(fp.shadow_up));
  put(&fp.shadow_half_extent, sizeof(fp.shadow_half_extent));
  put(&fp.shadow_bias, sizeof(fp.shadow_bias));
  put(&fp.shadow_size, sizeof(fp.shadow_size));
  put(setup.objects.data(), sizeof(UwObject) * setup.objects.size());
  return key;
}

}  // namespace

FroxelPass::FroxelPass(Device& device, const Scene& scene, const UnderwaterSetup& setup,
                       const std::vector<std::string>& defines)
    : FroxelPass(device, setup, froxelConfigFromScene(scene), defines) {}

FroxelPass::FroxelPass(Device& device, const UnderwaterSetup& setup, const FroxelConfig& config,
                       const std::vector<std::string>& defines)
    : device_(device), fp_(makeFroxelParams(setup, config)), defines_(defines) {
  requireDefine(defines_, "SEASIM_HAS_OBJECTS", setup.params.object_count > 0 ? 1 : 0);
  requireDefine(defines_, "SEASIM_CAUSTICS", setup.params.caustic_mode);
  requireDefine(defines_, "SEASIM_SPECTRAL_INJECTION", config.rgb_injection ? 0 : 1);

  shadow_key_ = shadowMapInputs(setup, fp_);
  const std::vector<UwBand> bands = froxelIntegrationBands(setup, fp_);
  const std::vector<float> column_dy = froxelColumnDy(setup, fp_);
  const size_t froxels = size_t(fp_.nx) * fp_.ny * fp_.nz;
  const size_t texels = fp_.shadow_size > 0 ? size_t(fp_.shadow_size) * fp_.shadow_size : 1;
  const cl_mem_flags in = CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR;
  onDevice("froxel pass set-up", [&] {
    const BuiltProgram& built = device.program("froxel.cl", defines_);
    shadow_kernel_ = cl::Kernel(built.program, "froxel_shadow_map");
    inject_kernel_ = cl::Kernel(built.program, "froxel_inject");
    extent_kernel_ = cl::Kernel(built.program, "froxel_column_extent");
    integrate_kernel_ = cl::Kernel(built.program, "froxel_integrate");
    resolve_kernel_ = cl::Kernel(built.program, "froxel_resolve");
    params_ = cl::Buffer(device.context(), in, sizeof(UwParams), const_cast<UwParams*>(&setup.params));
    fparams_ = cl::Buffer(device.context(), in, sizeof(FroxelParams), &fp_);
    objects_ = cl::Buffer(device.context(), in, sizeof(UwObject) * setup.objects.size(),
                          const_cast<UwObject*>(setup.objects.data()));
    bands_ = cl::Buffer(device.context(), in, sizeof(UwBand) * bands.size(), const_cast<UwBand*>(bands.data()));
    map_ = cl::Buffer(device.context(), CL_MEM_READ_WRITE, sizeof(float) * texels);
    no_caustics_ = noCausticMap(device);
    // The caustic textures' feature points (common/caustic_texture.h): constant, so filled here once.
    std::vector<float> caustic_table(CAUSTIC_TABLE_REALS);
    kmath_f::caustic_fill_table(caustic_table.data());
    caustic_table_ = cl::Buffer(device.context(), in, sizeof(float) * caustic_table.size(), caustic_table.data());
    light_ = cl::Buffer(device.context(), CL_MEM_READ_WRITE, sizeof(float) * froxels);
    column_last_ = cl::Buffer(device.context(), CL_MEM_READ_WRITE, sizeof(cl_int) * size_t(fp_.nx) * fp_.ny);
    column_dy_ = cl::Buffer(device.context(), in, sizeof(float) * column_dy.size(), const_cast<float*>(column_dy.data()));
    volume_ = cl::Buffer(device.context(), CL_MEM_READ_WRITE, sizeof(float) * 4 * froxels);
    shadow_kernel_.setArg(0, params_);
    shadow_kernel_.setArg(1, fparams_);
    shadow_kernel_.setArg(2, objects_);
    shadow_kernel_.setArg(3, map_);
    inject_kernel_.setArg(0, params_);
    inject_kernel_.setArg(1, fparams_);
    inject_kernel_.setArg(2, objects_);
    inject_kernel_.setArg(3, map_);
    inject_kernel_.setArg(4, no_caustics_);
    inject_kernel_.setArg(5, light_);
    inject_kernel_.setArg(6, caustic_table_);
    inject_kernel_.setArg(7, column_last_);
    extent_kernel_.setArg(0, fparams_);
    extent_kernel_.setArg(1, column_dy_);
    extent_kernel_.setArg(5, column_last_);
    integrate_kernel_.setArg(0, params_);
    integrate_kernel_.setArg(1, fparams_);
    integrate_kernel_.setArg(2, bands_);
    integrate_kernel_.setArg(3, light_);
    integrate_kernel_.setArg(4, volume_);
    integrate_kernel_.setArg(5, column_dy_);
    resolve_kernel_.setArg(0, fparams_);
    resolve_kernel_.setArg(1, volume_);
  });
}

double FroxelPass::run(const cl::Buffer* caustic_maps, const cl::Buffer* geom, int width, int height) {
  timings_.clear();
  onDevice("froxel pass", [&] {
    inject_kernel_.setArg(4, caustic_maps ? *caustic_maps : no_caustics_);
    auto enqueue = [&](cl::Kernel& kernel, const cl::NDRange& global, const cl::NDRange& local, const char* name) {
      timings_.push_back({name, runKernel(device_, "froxel", kernel, global, local)});
    };
    // The last slice each column needs: from the pixels' reads with a G-buffer, else every slice.
    const cl_int all = geom ? -1 : fp_.nz - 1;
    device_.queue().enqueueFillBuffer(column_last_, all, 0, sizeof(cl_int) * size_t(fp_.nx) * fp_.ny);
    if (geom) {
      extent_kernel_.setArg(2, *geom);
      extent_kernel_.setArg(3, width);
      extent_kernel_.setArg(4, height);
      enqueue(extent_kernel_, cl::NDRange(roundUp(size_t(width), 8), roundUp(size_t(height), 8)), cl::NDRange(8, 8),
              "froxel_column_extent");
    }
    if (fp_.shadow_size > 0 && !shadow_map_ready_) {
      const size_t n = roundUp(size_t(fp_.shadow_size), 8);
      enqueue(shadow_kernel_, cl::NDRange(n, n), cl::NDRange(8, 8), "froxel_shadow_map");
      shadow_map_ready_ = true;
    }
    enqueue(inject_kernel_, cl::NDRange(roundUp(fp_.nx, 8), roundUp(fp_.ny, 8)), cl::NDRange(8, 8), "froxel_inject");
    enqueue(integrate_kernel_, cl::NDRange(roundUp(fp_.nx, 8), roundUp(fp_.ny, 8)), cl::NDRange(8, 8), "froxel_integrate");
  });
  double total = 0;
  for (const PassTiming& t : timings_) total += t.ms;
  return total;
}

double FroxelPass::resolve(const cl::Buffer& geom, int width, int height, cl::Buffer& rgb) {
  onDevice("froxel pass: resolve", [&] {
    resolve_kernel_.setArg(2, geom);
    resolve_kernel_.setArg(3, width);
    resolve_kernel_.setArg(4, height);
    resolve_kernel_.setArg(5, rgb);
  });
  return runKernel2d(device_, "froxel", resolve_kernel_, size_t(width), size_t(height));
}


void FroxelPass::read(cl::Buffer& buffer, size_t floats, std::vector<float>& out, const char* what) {
  out.resize(floats);
  if (floats == 0) return;
  onDevice(std::string("froxel pass: reading the ") + what + " back",
           [&] { device_.queue().enqueueReadBuffer(buffer, CL_TRUE, 0, sizeof(float) * floats, out.data()); });
}

void FroxelPass::readVolume(std::vector<float>& out) {
  read(volume_, 4 * size_t(fp_.nx) * fp_.ny * fp_.nz, out, "volume");
}

void FroxelPass::readLight(std::vector<float>& out) { read(light_, size_t(fp_.nx) * fp_.ny * fp_.nz, out, "light"); }

void FroxelPass::adoptShadowMap(const cl::Buffer& map) {
  onDevice("froxel pass: the kept shadow map", [&] {
    map_ = map;
    shadow_kernel_.setArg(3, map_);
    inject_kernel_.setArg(3, map_);
  });
  shadow_map_ready_ = true;
}

void FroxelPass::readShadowMap(std::vector<float>& out) {
  read(map_, fp_.shadow_size > 0 ? size_t(fp_.shadow_size) * fp_.shadow_size : 0, out, "shadow map");
}

}  // namespace seasim
