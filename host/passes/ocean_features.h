// ocean_features.h — the kernel features of ocean.cl (the FFT ocean, paper 004), chosen by its plan
// rule (nodes/ocean_node.cpp).
#pragma once
#include "plan/features.h"

namespace seasim {

struct OceanFeatures final : PassFeatures {
  bool choppy = false;  // horizontal displacement (surface.choppiness > 0)

  void list(FeatureList& out) const override { out.flag("choppy", "SEASIM_HAS_CHOPPY", choppy); }
};

}  // namespace seasim
