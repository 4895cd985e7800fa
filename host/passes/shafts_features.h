// shafts_features.h — the kernel features of shafts.cl (spotlight shafts in air, paper 001), shared
// by its shadow_maps and shafts entries (one build), chosen by nodes/shafts_node.cpp.
#pragma once
#include "plan/features.h"

namespace seasim {

struct ShaftsFeatures final : PassFeatures {
  bool intervals = false;          // exact lit stretches and shadow volumes (plan/shafts_method.h)
  bool march = false;              // midpoint steps in the lamp's angle with exact shadow rays
  bool exact = false;              // quality.shafts_exact: the exact integral per plane
  bool henyey_greenstein = false;  // air.phase = HG
  bool objects = false;            // analytic objects cast per pixel
  bool light_map = false;          // a spotlight has a light map

  // Paper 001's sampling planes: the one method that reads shadow maps and the eq. 6 tables (the intervals
  // and the march take exact shadows and g).
  bool planes() const { return !intervals && !march; }

  void list(FeatureList& out) const override {
    out.flag("intervals", "SEASIM_SHAFTS_INTERVALS", intervals);
    out.flag("march", "SEASIM_SHAFTS_MARCH", march);
    out.flag("exact", "SEASIM_SHAFTS_EXACT", exact);
    out.flag("henyey_greenstein", "SEASIM_SHAFTS_HG", henyey_greenstein);
    out.flag("objects", "SEASIM_HAS_OBJECTS", objects);
    out.flag("light_map", "SEASIM_HAS_LIGHT_MAP", light_map);
  }
};

}  // namespace seasim
