// lamps_bottom_glow.h — the flat bottom's glow under each spotlight, for the "orders" model of the lamps
// under water (kernels/common/underwater_lamps_ms.h, "The bottom's glow"): the lit patch taken as one
// Lambertian source, its irradiance-weighted centre, its RMS radius and its strength per band. Built in
// double on the host by integrating the lamp's light over the bottom plane (the direct light over the
// lamp's solid angle, the orders' light over the plane), once per lamp and water.
#pragma once
#include <vector>

extern "C" {
#include "common/underwater_lamps_params.h"
#include "common/underwater_params.h"
}

namespace seasim {

// Floats per lamp in the kernel's glow buffer: centre x, y, z, radius, then band_count strengths J(λ)
// (= ρ(λ) ∫ E/π dA per unit I(λ), all the lamp's light), then band_count strengths of its direct light
// alone (the part that reaches the eye scattered once in the water). Radius 0: no glow (no bottom, the
// lamp not above it, or no light on it).
inline int lampGlowStride(int band_count) { return 4 + 2 * band_count; }

struct LampGlowModel {
  double g = 0.9;      // the water's HG asymmetry
  double kappa = 0.75; // quality.lamps_ms_kappa
  int orders = 8;      // quality.lamps_orders
};

// One lamp's glow: lampGlowStride(bands.size()) floats. ms_rows: the lamp's blurred profiles
// (lampMsProfiles, `orders` rows); s_min the lamps' clamp radius. The bottom is the plane
// y = -params.bottom_depth, its albedo bands[i].bottom_albedo.
std::vector<float> lampBottomGlow(const UwLamp& lamp, const UwParams& params, const std::vector<UwBand>& bands,
                                  const float* ms_rows, double s_min, const LampGlowModel& model);

// Every lamp's glow, lamp after lamp (ms_table as lampMsTable lays it out).
std::vector<float> lampBottomGlowTable(const std::vector<UwLamp>& lamps, const UwParams& params,
                                       const std::vector<UwBand>& bands, const std::vector<float>& ms_table, double s_min,
                                       const LampGlowModel& model);

}  // namespace seasim
