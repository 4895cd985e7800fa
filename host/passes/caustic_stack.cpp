#include "passes/caustic_stack.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "passes/caustics_pass.h"
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

cl::Buffer noCausticMap(Device& device) {
  float one = 1.0f;
  try {
    return cl::Buffer(device.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(float), &one);
  } catch (const cl::Error& e) {
    throw DeviceError(std::string("caustic map placeholder: ") + e.what() + " " + clErrorName(e.err()));
  }
}

}  // namespace seasim
