// whitecaps_threshold.h — where the ocean's texels are foam and how old (kernels/common/whitecaps.h):
// the threshold J_th, the `coverage`-quantile of the tile's Jacobian map, so that the foam covers that
// fraction of the tile (Monahan & O'Muircheartaigh's W at the scene's wind), and the table of J at
// evenly spaced ranks among the foam texels from which the kernel reads a texel's age.
#pragma once
#include <array>
#include <cstddef>
#include <vector>

#include "passes/whitecaps_math.h"

namespace seasim {

struct WhitecapsFoamLevels {
  float threshold = 0;                            // J_th: a texel is foam when J < J_th
  std::array<float, WHITECAPS_RANK_NODES> rank_j{};  // J at rank i / (nodes − 1) among the foam, non-decreasing
  std::size_t foam_texels = 0;                    // round(coverage · n)
};

// J_th such that exactly round(coverage · n) of the n texels have J < J_th when the texels' values
// are distinct (ties at the quantile leave fewer: J = 1 everywhere, a sea without choppiness, gives
// none). coverage 0: below every texel (no foam); 1: above every texel. The rank table interpolates
// the sorted foam values, texel r of k at rank (r + 1/2) / k. RuntimeError for an empty map, a
// non-finite J or a coverage outside [0, 1].
WhitecapsFoamLevels whitecapsFoamLevels(std::vector<float> jacobian, double coverage);

}  // namespace seasim
