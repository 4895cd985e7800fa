#include "passes/sea_second_pass.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "device/enqueue.h"
#include "geometry/kernel_camera.h"
#include "device/kernel_source.h"
#include "math/kernel_math.h"
#include "passes/sea_heightfield.h"
#include "spectral/jerlov.h"
#include "util/error.h"
#include "util/hash.h"

extern "C" {
#include "common/sea_params.h"
#include "common/sea_second_params.h"
}

namespace seasim {

// The kernel reads this struct with OpenCL C layout; float/int are 4 bytes on both sides.
static_assert(sizeof(SeaSecondParams) == 5 * 16 + 8 * 4 + 8 * 4, "SeaSecondParams layout changed");
static_assert(offsetof(SeaSecondParams, tan_half_fov_y) == 80);
static_assert(offsetof(SeaSecondParams, width) == 112);
static_assert(offsetof(SeaSecondParams, vsf_size) == 140);
static_assert(sizeof(SeaBand) == 48, "SeaBand must stay 48 bytes");

namespace {

// A knob's value, or `automatic` when the scene says "auto".
int knob(const Scene& scene, const char* name, int automatic) {
  const auto it = scene.quality.find(name);
  if (it == scene.quality.end() || it->second.automatic) return automatic;
  return static_cast<int>(it->second.value);
}


}  // namespace

void SeaSecondPass::splitDirections(int n_d, int* n_theta, int* n_phi) {
  *n_theta = std::max(1, static_cast<int>(std::lround(std::sqrt(n_d / 2.0))));
  *n_phi = std::max(1, n_d / *n_theta);
}

SeaSecondPass::Config SeaSecondPass::configFromScene(const Scene& scene) {
  // "auto" knobs: placeholders (n_z = 8, n_d = 512, from our 000 §6.1 runs in results/sea/); the
  // per-scene search of quality/sea_auto.h replaces them through passes/auto_quality.h.
  Config c;
  c.n_z = knob(scene, "sea_nz", 8);
  splitDirections(knob(scene, "sea_nd", 512), &c.n_theta, &c.n_phi);
  // 000 §6.1: 32 x 32 maps for a flat bottom, 64 x 64 over a height field (§5.4).
  c.map_size = knob(scene, "sea_map_size", scene.bottom.type == BottomDesc::Type::HeightField ? 64 : 32);
  return c;
}

namespace {

// The bands' fields the second order reads (SeaBand): the sun, the water, the sensor's weights.
std::vector<SeaBand> secondOrderBands(const std::vector<double>& sun_e, const BandOptics& water, const Sensor& sensor) {
  std::vector<SeaBand> bands(sun_e.size());
  for (size_t i = 0; i < bands.size(); ++i) {
    SeaBand& b = bands[i];
    b.sun_irradiance = static_cast<float>(sun_e[i]);
    b.a = static_cast<float>(water.a[i]);
    b.b = static_cast<float>(water.b[i]);
    b.c = static_cast<float>(water.c[i]);
    b.w_r = static_cast<float>(sensor.to_r[i]);
    b.w_g = static_cast<float>(sensor.to_g[i]);
    b.w_b = static_cast<float>(sensor.to_b[i]);
  }
  return bands;
}

// The height field's depth tables' cache key: the floor, the camera's map rays, the directions and the
// table nodes (all in p), the kernel that computes them, the device, and how that kernel was built here
// (tables computed under another build must not be read back: relaxed maths on Intel's runtime once
// put them wrong, and the cache kept them).
uint64_t depthTableKey(Device& device, const PassPlan& plan, const SeaSecondParams& p, const HeightField& floor) {
  uint64_t key = fnv1a64(&p, sizeof p);
  key = fnv1a64(&floor.params, sizeof floor.params, key);
  key = fnv1a64(floor.depth.data(), sizeof(float) * floor.depth.size(), key);
  key = fnv1a64(assembleKernelSource(plan.kernel_file).text, key);
  key = fnv1a64(device.info().name + device.info().driver, key);
  return fnv1a64(device.buildOptions(plan.defines), key);
}

}  // namespace

SeaSecondPass::SeaSecondPass(Device& device, const Scene& scene, const PassPlan& plan, const Config& config,
                             const WavelengthGrid& grid, const Sensor& sensor, cl::Buffer& rgb, cl::Buffer* spectral)
    : device_(device), config_(config), width_(scene.camera.width), height_(scene.camera.height) {
  namespace k = kmath_d;
  const CameraDesc& cam = scene.camera;
  SeaSecondParams p{};
  setKernelCamera(p, cam);
  // Sun direction from zenith and azimuth (azimuth from +x towards +z), refracted into the water.
  const k::real3 sun{std::sin(scene.sun.zenith) * std::cos(scene.sun.azimuth), std::cos(scene.sun.zenith),
                     std::sin(scene.sun.zenith) * std::sin(scene.sun.azimuth)};
  const bool sun_up = scene.sun.enabled && scene.sun.irradiance > 0 && sun.y > 0;
  k::real3 sun_in_water{0, -1, 0};
  double cos_io = 1, sun_beam = 0;
  if (sun_up) {
    k::refract_dir(-sun, k::real3{0, 1, 0}, 1.0 / scene.water.ior, &sun_in_water);
    cos_io = std::max(-sun_in_water.y, 1e-4);
    // Beam irradiance below the surface per unit normal irradiance: E_h T_i / cos_io (sea_surface.h).
    sun_beam = sun.y * (1 - k::fresnel_reflectance(sun.y, 1.0, scene.water.ior)) / cos_io;
  }
  set4(p.sun_in_water, Vec3{sun_in_water.x, sun_in_water.y, sun_in_water.z});
  p.tan_half_fov_y = static_cast<float>(std::tan(cam.fov_y / 2));
  p.aspect = static_cast<float>(cam.width) / static_cast<float>(cam.height);
  p.ior = static_cast<float>(scene.water.ior);
  p.g = static_cast<float>(scene.water.g);
  p.bottom_depth = static_cast<float>(scene.bottom.depth);
  p.cos_io = static_cast<float>(cos_io);
  p.sun_beam = static_cast<float>(sun_beam);
  p.width = cam.width;
  p.height = cam.height;
  p.band_count = static_cast<int>(grid.centers_nm.size());
  p.n_z = config_.n_z;
  p.n_theta = config_.n_theta;
  p.n_phi = config_.n_phi;
  p.map_size = config_.map_size;
  p.vsf_size = config_.vsf_size;

  const BandOptics water = resolveWater(scene.water, grid);
  // 000 §5.4: over a height field the planes span the water down to the deepest node, and the
  // depth tables' nodes are the plane-cell walls of the clearest band (its planes reach deepest).
  const bool height_field = scene.bottom.type == BottomDesc::Type::HeightField;
  HeightField floor;
  if (height_field) {
    floor = loadHeightField(scene.bottom, scene.files.get());
    p.bottom_depth = floor.params.max_depth;
    double c_min = 1e30;
    for (double c : water.c) c_min = std::min(c_min, c);
    p.table_c = static_cast<float>(std::max(c_min, 1e-6));
  }
  const std::vector<double> sun_e = sunIrradianceBands(grid, scene.sun.irradiance);
  std::vector<SeaBand> bands = secondOrderBands(sun_e, water, sensor);
  const size_t nb = bands.size();
  // The kernels read bands and directions in rows padded to a multiple of their lanes
  // (sea_second_params.h): the padded bands are zero (c = 0, no sensor weight), so they add nothing.
  const size_t band_stride = SEA_SECOND_STRIDE(nb);
  bands.resize(std::max<size_t>(band_stride, 1), SeaBand{});

  const size_t n_d = static_cast<size_t>(config_.n_theta) * config_.n_phi;
  const size_t dir_stride = SEA_SECOND_STRIDE(n_d);
  const size_t M = static_cast<size_t>(config_.map_size);
  onDevice("sea_second pass set-up", [&] {
    const BuiltProgram& built = device.program(plan.kernel_file, plan.defines);
    vsf_kernel_ = cl::Kernel(built.program, "sea_second_vsf_map");
    radiance_kernel_ = cl::Kernel(built.program, "sea_second_radiance_map");
    maps_kernel_ = cl::Kernel(built.program, "sea_second_scattering_map");
    accumulate_kernel_ = cl::Kernel(built.program, "sea_second_accumulate");
    params_ = cl::Buffer(device.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof p, &p);
    bands_ = cl::Buffer(device.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(SeaBand) * bands.size(),
                        bands.data());
    vsf_ = cl::Buffer(device.context(), CL_MEM_READ_WRITE, sizeof(float) * config_.vsf_size);
    dirs_ = cl::Buffer(device.context(), CL_MEM_READ_WRITE, sizeof(float) * 4 * dir_stride);
    radiance_ = cl::Buffer(device.context(), CL_MEM_READ_WRITE, sizeof(float) * config_.n_z * n_d * nb);
    plane_w_ = cl::Buffer(device.context(), CL_MEM_READ_WRITE, sizeof(float) * config_.n_z * band_stride);
    plane_bands_ = cl::Buffer(device.context(), CL_MEM_READ_WRITE, sizeof(float) * 4 * config_.n_z * band_stride);
    maps_ = cl::Buffer(device.context(), CL_MEM_READ_WRITE, sizeof(float) * config_.n_z * M * M * band_stride);
    vsf_kernel_.setArg(0, params_);
    vsf_kernel_.setArg(1, vsf_);
    radiance_kernel_.setArg(0, params_);
    radiance_kernel_.setArg(1, bands_);
    radiance_kernel_.setArg(2, dirs_);
    radiance_kernel_.setArg(3, radiance_);
    radiance_kernel_.setArg(4, plane_w_);
    radiance_kernel_.setArg(5, plane_bands_);
    maps_kernel_.setArg(0, params_);
    maps_kernel_.setArg(1, bands_);
    maps_kernel_.setArg(2, dirs_);
    maps_kernel_.setArg(3, vsf_);
    maps_kernel_.setArg(4, radiance_);
    maps_kernel_.setArg(5, maps_);
    if (height_field) {
      const HeightFieldBuffers hf = uploadHeightField(device, floor);
      hf_params_ = hf.params;
      hf_depth_ = hf.depth;
      const size_t table_count = (static_cast<size_t>(config_.n_z) + 1) * M * M * dir_stride;
      table_ = cl::Buffer(device.context(), CL_MEM_READ_WRITE, sizeof(float) * table_count);
      table_kernel_ = cl::Kernel(built.program, "sea_second_depth_table");
      table_kernel_.setArg(0, params_);
      table_kernel_.setArg(1, hf_params_);
      table_kernel_.setArg(2, hf_depth_);
      table_kernel_.setArg(3, table_);
      maps_kernel_.setArg(6, table_);
      maps_kernel_.setArg(7, plane_bands_);
      const cl_uint args = accumulate_kernel_.getInfo<CL_KERNEL_NUM_ARGS>();
      accumulate_kernel_.setArg(args - 2, hf_params_);
      accumulate_kernel_.setArg(args - 1, hf_depth_);
      // The tables depend on the floor, the camera's map rays, the directions and the table nodes
      // (all in p), and on the kernel that computes them: computed once, cached on disk by that key.
      table_key_ = depthTableKey(device, plan, p, floor);
      if (const auto cached = loadDepthTable(table_key_, table_count)) {
        device.queue().enqueueWriteBuffer(table_, CL_TRUE, 0, sizeof(float) * table_count, cached->data());
        table_ready_ = true;
      }
    }
    accumulate_kernel_.setArg(0, params_);
    accumulate_kernel_.setArg(1, bands_);
    accumulate_kernel_.setArg(2, maps_);
    accumulate_kernel_.setArg(3, plane_w_);
    accumulate_kernel_.setArg(4, rgb);
    if (scene.spectral.spectral_exr) {
      if (!spectral) throw RuntimeError("sea_second pass: spectral output asked for but no spectral buffer given");
      accumulate_kernel_.setArg(5, *spectral);
    }
  });
}

double SeaSecondPass::run() {
  cl::Event vsf_done, radiance_done, maps_done, accumulate_done;
  const size_t dir_stride = SEA_SECOND_STRIDE(static_cast<size_t>(config_.n_theta) * config_.n_phi);
  const size_t M = static_cast<size_t>(config_.map_size);
  onDevice("sea_second pass", [&] {
    cl::CommandQueue& q = device_.queue();  // in order: each kernel sees the previous one's output
    if (table_kernel_() && !table_ready_) {  // 000 §5.4's depth tables, once per scene
      cl::Event table_done;
      q.enqueueNDRangeKernel(table_kernel_, cl::NullRange, cl::NDRange(M, M, config_.n_z + 1), cl::NullRange, nullptr,
                             &table_done);
      table_done.wait();
      depth_table_ms_ = eventMs(table_done);
      std::vector<float> table((static_cast<size_t>(config_.n_z) + 1) * M * M * dir_stride);
      q.enqueueReadBuffer(table_, CL_TRUE, 0, sizeof(float) * table.size(), table.data());
      storeDepthTable(table_key_, table);
      table_ready_ = true;
    }
    q.enqueueNDRangeKernel(vsf_kernel_, cl::NullRange, cl::NDRange(config_.vsf_size), cl::NullRange, nullptr,
                           &vsf_done);
    q.enqueueNDRangeKernel(radiance_kernel_, cl::NullRange, cl::NDRange(dir_stride, config_.n_z), cl::NullRange, nullptr,
                           &radiance_done);
    q.enqueueNDRangeKernel(maps_kernel_, cl::NullRange, cl::NDRange(M, M, config_.n_z), cl::NullRange, nullptr,
                           &maps_done);
    const size_t local = 8;
    q.enqueueNDRangeKernel(accumulate_kernel_, cl::NullRange,
                           cl::NDRange(roundUp(width_, local), roundUp(height_, local)), cl::NDRange(local, local),
                           nullptr, &accumulate_done);
    accumulate_done.wait();
  });
  maps_ms_ = eventMs(vsf_done) + eventMs(radiance_done) + eventMs(maps_done);
  accumulate_ms_ = eventMs(accumulate_done);
  return maps_ms_ + accumulate_ms_;
}

}  // namespace seasim
