/* fourflow.cl — shallow water with a visible bottom (paper 003, Belyaev, "Real-time rendering of
 * shallow water"): the four-flow light field (eq. 4–9) per wavelength band, the refracted light of
 * eq. 20 per pixel, and the paper's real-time structure, RGB tables T0(l, h), T1(l, h), a(l, h)
 * (eq. 22–23) and a per-pixel blend with the bottom texture.
 *
 * Inputs per pixel (from the pass's geometry): l, the view path length through the water (m), h, the
 * bottom depth under the point seen (m), tex ∈ [0, 1], the bottom texture's mix of the two bottom
 * materials. Bands: FfBand[n_bands] (fourflow_params.h). Outputs: linear RGB, 3 floats per pixel
 * (the sensor weights of the bands carry the units of E through; the display transform comes after).
 *
 * Stiff cases (kernels/common/fourflow.h): λ0 -> λ, k -> 0, h -> 0 and deep water (ε h = 200) are
 * handled by the rescaled closed form; nothing here divides by a quantity that can vanish, and the
 * table lookup clamps (l, h) to the table's range.
 */
#include "common/compat.h"
#include "common/gauss_legendre.h"
#include "common/optics.h"
#include "common/fourflow_params.h"
#include "common/fourflow.h"
#ifndef SEASIM_SKY_MODEL
#define SEASIM_SKY_MODEL 0
#endif
#if SEASIM_SKY_MODEL != 0 /* the [sky] model (host/sky): one sky for every model, common/sky_view.h */
#include "common/polynomial_trig.h"
#include "common/sky.h"
#include "common/sky_params.h"
#include "common/sky_view.h"
#endif

/* The exact spectral path: eq. 20 per band per pixel, summed into linear RGB. */
__kernel void ff_exact(__global const FfBand* bands, int n_bands, __global const float* path_l,
                       __global const float* depth_h, __global const float* tex, __global float* out_rgb, int n) {
  const int i = get_global_id(0);
  if (i >= n) return;
  real rgb[3];
  ff_exact_rgb(bands, n_bands, path_l[i], depth_h[i], tex[i], rgb);
  vstore3((float3)(rgb[0], rgb[1], rgb[2]), i, out_rgb);
}

/* The (l, h) tables of eq. 22–23, one work-item per cell (i along l, j along h). */
__kernel void ff_build_tables(__global const FfBand* bands, __constant FfParams* p, __global float* table) {
  const int i = get_global_id(0), j = get_global_id(1);
  if (i >= p->n_l || j >= p->n_h) return;
  real cell[FF_TABLE_STRIDE];
  ff_table_cell(bands, p->n_bands, p->gamma, ff_table_l(*p, i), ff_table_h(*p, j), cell);
  for (int q = 0; q < FF_TABLE_STRIDE; ++q) table[(j * p->n_l + i) * FF_TABLE_STRIDE + q] = cell[q];
}

/* The real-time path: bilinear table lookup and the blend of eq. 22 (eq24 = 0) or eq. 24 per pixel. */
__kernel void ff_table_blend(__constant FfParams* p, __global const float* table, __global const float* path_l,
                             __global const float* depth_h, __global const float* tex, __global float* out_rgb, int n,
                             int eq24) {
  const int i = get_global_id(0);
  if (i >= n) return;
  real rgb[3];
  ff_table_rgb(*p, table, path_l[i], depth_h[i], tex[i], eq24, rgb);
  vstore3((float3)(rgb[0], rgb[1], rgb[2]), i, out_rgb);
}

