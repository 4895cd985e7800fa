#include "passes/sea_band_table.h"

#include <algorithm>
#include <cstddef>

#include "math/kernel_math.h"
#include "util/error.h"

namespace seasim {

std::vector<float> seaBandTable(const std::vector<SeaBand>& bands, const std::vector<float>& lut, int lut_size,
                                const std::vector<double>& ordinates) {
  const int count = static_cast<int>(bands.size());
  const int stride = SEA_BAND_STRIDE(std::max(count, 1));
  const bool with_ordinates = !ordinates.empty() && count > 0;
  if (with_ordinates && lut_size > 1)
    throw RuntimeError("sea band table: κ's rows take the LUT's place; no LUT with them");
  const int ordinate_nodes = with_ordinates ? static_cast<int>(ordinates.size() / count) : 0;
  const bool known_nodes = ordinate_nodes == SEA_ORD_NODES || ordinate_nodes == SEA_ORD_LAYER;
  if (with_ordinates && (ordinates.size() % count != 0 || !known_nodes))
    throw RuntimeError("sea band table: κ has " + std::to_string(ordinates.size()) + " entries, not " +
                       std::to_string(SEA_ORD_NODES) + " or " + std::to_string(SEA_ORD_LAYER) + " nodes x " +
                       std::to_string(count) + " bands");
  const int lut_rows = with_ordinates ? ordinate_nodes : std::max(lut_size, 1);
  std::vector<float> table(static_cast<size_t>(SEA_ROWS + lut_rows) * stride, 0.0f);
  if (count == 0) return table;
  if (lut_size > 1 && lut.size() != static_cast<size_t>(count) * lut_size)
    throw RuntimeError("sea band table: the LUT has " + std::to_string(lut.size()) + " entries, not " +
                       std::to_string(count) + " bands x " + std::to_string(lut_size));
  auto at = [&](int row, int band) -> float& { return table[static_cast<size_t>(row) * stride + band]; };
  for (int i = 0; i < stride; ++i) {
    const int k = std::min(i, count - 1);  // padding bands repeat the last one
    const SeaBand& b = bands[k];
    const bool real_band = i < count;
    at(SEA_ROW_SUN, i) = b.sun_irradiance;
    at(SEA_ROW_SKY, i) = b.sky_radiance;
    at(SEA_ROW_A, i) = b.a;
    at(SEA_ROW_B, i) = b.b;
    at(SEA_ROW_C, i) = b.c;
    at(SEA_ROW_BOTTOM_ALBEDO, i) = b.bottom_albedo;
    at(SEA_ROW_W_R, i) = real_band ? b.w_r : 0.0f;
    at(SEA_ROW_W_G, i) = real_band ? b.w_g : 0.0f;
    at(SEA_ROW_W_B, i) = real_band ? b.w_b : 0.0f;
    at(SEA_ROW_SKY_W_R, i) = b.sky_w_r;
    at(SEA_ROW_SKY_W_G, i) = b.sky_w_g;
    at(SEA_ROW_SKY_W_B, i) = b.sky_w_b;
    if (lut_size > 1)
      for (int j = 0; j < lut_size; ++j) at(SEA_ROW_LUT + j, i) = lut[static_cast<size_t>(k) * lut_size + j];
    if (with_ordinates)
      for (int j = 0; j < ordinate_nodes; ++j)
        at(SEA_ROW_ORDINATES + j, i) = static_cast<float>(ordinates[static_cast<size_t>(j) * count + k]);
  }
  return table;
}

}  // namespace seasim
