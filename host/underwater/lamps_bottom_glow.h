// lamps_bottom_glow.h — the flat bottom's glow under each spotlight, for the "orders" model of the lamps
// under water (kernels/common/underwater_lamps_ms.h, "The bottom's glow"): the lit patch taken as one
// Lambertian source, its irradiance-weighted centre, its RMS radius and its strength per band. Built in
// double on the host by integrating the lamp's direct light over its solid angle, once per lamp and
// water. The orders' light on the bottom (its halo) is not in it: the kernel takes that from the bottom
// right below each point it lights (common/underwater_lamps_ms.h, "The bottom's halo").
#pragma once
#include <vector>

extern "C" {
#include "common/underwater_lamps_params.h"
#include "common/underwater_params.h"
}

namespace seasim {

// Floats per lamp in the kernel's glow buffer: centre x, y, z, radius, then band_count strengths J(λ)
// (= ρ(λ) ∫ E/π dA per unit I(λ) of the lamp's direct light). Radius 0: no glow (no bottom, the lamp
// not above it, or no direct light on it).
inline int lampGlowStride(int band_count) { return 4 + band_count; }

// One lamp's glow: lampGlowStride(bands.size()) floats; s_min the lamps' clamp radius (the least
// radius). The bottom is the plane y = -params.bottom_depth, its albedo bands[i].bottom_albedo.
std::vector<float> lampBottomGlow(const UwLamp& lamp, const UwParams& params, const std::vector<UwBand>& bands,
                                  double s_min);

// Every lamp's glow, lamp after lamp.
std::vector<float> lampBottomGlowTable(const std::vector<UwLamp>& lamps, const UwParams& params,
                                       const std::vector<UwBand>& bands, double s_min);

}  // namespace seasim
