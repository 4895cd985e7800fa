/* kd_multiple.cl — the underwater frame's deferred shading (002 §4): per pixel and per wavelength band,
 * T(S) L_s + L_MS with L_MS the closed form of 002 eq. 4.7 (common/underwater.h), accumulated straight
 * into sensor RGB by the rectangle rule (002 eq. 4.8) — the n band values are never stored unless
 * SEASIM_SPECTRAL_OUTPUT asks for them — plus the froxel single scattering (002 eq. 5.2) read at the
 * pixel's depth.
 *
 * Explicit SIMD over the bands: SEASIM_BAND_LANES bands per step in floatN vectors
 * (common/band_lanes.h, common/underwater_bands.h), since PoCL does not vectorise this kernel across
 * work-items; the band table (common/underwater_band_table.h) holds every per-band value the loop reads.
 * underwater.model = "discrete_ordinates" (SEASIM_UNDERWATER_MODEL == 1) runs on the same lanes
 * (common/underwater_ordinates_bands.h), reading the table's discrete-ordinates rows.
 *
 * Inputs: UwParams, UwBand[band_count] and albedo[object * band_count + band] (the set-up as every
 * underwater pass gets it; the band loop reads their values from band_table), the objects (the discrete-ordinates
 * model traces the surface's reflected ray against them, once per surface pixel), the G-buffer of raycast.cl
 * (geom, material, sun_vis), with SEASIM_HAS_FROXEL the integrated froxel volume (froxel.cl) and its
 * FroxelParams. Output: rgb[3 * pixels]; spectral[band_count * pixels] (band-major per pixel) with
 * SEASIM_SPECTRAL_OUTPUT, holding T L_s + L_MS per band (the froxel term is integrated in RGB).
 * SkyParams and the sky buffer: the [sky] Snell's window shows (common/sky_view.h, host/sky).
 * With SEASIM_UWI_SPREAD (the discrete-ordinates model, g > 0, underwater.point_spread): the light scattered by
 * small angles (common/water_spread.h) is left out of rgb and spectral and kept apart as its moments,
 * forward_rgb [pixel][2][3], forward_depth [pixel][2] and, with SEASIM_SPECTRAL_OUTPUT, forward_spectral
 * [pixel][2][band_count] (common/water_spread_params.h), for water_spread.cl to add back blurred.
 * Defines (host/plan): SEASIM_HAS_MULTIPLE (L_MS), SEASIM_HAS_FROXEL (single scattering added here and
 * split off L_MS and L_s), SEASIM_SPECTRAL_OUTPUT, SEASIM_UWI_SPREAD, SEASIM_SKY_MODEL (common/sky.h);
 * SEASIM_BAND_LANES (4, 8 or 16; default 16, common/band_lanes.h).
 * SEASIM_LAYER_FORMATION (outputs.layers, docs/layers.md): the image split by where its light comes from,
 * in sensor RGB: formation[pixel][12] = clear (the hit's radiance with S = 0: no water between), direct
 * (clear e^{-c S} per band), backscatter (the in-scatter and the froxel term), transmission (direct/clear
 * per channel; the sensor's mean of e^{-c S} where clear is 0), forward_layer[pixel][3] (the hit's light
 * the water scattered by small angles: what delta-M's c' < c keeps; water_spread.cl adds its blurred part)
 * and lamps_layer[pixel][3] (0 here, underwater_lamps.cl adds into it); direct + backscatter + forward
 * + lamps is the image. SEASIM_LAYER_VEILING: veiling[pixel][3], B∞, the in-scatter with S = ∞.
 * SEASIM_LAYER_BANDS (with SEASIM_LAYER_FORMATION and SEASIM_SPECTRAL_OUTPUT: the split per band in
 * spectral.exr): layer_bands[pixel][5][band_count] = clear, direct, backscatter, lamps (0 here;
 * underwater_lamps.cl adds into it), transmission e^{-c S}, and forward_bands[pixel][band_count] (water_spread.cl
 * adds its blurred part); per band direct + backscatter + forward + lamps is spectral's value.
 * SEASIM_LAYER_VEILING_BANDS (with SEASIM_LAYER_VEILING and SEASIM_SPECTRAL_OUTPUT): veiling_bands[pixel][band_count],
 * B∞ per band (the froxel term per band is added on the host, as to spectral).
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
#include "common/output_layers.h"
#include "common/band_lanes.h"
#include "common/band_lanes_math.h"
#include "common/underwater_band_table.h"
#include "common/underwater_bands.h"
#if SEASIM_HAS_FROXEL
#include "common/froxel_params.h"
#include "common/froxel.h"
#endif
#ifndef SEASIM_UNDERWATER_MODEL
#define SEASIM_UNDERWATER_MODEL 0
#endif
#if SEASIM_UNDERWATER_MODEL == 1 /* underwater.model = "discrete_ordinates" on the band lanes */
#include "common/underwater_ordinates_params.h"
/* uwi_mirror_hit: the surface's reflected ray against the objects */
#include "common/underwater_ordinates.h"
#include "common/underwater_ordinates_bands.h"
#endif
#ifndef SEASIM_UWI_SPREAD
#define SEASIM_UWI_SPREAD 0
#endif
#ifndef SEASIM_LAYER_FORMATION
#define SEASIM_LAYER_FORMATION 0
#endif
#ifndef SEASIM_LAYER_VEILING
#define SEASIM_LAYER_VEILING 0
#endif
#ifndef SEASIM_LAYER_BANDS
#define SEASIM_LAYER_BANDS 0
#endif
#ifndef SEASIM_LAYER_VEILING_BANDS
#define SEASIM_LAYER_VEILING_BANDS 0
#endif
#if SEASIM_LAYER_VEILING_BANDS
#define BAND_VEILING(value) store_lanes((value), veiling_bands + (size_t)pixel * band_count + i, band_count - i)
#else
#define BAND_VEILING(value)
#endif
#if SEASIM_LAYER_BANDS
/* The split per band: slot k of layer_bands (see above), or forward_bands, for the step's lanes. */
#define BAND_LAYER(slot, value) \
  store_lanes((value), layer_bands + ((size_t)pixel * 5 + (slot)) * band_count + i, band_count - i)
