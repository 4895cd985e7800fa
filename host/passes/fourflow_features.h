// fourflow_features.h — the kernel features of fourflow.cl (shallow water, paper 003), chosen by its
// plan rule (nodes/fourflow_node.cpp) and read by FourFlowPass.
#pragma once
#include "plan/features.h"

namespace seasim {

struct FourFlowFeatures final : PassFeatures {
  int tables = 0;               // 0 the exact spectral path (eq. 20), 1 (l, h) tables (eq. 22-23), 2 pre-converted (eq. 24)
  bool height_field = false;    // a sloped or height-field bottom
  bool spectral_output = false; // the per-band image (spectral.spectral_exr)
  int sky_model = 0;            // common/sky.h: 0 uniform, 1 analytic, 2 image, 3 Preetham

  void list(FeatureList& out) const override {
    out.value("tables", "SEASIM_FF_TABLES", tables);
    out.flag("height_field", "SEASIM_FF_HEIGHTFIELD", height_field);
    out.flag("spectral_output", "SEASIM_SPECTRAL_OUTPUT", spectral_output);
    out.value("sky_model", "SEASIM_SKY_MODEL", sky_model);
  }
};

}  // namespace seasim
