// fourflow_pass.cpp — the four-flow pass (see the header).
#include "passes/fourflow_pass.h"

#include <algorithm>
#include <cmath>

#include "device/enqueue.h"
#include "geometry/kernel_camera.h"
#include "math/kernel_math.h"
#include "passes/fourflow_auto.h"
#include "passes/fourflow_features.h"
#include "spectral/jerlov.h"
#include "underwater/fourflow_setup.h"
#include "underwater/fourflow_waves.h"
#include "util/error.h"

namespace seasim {

namespace {

}  // namespace

double fourFlowTextureMean(double scale, double dark_fraction) {
  // 400 x 400 samples over 100 texture features: the lattice values are independent per cell, so the
  // sample mean is within ~1e-2 of the texture's mean, which moves R̄ by that share of ρa - ρb.
  double sum = 0;
  const int n = 400;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      sum += kmath_d::ff_bottom_texture((i + 0.5) * 100.0 * scale / n, (j + 0.5) * 100.0 * scale / n, scale, dark_fraction);
  return sum / (double(n) * n);
}

FourFlowSetup makeFourFlowSetup(const Scene& scene, const WavelengthGrid& grid, const Sensor& sensor, int table_size) {
  const ShallowDesc& sh = scene.shallow;
  FourFlowSetup s;
  const bool sun_up = scene.sun.enabled && scene.sun.irradiance > 0 && scene.sun.zenith < M_PI / 2;
  const double mu_sun = sun_up ? std::cos(scene.sun.zenith) : 1.0;
  const BandOptics water = resolveWater(scene.water, grid);
  const std::vector<double> sun_e = sunIrradianceBands(grid, scene.sun.irradiance);
  const SkyLight sky = makeSkyLight(scene, grid);  // host/sky: the one sky of every model
  const std::vector<double>& sky_l = sky.level;  // the uniform level, D65 shape
  const std::vector<double> sky_e = sky.horizontalIrradiance();
  const double tex_mean = fourFlowTextureMean(sh.texture_scale, sh.dark_fraction);
  double rgb_a_num[3] = {0, 0, 0}, rgb_den[3] = {0, 0, 0}, sky_rgb[3] = {0, 0, 0};
  double eps_min = 1e30;
  // The air–water coefficients: a flat mirror, or 003 eq. 10 over the FFT patch when the surface has waves.
  const FourFlowSurface surface =
      scene.surface.type == SurfaceDesc::Type::Fft
          ? waveAveragedSurface(oceanFacetNormals(scene.surface), scene.sun.zenith, scene.sun.azimuth, scene.water.ior)
          : flatFourFlowSurface(mu_sun, scene.water.ior);
  for (size_t i = 0; i < grid.centers_nm.size(); ++i) {
    FourFlowBandInput in;
    in.absorption = water.a[i];
    in.scattering = water.b[i];
    in.mean_cosine = scene.water.g;
    in.e_sun = sun_up ? sun_e[i] * mu_sun : 0.0;  // on the horizontal surface
    in.e_sky = sky_e[i];                          // ∫ L cos θ dω: π L for a uniform sky
    in.rho_a = scene.bottom.albedo.at(grid.centers_nm[i]);
    in.rho_b = sh.dark_albedo;
    in.rho_mean = (1 - tex_mean) * in.rho_a + tex_mean * in.rho_b;
    in.rgb = {sensor.to_r[i], sensor.to_g[i], sensor.to_b[i]};
    s.bands.push_back(makeFourFlowBand(in, surface));
    eps_min = std::min(eps_min, in.absorption + in.scattering);
    // The materials' RGB reflectance under the light that reaches the water (T_bottom of eq. 22).
    const double light = in.e_sun + in.e_sky;
    for (int c = 0; c < 3; ++c) {
      rgb_a_num[c] += in.rgb[c] * in.rho_a * light;
      rgb_den[c] += in.rgb[c] * light;
      sky_rgb[c] += in.rgb[c] * sky_l[i];
    }
  }
  // Bottom: the [shallow] slope or the [bottom] table.
  if (sh.slope) {
    const int n = kFourFlowSlopeNodes;
    std::vector<float> depth(size_t(n) * n);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        depth[size_t(j) * n + i] = float(sh.slope_deep + (sh.slope_shallow - sh.slope_deep) * j / (n - 1.0));
    s.field = makeHeightField(n, n, sh.slope_extent, depth);
    s.height_field = true;
  } else if (scene.bottom.type == BottomDesc::Type::HeightField) {
    s.field = loadHeightField(scene.bottom);
    s.height_field = true;
  }
  const double h_max = s.height_field ? s.field.params.max_depth : scene.bottom.depth;

  FfParams& p = s.params;
  p.n_bands = int(s.bands.size());
  // l beyond l_max: e^{-ε l} < 1e-4 in every band, so the bottom term is below 1e-4 of its value at
  // l = 0 and the clamped lookup only misses that.
  p.l_max = float(std::min(std::log(1e4) / eps_min, 1e4));
  p.h_max = float(std::max(h_max, 1e-3));
  p.gamma = float(sh.gamma);
  for (int c = 0; c < 3; ++c) {
    p.rgb_a[c] = float(rgb_den[c] > 0 ? rgb_a_num[c] / rgb_den[c] : 0.0);
    p.rgb_b[c] = float(sh.dark_albedo);
  }
  // Resolution: the argument, the knob, or "auto" (passes/fourflow_auto.h).
  const auto knob = scene.quality.find("fourflow_table_size");
  int n = table_size > 0 ? table_size : knob != scene.quality.end() ? int(knob->second.value) : 32;
  if (table_size <= 0 && knob != scene.quality.end() && knob->second.automatic)
    n = chooseFourFlowTableSize(s.bands, p).size;
  p.n_l = p.n_h = std::max(n, 2);

  FfView& v = s.view;
  const CameraDesc& cam = scene.camera;
  setKernelCamera(v, cam);
  for (int c = 0; c < 3; ++c) v.sky_rgb[c] = float(sky_rgb[c]);
  s.sky_params = sky.params;
  s.sky_buffer = sky.kernelBuffer();
  s.sky_rgb_matrix = sky.rgbMatrix(sensor.to_r, sensor.to_g, sensor.to_b);
  v.tan_half_fov_y = float(std::tan(cam.fov_y / 2));
  v.aspect = float(cam.width) / float(cam.height);
  v.width = cam.width;
  v.height = cam.height;
  v.ior = float(scene.water.ior);
  v.bottom_depth = float(scene.bottom.depth);
  v.texture_scale = float(sh.texture_scale);
  v.dark_fraction = float(sh.dark_fraction);
  return s;
}

FourFlowPass::FourFlowPass(Device& device, const Scene& scene, const PassPlan& plan, const WavelengthGrid& grid,
                           const Sensor& sensor, int table_size)
    : device_(device), width_(scene.camera.width), height_(scene.camera.height) {
  const FourFlowSetup s = makeFourFlowSetup(scene, grid, sensor, table_size);
  const FourFlowFeatures& features = plan.featuresAs<FourFlowFeatures>();
  const bool tables = features.tables != 0;
  const bool hf = features.height_field;
  if (hf != s.height_field) throw RuntimeError("fourflow pass: the plan's SEASIM_FF_HEIGHTFIELD does not match the scene");
  const size_t pixels = size_t(width_) * size_t(height_);
  onDevice("fourflow pass set-up", [&] {
    const BuiltProgram& built = device.program(plan.kernel_file, plan.defines);
    view_ = cl::Buffer(device.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(FfView), const_cast<FfView*>(&s.view));
    bands_ = cl::Buffer(device.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(FfBand) * s.bands.size(),
                        const_cast<FfBand*>(s.bands.data()));
    params_ = cl::Buffer(device.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(FfParams),
                         const_cast<FfParams*>(&s.params));
    const size_t cells = tables ? size_t(s.params.n_l) * s.params.n_h : 1;
    table_ = cl::Buffer(device.context(), CL_MEM_READ_WRITE, sizeof(float) * FF_TABLE_STRIDE * cells);
    rgb_ = cl::Buffer(device.context(), CL_MEM_READ_WRITE, sizeof(float) * 3 * pixels);
    if (tables) {  // 003 §6: the tables are the preprocessing stage, built once per scene
      cl::Kernel build(built.program, "ff_build_tables");
      build.setArg(0, bands_), build.setArg(1, params_), build.setArg(2, table_);
      cl::Event done;
      device.queue().enqueueNDRangeKernel(build, cl::NullRange, cl::NDRange(s.params.n_l, s.params.n_h), cl::NullRange,
                                          nullptr, &done);
      done.wait();
      table_ms_ = eventMs(done);
    }
    render_ = cl::Kernel(built.program, "ff_render");
    render_.setArg(0, view_), render_.setArg(1, bands_), render_.setArg(2, params_), render_.setArg(3, table_);
    render_.setArg(4, rgb_);
    if (hf) {
      const HeightFieldBuffers b = uploadHeightField(device, s.field);
      hf_params_ = b.params;
      hf_depth_ = b.depth;
      render_.setArg(5, hf_params_);
      render_.setArg(6, hf_depth_);
    }
    cl_uint next_arg = hf ? 7 : 5;
    if (features.spectral_output) {
      spectral_ = cl::Buffer(device.context(), CL_MEM_READ_WRITE, sizeof(float) * pixels * s.bands.size());
      render_.setArg(next_arg++, spectral_);
    }
    // A sky model other than the uniform one: its arguments follow.
    if (features.sky_model != 0) {
      const cl_uint arg = next_arg;
      const cl_mem_flags in = CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR;
      sky_params_ = cl::Buffer(device.context(), in, sizeof(SkyParams), const_cast<SkyParams*>(&s.sky_params));
      sky_ = cl::Buffer(device.context(), in, sizeof(float) * s.sky_buffer.size(), const_cast<float*>(s.sky_buffer.data()));
      sky_matrix_ = cl::Buffer(device.context(), in, sizeof(float) * s.sky_rgb_matrix.size(),
                               const_cast<float*>(s.sky_rgb_matrix.data()));
      render_.setArg(arg, sky_params_), render_.setArg(arg + 1, sky_), render_.setArg(arg + 2, sky_matrix_);
    }
  });
}

double FourFlowPass::run() { return runKernel2d(device_, "fourflow", render_, width_, height_); }

}  // namespace seasim