#define BAND_FORWARD(value) store_lanes((value), forward_bands + (size_t)pixel * band_count + i, band_count - i)
#else
#define BAND_LAYER(slot, value)
#define BAND_FORWARD(value)
#endif
#if SEASIM_LAYER_FORMATION || SEASIM_LAYER_VEILING
/* The layers' sums over bands in sensor RGB: name##_r += value * w_r, ... (002 eq. 4.8, as the image's). */
#define LAYER_LANES(name) realb name##_r = SPLATB(0.0f), name##_g = SPLATB(0.0f), name##_b = SPLATB(0.0f)
#define LAYER_ADD(name, value) \
  do {                         \
    const realb v_ = (value);  \
    name##_r += v_ * w_r_band; \
    name##_g += v_ * w_g_band; \
    name##_b += v_ * w_b_band; \
  } while (0)
#define LAYER_STORE(buffer, stride, at, name)          \
  do {                                                  \
    (buffer)[(size_t)pixel * (stride) + (at) + 0] = SUMB(name##_r); \
    (buffer)[(size_t)pixel * (stride) + (at) + 1] = SUMB(name##_g); \
    (buffer)[(size_t)pixel * (stride) + (at) + 2] = SUMB(name##_b); \
  } while (0)
#endif
#if SEASIM_UWI_SPREAD /* the water's point-spread: the forward light kept apart per layer */
#include "common/water_spread_params.h"
#include "common/water_spread.h"
#endif

/* The lanes' sky radiance in air along the refracted view (surface hits): the band's radiance, shaped
 * by the sky model (sky_shape, once per pixel) unless the sky is uniform. Both models' loops read it. */
realb kd_sky_lanes(__global const float* band_table, int stride, int i, float3 sky_shape) {
  const realb sky = LOADB(band_table + UW_ROW_SKY * stride, i);
#if SEASIM_SKY_MODEL != SEASIM_SKY_UNIFORM
  return sky * sky_view_band_b(SEASIM_SKY_MODEL, LOADB(band_table + UW_ROW_SKY_W_R * stride, i),
                               LOADB(band_table + UW_ROW_SKY_W_G * stride, i),
                               LOADB(band_table + UW_ROW_SKY_W_B * stride, i), sky_shape);
#else
  return sky;
#endif
}

#if SEASIM_UNDERWATER_MODEL == 1
/* What the discrete-ordinates model needs of a pixel's first surface to give its light (uwi_lanes_hit): set once
 * per pixel, read per step of bands. */
typedef struct {
  int mat, mirror_object, node_r, tilt_node, tilt_node_m, multiple;
  float3 sky_shape;
  float cos_dphi_r, frac, frac_m, cos_phi_n, cos_phi_m, phase_r, d_y, ior, bottom_depth;
  float n_dot_s, n_m_dot_s, vis, vis_b, mirror_s, mirror_vis;
} UwiHitPixel;

/* The light leaving the pixel's first surface towards the camera for SEASIM_BAND_LANES bands: the water
 * surface seen from below (its transmittance t_s), the bottom or an object (their ends `e`). The image
 * takes it with the hit's ends and t_s = T(S); the clear layer with the ends at S = 0 and t_s = 1. */
realb uwi_lanes_hit(const UwiHitPixel* h, __global const float* band_table, int stride, int uwi_row0, int i,
                    const UwiLanes* v, const UwiEnds* e, realb t_s, realb albedo, realb albedo_m) {
  if (h->mat == UW_MAT_SURFACE) {
    const realb sky_l = kd_sky_lanes(band_table, stride, i, h->sky_shape);
    UwiWeights w_r, tilt_m;
    uwi_lanes_weights(band_table, stride, uwi_row0, i, h->node_r, h->cos_dphi_r, &w_r);
    if (h->mirror_object)
      uwi_lanes_tilt(band_table, stride, uwi_row0, i, h->tilt_node_m, h->frac_m, h->cos_phi_m, 1.0f, &tilt_m);
    else
      uwi_lanes_down(v, &tilt_m);
    return uwi_lanes_surface(v, &w_r, t_s, sky_l, LOADB(band_table + (uwi_row0 + UWI_ROW_BOTTOM_L) * stride, i),
                             LOADB(band_table + (uwi_row0 + UWI_ROW_EXP_K_H) * stride, i), h->phase_r, h->bottom_depth,
                             h->d_y, h->ior, h->multiple, h->mirror_s, albedo_m, &tilt_m, h->n_m_dot_s, h->mirror_vis);
  }
  if (h->mat == UW_MAT_BOTTOM) {
    UwiWeights down;
    uwi_lanes_down(v, &down);
    return uwi_lanes_lambert(v, e, &down, albedo, h->bottom_depth, h->n_dot_s, h->vis);
  }
  if (h->mat == UW_MAT_NONE) return SPLATB(0.0f);
  UwiWeights tilt;
  uwi_lanes_tilt(band_table, stride, uwi_row0, i, h->tilt_node, h->frac, h->cos_phi_n, h->vis_b, &tilt);
  return uwi_lanes_lambert(v, e, &tilt, albedo, h->bottom_depth, h->n_dot_s, h->vis);
}
#endif

__kernel void kd_multiple(__constant UwParams* p, __global const UwBand* bands, __global const float* albedo,
                          __global const float* band_table, __global const UwObject* objects,
                          __global const float4* geom, __global const int* material, __global const float* sun_vis,
                          __constant SkyParams* sky_params, __global const float* sky,
#if SEASIM_HAS_FROXEL
                          __constant FroxelParams* fp, __global const float* froxel_volume,
#endif
                          __global float* rgb
#if SEASIM_SPECTRAL_OUTPUT
                          , __global float* spectral
#endif
#if SEASIM_UWI_SPREAD
                          , __global float* forward_rgb, __global float* forward_depth
#if SEASIM_SPECTRAL_OUTPUT
                          , __global float* forward_spectral
#endif
#endif
#if SEASIM_LAYER_FORMATION
                          , __global float* formation, __global float* forward_layer, __global float* lamps_layer
#endif
#if SEASIM_LAYER_VEILING
                          , __global float* veiling
#endif
#if SEASIM_LAYER_BANDS
                          , __global float* layer_bands, __global float* forward_bands
#endif
#if SEASIM_LAYER_VEILING_BANDS
                          , __global float* veiling_bands
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

  /* Sky and geometry once per pixel; then SEASIM_BAND_LANES bands per step (common/band_lanes.h),
   * reading the pixel-invariant per-band values from the band table with vector loads. The material
   * test stays in the loop: it is the same for every step of a pixel, one predictable branch per
   * SEASIM_BAND_LANES bands, and the lanes themselves are branch-free. Both models share this; the
   * discrete-ordinates one's lanes are common/underwater_ordinates_bands.h, the thesis's common/underwater_bands.h. */
#if SEASIM_SKY_MODEL != SEASIM_SKY_UNIFORM
  const float3 sky_shape = mat == UW_MAT_SURFACE ? sky_view_shape(sky_params, sky, sky_window_air_dir(d, p->ior))
                                                 : (float3)(0.0f, 0.0f, 0.0f);
#else
  const float3 sky_shape = (float3)(1.0f, 1.0f, 1.0f); /* unused: a uniform sky is the band's radiance */
#endif
  const float y_hit = fmax(o_d - S * d.y, 0.0f);
  const float n_dot_s = dot(n, s_w);
  const int band_count = p->band_count;
  const int stride = UW_BAND_STRIDE(band_count);
#define ROW(r) (band_table + (r) * stride)
  __global const float* albedo_row = ROW(mat >= 0 ? UW_ROWS + mat : UW_ROW_BOTTOM_ALBEDO);
  realb r_lanes = SPLATB(0.0f), g_lanes = SPLATB(0.0f), b_lanes = SPLATB(0.0f);
#if SEASIM_LAYER_FORMATION
  LAYER_LANES(clear);
  LAYER_LANES(direct);
  LAYER_LANES(scatter);
  LAYER_LANES(trans);
  LAYER_LANES(weight);
  LAYER_LANES(fwdl);
#endif
#if SEASIM_LAYER_VEILING
  LAYER_LANES(veil);
#endif
#if SEASIM_UNDERWATER_MODEL == 1
  /* underwater.model = "discrete_ordinates": its rows follow the objects' albedo rows; the phase of the view and
   * (surface hits) of the reflected ray (d.x, -d.y, d.z) once per pixel. */
  const int uwi_row0 = UW_ROWS + p->object_count;
  const float cos_s = dot(d, s_w);
  const float phase = hg_phase(cos_s, p->g);
  const float cos_r = cos_s - 2.0f * d.y * s_w.y;
  const float phase_r = mat == UW_MAT_SURFACE ? hg_phase(cos_r, p->g) : 0.0f;
  /* The source table's nearest node in ν and the azimuth's cosine from the sun's, of the camera's ray's
   * photon (ν = d.y) and the reflected ray's (ν = -d.y). */
  const int node = uwi_source_node(d.y);
  const int node_r = uwi_source_node(-d.y);
  const float cos_dphi = uwi_cos_azimuth(cos_s, d.y, s_w.y);
  const float cos_dphi_r = uwi_cos_azimuth(cos_r, -d.y, s_w.y);
  /* The forward peak's aureole (uwi_aureole) of a ray looking up: its table's node, and where the ray ends
   * (the surface: 0, where every band's share is 1). */
  float aureole_frac;
  const int aureole_node = uwi_aureole_node(cos_s, &aureole_frac);
  const float aureole_end = mat == UW_MAT_SURFACE ? 0.0f : y_hit;
  /* The share of the sunlit sand's light the ray gathers that no object hides or shades (uwi_sand_share,
   * with the first band's c' and k). */
  const float v_sand = multiple ? uwi_sand_share(objects, p->object_count, p->bottom_depth,
                                                 (float3)(p->cam_pos[0], p->cam_pos[1], p->cam_pos[2]), d, S,
                                                 band_table[(uwi_row0 + UWI_ROW_C_DM) * stride],
                                                 band_table[(uwi_row0 + UWI_ROW_K) * stride], s_w,
                                                 band_table + UW_ROWS * stride, stride,
                                                 band_table[UW_ROW_BOTTOM_ALBEDO * stride])
                                : 1.0f;
  /* The object the reflected ray meets first, if any (surface hits; uwi_mirror_hit). */
  int mat_m = UW_MAT_NONE;
  const UwiMirrorHit mirror =
      mat == UW_MAT_SURFACE
          ? uwi_mirror_hit(objects, p->object_count, (float3)(p->cam_pos[0], p->cam_pos[1], p->cam_pos[2]), d, S, s_w,
                           &mat_m)
          : uwi_no_mirror_object();
  __global const float* albedo_m_row = ROW(mat_m >= 0 ? UW_ROWS + mat_m : UW_ROW_BOTTOM_ALBEDO);
  const float n_m_dot_s = dot(mirror.n, s_w);
  /* The tilted plane table's node and azimuth of the object hit's normal and of the mirrored object's
   * (uwi_tilt_node, uwi_tilt_irradiance); the bottom reads E_d. */
  float frac, frac_m;
  const int tilt_node = uwi_tilt_node(n.y, &frac);
  const int tilt_node_m = uwi_tilt_node(mirror.n.y, &frac_m);
  const float cos_phi_n = uwi_cos_azimuth(n_dot_s, n.y, s_w.y);
  const float cos_phi_m = uwi_cos_azimuth(n_m_dot_s, mirror.n.y, s_w.y);
  const int mirror_object = mat_m >= 0;
  /* The share of the sand an object's face sees that is sunlit (uwi_bottom_visibility; the mirrored
   * object's is taken as 1). */
  const float vis_b = mat >= 0 ? uwi_bottom_visibility(objects, p->object_count, p->bottom_depth,
                                                       (float3)(p->cam_pos[0], p->cam_pos[1], p->cam_pos[2]) + S * d,
                                                       n, s_w)
                               : 1.0f;
  const UwiHitPixel hp = {.mat = mat, .mirror_object = mirror_object, .node_r = node_r, .tilt_node = tilt_node,
                          .tilt_node_m = tilt_node_m, .multiple = multiple, .sky_shape = sky_shape,
                          .cos_dphi_r = cos_dphi_r, .frac = frac, .frac_m = frac_m, .cos_phi_n = cos_phi_n,
                          .cos_phi_m = cos_phi_m, .phase_r = phase_r, .d_y = d.y, .ior = p->ior,
                          .bottom_depth = p->bottom_depth, .n_dot_s = n_dot_s, .n_m_dot_s = n_m_dot_s, .vis = vis,
                          .vis_b = vis_b, .mirror_s = mirror.s, .mirror_vis = mirror.vis};
#if SEASIM_UWI_SPREAD
  /* The light scattered by small angles, its moments (common/water_spread.h) in sensor RGB: F, F E, and
   * the sums over bands of (w_r + w_g + w_b) F D and (w_r + w_g + w_b) F. */
  realb fwd_r = SPLATB(0.0f), fwd_g = SPLATB(0.0f), fwd_b = SPLATB(0.0f);
  realb cnt_r = SPLATB(0.0f), cnt_g = SPLATB(0.0f), cnt_b = SPLATB(0.0f);
  realb fwd_light_depth = SPLATB(0.0f);
  const float s_spread = fmin(S, 1e4f);
#endif
  for (int i = 0; i < band_count; i += SEASIM_BAND_LANES) {
    /* The sensor's weights of these bands (002 eq. 4.8; the padding bands' are 0). */
    const realb w_r_band = LOADB(ROW(UW_ROW_W_R), i), w_g_band = LOADB(ROW(UW_ROW_W_G), i),
                w_b_band = LOADB(ROW(UW_ROW_W_B), i);
    UwiLanes v;
    uwi_lanes_load(band_table, stride, uwi_row0, i, &v);
    /* The in-scatter's integrals start at the camera (per-frame rows: o_d is the frame's) and end at the
     * hit, whose exps a Lambertian hit shares. */
    UwiStart camera;
    uwi_start_camera(band_table, stride, uwi_row0, i, &camera);
    UwiEnds ends;
    uwi_ends(&v, p->bottom_depth, S, y_hit, single & multiple, &ends);
    UwiWeights w;
    uwi_lanes_weights(band_table, stride, uwi_row0, i, node, cos_dphi, &w);
    if (v_sand < 1.0f) uwi_lanes_hide_sand(band_table, stride, uwi_row0, i, node, v_sand, &w);
    realb strict;
    realb L = multiple ? uwi_lanes_multiple(&v, &w, &camera, &ends, phase, p->bottom_depth, S, d.y, single, &strict)
                       : SPLATB(0.0f);
    /* The in-scatter with the forward peak's light (uwi_forward_peak), as uwi_band_radiance sums it; the
     * point-spread below takes its share of the rest alone: the aureole is the light's spread at the
     * camera already. */
    const realb in_scatter = multiple ? fmax(L + uwi_lanes_forward_peak(band_table, stride, uwi_row0, i, &v, aureole_node,
                                                                         aureole_frac, node, cos_dphi, phase, d.y, o_d,
                                                                         aureole_end,
                                                                         s_w.y, strict),
                                             SPLATB(0.0f))
                                      : SPLATB(0.0f);
    /* the light of what the ray meets, T(S) included */
    const realb hit = uwi_lanes_hit(&hp, band_table, stride, uwi_row0, i, &v, &ends, ends.k, LOADB(albedo_row, i),
                                    LOADB(albedo_m_row, i));
#if SEASIM_LAYER_FORMATION
    /* clear: the same hit with S = 0 (its ends at the hit's depth without T; the surface's t_s = 1). */
    UwiEnds ends0;
    uwi_ends(&v, p->bottom_depth, 0.0f, y_hit, 0, &ends0);
    const realb clear = uwi_lanes_hit(&hp, band_table, stride, uwi_row0, i, &v, &ends0, SPLATB(1.0f),
                                      LOADB(albedo_row, i), LOADB(albedo_m_row, i));
    /* direct: clear through the whole extinction c (delta-M's c' < c keeps the small-angle light in hit). */
    const realb trans = exp(-v.c * S);
    const realb direct = clear * trans;
    LAYER_ADD(clear, clear);
    LAYER_ADD(direct, direct);
    LAYER_ADD(trans, trans);
    LAYER_ADD(weight, SPLATB(1.0f));
    BAND_LAYER(0, clear);
    BAND_LAYER(1, direct);
    BAND_LAYER(3, SPLATB(0.0f));
    BAND_LAYER(4, trans);
#endif
#if SEASIM_LAYER_VEILING
    /* B∞: the in-scatter of the same ray with S = ∞ (every far end 0; the aureole's end at the depth it
     * tends to). */
    {
      const float y_inf = d.y < 0.0f ? UW_INFINITE : 0.0f;
      UwiEnds ends_inf;
      uwi_ends(&v, p->bottom_depth, UW_INFINITE, y_inf, single & multiple, &ends_inf);
      realb strict_inf;
      const realb l_inf = multiple ? uwi_lanes_multiple(&v, &w, &camera, &ends_inf, phase, p->bottom_depth, UW_INFINITE,
                                                        d.y, single, &strict_inf)
                                   : SPLATB(0.0f);
      const realb veil = multiple ? fmax(l_inf + uwi_lanes_forward_peak(band_table, stride, uwi_row0, i, &v, aureole_node,
                                                                        aureole_frac, node, cos_dphi, phase, d.y, o_d,
                                                                        y_inf, s_w.y, strict_inf),
                                         SPLATB(0.0f))
                                  : SPLATB(0.0f);
      LAYER_ADD(veil, veil);
      BAND_VEILING(veil);
    }
#endif
#if SEASIM_UWI_SPREAD
    /* Its share scattered by small angles (water_spread.h (1), (3)) and the in-scatter's ((4), (5)), kept
     * apart as moments; water_spread.cl puts them back blurred. */
    const realb delta = v.c - v.c_dm;
    const realb em = uws_expm1_neg_b(delta * s_spread);
    realb count_in, depth_in;
    const realb share_in = uws_inscatter_share_b(v.c_dm, delta, s_spread, em, &count_in, &depth_in);
    const realb fwd_hit = hit * uws_hit_share_b(em);
    const realb L_in_share = L * share_in;
    const realb fwd = fwd_hit + fmin(L_in_share, in_scatter);
    const realb cnt = hit * (delta * s_spread) + L * count_in;
    const realb fwd_depth = fwd_hit * s_spread + L * depth_in;
    fwd_r += fwd * w_r_band;
    fwd_g += fwd * w_g_band;
    fwd_b += fwd * w_b_band;
    cnt_r += cnt * w_r_band;
    cnt_g += cnt * w_g_band;
    cnt_b += cnt * w_b_band;
    fwd_light_depth += fwd_depth * (w_r_band + w_g_band + w_b_band);
    L = in_scatter + hit - fwd;
#if SEASIM_LAYER_FORMATION
    /* The small-angle share of the in-scatter leaves the backscatter; water_spread.cl adds it (blurred)
     * to the forward layer with the hit's. */
    LAYER_ADD(scatter, in_scatter - fmin(L_in_share, in_scatter));
    LAYER_ADD(fwdl, hit - fwd_hit - direct);
    BAND_LAYER(2, in_scatter - fmin(L_in_share, in_scatter));
    BAND_FORWARD(hit - fwd_hit - direct);
#endif
#if SEASIM_SPECTRAL_OUTPUT
    store_lanes(fwd, forward_spectral + ((size_t)pixel * 2) * band_count + i, band_count - i);
    store_lanes(cnt, forward_spectral + ((size_t)pixel * 2 + 1) * band_count + i, band_count - i);
#endif
#else
    L = in_scatter + hit;
#if SEASIM_LAYER_FORMATION
    LAYER_ADD(scatter, in_scatter);
    LAYER_ADD(fwdl, hit - direct);
    BAND_LAYER(2, in_scatter);
    BAND_FORWARD(hit - direct);
#endif
#endif
#else
  for (int i = 0; i < band_count; i += SEASIM_BAND_LANES) {
    /* The sensor's weights of these bands (002 eq. 4.8; the padding bands' are 0). */
    const realb w_r_band = LOADB(ROW(UW_ROW_W_R), i), w_g_band = LOADB(ROW(UW_ROW_W_G), i),
                w_b_band = LOADB(ROW(UW_ROW_W_B), i);
    const realb c = LOADB(ROW(UW_ROW_C), i);
    const realb kd = LOADB(ROW(UW_ROW_KD), i);
    const realb k_beam = LOADB(ROW(UW_ROW_K_BEAM), i);
    const realb ms_total = LOADB(ROW(UW_ROW_MS_TOTAL), i);
    const realb ms_direct = LOADB(ROW(UW_ROW_MS_DIRECT), i);
    /* L = T(S) L_s + L_MS (002 eq. 2.7 with 4.7), T(S) folded into L_s (common/underwater_bands.h). */
    realb L = multiple ? uw_lanes_multiple(ms_total, ms_direct, kd, k_beam, c, single, d.y, o_d, S) : SPLATB(0.0f);
#if SEASIM_LAYER_FORMATION
    /* The in-scatter is the backscatter; the hit, T(S) L_s, the direct light (the thesis has no forward
     * term); clear is the hit at S = 0, where S enters only T(S). */
    LAYER_ADD(scatter, L);
    BAND_LAYER(2, L);
    realb clear = SPLATB(0.0f), hit = SPLATB(0.0f);
#endif
#if SEASIM_LAYER_VEILING
    {
      const realb veil =
          multiple ? uw_lanes_multiple(ms_total, ms_direct, kd, k_beam, c, single, d.y, o_d, UW_INFINITE) : SPLATB(0.0f);
      LAYER_ADD(veil, veil);
      BAND_VEILING(veil);
    }
#endif
    if (mat == UW_MAT_SURFACE) {
      const realb sky_l = kd_sky_lanes(band_table, stride, i, sky_shape);
      const realb surface = uw_lanes_surface(sky_l, ms_total, ms_direct, kd, k_beam, c, single, multiple, S, d.y,
                                             p->ior, p->bottom_depth);
      L += surface;
#if SEASIM_LAYER_FORMATION
      hit = surface;
      clear = uw_lanes_surface(sky_l, ms_total, ms_direct, kd, k_beam, c, single, multiple, 0.0f, d.y, p->ior,
                               p->bottom_depth);
#endif
    } else if (mat != UW_MAT_NONE) {
      /* Objects read their albedo row; the bottom (UW_MAT_BOTTOM) reads the bottom's. */
      const realb lambert = uw_lanes_lambert(LOADB(albedo_row, i), c, kd, k_beam, LOADB(ROW(UW_ROW_E_TOTAL), i),
                                             LOADB(ROW(UW_ROW_E_SUN), i), LOADB(ROW(UW_ROW_E_BEAM), i), single, S,
                                             y_hit, n.y, n_dot_s, vis);
      L += lambert;
#if SEASIM_LAYER_FORMATION
      hit = lambert;
      clear = uw_lanes_lambert(LOADB(albedo_row, i), c, kd, k_beam, LOADB(ROW(UW_ROW_E_TOTAL), i),
                               LOADB(ROW(UW_ROW_E_SUN), i), LOADB(ROW(UW_ROW_E_BEAM), i), single, 0.0f, y_hit, n.y,
                               n_dot_s, vis);
#endif
    }
#if SEASIM_LAYER_FORMATION
    const realb trans = exp(-c * S);
    LAYER_ADD(clear, clear);
    LAYER_ADD(direct, hit);
    LAYER_ADD(trans, trans);
    LAYER_ADD(weight, SPLATB(1.0f));
    BAND_LAYER(0, clear);
    BAND_LAYER(1, hit);
    BAND_LAYER(3, SPLATB(0.0f));
    BAND_LAYER(4, trans);
    BAND_FORWARD(SPLATB(0.0f)); /* the thesis has no forward term */
#endif
#endif /* SEASIM_UNDERWATER_MODEL */
    /* 002 eq. 4.8. */
    r_lanes += L * w_r_band;
    g_lanes += L * w_g_band;
    b_lanes += L * w_b_band;
#if SEASIM_SPECTRAL_OUTPUT
    store_lanes(L, spectral + (size_t)pixel * band_count + i, band_count - i);
#endif
  }
#undef ROW
  float r = SUMB(r_lanes), gr = SUMB(g_lanes), b = SUMB(b_lanes);
#if SEASIM_HAS_FROXEL
  const float3 ss = froxel_lookup(fp, froxel_volume, x, y, p->width, p->height, S);
  r += ss.x;
  gr += ss.y;
  b += ss.z;
#endif
  rgb[3 * pixel + 0] = r;
  rgb[3 * pixel + 1] = gr;
  rgb[3 * pixel + 2] = b;
#if SEASIM_LAYER_FORMATION
  LAYER_STORE(formation, 12, 0, clear);
  LAYER_STORE(formation, 12, 3, direct);
  LAYER_STORE(formation, 12, 6, scatter);
  LAYER_STORE(forward_layer, 3, 0, fwdl);
#if SEASIM_HAS_FROXEL
  formation[(size_t)pixel * 12 + 6] += ss.x;
  formation[(size_t)pixel * 12 + 7] += ss.y;
  formation[(size_t)pixel * 12 + 8] += ss.z;
#endif
  {
    /* transmission per channel: direct/clear (so direct = clear x transmission), or where the hit sends no
     * light (open water, black objects) the sensor's mean of e^{-c S}. */
    const float cl[3] = {SUMB(clear_r), SUMB(clear_g), SUMB(clear_b)};
    const float di[3] = {SUMB(direct_r), SUMB(direct_g), SUMB(direct_b)};
    const float tw[3] = {SUMB(trans_r), SUMB(trans_g), SUMB(trans_b)};
    const float ww[3] = {SUMB(weight_r), SUMB(weight_g), SUMB(weight_b)};
    for (int k = 0; k < 3; ++k)
      formation[(size_t)pixel * 12 + 9 + k] = fabs(cl[k]) > 1e-30f ? di[k] / cl[k] : layer_weighted_mean(tw[k], ww[k]);
  }
  lamps_layer[3 * pixel + 0] = 0.0f;
  lamps_layer[3 * pixel + 1] = 0.0f;
  lamps_layer[3 * pixel + 2] = 0.0f;
#endif
#if SEASIM_LAYER_VEILING
#if SEASIM_HAS_FROXEL
  /* The froxel term of the whole column (froxel_lookup reads S >= z_far at z_far). */
  const float3 ss_inf = froxel_lookup(fp, froxel_volume, x, y, p->width, p->height, UW_INFINITE);
#else
  const float3 ss_inf = (float3)(0.0f, 0.0f, 0.0f);
#endif
  veiling[3 * pixel + 0] = SUMB(veil_r) + ss_inf.x;
  veiling[3 * pixel + 1] = SUMB(veil_g) + ss_inf.y;
  veiling[3 * pixel + 2] = SUMB(veil_b) + ss_inf.z;
#endif
#if SEASIM_UWI_SPREAD
  forward_rgb[6 * pixel + 0] = SUMB(fwd_r);
  forward_rgb[6 * pixel + 1] = SUMB(fwd_g);
  forward_rgb[6 * pixel + 2] = SUMB(fwd_b);
  forward_rgb[6 * pixel + 3] = SUMB(cnt_r);
  forward_rgb[6 * pixel + 4] = SUMB(cnt_g);
  forward_rgb[6 * pixel + 5] = SUMB(cnt_b);
  forward_depth[2 * pixel + 0] = SUMB(fwd_light_depth);
  forward_depth[2 * pixel + 1] = SUMB(fwd_r) + SUMB(fwd_g) + SUMB(fwd_b); /* the sum of (w_r + w_g + w_b) F */
#endif
}
