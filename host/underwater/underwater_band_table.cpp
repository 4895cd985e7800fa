#include "underwater/underwater_band_table.h"

#include <algorithm>
#include <cmath>

namespace seasim {

std::vector<float> underwaterBandTable(const UnderwaterSetup& setup) {
  const int bands = static_cast<int>(setup.bands.size());
  const int objects = static_cast<int>(setup.objects.size());
  const int stride = UW_BAND_STRIDE(std::max(bands, 1));
  std::vector<float> table(static_cast<size_t>(UW_ROWS + objects) * stride, 0.0f);
  if (bands == 0) return table;
  auto at = [&](int row, int band) -> float& { return table[static_cast<size_t>(row) * stride + band]; };
  // The same clamp of μ_w as kd_multiple_scattering and uw_beam_irradiance (common/underwater.h).
  const double mu_w = std::max(static_cast<double>(setup.params.sun_dir_water[1]), 1e-4);
  constexpr double kFourPi = 4.0 * 3.14159265358979323846;
  for (int i = 0; i < stride; ++i) {
    const int k = std::min(i, bands - 1);  // padding bands repeat the last one
    const UwBand& b = setup.bands[k];
    at(UW_ROW_C, i) = b.c;
    at(UW_ROW_KD, i) = b.kd;
    at(UW_ROW_K_BEAM, i) = static_cast<float>(b.c / mu_w);
    at(UW_ROW_MS_TOTAL, i) = static_cast<float>(b.b / kFourPi * (double(b.e_sky0) + b.e_sun0));
    at(UW_ROW_MS_DIRECT, i) = static_cast<float>(b.b / kFourPi * b.e_sun0);
    at(UW_ROW_E_TOTAL, i) = static_cast<float>(double(b.e_sky0) + b.e_sun0);
    at(UW_ROW_E_SUN, i) = b.e_sun0;
    at(UW_ROW_E_BEAM, i) = b.e_beam0;
    at(UW_ROW_SKY, i) = b.sky_radiance;
    at(UW_ROW_SKY_W_R, i) = b.sky_w_r;
    at(UW_ROW_SKY_W_G, i) = b.sky_w_g;
    at(UW_ROW_SKY_W_B, i) = b.sky_w_b;
    const bool real_band = i < bands;
    at(UW_ROW_W_R, i) = real_band ? b.w_r : 0.0f;
    at(UW_ROW_W_G, i) = real_band ? b.w_g : 0.0f;
    at(UW_ROW_W_B, i) = real_band ? b.w_b : 0.0f;
    at(UW_ROW_BOTTOM_ALBEDO, i) = b.bottom_albedo;
    for (int o = 0; o < objects; ++o) {
      const size_t a = static_cast<size_t>(o) * bands + k;
      at(UW_ROWS + o, i) = a < setup.albedo.size() ? setup.albedo[a] : 0.0f;
    }
  }
  return table;
}

}  // namespace seasim
