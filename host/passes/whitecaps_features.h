// whitecaps_features.h — the kernel features of whitecaps.cl (sea-surface foam), chosen by its plan
// rule (nodes/whitecaps_node.cpp).
#pragma once
#include "plan/features.h"

namespace seasim {

struct WhitecapsFeatures final : PassFeatures {
  bool spectral_output = false;  // the foam is composited into the per-band image too (spectral.spectral_exr)

  void list(FeatureList& out) const override { out.flag("spectral_output", "SEASIM_SPECTRAL_OUTPUT", spectral_output); }
};

}  // namespace seasim
