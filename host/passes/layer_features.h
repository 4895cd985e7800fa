// layer_features.h — the kernel features of the ground-truth layer passes (scene/output_layers.h):
// which layers a kernel writes and where, chosen by their plan rules (nodes/geometry_layers_node.cpp,
// nodes/effective_coefficients_node.cpp).
#pragma once
#include <string>
#include <vector>

#include "plan/features.h"

namespace seasim {

// geometry_layers.cl: each asked layer's first channel in the output's pixel (-1: not asked).
struct GeometryLayerFeatures final : PassFeatures {
  int range = -1, depth = -1, normal = -1, object_id = -1, albedo = -1;
  int channels = 0;            // floats per pixel
  bool albedo_bands = false;   // the albedo also per band (spectral.exr)

  void list(FeatureList& out) const override {
    out.value("range", "SEASIM_LAYER_RANGE", range);
    out.value("depth", "SEASIM_LAYER_DEPTH", depth);
    out.value("normal", "SEASIM_LAYER_NORMAL", normal);
    out.value("object_id", "SEASIM_LAYER_OBJECT_ID", object_id);
    out.value("albedo", "SEASIM_LAYER_ALBEDO", albedo);
    out.value("channels", "SEASIM_LAYER_CHANNELS", channels);
    if (albedo_bands) out.flag("albedo_bands", "SEASIM_LAYER_ALBEDO_BANDS", true);
  }
};

// effective_coefficients.cl: beta_d's and beta_b's first channel (-1: not asked).
struct EffectiveCoefficientsFeatures final : PassFeatures {
  int beta_d = -1, beta_b = -1;
  int channels = 0;  // floats per pixel

  void list(FeatureList& out) const override {
    out.value("beta_d", "SEASIM_LAYER_BETA_D", beta_d);
    out.value("beta_b", "SEASIM_LAYER_BETA_B", beta_b);
    out.value("channels", "SEASIM_LAYER_CHANNELS", channels);
  }
};

}  // namespace seasim
