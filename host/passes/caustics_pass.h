// caustics_pass.h — host side of kernels/caustics.cl: the caustic pattern on a plane at depth d under
// the FFT ocean, by flux conservation (004 §5.2.1). Reads the ocean pass's field buffer as it stands
// after OceanPass::run(t); writes an M x M float map over the same periodic L x L patch: irradiance on
// the plane / sun irradiance on a horizontal surface above water (flat sea: T(θ) e^{-c d / cos θt}).
#pragma once
#include <CL/opencl.hpp>

#include <vector>

#include "device/device.h"
#include "passes/ocean_pass.h"
#include "passes/sea_heightfield.h"

namespace seasim {

struct CausticsConfig {
  double plane_depth = 5.0;   // d, m below the mean surface
  double sun_zenith = 0.0;    // radians
  double sun_azimuth = 0.0;   // radians, from +x towards +z
  double ior = 1.333;         // water relative to air
  double attenuation = 0.0;   // c, 1/m (Beer–Lambert along the refracted path)
  int map_size = 0;           // M; 0 = the ocean's N
  int supersample = 2;        // s: s x s rays per surface cell
};

class CausticsPass {
 public:
  // Reads `ocean`'s field buffer as it stands at each run. Throws RuntimeError on bad values.
  CausticsPass(Device& device, const OceanMaps& ocean, const CausticsConfig& config);

  // Splats the ocean's current surface onto the plane; waits; returns wall milliseconds.
  double run();
  // Same at another plane depth (m).
  double run(double plane_depth);

  int mapSize() const { return map_size_; }
  double patchSize() const { return ocean_.patchSize(); }
  cl::Buffer& map() { return map_; }  // M² floats (stored as bits in int words), row = z
  std::vector<float> readMap();

  // The splat onto a height-field floor instead of the plane (caustics_splat_floor in caustics.cl):
  // an M x M map over the floor's square [-E/2, E/2]² (E = field.params.extent), M = mapSize(): the
  // irradiance on the floor itself over the sun's on a horizontal surface above water (a level floor
  // gives the plane's map). The ocean tiles over the square plus a margin of the deepest
  // node's depth on every side. Waits; returns wall ms. Read with readFloorMap().
  double runFloor(const HeightField& field);
  std::vector<float> readFloorMap();
  const CausticsConfig& config() const { return config_; }

 private:
  Device& device_;
  OceanMaps ocean_;
  CausticsConfig config_;
  int map_size_;
  cl::Kernel splat_, splat_floor_;
  cl::Buffer params_, map_, floor_map_;
};

// Probability density of I/<I> over the map's texels (004 §5.2.1, Figure 29): `bins` equal bins on
// [0, max_ratio]; density[b] integrates to the fraction of texels in bin b (values above max_ratio
// are counted in the last bin). Returns the bin centres in `ratio_out` when non-null.
std::vector<double> causticIntensityPdf(const std::vector<float>& map, int bins, double max_ratio,
                                        std::vector<double>* ratio_out = nullptr);

}  // namespace seasim
