// sea_single_features.h — the kernel features of sea_single.cl (the sea seen from above, paper 000),
// chosen by its plan rule (nodes/sea_single_node.cpp) and read by SeaSinglePass.
#pragma once
#include "plan/features.h"

namespace seasim {

struct SeaSingleFeatures final : PassFeatures {
  bool reflection = false;         // the sky and sun mirrored by the surface
  bool single_scattering = false;  // 000 eq. 5 (with sea_model 1 also the skylight scattered in the water)
  bool bottom = false;             // a flat or height-field bottom
  bool sun = false;                // the sun is on and gives light
  bool spectral_output = false;    // the per-band image (spectral.spectral_exr)
  bool waves = false;              // local normals from the ocean's normal map (common/sea_waves.h)
  int sky_model = 0;               // common/sky.h: 0 uniform, 1 analytic, 2 image, 3 Preetham
  bool bottom_caustics = false;    // the ocean's caustics on the bottom (sea.bottom_caustics)
  int sea_model = 0;               // 0 paper 000's eq. 5 and 9, 1 "multiple" (all orders in closed form)
  bool bottom_height_field = false;  // 000 §5.4: z_Q per pixel
  bool wave_filter = false;        // wave normals filtered over the pixel's footprint (common/sea_lean.h)
  int supersample = 1;             // n x n rays per pixel over the unfiltered normals (the filter's reference)
  int sky_table = 0;               // n: the reflected analytic sky from an n x n table (common/sky_table.h); 0 exact

  void list(FeatureList& out) const override {
    out.flag("reflection", "SEASIM_HAS_REFLECTION", reflection);
    out.flag("single_scattering", "SEASIM_HAS_SINGLE_SCATTERING", single_scattering);
    out.flag("bottom", "SEASIM_HAS_BOTTOM", bottom);
    out.flag("sun", "SEASIM_HAS_SUN", sun);
    out.flag("spectral_output", "SEASIM_SPECTRAL_OUTPUT", spectral_output);
    out.flag("waves", "SEASIM_HAS_WAVES", waves);
    out.value("sky_model", "SEASIM_SKY_MODEL", sky_model);
    out.flag("bottom_caustics", "SEASIM_BOTTOM_CAUSTICS", bottom_caustics);
    out.value("sea_model", "SEASIM_SEA_MODEL", sea_model);
    if (bottom_height_field) out.flag("bottom_height_field", "SEASIM_BOTTOM_HEIGHTFIELD", true);
    if (waves) out.flag("wave_filter", "SEASIM_WAVE_FILTER", wave_filter);
    if (supersample > 1) out.value("supersample", "SEASIM_SUPERSAMPLE", supersample);
    if (sky_table > 0) out.value("sky_table", "SEASIM_SEA_SKY_TABLE", sky_table);
  }
};

}  // namespace seasim
