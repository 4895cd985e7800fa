// underwater_features.h — the kernel features of the underwater frame's kernels (paper 002):
// raycast.cl's G-buffer, froxel.cl, kd_multiple.cl and underwater_lamps.cl, each chosen by its plan
// rule (nodes/raycast_node.cpp, froxel_node.cpp, kd_multiple_node.cpp, underwater_lamps_node.cpp).
#pragma once
#include "plan/features.h"

namespace seasim {

struct UnderwaterRaycastFeatures final : PassFeatures {
  bool objects = false;  // analytic objects in the water
  bool sun = false;      // the sun is up: its visibility per pixel
  int caustics = 0;      // 0 none, 1 texture, 2 the ocean's caustic maps

  void list(FeatureList& out) const override {
    out.flag("objects", "SEASIM_HAS_OBJECTS", objects);
    out.flag("sun", "SEASIM_HAS_SUN", sun);
    out.value("caustics", "SEASIM_CAUSTICS", caustics);
  }
};

struct FroxelFeatures final : PassFeatures {
  bool objects = false;             // objects shadow the beam
  int caustics = 0;                 // 0 none, 1 texture, 2 the ocean's caustic maps
  bool spectral_injection = false;  // underwater.injection = "spectral" (else RGB)

  void list(FeatureList& out) const override {
    out.flag("objects", "SEASIM_HAS_OBJECTS", objects);
    out.value("caustics", "SEASIM_CAUSTICS", caustics);
    out.flag("spectral_injection", "SEASIM_SPECTRAL_INJECTION", spectral_injection);
  }
};

struct KdFeatures final : PassFeatures {
  bool multiple = false;         // L_MS (underwater.multiple_scattering)
  bool froxel = false;           // the froxel volume's single scattering is added
  bool spectral_output = false;  // the per-band image (spectral.spectral_exr)
  int sky_model = 0;             // Snell's window: common/sky.h's models
  int underwater_model = 0;      // 0 thesis (002 eq. 4.7), 1 discrete ordinates (common/underwater_ordinates.h)
  bool point_spread = false;     // the forward light kept apart for water_spread
  bool formation_layers = false;  // outputs.layers clear, direct, backscatter, forward, lamps, transmission
  bool veiling_layer = false;     // outputs.layers veiling (B∞: the in-scatter with S = ∞)
  bool band_layers = false;       // the split also per band in spectral.exr (formation_layers + spectral_output)
  bool veiling_bands = false;     // the veiling also per band in spectral.exr (veiling_layer + spectral_output)
  // How many of outputs.layers lamps_single, lamps_multiple were asked (3 floats per pixel each): their
  // buffer is zeroed before the kernel (no define: the kernel does not touch it), underwater_lamps adds
  // into it.
  int lamps_split_layers = 0;
  bool sand_map = false;  // the objects' shares from sand_share.cl's lattice (quality.sand_share_step > 1)

  void list(FeatureList& out) const override {
    out.flag("multiple", "SEASIM_HAS_MULTIPLE", multiple);
    out.flag("froxel", "SEASIM_HAS_FROXEL", froxel);
    out.flag("spectral_output", "SEASIM_SPECTRAL_OUTPUT", spectral_output);
    out.value("sky_model", "SEASIM_SKY_MODEL", sky_model);
    out.value("underwater_model", "SEASIM_UNDERWATER_MODEL", underwater_model);
    out.flag("point_spread", "SEASIM_UWI_SPREAD", point_spread);
    // Listed only when asked: a plan without layers keeps its defines, and its kernels their cache.
    if (formation_layers) out.flag("formation_layers", "SEASIM_LAYER_FORMATION", true);
    if (veiling_layer) out.flag("veiling_layer", "SEASIM_LAYER_VEILING", true);
    if (band_layers) out.flag("band_layers", "SEASIM_LAYER_BANDS", true);
    if (veiling_bands) out.flag("veiling_bands", "SEASIM_LAYER_VEILING_BANDS", true);
    if (sand_map) out.flag("sand_map", "SEASIM_SAND_SHARE_MAP", true);
  }
};

struct UnderwaterLampsFeatures final : PassFeatures {
  bool objects = false;          // objects shadow the lamps
  bool spectral_output = false;  // the per-band image (spectral.spectral_exr)
  bool lamps_layer = false;      // outputs.layers: the lamps' light also added into its own layer
  bool band_layers = false;      // and per band into kd_multiple's band layers (spectral.exr)
  bool orders = false;           // quality.lamps_model = "orders": multiple scattering (underwater_lamps_ms.h)
  bool lamps_split = false;      // outputs.layers lamps_single / lamps_multiple (kd_multiple's lamps_split_layer)
  bool ms_lattice = false;       // the orders' smooth part on a lattice (quality.lamps_ms_cell_deg over 2 pixels)

  void list(FeatureList& out) const override {
    out.flag("objects", "SEASIM_HAS_OBJECTS", objects);
    out.flag("spectral_output", "SEASIM_SPECTRAL_OUTPUT", spectral_output);
    if (lamps_layer) out.flag("lamps_layer", "SEASIM_LAYER_LAMPS", true);
    if (band_layers) out.flag("band_layers", "SEASIM_LAYER_BANDS", true);
    if (orders) out.flag("orders", "SEASIM_LAMPS_ORDERS", true);
    if (lamps_split) out.flag("lamps_split", "SEASIM_LAYER_LAMPS_SPLIT", true);
    if (ms_lattice) out.flag("ms_lattice", "SEASIM_LAMPS_MS_LATTICE", true);
  }
};

}  // namespace seasim
