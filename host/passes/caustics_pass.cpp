#include "passes/caustics_pass.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <string>

#include "device/enqueue.h"
#include "util/error.h"

extern "C" {
#include "common/ocean_params.h"
}

namespace seasim {

static_assert(sizeof(CausticsParams) == 16 + 8 * 4, "CausticsParams layout changed: update ocean_params.h users");
static_assert(offsetof(CausticsParams, patch_size) == 16);
static_assert(offsetof(CausticsParams, n) == 36);

CausticsPass::CausticsPass(Device& device, const OceanMaps& ocean, const CausticsConfig& config)
    : device_(device), ocean_(ocean), config_(config), map_size_(config.map_size > 0 ? config.map_size : ocean.n()) {
  if (map_size_ < 1 || map_size_ > 8192) throw RuntimeError("caustics: map_size must be in 1..8192");
  if (config_.supersample < 1 || config_.supersample > 16) throw RuntimeError("caustics: supersample must be in 1..16");
  if (!(config_.plane_depth >= 0)) throw RuntimeError("caustics: plane depth must be >= 0 m");
  if (!(config_.ior >= 1)) throw RuntimeError("caustics: ior must be >= 1");
  if (!(config_.attenuation >= 0)) throw RuntimeError("caustics: attenuation must be >= 0 1/m");
  onDevice("caustics pass set-up", [&] {
    const BuiltProgram& built = device.program("caustics.cl", {});
    splat_ = cl::Kernel(built.program, "caustics_splat");
    splat_floor_ = cl::Kernel(built.program, "caustics_splat_floor");
    params_ = cl::Buffer(device.context(), CL_MEM_READ_ONLY, sizeof(CausticsParams));
    map_ = cl::Buffer(device.context(), CL_MEM_READ_WRITE, sizeof(float) * map_size_ * map_size_);
    splat_.setArg(0, params_);
    splat_.setArg(1, ocean_.fields);
    splat_.setArg(2, map_);
  });
}

double CausticsPass::run(double plane_depth) {
  if (!(plane_depth >= 0)) throw RuntimeError("caustics: plane depth must be >= 0 m");
  config_.plane_depth = plane_depth;
  return run();
}

namespace {

CausticsParams makeParams(const CausticsConfig& config, const OceanMaps& ocean, int map_size) {
  CausticsParams p{};
  const double sz = config.sun_zenith, sa = config.sun_azimuth;
  p.sun_dir[0] = static_cast<float>(std::sin(sz) * std::cos(sa));
  p.sun_dir[1] = static_cast<float>(std::cos(sz));
  p.sun_dir[2] = static_cast<float>(std::sin(sz) * std::sin(sa));
  p.patch_size = static_cast<float>(ocean.patchSize());
  p.plane_depth = static_cast<float>(config.plane_depth);
  p.ior = static_cast<float>(config.ior);
  p.attenuation = static_cast<float>(config.attenuation);
  p.choppiness = static_cast<float>(ocean.config.choppiness);
  p.n = ocean.n();
  p.map_size = map_size;
  p.supersample = config.supersample;
  return p;
}

}  // namespace

double CausticsPass::run() {
  const auto start = std::chrono::steady_clock::now();
  const CausticsParams p = makeParams(config_, ocean_, map_size_);
  onDevice("caustics pass", [&] {
    cl::CommandQueue& q = device_.queue();
    q.enqueueWriteBuffer(params_, CL_FALSE, 0, sizeof p, &p);
    q.enqueueFillBuffer(map_, 0.0f, 0, sizeof(float) * map_size_ * map_size_);
    // A sun at or below the horizon puts no direct light into the water: the map stays 0.
    if (p.sun_dir[1] > 1e-6f) {
      const size_t rays = static_cast<size_t>(ocean_.n()) * static_cast<size_t>(config_.supersample);
      q.enqueueNDRangeKernel(splat_, cl::NullRange, cl::NDRange(rays, rays));
    }
    q.finish();
  });
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

double CausticsPass::runFloor(const HeightField& field) {
  const auto start = std::chrono::steady_clock::now();
  const CausticsParams p = makeParams(config_, ocean_, map_size_);
  const double L = ocean_.patchSize(), E = field.params.extent;
  // Refracted sunlight drifts at most depth · tan θt (< depth for water) sideways before it lands.
  const double margin = static_cast<double>(field.params.max_depth) + L / ocean_.n();
  const double origin = -0.5 * E - margin;
  const int tiles = static_cast<int>(std::ceil((E + 2 * margin) / L));
  const size_t rays = static_cast<size_t>(ocean_.n()) * static_cast<size_t>(config_.supersample) * tiles;
  if (rays > 65536) throw RuntimeError("caustics: the floor (" + std::to_string(E) + " m) needs " + std::to_string(rays) +
                                       " rays per side at this surface resolution; lower the ocean grid or supersample");
  onDevice("caustics pass (floor)", [&] {
    cl::CommandQueue& q = device_.queue();
    const HeightFieldBuffers hf = uploadHeightField(device_, field);
    floor_map_ = cl::Buffer(device_.context(), CL_MEM_READ_WRITE, sizeof(float) * map_size_ * map_size_);
    q.enqueueWriteBuffer(params_, CL_FALSE, 0, sizeof p, &p);
    q.enqueueFillBuffer(floor_map_, 0.0f, 0, sizeof(float) * map_size_ * map_size_);
    if (p.sun_dir[1] > 1e-6f) {
      cl_uint arg = 0;
      splat_floor_.setArg(arg++, params_);
      splat_floor_.setArg(arg++, ocean_.fields);
      splat_floor_.setArg(arg++, hf.params);
      splat_floor_.setArg(arg++, hf.depth);
      splat_floor_.setArg(arg++, tiles);
      splat_floor_.setArg(arg++, static_cast<float>(origin));
      splat_floor_.setArg(arg++, static_cast<float>(origin));
      splat_floor_.setArg(arg++, floor_map_);
      q.enqueueNDRangeKernel(splat_floor_, cl::NullRange, cl::NDRange(rays, rays));
    }
    q.finish();
  });
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

std::vector<float> CausticsPass::readFloorMap() {
  if (!floor_map_()) throw RuntimeError("caustics: readFloorMap before runFloor");
  std::vector<float> out(static_cast<size_t>(map_size_) * map_size_);
  onDevice("caustics read-back (floor)", [&] {
    device_.queue().enqueueReadBuffer(floor_map_, CL_TRUE, 0, sizeof(float) * out.size(), out.data());
  });
  return out;
}

std::vector<float> CausticsPass::readMap() {
  std::vector<float> out(static_cast<size_t>(map_size_) * map_size_);
  onDevice("caustics read-back", [&] {
    device_.queue().enqueueReadBuffer(map_, CL_TRUE, 0, sizeof(float) * out.size(), out.data());
  });
  return out;
}

std::vector<double> causticIntensityPdf(const std::vector<float>& map, int bins, double max_ratio,
                                        std::vector<double>* ratio_out) {
  if (bins < 1 || !(max_ratio > 0)) throw RuntimeError("caustic PDF: bins must be >= 1 and max_ratio > 0");
  double mean = 0;
  for (float v : map) mean += v;
  mean /= static_cast<double>(map.size());
  std::vector<double> density(bins, 0.0);
  const double width = max_ratio / bins;
  if (ratio_out) {
    ratio_out->resize(bins);
    for (int b = 0; b < bins; ++b) (*ratio_out)[b] = (b + 0.5) * width;
  }
  if (map.empty() || !(mean > 0)) return density;
  for (float v : map) {
    const int b = std::min(bins - 1, std::max(0, static_cast<int>(v / mean / width)));
    density[b] += 1.0;
  }
  for (double& d : density) d /= static_cast<double>(map.size()) * width;
  return density;
}

}  // namespace seasim