/* ---------------------------------------------------------------------------------------------
 * The frame: the view from above a flat water surface (003 eq. 1). Per pixel: the camera ray meets
 * the surface (y = 0) at B with Fresnel term F(θ); the reflected part sees the sky (uniform, or the
 * [sky] model towards the mirrored view with SEASIM_SKY_MODEL); the
 * refracted ray runs to the bottom point C (flat bottom, or the sea module's height field:
 * common/sea_bottom.h), giving the view path length l = |BC| and the depth h of C; the bottom texture
 * at C gives the dark material's share. Then E_refr (eq. 20) by the exact band sum or the tables.
 *
 * With SEASIM_SPECTRAL_OUTPUT the kernel also writes every band's radiance (ff_band_radiance), the
 * exact eq. 20 per band on every path: the tables hold RGB only, so a spectral image of the table path
 * would not exist; on the exact path the bands through the sensor weights give the RGB image.
 *
 * Radiance: E_refr is an irradiance-like flow (the paper's units); a diffuse field of that exitance
 * has radiance E/π in the water, and radiance over n² is conserved across the surface (docs/:
 * one radiometric convention), so the pixel gets F L_sky + (1 - F) E_refr / (π n²).
 */
#if SEASIM_FF_HEIGHTFIELD /* the sea module's height field and its exact ray walk (000 §5.4) */
#include "common/sea_bottom_params.h"
#include "common/sea_surface.h"
#include "common/sea_second.h"
#include "common/sea_bottom.h"
#endif

__kernel void ff_render(__constant FfView* v, __global const FfBand* bands, __constant FfParams* p,
                        __global const float* table, __global float* rgb
#if SEASIM_FF_HEIGHTFIELD
                        , __constant SeaHeightField* hf, __global const float* hf_depth
#endif
#if SEASIM_SPECTRAL_OUTPUT /* one radiance per band per pixel, always the exact eq. 20 (spectral.exr) */
                        , __global float* spectral
#endif
#if SEASIM_SKY_MODEL != 0 /* after the spectral buffer: the host sets them in this order */
                        , __constant SkyParams* sky_params, __global const float* sky, __constant float* sky_rgb_matrix
#endif
) {
  const int x = get_global_id(0), y = get_global_id(1);
  if (x >= v->width || y >= v->height) return;
  FfView view = *v;
  const real3 o = MAKE_REAL3(view.cam_pos[0], view.cam_pos[1], view.cam_pos[2]);
  const real3 d = ff_camera_dir(view, x, y);
#if SEASIM_SKY_MODEL != 0
  /* The sky towards the view, or towards its mirror image in the flat surface: the sky the pixel sees
   * above the horizon, or the one ff_shade reflects (F L_sky(reflected), 003 eq. 1). */
  const float3 seen = sky_view_rgb(sky_rgb_matrix, sky_view_shape(sky_params, sky, (float3)(d.x, fabs(d.y), d.z)));
  view.sky_rgb[0] = seen.x;
  view.sky_rgb[1] = seen.y;
  view.sky_rgb[2] = seen.z;
#endif
  real out[3] = {view.sky_rgb[0], view.sky_rgb[1], view.sky_rgb[2]};
  real3 b, dw;
  real F;
  if (ff_enter_water(view, o, d, &b, &F, &dw)) {
    real l, h;
#if SEASIM_FF_HEIGHTFIELD
    real3 n_floor;
    const real t_max = R(1e4);
    const int hit = sea_hf_intersect(hf, hf_depth, b, dw, t_max, &l, &n_floor);
    h = hit ? -(b.y + l * dw.y) : (real)hf->max_depth;
    l = hit ? l : t_max;
#else
    h = view.bottom_depth;
    l = h / fmax(-dw.y, R(1e-6));
#endif
#ifndef SEASIM_FF_TABLES
#define SEASIM_FF_TABLES 0
#endif
    ff_shade(view, bands, *p, table, SEASIM_FF_TABLES, F, l, h, b + l * dw, out);
#if SEASIM_SPECTRAL_OUTPUT
    const real3 c = b + l * dw;
    const real tex = ff_bottom_texture(c.x, c.z, (real)view.texture_scale, (real)view.dark_fraction);
    for (int i = 0; i < p->n_bands; ++i)
      spectral[(size_t)(y * view.width + x) * p->n_bands + i] = ff_band_radiance(bands[i], (real)view.ior, F, l, h, tex);
  } else {
    for (int i = 0; i < p->n_bands; ++i)
      spectral[(size_t)(y * view.width + x) * p->n_bands + i] = (real)bands[i].e_sky / SEASIM_PI;
#endif
  }
  vstore3((float3)(out[0], out[1], out[2]), y * view.width + x, rgb);
}
