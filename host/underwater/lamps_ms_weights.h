// lamps_ms_weights.h — the "orders" model's weights (kernels/common/underwater_lamps_ms.h: the lamp's
// W_n(s), uw_ms_weight, with the path stretch, absorption and the Poisson share of n scatterings, and the
// bottom glow's straight-path w_n(s), uw_ms_glow_weights) tabulated per band and order over the distance
// from the source, so the kernel interpolates them instead of evaluating exps and the last order's
// Poisson tail per step, band and order. Built in double from those functions themselves;
// the layout and the grid are the header's (UW_MS_WEIGHT_*). After them the bottom halo's F(z, μ_e) per
// band (uw_ms_halo_plane_from over UW_MS_HALO_DIRS x UW_MS_HALO_Z nodes): the plane's light at height z
// scattered towards the eye. It depends on the water (each band's a and b), g, κ and the number of
// orders, not on the lamps: one table for all of them.
#pragma once
#include <cstddef>
#include <vector>

extern "C" {
#include "common/underwater_params.h"
}

namespace seasim {

std::vector<float> lampMsWeights(const std::vector<UwBand>& bands, double g, double kappa, int orders);
// Its length in floats for that many bands and orders.
std::size_t lampMsWeightsSize(std::size_t bands, int orders);

}  // namespace seasim
