#include "reference/underwater_reference.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "device/enqueue.h"
#include "math/kernel_math.h"
#include "reference/batch_error.h"
#include "util/error.h"

namespace seasim {

namespace {

namespace kd = kmath_d;

kd::real3 r3(Vec3 v) { return kd::real3{v.x, v.y, v.z}; }
Vec3 v3(const float a[4]) { return {a[0], a[1], a[2]}; }

void validate(const UnderwaterSetup& setup, bool camera_above) {
  const UwParams& p = setup.params;
  if (p.width < 1 || p.height < 1) throw RuntimeError("underwater reference: the image is empty");
  if (p.band_count < 1 || setup.bands.size() != static_cast<size_t>(p.band_count)) {
    throw RuntimeError("underwater reference: " + std::to_string(setup.bands.size()) + " bands for band_count " +
                       std::to_string(p.band_count));
  }
  if (p.object_count < 0 || setup.objects.size() < static_cast<size_t>(std::max(p.object_count, 1)) ||
      setup.albedo.size() < static_cast<size_t>(std::max(p.object_count * p.band_count, 1))) {
    throw RuntimeError("underwater reference: object or albedo arrays shorter than object_count says");
  }
  if (camera_above ? !(p.cam_pos[1] > 0.0f) : !(p.cam_pos[1] < 0.0f)) {
    throw RuntimeError(std::string("underwater reference: the camera must be ") +
                       (camera_above ? "above the water surface (y > 0)" : "below the water surface (y < 0)") +
                       ", got y = " + std::to_string(p.cam_pos[1]));
  }
  if (!(std::fabs(p.g) < 1.0f)) throw RuntimeError("underwater reference: |g| must be < 1, got " + std::to_string(p.g));
}

// The image, its direct part and their standard errors from the blocks (a single block: the
// per-sample estimate), and the image-wide noise figures; result.samples and .blocks already set.
void summariseBlocks(const BatchMeans& per_value, const BatchMeans& per_direct, const BatchMeans& per_image, int width,
                     int height, UnderwaterReferenceResult& result) {
  const size_t pixels = static_cast<size_t>(width) * static_cast<size_t>(height);
  const int blocks = result.blocks, total = result.samples;
  result.rgb.resize(width, height, 3);
  result.rgb.channel_names = {"R", "G", "B"};
  result.std_error.resize(width, height, 3);
  result.std_error.channel_names = {"R", "G", "B"};
  result.direct.resize(width, height, 3);
  result.direct.channel_names = {"R", "G", "B"};
  result.direct_std_error.resize(width, height, 3);
  result.direct_std_error.channel_names = {"R", "G", "B"};
  long long nonfinite = 0;
  double sum = 0, sum_se = 0, sum_se2 = 0, sum_sample_se2 = 0;
  for (size_t i = 0; i < 3 * pixels; ++i) {
    // With one block the spread is unknown: the per-sample estimate stands in (0 with one sample).
    const BatchEstimate e = per_value.estimate(i);
    const double m = e.mean, se = blocks > 1 ? e.std_error : e.sample_std_error;
    if (!std::isfinite(m) || !std::isfinite(se)) ++nonfinite;
    result.rgb.pixels[i] = static_cast<float>(m);
    result.std_error.pixels[i] = static_cast<float>(se);
    sum += m;
    sum_se += se;
    sum_se2 += se * se;
    sum_sample_se2 += e.sample_std_error * e.sample_std_error;
    const BatchEstimate ed = per_direct.estimate(i);
    const double md = ed.mean, sed = blocks > 1 ? ed.std_error : ed.sample_std_error;
    if (!std::isfinite(md) || !std::isfinite(sed)) ++nonfinite;
    result.direct.pixels[i] = static_cast<float>(md);
    result.direct_std_error.pixels[i] = static_cast<float>(sed);
  }
  if (nonfinite > 0) {
    throw RuntimeError("underwater reference: " + std::to_string(nonfinite) +
                       " non-finite pixel values (a bug in reference.cl; please report the scene)");
  }
  const double values = 3.0 * static_cast<double>(pixels);
  result.image_mean = sum / values;
  result.mean_std_error = sum_se / values;
  result.rms_std_error = std::sqrt(sum_se2 / values);
  result.image_mean_sample_std_error = std::sqrt(sum_sample_se2) / values;  // independent pixels: variances add
  const BatchEstimate image = per_image.estimate(0);
  result.image_mean_std_error = blocks > 1 ? image.std_error : result.image_mean_sample_std_error;
  result.effective_samples =
      result.image_mean_std_error > 0
          ? total * (result.image_mean_sample_std_error / result.image_mean_std_error) *
                (result.image_mean_sample_std_error / result.image_mean_std_error)
          : total;
}

// The kernel's defines: objects, phase, pixel sampling, lamp estimator, sky model, height-field floor.
// Throws for settings it cannot trace (phase tables of the wrong size, a floor and a flat bottom at once).
std::vector<std::string> tracerDefines(const UnderwaterSetup& setup, const UnderwaterReferenceSettings& settings) {
  if (settings.height_field && setup.params.bottom_depth > 0)
    throw RuntimeError("underwater reference: a height-field floor and a flat bottom at once");
  if (settings.waves && !settings.camera_above)
    throw RuntimeError("underwater reference: FFT waves are traced for a camera above the surface only");
  if (settings.waves && (settings.waves->grid < 1 || !(settings.waves->patch > 0) ||
                         settings.waves->normals.size() != 4 * static_cast<size_t>(settings.waves->grid) * settings.waves->grid))
    throw RuntimeError("underwater reference: the waves' normal map is not grid x grid texels of 4 floats over a patch > 0");
  if (!settings.phase_tables.empty() && settings.phase_tables.size() != PHASE_PT_VALUES + PHASE_PT_SAMPLES)
    throw RuntimeError("underwater reference: the phase tables hold " + std::to_string(settings.phase_tables.size()) +
                       " values, not " + std::to_string(PHASE_PT_VALUES + PHASE_PT_SAMPLES));
  return {std::string("SEASIM_HAS_OBJECTS=") + (setup.params.object_count > 0 ? "1" : "0"),
          std::string("SEASIM_PT_ISOTROPIC=") + (settings.isotropic ? "1" : "0"),
          std::string("SEASIM_PT_JITTER=") + (settings.jitter ? "1" : "0"),
          std::string("SEASIM_PT_LAMP_MIS=") + (settings.lamp_mis ? "1" : "0"),
          std::string("SEASIM_PT_PHASE_TABLE=") + (settings.phase_tables.empty() ? "0" : "1"),
          "SEASIM_SKY_MODEL=" + std::to_string(setup.sky_params.model),
          std::string("SEASIM_PT_HEIGHT_FIELD=") + (settings.height_field ? "1" : "0"),
          std::string("SEASIM_PT_WAVES=") + (settings.waves ? "1" : "0")};
}

// The scene's read-only inputs on the device, in the kernel's argument order (an absent input is one
// zero entry: lamps, the phase tables for HG, the sky's texels, a 2 x 2 floor; the kernel does not read it).
struct SceneBuffers {
  cl::Buffer params, bands, objects, albedo, lamp_params, lamps, lamp_spectra, phase, sky_params, sky, hf_params,
      hf_depth, wave_normals;
  int wave_grid = 1;
  float wave_patch = 1.0f;
  float sun_cos_radius = 1.0f;

