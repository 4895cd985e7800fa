#include "passes/sea_single_pass.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "device/enqueue.h"
#include "geometry/kernel_camera.h"
#include "math/kernel_math.h"
#include "passes/sea_band_table.h"
#include "passes/sea_heightfield.h"
#include "passes/sea_ordinates_table.h"
#include "passes/sea_single_features.h"
#include "passes/sea_sky.h"
#include "sky/sky_light.h"
#include "spectral/jerlov.h"
#include "underwater/underwater_setup.h"
#include "util/error.h"

extern "C" {
#include "common/sea_params.h"
}

namespace seasim {

// The kernel reads these structs with OpenCL C layout; float/int are 4 bytes on both sides.
static_assert(sizeof(SeaParams) == 5 * 16 + 8 * 4 + 4 * 4 + 10 * 4 + 16, "SeaParams layout changed: update sea_params.h users");
static_assert(offsetof(SeaParams, sky_fresnel_mean) == 164);
static_assert(offsetof(SeaParams, column_hemisphere) == 168);
static_assert(offsetof(SeaParams, pixel_angle) == 108);
static_assert(offsetof(SeaParams, sun_slope_variance) == 160);
static_assert(offsetof(SeaParams, tan_half_fov_y) == 80);
static_assert(offsetof(SeaParams, width) == 112);
static_assert(offsetof(SeaParams, ocean_patch) == 128);
static_assert(offsetof(SeaParams, sky_scale) == 144);
static_assert(offsetof(SeaBand, sky_w_r) == 36);
static_assert(sizeof(SeaBand) == 48, "SeaBand must stay 48 bytes");

namespace {

namespace kd = kmath_d;

// One band's LUT of 000 eq. 5 (kernels/sea_single.cl): the factors except beta and T_o, in double, at
// angle j/(n-1) * pi/2: theta_jo on a flat sea, theta_ji (the refracted view) with waves.
// e_h: sun irradiance on the horizontal surface.
std::vector<double> singleScatteringLut(int n, double e_h, double t_in, double c, double albedo, double c_f,
                                        double cos_io, double z_d, double ior, bool over_theta_ji) {
  std::vector<double> lut(n);
  for (int j = 0; j < n; ++j) {
    const double angle = n > 1 ? j * (M_PI / 2) / (n - 1) : 0.0;
    const double cos_ji = over_theta_ji
                              ? std::max(std::cos(angle), 1e-4)
                              : std::max(std::sqrt(std::max(kd::snell_cos_t2(std::cos(angle), 1.0 / ior), 0.0)), 1e-4);
    lut[j] = kd::sea_single_scattering(e_h, t_in, 1.0, 1.0, c, albedo, c_f, cos_io, cos_ji, z_d);
  }
  return lut;
}

// The kernel's Catmull–Rom read (mirrored ends), in double, for choosing the "auto" size.
double lutRead(const std::vector<double>& lut, double x) {
  const int n = static_cast<int>(lut.size());
  const int j = std::clamp(static_cast<int>(x), 0, n - 2);
  const double t = x - j;
  const double p0 = lut[j > 0 ? j - 1 : 1], p1 = lut[j], p2 = lut[j + 1], p3 = lut[j + 2 < n ? j + 2 : n - 2];
  return p1 + 0.5 * t * (p2 - p0 + t * (2 * p0 - 5 * p1 + 4 * p2 - p3 + t * (3 * (p1 - p2) + p3 - p0)));
}

// Sun direction from zenith and azimuth (azimuth from +x towards +z).
Vec3 sunDirection(const Scene& scene) {
  return Vec3{std::sin(scene.sun.zenith) * std::cos(scene.sun.azimuth), std::cos(scene.sun.zenith),
              std::sin(scene.sun.zenith) * std::sin(scene.sun.azimuth)};
}

// The kernel's parameters but the sky's and the LUT's (ocean: the FFT waves, null without; bottom_caustics:
// the caustic map, null without).
SeaParams seaParams(const Scene& scene, const WavelengthGrid& grid, const Vec3& sun, const OceanMaps* ocean,
                    const SeaBottomCaustics* bottom_caustics) {
  const CameraDesc& cam = scene.camera;
  SeaParams p{};
  setKernelCameraView(p, cam);
  set4(p.sun_dir, sun);
  p.aspect = static_cast<float>(cam.width) / static_cast<float>(cam.height);
  p.ior = static_cast<float>(scene.water.ior);
  p.g = static_cast<float>(scene.water.g);
  p.bottom_depth = static_cast<float>(scene.bottom.depth);
  p.cos_sun_radius = static_cast<float>(std::cos(scene.sun.angular_radius));
  p.sun_solid_angle = static_cast<float>(2 * M_PI * (1 - std::cos(scene.sun.angular_radius)));
  p.sun_slope_variance = static_cast<float>(scene.sun.angular_radius * scene.sun.angular_radius / 16);
  p.sky_fresnel_mean = static_cast<float>(skyFresnelMean(scene.water.ior));
  // sea_pixel's cos_io (sea_sun_entry: the sun refracted through the flat mean surface; 1 with the sun down),
  // mu_sky and mu_ret, by the kernel's own float functions, each through sea_column_hemisphere once per frame.
  {
    namespace kf = kmath_f;
    kf::SeaPixel px{};
    kf::sea_sun_entry(1, &p, &px);
    const float mu_sky = kf::sea_sky_mean_cosine(p.ior);
    const float mu_ret =
        kf::sea_reflected_mean_cosine(kf::sea_surface_reflectance_below(p.sky_fresnel_mean, p.ior), p.ior);
    p.column_hemisphere[0] = kf::sea_column_hemisphere(px.cos_io);
    p.column_hemisphere[1] = kf::sea_column_hemisphere(mu_sky);
    p.column_hemisphere[2] = kf::sea_column_hemisphere(mu_ret);
  }
  p.width = cam.width;
  p.height = cam.height;
  p.band_count = static_cast<int>(grid.centers_nm.size());
  p.ocean_patch = ocean ? static_cast<float>(ocean->patchSize()) : 1.0f;
  p.ocean_n = ocean ? ocean->n() : 1;
  if (bottom_caustics) {
    p.caustic_map_size = bottom_caustics->map_size;
    p.caustic_extent = static_cast<float>(bottom_caustics->extent);
    p.caustic_origin = static_cast<float>(bottom_caustics->origin);
  }
  return p;
}

// Each band's radiometry, water and sensor weights (SeaBand), from the sky's level and shape.
std::vector<SeaBand> seaBands(const Scene& scene, const WavelengthGrid& grid, const Sensor& sensor,
                              const BandOptics& water, const std::vector<double>& sun_e, const SkyLight& light) {
  const SeaSky& sky = light.shape;
  const std::vector<double>& sky_l = light.level;  // the uniform level: D65 shape
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
    b.sky_w_r = static_cast<float>(sky.band_weights[i][0]);
    b.sky_w_g = static_cast<float>(sky.band_weights[i][1]);
    b.sky_w_b = static_cast<float>(sky.band_weights[i][2]);
  }

