#include "passes/caustic_stack.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <string>

#include "device/enqueue.h"
#include "math/kernel_math.h"
#include "passes/caustics_pass.h"
#include "passes/sea_heightfield.h"
#include "util/error.h"

namespace seasim {

namespace {

// The splat of the scene's sun into its water. No attenuation: the mean beam's e^{-c l} is the
// model's (002 eq. 4.7 under water, 000 eq. 9 from above); the maps only redistribute it (the
// per-ray path differences are second order in the slopes).
CausticsConfig splatConfig(const Scene& scene, int map_size) {
  CausticsConfig config;
  config.sun_zenith = scene.sun.zenith;
  config.sun_azimuth = scene.sun.azimuth;
  config.ior = scene.water.ior;
  config.attenuation = 0.0;
  config.map_size = map_size;
  return config;
}

// Divides the map by its mean; a map that received nothing (every facet turned from a grazing sun)
// becomes uniform.
void divideByMean(std::vector<float>& map) {
  double sum = 0;
  for (float v : map) sum += v;
  const double mean = sum / static_cast<double>(map.size());
  for (float& v : map) v = mean > 0 && std::isfinite(mean) ? static_cast<float>(v / mean) : 1.0f;
}

cl::Buffer upload(Device& device, const std::vector<float>& values, const char* what) {
  return onDevice(std::string(what) + " upload", [&] {
    return cl::Buffer(device.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(float) * values.size(),
                      const_cast<float*>(values.data()));
  });
}

}  // namespace

CausticStack::CausticStack(Device& device, const Scene& scene, const UnderwaterSetup& setup)
    : CausticStack(device, scene, setup, nullptr) {}

CausticStack::CausticStack(Device& device, const Scene& scene, const UnderwaterSetup& setup, const OceanMaps* ocean) {
  const UwParams& p = setup.params;
  layers_ = p.caustic_layers;
  if (layers_ < 1 || layers_ > 64) throw RuntimeError("quality.caustic_layers must be in 1..64");
  const OceanConfig ocean_config = oceanConfigFromSurface(scene.surface);
  map_size_ = p.caustic_map_size;
  const size_t texels = static_cast<size_t>(map_size_) * static_cast<size_t>(map_size_);
  host_.assign(texels * static_cast<size_t>(layers_), 1.0f);

  if (setup.sun_air.y > 0) {
    std::unique_ptr<OceanPass> own;
    OceanMaps own_maps;
    if (!ocean) {
      own = std::make_unique<OceanPass>(device, ocean_config);
      timings_.push_back({"ocean_fft", own->run(scene.surface.time)});
      own_maps = own->maps();
      ocean = &own_maps;
    }
    CausticsPass splat(device, *ocean, splatConfig(scene, map_size_));
    double ms = 0;
    for (int k = 0; k < layers_; ++k) {
      ms += splat.run((k + 1) * static_cast<double>(p.caustic_depth_max) / layers_);
      std::vector<float> layer = splat.readMap();
      divideByMean(layer);
      std::copy(layer.begin(), layer.end(), host_.begin() + static_cast<std::ptrdiff_t>(k * texels));
    }
    timings_.push_back({"caustics", ms});
  }
  maps_ = upload(device, host_, "caustic map");
}

SeaBottomCaustics seaBottomCaustics(Device& device, const Scene& scene, const OceanMaps& ocean) {
  const auto start = std::chrono::steady_clock::now();
  SeaBottomCaustics out;
  const auto size = scene.quality.find("caustic_map_size");
  out.map_size = size != scene.quality.end() ? static_cast<int>(size->second.value) : 256;
  CausticsConfig config = splatConfig(scene, out.map_size);
  if (scene.bottom.type == BottomDesc::Type::HeightField) {
    const HeightField field = loadHeightField(scene.bottom, scene.files.get());
    // The floor usually spans many ocean patches: one ray per surface texel keeps the walk count at
    // (N · tiles)² instead of 4× that (the map is coarser than the tiled surface anyway).
    config.supersample = 1;
    CausticsPass floor_splat(device, ocean, config);
    floor_splat.runFloor(field);
    out.host = floor_splat.readFloorMap();
    out.extent = field.params.extent;
    out.origin = -0.5 * out.extent;
    out.periodic = false;
    // The calm-sea value of each texel: T(θ) times the slope's Lambert cosine relative to level.
    const double sz = config.sun_zenith, sa = config.sun_azimuth, ior = config.ior;
    const double T = 1.0 - kmath_d::fresnel_reflectance(std::cos(sz), 1.0, ior);
    const double sin_t = std::sin(sz) / ior, cos_t = std::sqrt(std::max(0.0, 1.0 - sin_t * sin_t));
    const double tx = -sin_t * std::cos(sa), ty = -cos_t, tz = -sin_t * std::sin(sa);  // refracted travel
    const double texel = out.extent / out.map_size;
    for (int j = 0; j < out.map_size; ++j)
      for (int i = 0; i < out.map_size; ++i) {
        const kmath_d::real3 n = kmath_d::sea_hf_normal_at(&field.params, field.depth.data(), out.origin + (i + 0.5) * texel,
                                                           out.origin + (j + 0.5) * texel);
        const double calm = T * std::max(0.0, -(tx * n.x + ty * n.y + tz * n.z)) / std::max(cos_t, 1e-6);
        float& v = out.host[static_cast<size_t>(j) * out.map_size + i];
        v = calm > 1e-6 ? static_cast<float>(v / calm) : 1.0f;
      }
  } else {
    CausticsPass splat(device, ocean, config);
    splat.run(scene.bottom.depth);
    out.host = splat.readMap();
    out.extent = ocean.patchSize();
    divideByMean(out.host);
  }
  out.map = upload(device, out.host, "bottom caustic map");
  out.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return out;
}

cl::Buffer noCausticMap(Device& device) { return upload(device, {1.0f}, "caustic map placeholder"); }

}  // namespace seasim
