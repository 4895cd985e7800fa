#include "passes/caustic_stack.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "math/kernel_math.h"
#include "passes/caustics_pass.h"
#include "passes/sea_heightfield.h"
#include "util/error.h"

namespace seasim {

CausticStack::CausticStack(Device& device, const Scene& scene, const UnderwaterSetup& setup) {
  const UwParams& p = setup.params;
  layers_ = p.caustic_layers;
  if (layers_ < 1 || layers_ > 64) throw RuntimeError("quality.caustic_layers must be in 1..64");
  const OceanConfig ocean_config = oceanConfigFromSurface(scene.surface);
  map_size_ = p.caustic_map_size;
  const size_t texels = static_cast<size_t>(map_size_) * static_cast<size_t>(map_size_);
  host_.assign(texels * static_cast<size_t>(layers_), 1.0f);

  const Vec3 sun = setup.sun_air;
  if (sun.y > 0) {
    OceanPass ocean(device, ocean_config);
    timings_.push_back({"ocean_fft", ocean.run(scene.surface.time)});
    CausticsConfig config;
    config.sun_zenith = std::acos(std::min(1.0, sun.y));
    config.sun_azimuth = std::atan2(sun.z, sun.x);
    config.ior = scene.water.ior;
    // No attenuation in the splat: the mean beam's e^{-c y/μ_w} is the model's (002 eq. 4.7); the
    // maps only redistribute it (the per-ray path differences are second order in the slopes).
    config.attenuation = 0.0;
    config.map_size = map_size_;
    CausticsPass splat(device, ocean, config);
    double ms = 0;
    for (int k = 0; k < layers_; ++k) {
      ms += splat.run((k + 1) * static_cast<double>(p.caustic_depth_max) / layers_);
      std::vector<float> layer = splat.readMap();
      double sum = 0;
      for (float v : layer) sum += v;
      const double mean = sum / static_cast<double>(texels);
      // A layer that received nothing (every facet turned from a grazing sun) stays uniform.
      if (!(mean > 0) || !std::isfinite(mean)) continue;
      for (size_t t = 0; t < texels; ++t) host_[k * texels + t] = static_cast<float>(layer[t] / mean);
    }
    timings_.push_back({"caustics", ms});
  }
  try {
    maps_ = cl::Buffer(device.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(float) * host_.size(),
                       host_.data());
  } catch (const cl::Error& e) {
    throw DeviceError(std::string("caustic map upload: ") + e.what() + " " + clErrorName(e.err()));
  }
}

SeaBottomCaustics seaBottomCaustics(Device& device, const Scene& scene, OceanPass& ocean) {
  const auto start = std::chrono::steady_clock::now();
  SeaBottomCaustics out;
  const auto size = scene.quality.find("caustic_map_size");
  out.map_size = size != scene.quality.end() ? static_cast<int>(size->second.value) : 256;
  CausticsConfig config;
  config.sun_zenith = scene.sun.zenith;
  config.sun_azimuth = scene.sun.azimuth;
  config.ior = scene.water.ior;
  config.attenuation = 0.0;  // eq. 9 attenuates the mean beam; the map only redistributes it
  config.map_size = out.map_size;
  CausticsPass splat(device, ocean, config);
  const size_t texels = static_cast<size_t>(out.map_size) * static_cast<size_t>(out.map_size);
  if (scene.bottom.type == BottomDesc::Type::HeightField) {
    const HeightField field = loadHeightField(scene.bottom);
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
    splat.run(scene.bottom.depth);
    out.host = splat.readMap();
    out.extent = ocean.patchSize();
    double sum = 0;
    for (float v : out.host) sum += v;
    const double mean = sum / static_cast<double>(texels);
    for (float& v : out.host) v = mean > 0 && std::isfinite(mean) ? static_cast<float>(v / mean) : 1.0f;
  }
  try {
    out.map = cl::Buffer(device.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(float) * out.host.size(),
                         out.host.data());
  } catch (const cl::Error& e) {
    throw DeviceError(std::string("bottom caustic map upload: ") + e.what() + " " + clErrorName(e.err()));
  }
  out.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return out;
}

cl::Buffer noCausticMap(Device& device) {
  float one = 1.0f;
  try {
    return cl::Buffer(device.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(float), &one);
  } catch (const cl::Error& e) {
    throw DeviceError(std::string("caustic map placeholder: ") + e.what() + " " + clErrorName(e.err()));
  }
}

}  // namespace seasim
