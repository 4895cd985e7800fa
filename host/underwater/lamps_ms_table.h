// lamps_ms_table.h — the blurred profiles P_n = P ⊛ HG(h_n) of each spotlight under water, orders
// n = 1..N (kernels/common/underwater_lamps_ms.h): what the "orders" model of the lamps looks up per
// point instead of integrating the lamp's cone against a phase function there. Built in double on the
// host from the lamp's cone, its soft edge and the water's g (the only inputs: no per-band data).
#pragma once
#include <vector>

extern "C" {
#include "common/underwater_lamps_params.h"
}

namespace seasim {

// One row of UW_MS_ROW floats per order: P_n(ψ) at ψ = 0°, 1°, .., 180° (UW_MS_TABLE floats) for a lamp of cone cos_cone
// and inner cos_inner (common/shafts.h's profile), P_n = ∫ P(ω') p_HG(ω·ω'; h_n) dω', h_n =
// uw_ms_spread(g, n, β); β the spread knob (quality.lamps_ms_spread). Quadrature over the HG kernel by its inverse CDF (u_steps midpoints in u, so a
// kernel as narrow as g -> 1 gives is sampled where its mass is) and phi_steps in azimuth. Then the order's
// irradiance factor F(g^n, cos θ_i) at UW_MS_IRRADIANCE cosines uniform over [-1, 1] (uw_ms_irradiance_exact).
std::vector<float> lampMsProfiles(double cos_cone, double cos_inner, double g, double beta, int orders, int u_steps = 256,
                                  int phi_steps = 64);

// The rows of every lamp, lamp after lamp (lamp l's order n at (l * orders + n - 1) * UW_MS_ROW).
std::vector<float> lampMsTable(const std::vector<UwLamp>& lamps, double g, double beta, int orders);

}  // namespace seasim