  void bind(cl::Kernel& kernel) const {
    kernel.setArg(0, params);
    kernel.setArg(1, bands);
    kernel.setArg(2, objects);
    kernel.setArg(3, albedo);
    kernel.setArg(10, lamp_params);
    kernel.setArg(11, lamps);
    kernel.setArg(12, lamp_spectra);
    kernel.setArg(13, phase);
    kernel.setArg(16, sky_params);
    kernel.setArg(17, sky);
    kernel.setArg(18, hf_params);
    kernel.setArg(19, hf_depth);
    kernel.setArg(20, wave_normals);
    kernel.setArg(21, static_cast<cl_int>(wave_grid));
    kernel.setArg(22, static_cast<cl_float>(wave_patch));
    kernel.setArg(23, static_cast<cl_float>(sun_cos_radius));
  }
};

template <typename T>
cl::Buffer readOnly(cl::Context& ctx, const T* data, size_t count) {
  return cl::Buffer(ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(T) * count, const_cast<T*>(data));
}

SceneBuffers makeSceneBuffers(cl::Context& ctx, const UnderwaterSetup& setup,
                              const UnderwaterReferenceSettings& settings) {
  UnderwaterLamps no_lamps;  // lamp_count 0
  no_lamps.lamps.push_back(UwLamp{});
  no_lamps.spectra.push_back(0.0f);
  const UnderwaterLamps& lamps = settings.lamps ? *settings.lamps : no_lamps;
  const std::vector<float> none(1, 0.0f);
  const std::vector<float>& phase = settings.phase_tables.empty() ? none : settings.phase_tables;
  const std::vector<float>& sky = setup.sky_buffer.empty() ? none : setup.sky_buffer;
  const HeightField no_floor = makeHeightField(2, 2, 1.0, std::vector<float>(4, 1.0f));
  const HeightField& floor = settings.height_field ? *settings.height_field : no_floor;
  SceneBuffers b;
  b.params = readOnly(ctx, &setup.params, 1);
  b.bands = readOnly(ctx, setup.bands.data(), setup.bands.size());
  b.objects = readOnly(ctx, setup.objects.data(), setup.objects.size());
  b.albedo = readOnly(ctx, setup.albedo.data(), setup.albedo.size());
  b.lamp_params = readOnly(ctx, &lamps.params, 1);
  b.lamps = readOnly(ctx, lamps.lamps.data(), lamps.lamps.size());
  b.lamp_spectra = readOnly(ctx, lamps.spectra.data(), lamps.spectra.size());
  b.phase = readOnly(ctx, phase.data(), phase.size());
  b.sky_params = readOnly(ctx, &setup.sky_params, 1);
  b.sky = readOnly(ctx, sky.data(), sky.size());
  b.hf_params = readOnly(ctx, &floor.params, 1);
  b.hf_depth = readOnly(ctx, floor.depth.data(), floor.depth.size());
  const std::vector<float> flat = {0.0f, 1.0f, 0.0f, 0.0f};
  const std::vector<float>& normals = settings.waves ? settings.waves->normals : flat;
  b.wave_normals = readOnly(ctx, normals.data(), normals.size());
  if (settings.waves) {
    b.wave_grid = settings.waves->grid;
    b.wave_patch = static_cast<float>(settings.waves->patch);
    b.sun_cos_radius = static_cast<float>(std::cos(settings.sun_angular_radius));
  }
  return b;
}

}  // namespace

Vec3 underwaterPixelDirection(const UwParams& p, double x, double y) {
  // The kernels' own pinhole (common/underwater.h uw_screen_dir), evaluated in double.
  const kmath_d::real3 d = kmath_d::uw_screen_dir(&p, x / p.width, y / p.height);
  return Vec3{d.x, d.y, d.z};
}

UnderwaterReferenceResult renderUnderwaterReference(Device& device, const UnderwaterSetup& setup,
                                                    const UnderwaterReferenceSettings& settings) {
  validate(setup, settings.camera_above);
  if (settings.samples_per_pixel < 1) throw RuntimeError("underwater reference: samples per pixel must be >= 1");
  if (settings.batch < 1) throw RuntimeError("underwater reference: batch must be >= 1");
  if (settings.max_bounces < 1) throw RuntimeError("underwater reference: max_bounces must be >= 1");
  const UwParams& p = setup.params;
  const size_t pixels = static_cast<size_t>(p.width) * static_cast<size_t>(p.height);
  const int total = settings.samples_per_pixel;
  const int blocks = std::clamp(settings.blocks, 1, total);

  UnderwaterReferenceResult result;
  std::vector<cl_float4> mean(pixels), m2(pixels), direct_mean(pixels), direct_m2(pixels);
  BatchMeans per_value(3 * pixels);   // per pixel and channel
  BatchMeans per_direct(3 * pixels);  // the unscattered part, the same way
  BatchMeans per_image(1);           // the blocks' image means
  try {
    const BuiltProgram& built = device.program("reference.cl", tracerDefines(setup, settings));
    cl::Kernel kernel(built.program, "reference_path_trace");
    cl::Context& ctx = device.context();
    const SceneBuffers scene = makeSceneBuffers(ctx, setup, settings);
    scene.bind(kernel);
    cl::Buffer mean_buf(ctx, CL_MEM_READ_WRITE, sizeof(cl_float4) * pixels);
    cl::Buffer m2_buf(ctx, CL_MEM_READ_WRITE, sizeof(cl_float4) * pixels);
    cl::Buffer direct_mean_buf(ctx, CL_MEM_READ_WRITE, sizeof(cl_float4) * pixels);
    cl::Buffer direct_m2_buf(ctx, CL_MEM_READ_WRITE, sizeof(cl_float4) * pixels);
    cl::CommandQueue& queue = device.queue();
    kernel.setArg(4, static_cast<cl_uint>(settings.seed));
    kernel.setArg(7, static_cast<cl_int>(settings.max_bounces));
    kernel.setArg(8, mean_buf);
    kernel.setArg(9, m2_buf);
    kernel.setArg(14, direct_mean_buf);
    kernel.setArg(15, direct_m2_buf);
    const size_t local = 8;
    const cl::NDRange global((static_cast<size_t>(p.width) + local - 1) / local * local,
                             (static_cast<size_t>(p.height) + local - 1) / local * local);
    const cl_float4 zero{};
    int done = 0;
    for (int block = 0; block < blocks; ++block) {
      // Block `block` holds paths [total·block/blocks, total·(block+1)/blocks): the same paths for a
      // seed whatever the blocking, since sample_start numbers them.
      const int block_end = static_cast<int>(static_cast<long long>(total) * (block + 1) / blocks);
      const int block_start = done;
      queue.enqueueFillBuffer(mean_buf, zero, 0, sizeof(cl_float4) * pixels);
      queue.enqueueFillBuffer(m2_buf, zero, 0, sizeof(cl_float4) * pixels);
      queue.enqueueFillBuffer(direct_mean_buf, zero, 0, sizeof(cl_float4) * pixels);
      queue.enqueueFillBuffer(direct_m2_buf, zero, 0, sizeof(cl_float4) * pixels);
      while (done < block_end) {
        const int n = std::min(settings.batch, block_end - done);
        kernel.setArg(5, static_cast<cl_int>(done));
        kernel.setArg(6, static_cast<cl_int>(n));
        cl::Event event;
        queue.enqueueNDRangeKernel(kernel, cl::NullRange, global,
                                   workGroupFor(device, kernel, cl::NDRange(local, local)), nullptr, &event);
        event.wait();  // one launch at a time: bounded kernel length (GPU watchdogs) and live progress
        result.ms += eventMs(event);
        done += n;
        if (settings.progress) settings.progress(done, total);
      }
      queue.enqueueReadBuffer(mean_buf, CL_TRUE, 0, sizeof(cl_float4) * pixels, mean.data());
      queue.enqueueReadBuffer(m2_buf, CL_TRUE, 0, sizeof(cl_float4) * pixels, m2.data());
      queue.enqueueReadBuffer(direct_mean_buf, CL_TRUE, 0, sizeof(cl_float4) * pixels, direct_mean.data());
      queue.enqueueReadBuffer(direct_m2_buf, CL_TRUE, 0, sizeof(cl_float4) * pixels, direct_m2.data());
      per_value.addBlock(&mean[0].s[0], &m2[0].s[0], 4, block_end - block_start);
      per_direct.addBlock(&direct_mean[0].s[0], &direct_m2[0].s[0], 4, block_end - block_start);
      double image = 0.0;
      for (size_t i = 0; i < pixels; ++i) image += double(mean[i].s[0]) + double(mean[i].s[1]) + double(mean[i].s[2]);
      image /= 3.0 * static_cast<double>(pixels);
      per_image.addBlock(&image, nullptr, block_end - block_start);
    }
  } catch (const cl::Error& e) {
    throw DeviceError(std::string("underwater reference (reference.cl): ") + e.what() + " " + clErrorName(e.err()));
  }

  result.samples = total;
  result.blocks = blocks;
  summariseBlocks(per_value, per_direct, per_image, p.width, p.height, result);
  return result;
}

double underwaterSingleScatteringRay(const UnderwaterSetup& setup, int band, Vec3 origin, Vec3 dir, bool isotropic,
                                     int steps) {
  const UwParams& p = setup.params;
  const UwBand& bn = setup.bands.at(static_cast<size_t>(band));
  const double c = bn.c, b = bn.b;
  if (c <= 0 || b <= 0 || bn.e_beam0 <= 0 || steps < 1) return 0.0;
  const int count = p.object_count;
  const kd::real3 o = r3(origin), d = r3(dir);
  const kd::real3 s_w = r3(v3(p.sun_dir_water));
  kd::real3 n{};
  int mat = 0;
  const double S = kd::uw_scene_hit(setup.objects.data(), count, p.bottom_depth, o, d, 0.0, &n, &mat);
  const double phase = isotropic ? 1.0 / (4.0 * M_PI) : kd::hg_phase(kd::dot(s_w, d), p.g);
  // Without shadows the integrand is e_beam0 e^{-c o_d/μ_w} e^{-κ z}, κ = c (1 - d_y/μ_w) (y(z) = o_d -
  // z d_y, μ_w clamped as uw_beam_irradiance does). For κ > 0 the substitution u = 1 - e^{-κ z} makes
  // it constant in u, so the midpoint rule is exact but for V's steps (and deep water needs no
  // truncation); for κ <= 0 (looking up more steeply than the sun; S finite) midpoints in z.
  const double mu = std::max(s_w.y, 1e-4);
  const double o_d = std::max(-o.y, 0.0);
  const double kappa = c * (1.0 - d.y / mu);
  const double scale = bn.e_beam0 * std::exp(-c * o_d / mu);
  if (scale <= 0) return 0.0;
  const bool substitute = kappa > 0;
  if (!substitute && S >= 1e29) return 0.0;  // cannot happen in water (d_y > μ_w > 0 reaches the surface)
  const double U = substitute ? (S >= 1e29 ? 1.0 : -std::expm1(-kappa * S)) : S;
  double sum = 0;
  for (int i = 0; i < steps; ++i) {
    const double u = (i + 0.5) * U / steps;
    const double z = substitute ? -std::log1p(-u) / kappa : u;
    if (count > 0) {
      kd::real3 sn{};
      int smat = 0;
      kd::uw_scene_hit(setup.objects.data(), count, 0.0, o + z * d, s_w, 0.0, &sn, &smat);
      if (smat >= 0) continue;
    }
    sum += substitute ? 1.0 / kappa : std::exp(-kappa * z);
  }
  return b * phase * scale * sum * (U / steps);
}

Image renderUnderwaterSingleScatteringQuadrature(const UnderwaterSetup& setup, bool isotropic, int steps) {
  validate(setup, false);
  const UwParams& p = setup.params;
  Image img;
  img.resize(p.width, p.height, 3);
  img.channel_names = {"R", "G", "B"};
  const Vec3 eye = v3(p.cam_pos);
  tbb::parallel_for(0, p.height, [&](int y) {
    for (int x = 0; x < p.width; ++x) {
      const Vec3 d = underwaterPixelDirection(p, x + 0.5, y + 0.5);
      double rgb[3] = {0, 0, 0};
      for (int i = 0; i < p.band_count; ++i) {
        const double L = underwaterSingleScatteringRay(setup, i, eye, d, isotropic, steps);
        const UwBand& bn = setup.bands[static_cast<size_t>(i)];
        rgb[0] += L * bn.w_r;
        rgb[1] += L * bn.w_g;
        rgb[2] += L * bn.w_b;
      }
      for (int ch = 0; ch < 3; ++ch) img.at(x, y, ch) = static_cast<float>(rgb[ch]);
    }
  });
  return img;
}

}  // namespace seasim
