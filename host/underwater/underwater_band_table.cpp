#include "underwater/underwater_band_table.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "math/kernel_math.h"

namespace seasim {

std::vector<float> underwaterBandTable(const UnderwaterSetup& setup) {
  const int bands = static_cast<int>(setup.bands.size());
  // The scene's objects: the kernel reads its rows after params.object_count albedo rows (setup.objects
  // holds one placeholder when there is none, since OpenCL buffers cannot be empty).
  const int objects = setup.params.object_count;
  const int stride = UW_BAND_STRIDE(std::max(bands, 1));
  const bool ordinates_rows = !setup.ordinates.empty();
  const int uwi_row0 = UW_ROWS + objects;
  std::vector<float> table(static_cast<size_t>(uwi_row0 + (ordinates_rows ? UWI_ROWS : 0)) * stride, 0.0f);
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
    if (ordinates_rows && k < static_cast<int>(setup.ordinates.size())) {
      const UwiBand& ib = setup.ordinates[k];
      auto uwi = [&](int row, double v) { at(uwi_row0 + row, i) = static_cast<float>(v); };
      uwi(UWI_ROW_C_DM, ib.c_dm);
      uwi(UWI_ROW_K, ib.k);
      uwi(UWI_ROW_M, ib.m);
      for (int q = 0; q < UWI_SOURCE_NODES * UWI_SOURCE_TERMS; ++q) uwi(UWI_ROW_SRC + q, ib.src[q]);
      for (int q = 0; q < UWI_TILT_NODES * UWI_SOURCE_TERMS; ++q) uwi(UWI_ROW_TILT + q, ib.tilt[q]);
      for (int q = 0; q < UWI_TILT_NODES * 3; ++q) uwi(UWI_ROW_TILT_BOTTOM + q, ib.tilt_bottom[q]);
      uwi(UWI_ROW_B_E_BEAM, double(b.b) * b.e_beam0);
      // No ceiling: the largest float, which min() and the excess (p_HG - p_clip)+ then pass by.
      uwi(UWI_ROW_P_CLIP, ib.p_clip > 0 ? double(ib.p_clip) : double(std::numeric_limits<float>::max()));
      uwi(UWI_ROW_AUREOLE_1, ib.aureole_single);
      for (int j = 0; j < UWI_AUREOLE_NODES; ++j) uwi(UWI_ROW_AUREOLE + j, ib.aureole[j]);
      for (int j = 0; j < UWI_SOURCE_NODES * 3; ++j) uwi(UWI_ROW_AUREOLE_M + j, ib.aureole_modes[j]);
      for (int j = 0; j < UWI_SOURCE_NODES * 3; ++j) uwi(UWI_ROW_SRC_SAND + j, ib.src_sand[j]);
      uwi(UWI_ROW_SAND_BEAM, ib.sand_beam);
      uwi(UWI_ROW_SAND_DIFFUSE, ib.sand_diffuse);
      uwi(UWI_ROW_D1, ib.d1);
      uwi(UWI_ROW_D2, ib.d2);
      uwi(UWI_ROW_DP, ib.dp);
      // The bottom that the surface's reflected ray ends on (uwi_surface): no bottom, no term.
      const double depth = setup.params.bottom_depth;
      const kmath_d::real3 s_w{setup.params.sun_dir_water[0], setup.params.sun_dir_water[1],
                               setup.params.sun_dir_water[2]};
      uwi(UWI_ROW_BOTTOM_L, depth > 0 ? kmath_d::uwi_lambert(&ib, &b, depth, depth, kmath_d::real3{0, 1, 0}, s_w,
                                                               b.bottom_albedo, 1.0, 1.0)
                                      : 0.0);
      // The integrals' start factors at the camera's depth, as the kernel forms their exponents: from
      // the float rows and the float depth o_d = -cam_pos[1] (>= 0: the underwater frame's camera is
      // below the surface), in double, then rounded once. Deep cameras underflow them to 0, which is
      // their value to float precision (kd_exp_integral_ends_b).
      const float o_d = -setup.params.cam_pos[1];
      const float h_od = std::max(setup.params.bottom_depth - o_d, 0.0f);
      const double k_f = at(uwi_row0 + UWI_ROW_K, i), m_f = at(uwi_row0 + UWI_ROW_M, i);
      uwi(UWI_ROW_EXP_K_OD, std::exp(-k_f * o_d));
      uwi(UWI_ROW_EXP_M_OD, std::exp(-m_f * o_d));
      uwi(UWI_ROW_EXP_BEAM_OD, std::exp(-double(at(UW_ROW_K_BEAM, i)) * o_d));
      uwi(UWI_ROW_EXP_K_HOD, std::exp(-k_f * h_od));
      uwi(UWI_ROW_EXP_K_H, std::exp(-k_f * std::max(depth, 0.0)));
    }
  }
  return table;
}

}  // namespace seasim