  return bands;
}

// The LUT over theta_jo (theta_ji with waves) of 000 eq. 5 (quality.sea_lut_size), its entries per band
// into lut_values; returns its size. The parser takes positive sizes or "auto": auto doubles the size from
// 16 until the interpolation is within 1e-4 (relative to the band's largest entry) of the exact factors
// everywhere; size 1 asks for the exact evaluation (SEASIM_SEA_LUT=0), as a one-entry table could not
// follow theta_jo at all.
int singleScatteringTable(const Scene& scene, const WavelengthGrid& grid, const Vec3& sun, const BandOptics& water,
                          const std::vector<double>& sun_e, bool waves, std::vector<float>& lut_values) {
  const auto knob = scene.quality.find("sea_lut_size");
  // 000 §5.4: over a height-field bottom z_Q changes from pixel to pixel, so eq. 5 is evaluated
  // exactly (a table over the angle alone cannot hold it).
  const bool height_field = scene.bottom.type == BottomDesc::Type::HeightField;
  // sea.model = "multiple" evaluates eq. 5 exactly too: its depth factor is not eq. 5's.
  const bool exact = height_field || scene.sea.model == SeaDesc::Model::Multiple;
  const bool automatic = !exact && knob != scene.quality.end() && knob->second.automatic;
  int lut_size = exact ? 1
                 : automatic  ? 16
                              : (knob != scene.quality.end() ? static_cast<int>(knob->second.value) : 64);
  const kd::real3 sun_d{sun.x, sun.y, sun.z};
  double t_in = 0, cos_io = 1, e_h = 0;
  if (sun.y > 0) {
    t_in = 1 - kd::fresnel_reflectance(sun.y, 1.0, scene.water.ior);
    e_h = sun.y;
    kd::real3 sun_in_water{};
    kd::refract_dir(-sun_d, kd::real3{0, 1, 0}, 1.0 / scene.water.ior, &sun_in_water);
    cos_io = std::max(-sun_in_water.y, 1e-4);
  }
  const double c_f = kd::hg_forward_fraction(scene.water.g);
  const double z_d = scene.bottom.type == BottomDesc::Type::Flat ? scene.bottom.depth : -1.0;
  auto build = [&](int n) {
    std::vector<std::vector<double>> per_band;
    for (size_t i = 0; i < grid.centers_nm.size(); ++i) {
      const double c = water.c[i], albedo = c > 0 ? water.b[i] / c : 0.0;
      per_band.push_back(
          singleScatteringLut(n, sun_e[i] * e_h, t_in, c, albedo, c_f, cos_io, z_d, scene.water.ior, waves));
    }
    return per_band;
  };
  std::vector<std::vector<double>> tables = lut_size > 1 ? build(lut_size) : std::vector<std::vector<double>>{};
  while (automatic && lut_size < 4096) {
    double worst = 0;
    const std::vector<std::vector<double>> fine = build(4 * (lut_size - 1) + 1);  // 3 points between entries
    for (size_t i = 0; i < tables.size(); ++i) {
      const double peak = *std::max_element(tables[i].begin(), tables[i].end());
      for (size_t q = 0; q < fine[i].size(); ++q)
        worst = std::max(worst, std::fabs(lutRead(tables[i], q / 4.0) - fine[i][q]) / std::max(peak, 1e-30));
    }
    if (worst < 1e-4) break;
    lut_size = 2 * (lut_size - 1) + 1;
    tables = build(lut_size);
  }
  if (lut_size > 1) {
    lut_values.clear();
    for (const auto& t : tables)
      for (double v : t) lut_values.push_back(static_cast<float>(v));
  }
  return lut_size;
}

}  // namespace

