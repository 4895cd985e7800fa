#include "passes/render_frame.h"

#include <chrono>
#include <memory>

#include "passes/caustic_stack.h"
#include "passes/froxel_pass.h"
#include "passes/nonfinite_check.h"
#include "passes/sea_second_pass.h"
#include "passes/sea_single_pass.h"
#include "passes/shafts_pass.h"
#include "passes/underwater_pass.h"
#include "spectral/sensor.h"
#include "spectral/wavelength_grid.h"
#include "underwater/underwater_setup.h"
#include "util/error.h"

namespace seasim {

namespace {

// The NaN/Inf check on the frame's buffers and the read-back into result (rgb, and the per-band values
// when the scene asks for spectral output).
void finishFrame(Device& device, const Scene& scene, cl::Buffer& rgb, cl::Buffer* spectral, size_t bands,
                 FrameResult& result) {
  const size_t pixels = static_cast<size_t>(scene.camera.width) * static_cast<size_t>(scene.camera.height);
  NonfiniteCheck check(device);
  double check_ms = 0;
  result.nonfinite = check.count(rgb, 3 * pixels, &check_ms);
  if (spectral) {
    double ms = 0;
    result.nonfinite += check.count(*spectral, pixels * bands, &ms);
    check_ms += ms;
  }
  result.timings.push_back({"nonfinite_check", check_ms});
  try {
    device.queue().enqueueReadBuffer(rgb, CL_TRUE, 0, sizeof(float) * 3 * pixels, result.rgb.pixels.data());
    if (spectral) {
      result.spectral.resize(pixels * bands);
      device.queue().enqueueReadBuffer(*spectral, CL_TRUE, 0, sizeof(float) * result.spectral.size(),
                                       result.spectral.data());
    }
  } catch (const cl::Error& e) {
    throw DeviceError(std::string("reading the frame back: ") + e.what() + " " + clErrorName(e.err()));
  }
}

}  // namespace

FrameResult renderFrame(Device& device, const Scene& scene, const Plan& plan) {
  for (const auto& pass : plan.passes) {
    if (!pass.implemented) {
      throw RuntimeError("scene '" + scene.name + "' needs pass '" + pass.name + "' (" + pass.why +
                         "), which is not implemented yet: " + pass.missing + ". `seasim plan` shows the plan.");
    }
  }
  const auto t0 = std::chrono::steady_clock::now();
  const double build_before = device.totalBuildMs();
  FrameResult result;
  const WavelengthGrid grid = makeGrid(scene.spectral.count, scene.spectral.min_nm, scene.spectral.max_nm);
  const Sensor sensor = makeSensor(scene.spectral.sensor, grid, scene.spectral.white_balance, scene.spectral.camera_dir);
  result.wavelengths_nm = grid.centers_nm;

  const int w = scene.camera.width, h = scene.camera.height;
  const size_t pixels = static_cast<size_t>(w) * static_cast<size_t>(h);
  result.rgb.width = w;
  result.rgb.height = h;
  result.rgb.channels = 3;
  result.rgb.channel_names = {"R", "G", "B"};
  result.rgb.pixels.resize(3 * pixels);

  if (const PassPlan* shafts = plan.find("shafts")) {  // issue 4: spotlight shafts (paper 001)
    ShaftsPass pass(device, scene, *shafts);
    pass.run();
    if (plan.hasPass("shadow_maps")) result.timings.push_back({"shadow_maps", pass.shadowMapMs()});
    result.timings.push_back({"shafts", pass.shaftsMs()});
    NonfiniteCheck check(device);
    double check_ms = 0;
    result.nonfinite = check.count(pass.rgb(), 3 * pixels, &check_ms);
    result.timings.push_back({"nonfinite_check", check_ms});
    pass.readRgb(result.rgb.pixels);
    result.build_ms = device.totalBuildMs() - build_before;
    result.wall_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return result;
  }

  if (const PassPlan* kd = plan.find("kd_multiple")) {  // issue 5: the underwater frame (paper 002)
    const UnderwaterSetup setup = makeUnderwaterSetup(scene, grid, sensor);
    UnderwaterPass pass(device, setup, *plan.find("raycast"), *kd, scene.spectral.spectral_exr);
    // The ocean's caustic maps (004 §5.2.1) when the scene asks for them, shared by raycast and froxels.
    std::unique_ptr<CausticStack> caustics;
    if (plan.hasPass("caustics")) {
      caustics = std::make_unique<CausticStack>(device, scene, setup);
      for (const PassTiming& t : caustics->timings()) result.timings.push_back(t);
    }
    const cl::Buffer* caustic_maps = caustics ? &caustics->maps() : nullptr;
    result.timings.push_back({"raycast", pass.runRaycast(caustic_maps)});
    // Froxel single scattering of the sun beam (002 §5.1–5.2), read by the shading at each pixel's depth.
    std::unique_ptr<FroxelPass> froxels;
    if (const PassPlan* fx = plan.find("froxel")) {
      froxels = std::make_unique<FroxelPass>(device, scene, setup, fx->defines);
      froxels->run(caustic_maps);
      for (const PassTiming& t : froxels->timings()) result.timings.push_back(t);
    }
    result.timings.push_back({"kd_multiple", pass.runShading(froxels ? &froxels->paramsBuffer() : nullptr,
                                                             froxels ? &froxels->volume() : nullptr)});
    finishFrame(device, scene, pass.rgb(), scene.spectral.spectral_exr ? &pass.spectral() : nullptr, grid.size(), result);
    // spectral.exr holds the whole image: kd_multiple wrote T L_s + L_MS per band; the froxel term
    // per band is added here (issue 13), from the same injected light.
    if (froxels && scene.spectral.spectral_exr) {
      result.timings.push_back({"froxel_spectral_bands",
                                froxels->addBandsToSpectral(setup, pass.geometry(), w, h, result.spectral)});
    }
    result.build_ms = device.totalBuildMs() - build_before;
    result.wall_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return result;
  }

  const PassPlan* sea = plan.find("sea_single");
  if (!sea) throw RuntimeError("scene '" + scene.name + "' has nothing to render (no water in view)");
  // FFT waves (004 §3): the ocean at the frame's time (surface.time) first; sea_single reads its normals.
  std::unique_ptr<OceanPass> ocean;
  if (plan.hasPass("ocean_fft")) {
    ocean = std::make_unique<OceanPass>(device, oceanConfigFromSurface(scene.surface));
    result.timings.push_back({"ocean_fft", ocean->run(scene.surface.time)});
  }
  // The ocean's caustics on the bottom (004 §5.2.1), when the scene asks for them.
  std::unique_ptr<SeaBottomCaustics> bottom_caustics;
  if (plan.hasPass("caustics")) {
    bottom_caustics = std::make_unique<SeaBottomCaustics>(seaBottomCaustics(device, scene, *ocean));
    result.timings.push_back({"caustics", bottom_caustics->ms});
  }
  SeaSinglePass pass(device, scene, *sea, grid, sensor, ocean.get(), bottom_caustics.get());
  result.timings.push_back({"sea_single", pass.run()});

  // Second-order scattering by scattering maps (000 eq. 6–8), added into sea_single's buffers.
  if (const PassPlan* second = plan.find("sea_second")) {
    SeaSecondPass second_pass(device, scene, *second, grid, sensor, pass.rgb(),
                              scene.spectral.spectral_exr ? &pass.spectral() : nullptr);
    result.timings.push_back({"sea_second", second_pass.run()});
  }

  finishFrame(device, scene, pass.rgb(), scene.spectral.spectral_exr ? &pass.spectral() : nullptr, grid.size(), result);
  result.build_ms = device.totalBuildMs() - build_before;
  result.wall_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

}  // namespace seasim
