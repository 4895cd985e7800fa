/* kd_multiple.cl — the underwater frame's deferred shading (002 §4): per pixel and per wavelength band,
 * T(S) L_s + L_MS with L_MS the closed form of 002 eq. 4.7 (common/underwater.h), accumulated straight
 * into sensor RGB by the rectangle rule (002 eq. 4.8) — the n band values are never stored unless
 * SEASIM_SPECTRAL_OUTPUT asks for them — plus the froxel single scattering (002 eq. 5.2) read at the
 * pixel's depth.
 *
 * Inputs: UwParams, UwBand[band_count], albedo[object * band_count + band], the G-buffer of raycast.cl
 * (geom, material, sun_vis), with SEASIM_HAS_FROXEL the integrated froxel volume (froxel.cl) and its
 * FroxelParams. Output: rgb[3 * pixels]; spectral[band_count * pixels] (band-major per pixel) with
 * SEASIM_SPECTRAL_OUTPUT, holding T L_s + L_MS per band (the froxel term is integrated in RGB).
 * SkyParams and the sky buffer: the [sky] Snell's window shows (common/sky_view.h, host/sky).
 * Defines (host/plan): SEASIM_HAS_MULTIPLE (L_MS), SEASIM_HAS_FROXEL (single scattering added here and
 * split off L_MS and L_s), SEASIM_SPECTRAL_OUTPUT, SEASIM_SKY_MODEL (common/sky.h).
 */
#include "common/compat.h"
#include "common/optics.h"
#include "common/shafts.h"
#include "common/underwater_params.h"
#include "common/underwater.h"
#ifndef SEASIM_SKY_MODEL
#define SEASIM_SKY_MODEL 0
#endif
#include "common/sky.h"
#include "common/sky_params.h"
#include "common/sky_view.h"
#if SEASIM_HAS_FROXEL
#include "common/froxel_params.h"
#include "common/froxel.h"
#endif
#ifndef SEASIM_UNDERWATER_MODEL
#define SEASIM_UNDERWATER_MODEL 0
#endif
#if SEASIM_UNDERWATER_MODEL == 1 /* underwater.model = "improved" (issue 13): its header and per-band block */
#include "common/underwater_improved_params.h"
#include "common/underwater_improved.h"
#endif