SeaSinglePass::SeaSinglePass(Device& device, const Scene& scene, const PassPlan& plan,
                             const WavelengthGrid& grid, const Sensor& sensor, const OceanMaps* ocean,
                             const SeaBottomCaustics* bottom_caustics)
    : device_(device), width_(scene.camera.width), height_(scene.camera.height) {
  const SeaSingleFeatures& features = plan.featuresAs<SeaSingleFeatures>();
  const bool caustics = features.bottom_caustics;
  if (caustics && !bottom_caustics) {
    throw RuntimeError("sea_single pass: the plan has bottom caustics (SEASIM_BOTTOM_CAUSTICS=1) but no caustic map "
                       "was given (the renderer makes it with seaBottomCaustics)");
  }
  const bool waves = features.waves;
  if (waves && !ocean) {
    throw RuntimeError("sea_single pass: the plan has FFT waves (SEASIM_HAS_WAVES=1) but no ocean normal map was "
                       "given; run the ocean_fft pass first (the renderer does)");
  }
  const Vec3 sun = sunDirection(scene);
  SeaParams p = seaParams(scene, grid, sun, waves ? ocean : nullptr, caustics ? bottom_caustics : nullptr);
  // The sky through the one sky interface (host/sky): its shape for the kernel, its level per band.
  const SkyLight light = makeSkyLight(scene, grid);
  const SeaSky& sky = light.shape;
  p.sky_width = sky.width;
  p.sky_height = sky.height;
  p.sky_scale = static_cast<float>(sky.scale);

  const BandOptics water = resolveWater(scene.water, grid);
  const std::vector<double> sun_e = sunIrradianceBands(grid, scene.sun.irradiance);
  std::vector<SeaBand> bands = seaBands(scene, grid, sensor, water, sun_e, light);
  std::vector<float> lut_values(1, 0.0f);
  const int lut_size = singleScatteringTable(scene, grid, sun, water, sun_e, waves, lut_values);
  p.lut_size = lut_size;
  // sea.model "multiple": its factor κ from the discrete-ordinates solution of the flat layer
  // (common/sea_ordinates.h), at the depth nodes the scene's bottom reaches.
  std::vector<double> ordinates;
  if (features.sea_model == 1) {
    const Vec3 sun_lit = features.sun ? sun : Vec3{0, -1, 0};
    const SeaOrdinatesLight ord_light =
        seaOrdinatesLight(scene, sun_lit, p.sky_fresnel_mean, features.single_scattering, features.bottom);
    std::vector<SeaOrdinatesBand> ord_bands;
    for (const SeaBand& b : bands) {
      const double sky = kd::sea_sky_band(features.sky_model, &b, kd::real3{1, 1, 1});
      ord_bands.push_back({b.a, b.b, b.sun_irradiance, M_PI * sky * (1 - p.sky_fresnel_mean), b.bottom_albedo});
    }
    ordinates = seaOrdinatesTable(ord_light, ord_bands);
  }
  // SEASIM_SEA_LUT is set here rather than by the planner: it follows a quality knob of this pass.
  std::vector<std::string> defines = plan.defines;
  defines.push_back(std::string("SEASIM_SEA_LUT=") + (lut_size > 1 ? "1" : "0"));

  const size_t pixels = static_cast<size_t>(width_) * static_cast<size_t>(height_);
  onDevice("sea_single pass set-up", [&] {
    const BuiltProgram& built = device.program(plan.kernel_file, defines);
    kernel_ = cl::Kernel(built.program, "sea_single");
    params_ = cl::Buffer(device.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof p, &p);
    host_params_ = p;
    // The band lanes' table (kernels/common/sea_band_table.h): the bands' fields and the LUT, bands contiguous.
    const std::vector<float> table = seaBandTable(bands, lut_values, lut_size, ordinates);
    table_ = cl::Buffer(device.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(float) * table.size(),
                        const_cast<float*>(table.data()));
    // One dummy float4 stands in for a map the kernel's defines do not read.
    std::vector<float> dummy(4, 0.0f);
    normals_ = waves ? ocean->normal
                     : cl::Buffer(device.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(float) * 4, dummy.data());
    std::vector<float> sky_texels(sky.texels.begin(), sky.texels.end());
    if (features.sky_table > 0) {  // the reflected sky's table after the model's reals (common/sky_table.h)
      const std::vector<double> t = seaSkyTable(sky, features.sky_table);
      sky_texels.resize(SKY_TABLE_OFFSET, 0.0f);
      sky_texels.insert(sky_texels.end(), t.begin(), t.end());
    }
    sky_ = cl::Buffer(device.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(float) * sky_texels.size(),
                      sky_texels.data());
    caustics_ = caustics ? bottom_caustics->map
                         : cl::Buffer(device.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(float) * 4,
                                      dummy.data());
    rgb_ = cl::Buffer(device.context(), CL_MEM_READ_WRITE,  // sea_second adds into it
                       sizeof(float) * 3 * pixels);
    kernel_.setArg(0, params_);
    kernel_.setArg(1, table_);
    kernel_.setArg(2, normals_);
    // The wave filter's slope-moment mip chain (common/sea_lean.h), rebuilt from the normal map each run.
    const bool filter = features.waves && features.wave_filter;
    if (filter) {
      ocean_n_ = ocean->n();
      mips_ = cl::Buffer(device.context(), CL_MEM_READ_WRITE,
                         sizeof(float) * static_cast<size_t>(kd::sea_lean_level_offset(ocean_n_, kd::sea_lean_levels(ocean_n_))));
      moments_ = cl::Kernel(built.program, "sea_slope_moments");
      moments_.setArg(0, normals_);
      moments_.setArg(1, ocean_n_);
      moments_.setArg(2, mips_);
      cells_ = cl::Kernel(built.program, "sea_slope_cells");
      cells_.setArg(0, mips_);
      cells_.setArg(1, ocean_n_);
      downsample_ = cl::Kernel(built.program, "sea_slope_downsample");
      downsample_.setArg(0, mips_);
    } else {
      mips_ = cl::Buffer(device.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(float) * 4, dummy.data());
    }
    kernel_.setArg(3, mips_);
    kernel_.setArg(4, sky_);
    kernel_.setArg(5, caustics_);
    kernel_.setArg(6, rgb_);
    if (scene.spectral.spectral_exr) {
      spectral_ = cl::Buffer(device.context(), CL_MEM_READ_WRITE, sizeof(float) * pixels * bands.size());
      kernel_.setArg(7, spectral_);
    }
    if (scene.bottom.type == BottomDesc::Type::HeightField) {  // 000 §5.4: the kernel's last two arguments
      const HeightFieldBuffers hf = uploadHeightField(device, loadHeightField(scene.bottom, scene.files.get()));
      hf_params_ = hf.params;
      hf_depth_ = hf.depth;
      const cl_uint args = kernel_.getInfo<CL_KERNEL_NUM_ARGS>();
      kernel_.setArg(args - 2, hf_params_);
      kernel_.setArg(args - 1, hf_depth_);
    }
  });
}

