// sea_second_features.h — the kernel features of sea_second.cl (000 eq. 6-8), chosen by its plan
// rule (nodes/sea_second_node.cpp).
#pragma once
#include "plan/features.h"

namespace seasim {

struct SeaSecondFeatures final : PassFeatures {
  bool bottom = false;               // a flat or height-field bottom
  bool spectral_output = false;      // the per-band image (spectral.spectral_exr)
  bool bottom_height_field = false;  // depth tables per map texel (000 §5.4)

  void list(FeatureList& out) const override {
    out.flag("bottom", "SEASIM_HAS_BOTTOM", bottom);
    out.flag("spectral_output", "SEASIM_SPECTRAL_OUTPUT", spectral_output);
    if (bottom_height_field) out.flag("bottom_height_field", "SEASIM_BOTTOM_HEIGHTFIELD", true);
  }
};

}  // namespace seasim