__kernel void kd_multiple(__constant UwParams* p, __global const UwBand* bands, __global const float* albedo,
                          __global const float4* geom, __global const int* material, __global const float* sun_vis,
                          __constant SkyParams* sky_params, __global const float* sky,
#if SEASIM_HAS_FROXEL
                          __constant FroxelParams* fp, __global const float* froxel_volume,
#endif
                          __global float* rgb
#if SEASIM_SPECTRAL_OUTPUT
                          , __global float* spectral
#endif
#if SEASIM_UNDERWATER_MODEL == 1
                          , __global const UwiBand* improved
#endif
) {
  const int x = get_global_id(0);
  const int y = get_global_id(1);
  if (x >= p->width || y >= p->height) return;
  const int pixel = y * p->width + x;

  const float3 d = uw_screen_dir(p, (x + 0.5f) / p->width, (y + 0.5f) / p->height);
  const float3 s_w = (float3)(p->sun_dir_water[0], p->sun_dir_water[1], p->sun_dir_water[2]);
  const float o_d = -p->cam_pos[1];

  const float4 g = geom[pixel];
  const float S = g.x;
  const float3 n = (float3)(g.y, g.z, g.w);
  const int mat = material[pixel];
  const float vis = sun_vis[pixel];

#if SEASIM_HAS_FROXEL
  const int single = 1;
#else
  const int single = 0;
#endif
#if SEASIM_HAS_MULTIPLE
  const int multiple = 1;
#else
  const int multiple = 0;
#endif

  /* The material is tested once per pixel, outside the band loops (common/underwater.h splits the
   * band radiance by what the ray hit), so each band loop is one straight line of arithmetic. */
  float r = 0.0f, gr = 0.0f, b = 0.0f;
#if SEASIM_SPECTRAL_OUTPUT
#define KD_ACCUMULATE(L)                                         \
  r += (L) * band->w_r;                                          \
  gr += (L) * band->w_g;                                         \
  b += (L) * band->w_b;                                          \
  spectral[(size_t)pixel * p->band_count + i] = (L)
#else
#define KD_ACCUMULATE(L) \
  r += (L) * band->w_r;  \
  gr += (L) * band->w_g; \
  b += (L) * band->w_b
#endif
#if SEASIM_UNDERWATER_MODEL == 1
  /* underwater.model = "improved" (common/underwater_improved.h): one loop, the material tested per band. */
  {
    __global const float* alb = mat >= 0 ? albedo + mat * p->band_count : &bands[0].bottom_albedo;
    const int alb_stride = mat >= 0 ? 1 : (int)(sizeof(UwBand) / sizeof(float));
#if SEASIM_SKY_MODEL != SEASIM_SKY_UNIFORM
    const float3 sky_shape = mat == UW_MAT_SURFACE ? sky_view_shape(sky_params, sky, sky_window_air_dir(d, p->ior))
                                                   : (float3)(0.0f, 0.0f, 0.0f);
#endif
    for (int i = 0; i < p->band_count; ++i) {
      __global const UwBand* band = &bands[i];
#if SEASIM_SKY_MODEL != SEASIM_SKY_UNIFORM
      const float sky_l = band->sky_radiance *
                          sky_view_band(SEASIM_SKY_MODEL, (float3)(band->sky_w_r, band->sky_w_g, band->sky_w_b), sky_shape);
#else
      const float sky_l = band->sky_radiance;
#endif
      const float a_i = mat == UW_MAT_NONE || mat == UW_MAT_SURFACE ? 0.0f : alb[i * alb_stride];
      const float L = uwi_band_radiance(&improved[i], band, p->g, mat, S, n, d, o_d, s_w, a_i, vis, sky_l, p->ior,
                                        p->bottom_depth, single, multiple);
      KD_ACCUMULATE(L);
    }
  }
#else
  if (mat == UW_MAT_NONE) {
    for (int i = 0; i < p->band_count; ++i) {
      __global const UwBand* band = &bands[i];
      const float L = uw_band_multiple(band, S, d.y, o_d, s_w.y, single, multiple);
      KD_ACCUMULATE(L);
    }
  } else if (mat == UW_MAT_SURFACE) {
    /* Snell's window sees the sky along the refracted view (common/sky_view.h): its shape once per
     * pixel, each band's share in the loop; the uniform sky reads the band's radiance as it always did. */
#if SEASIM_SKY_MODEL != SEASIM_SKY_UNIFORM
    const float3 sky_shape = sky_view_shape(sky_params, sky, sky_window_air_dir(d, p->ior));
#endif
    for (int i = 0; i < p->band_count; ++i) {
      __global const UwBand* band = &bands[i];
#if SEASIM_SKY_MODEL != SEASIM_SKY_UNIFORM
      const float sky_l = band->sky_radiance *
                          sky_view_band(SEASIM_SKY_MODEL, (float3)(band->sky_w_r, band->sky_w_g, band->sky_w_b), sky_shape);
#else
      const float sky_l = band->sky_radiance;
#endif
      const float L = exp(-band->c * S) *
                          uw_band_surface_sky(band, sky_l, d.y, s_w.y, p->ior, p->bottom_depth, single, multiple) +
                      uw_band_multiple(band, S, d.y, o_d, s_w.y, single, multiple);
      KD_ACCUMULATE(L);
    }
  } else {
    /* Objects read their albedo per band; the bottom (UW_MAT_BOTTOM) reads the band's. */
    __global const float* alb = mat >= 0 ? albedo + mat * p->band_count : &bands[0].bottom_albedo;
    const int alb_stride = mat >= 0 ? 1 : (int)(sizeof(UwBand) / sizeof(float));
    for (int i = 0; i < p->band_count; ++i) {
      __global const UwBand* band = &bands[i];
      const float L = exp(-band->c * S) * uw_band_lambert(band, S, n, d.y, o_d, s_w, alb[i * alb_stride], vis, single) +
                      uw_band_multiple(band, S, d.y, o_d, s_w.y, single, multiple);
      KD_ACCUMULATE(L);
    }
  }
#endif /* SEASIM_UNDERWATER_MODEL */
#undef KD_ACCUMULATE
#if SEASIM_HAS_FROXEL
  const float3 ss = froxel_lookup(fp, froxel_volume, x, y, p->width, p->height, S);
  r += ss.x;
  gr += ss.y;
  b += ss.z;
#endif
  rgb[3 * pixel + 0] = r;
  rgb[3 * pixel + 1] = gr;
  rgb[3 * pixel + 2] = b;
}