void SeaSinglePass::moveCamera(const CameraDesc& cam) {
  if (cam.width != width_ || cam.height != height_) {
    throw RuntimeError("sea_single pass: the image size changed without a new set-up (camera.width and "
                       "camera.height are among the keys that set this pass up again)");
  }
  setKernelCameraView(host_params_, cam);
  onDevice("sea_single pass (moving the camera)", [&] {
    device_.queue().enqueueWriteBuffer(params_, CL_TRUE, 0, sizeof host_params_, &host_params_);
  });
}

double SeaSinglePass::run() {
  double ms = 0;
  if (ocean_n_ > 0) {  // the wave filter's moment mips: level 0 from the normals, then 2 x 2 averages
    const size_t n = static_cast<size_t>(ocean_n_);
    ms += runKernel(device_, "sea_single", moments_, cl::NDRange(n, n));
    ms += runKernel(device_, "sea_single", cells_, cl::NDRange(n, n));
    for (int level = 0; (ocean_n_ >> level) > 1; ++level) {
      const int src_n = ocean_n_ >> level;
      onDevice("sea_single pass", [&] {
        downsample_.setArg(1, kd::sea_lean_level_offset(ocean_n_, level));
        downsample_.setArg(2, src_n);
        downsample_.setArg(3, kd::sea_lean_level_offset(ocean_n_, level + 1));
      });
      const size_t half = static_cast<size_t>(src_n / 2);
      ms += runKernel(device_, "sea_single", downsample_, cl::NDRange(half, half));
    }
  }
  return ms + runKernel2d(device_, "sea_single", kernel_, width_, height_);
}

}  // namespace seasim
