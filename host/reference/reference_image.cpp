#include "reference/reference_image.h"

#include <chrono>
#include <optional>

#include "device/device.h"
#include "ocean/ocean_cpu.h"
#include "passes/ocean_pass.h"
#include "plan/scene_facts.h"
#include "reference/froxel_reference.h"
#include "reference/sea_reference.h"
#include "reference/sea_second_reference.h"
#include "reference/shafts_reference.h"
#include "reference/underwater_reference.h"
#include "scene/water_phase.h"
#include "spectral/sensor.h"
#include "spectral/wavelength_grid.h"
#include "underwater/underwater_setup.h"
#include "util/error.h"

namespace seasim {

namespace {

// The given steps, else the scene's quality knob (a count: "auto" has no meaning for a reference).
int referenceSteps(const Scene& scene, int steps, const char* knob) {
  if (steps > 0) return steps;
  const auto it = scene.quality.find(knob);
  if (it == scene.quality.end()) throw RuntimeError(std::string("reference: no quality.") + knob);
  if (it->second.automatic) {
    throw RuntimeError(std::string("reference: quality.") + knob +
                       " = \"auto\" is not supported (a reference has no error budget): give a number or --steps");
  }
  return static_cast<int>(it->second.value);
}

}  // namespace

namespace {

WaveNormalMap waveNormalMap(const SurfaceDesc& surface) {
  const OceanConfig config = oceanConfigFromSurface(surface);
  OceanCpu ocean(config, OceanCpu::Precision::Double);
  ocean.run(surface.time);
  WaveNormalMap map;
  map.grid = config.grid;
  map.patch = config.patch_size;
  for (double v : ocean.normal()) map.normals.push_back(static_cast<float>(v));
  return map;
}

// Under water, single scattering only: the froxel pass's term by deterministic quadrature over each
// pixel's area (froxel_reference.h froxelBruteForcePixelArea). The scene's surfaces are lit as well in
// a render: compare the term alone with black surfaces and a dark sky (results/BENCHMARKS.md).
ReferenceImage sunSingleQuadrature(const Scene& scene, const ReferenceOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  if (!cameraUnderwater(scene) || scene.underwater.multiple_scattering || !scene.spotlights.empty())
    throw RuntimeError("reference --sun-single-quadrature: for an underwater camera with "
                       "underwater.multiple_scattering = false and no spotlights (the sun beam's single scattering)");
  if (scene.underwater.caustics == UnderwaterDesc::Caustics::Map)
    throw RuntimeError("reference --sun-single-quadrature: underwater.caustics = \"map\" is not modelled; use "
                       "\"texture\" or \"none\"");
  const WavelengthGrid grid = makeGrid(scene.spectral.count, scene.spectral.min_nm, scene.spectral.max_nm);
  const UnderwaterSetup setup = makeUnderwaterSetup(
      scene, grid, makeSensor(scene.spectral.sensor, grid, scene.spectral.white_balance, scene.spectral.camera_dir));
  ReferenceImage out;
  out.steps = referenceSteps(scene, options.steps, "reference_steps");
  const std::vector<double> rgb = froxelBruteForcePixelArea(setup, out.steps, options.sun_single_subpixels);
  out.rgb.resize(setup.params.width, setup.params.height, 3);
  for (size_t i = 0; i < rgb.size(); ++i) out.rgb.pixels[i] = static_cast<float>(rgb[i]);
  out.method = "quadrature";
  out.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace

ReferenceImage renderReference(const Scene& scene, const ReferenceOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  const bool above = options.all_orders;
  if (above && (cameraUnderwater(scene) || !scene.water.present || !(scene.camera.position.y > 0))) {
    throw RuntimeError("reference --all-orders: for the sea seen from above only (a [water] scene, camera y > 0)");
  }
  ReferenceImage out;
  if (options.sun_single_subpixels > 0) return sunSingleQuadrature(scene, options);
  if (above || cameraUnderwater(scene)) {
    // Under water: the spectral path tracer on the device, `steps` paths per pixel. With
    // underwater.multiple_scattering = false it traces single scattering of the sun beam only, the
    // reference of the froxel pass (make surfaces black and the sky dark to compare that term alone).
    Device device(chooseDevice(options.device));
    const WavelengthGrid grid = makeGrid(scene.spectral.count, scene.spectral.min_nm, scene.spectral.max_nm);
    const UnderwaterSetup setup = makeUnderwaterSetup(
        scene, grid, makeSensor(scene.spectral.sensor, grid, scene.spectral.white_balance, scene.spectral.camera_dir));
    UnderwaterReferenceSettings settings;
    settings.samples_per_pixel = referenceSteps(scene, options.steps, "reference_spp");
    settings.seed = options.seed >= 0 ? static_cast<unsigned>(options.seed) : 1u;
    settings.camera_above = above;
    if (options.max_bounces > 0) settings.max_bounces = options.max_bounces;
    if (!scene.underwater.multiple_scattering) settings.max_bounces = 1;
    const UnderwaterLamps lamps = makeUnderwaterLamps(scene, grid);  // [[spotlights]] under water, by NEE
    settings.lamps = &lamps;
    // The sea's height-field floor (000 §5.4), met exactly by every path (common/sea_bottom.h).
    std::optional<HeightField> floor;
    if (scene.bottom.type == BottomDesc::Type::HeightField) {
      floor = loadHeightField(scene.bottom, scene.files.get());
      settings.height_field = &*floor;
    }
    // FFT waves seen from above: the ocean at surface.time in double on the CPU (ocean_cpu.h), its normal
    // map traced as the fast sea model reads the ocean pass's (common/sea_waves.h; kernels/reference.cl).
    std::optional<WaveNormalMap> waves;
    if (above && scene.surface.type == SurfaceDesc::Type::Fft) waves = waveNormalMap(scene.surface);
    settings.waves = waves ? &*waves : nullptr;
    settings.sun_angular_radius = scene.sun.angular_radius;
    settings.lamp_mis = options.lamp_mis;
    settings.jitter = !options.pixel_centre;
    settings.progress = options.progress;
    // A phase other than HG (`[water] phase`) is traced exactly from its tables; HG keeps its closed form.
    if (scene.water.phase != "hg") settings.phase_tables = waterPhase(scene.water).pathTracerTables();
    UnderwaterReferenceResult r = renderUnderwaterReference(device, setup, settings);
    out.rgb = std::move(r.rgb);
    out.std_error = std::move(r.std_error);
    if (!above) {
      out.direct = std::move(r.direct);
      out.direct_std_error = std::move(r.direct_std_error);
    }
    out.method = "path tracer";
    out.steps = r.samples;
    out.seed = settings.seed;
    out.max_bounces = settings.max_bounces;
    out.ms = r.ms;
    out.mean_std_error = r.mean_std_error;
    out.image_mean = r.image_mean;
    out.image_mean_std_error = r.image_mean_std_error;
    out.effective_samples = r.effective_samples;
    out.blocks = r.blocks;
    out.device_name = device.info().name;
    return out;
  }
  // Spotlights in air: the shafts ray marcher; otherwise the sea reference.
  const bool shafts = scene.air.present && !scene.spotlights.empty();
  out.steps = referenceSteps(scene, options.steps, "reference_steps");
  out.method = shafts ? "ray-march" : "quadrature";
  out.rgb = shafts ? renderShaftsReference(scene, out.steps) : renderSeaReference(scene, out.steps);
  if (!shafts && scene.sea.second_order) {  // + L^(2) by direct quadrature (000 eq. 6)
    const Image second = renderSeaSecondReference(scene);
    for (size_t i = 0; i < out.rgb.pixels.size(); ++i) out.rgb.pixels[i] += second.pixels[i];
  }
  out.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace seasim
