#include "underwater/lamps_setup.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "geometry/shafts_geometry.h"
#include "spectral/lamp_spectrum.h"

namespace seasim {

// The kernels read these structs with OpenCL C layout; float/int are 4 bytes on both sides.
static_assert(sizeof(UwLamp) == 2 * 16 + 4 * 4, "UwLamp must stay 48 bytes");
static_assert(offsetof(UwLamp, cos_cone) == 32);
static_assert(offsetof(UwLamp, sin2_cone) == 40 && offsetof(UwLamp, sin2_inner) == 44);
static_assert(sizeof(UwLampParams) == 8 * 4, "UwLampParams must stay 32 bytes");
static_assert(offsetof(UwLampParams, lamp_count) == 16);
static_assert(offsetof(UwLampParams, band_count) == 28);

UnderwaterLamps makeUnderwaterLamps(const Scene& scene, const WavelengthGrid& grid) {
  UnderwaterLamps out;
  out.params.s_min = static_cast<float>(kShaftsLampRadius);
  out.params.lamp_count = static_cast<int>(scene.spotlights.size());
  out.params.band_count = static_cast<int>(grid.size());
  for (const SpotlightDesc& l : scene.spotlights) {
    UwLamp L{};
    const Vec3 axis = normalize(l.direction);
    const double pos[3] = {l.position.x, l.position.y, l.position.z}, dir[3] = {axis.x, axis.y, axis.z};
    for (int k = 0; k < 3; ++k) {
      L.position[k] = static_cast<float>(pos[k]);
      L.direction[k] = static_cast<float>(dir[k]);
    }
    L.cos_cone = static_cast<float>(std::cos(l.cone));
    L.cos_inner = static_cast<float>(std::cos(l.cone - l.falloff));
    L.sin2_cone = static_cast<float>(std::sin(l.cone) * std::sin(l.cone));
    L.sin2_inner = static_cast<float>(std::sin(l.cone - l.falloff) * std::sin(l.cone - l.falloff));
    out.lamps.push_back(L);
    for (double v : lampSpectralIntensity(l, grid, scene.files.get())) out.spectra.push_back(static_cast<float>(v));
  }
  if (out.lamps.empty()) out.lamps.push_back(UwLamp{});
  if (out.spectra.empty()) out.spectra.push_back(0.0f);
  return out;
}

void deltaMScale(UwParams& params, std::vector<UwBand>& bands) {
  const double g = std::min(static_cast<double>(params.g), 1.0);
  if (!(g > 0)) return;
  const double f = g * g;
  for (UwBand& band : bands) {
    const double b = band.b * (1 - f);
    band.c = static_cast<float>(band.a + b);
    band.b = static_cast<float>(b);
  }
  // (g - f)/(1 - f) in the form without its 0/0 at g = 1 (where all of the light is in the peak).
  params.g = static_cast<float>(g / (1 + g));
}

}  // namespace seasim
