#include "passes/sea_single_pass.h"

#include <cmath>
#include <cstddef>

#include "spectral/jerlov.h"
#include "util/error.h"

extern "C" {
#include "common/sea_params.h"
}

namespace seasim {

// The kernel reads these structs with OpenCL C layout; float/int are 4 bytes on both sides.
static_assert(sizeof(SeaParams) == 5 * 16 + 8 * 4 + 4 * 4, "SeaParams layout changed: update sea_params.h users");
static_assert(offsetof(SeaParams, tan_half_fov_y) == 80);
static_assert(offsetof(SeaParams, width) == 112);
static_assert(sizeof(SeaBand) == 48, "SeaBand must stay 48 bytes");

namespace {

void set4(float out[4], Vec3 v) {
  out[0] = static_cast<float>(v.x);
  out[1] = static_cast<float>(v.y);
  out[2] = static_cast<float>(v.z);
  out[3] = 0.0f;
}

}  // namespace

SeaSinglePass::SeaSinglePass(Device& device, const Scene& scene, const PassPlan& plan,
                             const WavelengthGrid& grid, const Sensor& sensor)
    : device_(device), width_(scene.camera.width), height_(scene.camera.height) {
  const CameraDesc& cam = scene.camera;
  SeaParams p{};
  Vec3 forward = normalize(cam.look_at - cam.position);
  Vec3 right = normalize(cross(forward, cam.up));
  Vec3 up = cross(right, forward);
  set4(p.cam_pos, cam.position);
  set4(p.cam_right, right);
  set4(p.cam_up, up);
  set4(p.cam_forward, forward);
  // Sun direction from zenith and azimuth (azimuth from +x towards +z).
  Vec3 sun{std::sin(scene.sun.zenith) * std::cos(scene.sun.azimuth), std::cos(scene.sun.zenith),
           std::sin(scene.sun.zenith) * std::sin(scene.sun.azimuth)};
  set4(p.sun_dir, sun);
  p.tan_half_fov_y = static_cast<float>(std::tan(cam.fov_y / 2));
  p.aspect = static_cast<float>(cam.width) / static_cast<float>(cam.height);
  p.ior = static_cast<float>(scene.water.ior);
  p.g = static_cast<float>(scene.water.g);
  p.bottom_depth = static_cast<float>(scene.bottom.depth);
  p.cos_sun_radius = static_cast<float>(std::cos(scene.sun.angular_radius));
  p.sun_solid_angle = static_cast<float>(2 * M_PI * (1 - std::cos(scene.sun.angular_radius)));
  p.width = cam.width;
  p.height = cam.height;
  p.band_count = static_cast<int>(grid.centers_nm.size());

  const BandOptics water = resolveWater(scene.water, grid);
  const std::vector<double> sun_e = sunIrradianceBands(grid, scene.sun.irradiance);
  const std::vector<double> sky_l = sunIrradianceBands(grid, scene.sky.radiance);  // uniform sky: D65 shape
  std::vector<SeaBand> bands(grid.centers_nm.size());
  for (size_t i = 0; i < bands.size(); ++i) {
    SeaBand& b = bands[i];
    b.sun_irradiance = static_cast<float>(sun_e[i]);
    b.sky_radiance = static_cast<float>(sky_l[i]);
    b.a = static_cast<float>(water.a[i]);
    b.b = static_cast<float>(water.b[i]);
    b.c = static_cast<float>(water.c[i]);
    b.bottom_albedo = static_cast<float>(scene.bottom.albedo.at(grid.centers_nm[i]));
    b.w_r = static_cast<float>(sensor.to_r[i]);
    b.w_g = static_cast<float>(sensor.to_g[i]);
    b.w_b = static_cast<float>(sensor.to_b[i]);
  }

  const size_t pixels = static_cast<size_t>(width_) * static_cast<size_t>(height_);
  try {
    const BuiltProgram& built = device.program(plan.kernel_file, plan.defines);
    kernel_ = cl::Kernel(built.program, "sea_single");
    params_ = cl::Buffer(device.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof p, &p);
    bands_ = cl::Buffer(device.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(SeaBand) * bands.size(),
                        bands.data());
    rgb_ = cl::Buffer(device.context(), CL_MEM_WRITE_ONLY, sizeof(float) * 3 * pixels);
    kernel_.setArg(0, params_);
    kernel_.setArg(1, bands_);
    kernel_.setArg(2, rgb_);
    if (scene.spectral.spectral_exr) {
      spectral_ = cl::Buffer(device.context(), CL_MEM_WRITE_ONLY, sizeof(float) * pixels * bands.size());
      kernel_.setArg(3, spectral_);
    }
  } catch (const cl::Error& e) {
    throw DeviceError(std::string("sea_single pass set-up: ") + e.what() + " " + clErrorName(e.err()));
  }
}

double SeaSinglePass::run() {
  cl::Event done;
  try {
    const size_t local = 8;
    cl::NDRange global((static_cast<size_t>(width_) + local - 1) / local * local,
                       (static_cast<size_t>(height_) + local - 1) / local * local);
    device_.queue().enqueueNDRangeKernel(kernel_, cl::NullRange, global, cl::NDRange(local, local), nullptr, &done);
    done.wait();
  } catch (const cl::Error& e) {
    throw DeviceError(std::string("sea_single pass: ") + e.what() + " " + clErrorName(e.err()));
  }
  return eventMs(done);
}

}  // namespace seasim
