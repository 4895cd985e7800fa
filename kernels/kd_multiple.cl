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
 * SEASIM_BAND_LANES (4, 8 or 16; default 16, common/band_lanes.h). SEASIM_SAND_SHARE_MAP (the
 * discrete-ordinates model with objects over a bottom, quality.sand_share_step > 1): the sand's shares
 * (sunlit, diffusely lit) interpolated from sand_share.cl's lattice (sand_map, two planes of sand_w x
 * sand_h, every sand_step-th pixel) where its hits see the pixel's surface, evaluated here elsewhere.
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
 * B∞ per band (the froxel term per band is added by the froxel_bands pass, as to spectral).
 */
#include "common/compat.h"
#include "common/optics.h"
#include "common/shafts.h"
#include "common/underwater_params.h"
#include "common/underwater.h"
#ifndef SEASIM_SKY_MODEL
#define SEASIM_SKY_MODEL 0
#endif
#include "common/polynomial_trig.h"
#include "common/sky.h"
#include "common/sky_params.h"
#include "common/sky_view.h"
#include "common/output_layers.h"
#include "common/band_lanes.h"
#include "common/band_lanes_math.h"
#include "common/sky_view_lanes.h"
#include "common/underwater_band_table.h"
#include "common/underwater_bands.h"
#if SEASIM_HAS_FROXEL
#include "common/froxel_params.h"
#include "common/froxel.h"
#endif
#ifndef SEASIM_UNDERWATER_MODEL
#define SEASIM_UNDERWATER_MODEL 0
#endif
#ifndef SEASIM_SAND_SHARE_MAP
#define SEASIM_SAND_SHARE_MAP 0
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
/* The pixel's sums over bands in sensor RGB (002 eq. 4.8): the image's and, with the layers and the
 * point-spread, theirs. Each step of bands adds its lanes; the kernel's end stores their sums. */
typedef struct {
  realb r, g, b;
#if SEASIM_LAYER_FORMATION
  realb clear_r, clear_g, clear_b, direct_r, direct_g, direct_b, scatter_r, scatter_g, scatter_b;
  realb trans_r, trans_g, trans_b, weight_r, weight_g, weight_b, fwdl_r, fwdl_g, fwdl_b;
#endif
#if SEASIM_LAYER_VEILING
  realb veil_r, veil_g, veil_b;
#endif
#if SEASIM_UWI_SPREAD
  /* The light scattered by small angles, its moments (common/water_spread.h) in sensor RGB: F, F E, and
   * the sums over bands of (w_r + w_g + w_b) F D and (w_r + w_g + w_b) F. */
  realb fwd_r, fwd_g, fwd_b, cnt_r, cnt_g, cnt_b, fwd_light_depth;
#endif
} KdSums;

#define KD_ZERO3(s, name) (s).name##_r = (s).name##_g = (s).name##_b = SPLATB(0.0f)

/* A step of SEASIM_BAND_LANES bands from band i: the sensor's weights of its lanes (002 eq. 4.8; the
 * padding bands' are 0) and the per-band buffers its values go to, at the pixel's slots (null when the
 * plan does not write them). */
typedef struct {
  int pixel, band_count, i;
  realb w_r, w_g, w_b;
  __global float* forward_spectral;
  __global float* layer_bands;
  __global float* forward_bands;
  __global float* veiling_bands;
} KdStep;

/* In the functions of a step: `s` is the pixel's KdSums, `st` the KdStep. */
#if SEASIM_LAYER_FORMATION || SEASIM_LAYER_VEILING
/* A layer's lanes into its sums: name##_r += value * w_r, ... (as the image's). */
#define LAYER_ADD(name, value)   \
  do {                           \
    const realb v_ = (value);    \
    s->name##_r += v_ * st->w_r; \
    s->name##_g += v_ * st->w_g; \
    s->name##_b += v_ * st->w_b; \
  } while (0)
#define LAYER_STORE(buffer, stride, at, name)                          \
  do {                                                                 \
    (buffer)[(size_t)pixel * (stride) + (at) + 0] = SUMB(s->name##_r); \
    (buffer)[(size_t)pixel * (stride) + (at) + 1] = SUMB(s->name##_g); \
    (buffer)[(size_t)pixel * (stride) + (at) + 2] = SUMB(s->name##_b); \
  } while (0)
#endif
#if SEASIM_LAYER_VEILING_BANDS
#define BAND_VEILING(value) \
  store_lanes((value), st->veiling_bands + (size_t)st->pixel * st->band_count + st->i, st->band_count - st->i)
#else
#define BAND_VEILING(value)
#endif
#if SEASIM_LAYER_BANDS
/* The split per band: slot k of layer_bands (see above), or forward_bands, for the step's lanes. */
#define BAND_LAYER(slot, value)                                                                      \
  store_lanes((value), st->layer_bands + ((size_t)st->pixel * 5 + (slot)) * st->band_count + st->i, \
              st->band_count - st->i)
#define BAND_FORWARD(value) \
  store_lanes((value), st->forward_bands + (size_t)st->pixel * st->band_count + st->i, st->band_count - st->i)
#else
#define BAND_LAYER(slot, value)
#define BAND_FORWARD(value)
#endif

/* What both models read of a pixel once, for every step of bands: its G-buffer and view. */
typedef struct {
  int mat, single, multiple;
  float S, y_hit, d_y, o_d, n_y, n_dot_s, vis;
  float3 sky_shape;
  __global const float* albedo_row; /* the band table's albedo row of what the ray meets */
} KdPixel;

/* The defines as values: the froxel pass runs (L_MS and L_s then leave out the direct beam), L_MS. */
#if SEASIM_HAS_FROXEL
#define KD_SINGLE 1
#else
#define KD_SINGLE 0
#endif
#if SEASIM_HAS_MULTIPLE
#define KD_MULTIPLE 1
#else
#define KD_MULTIPLE 0
#endif
/* The kernel's per-band buffers a KdStep holds, null where the plan does not write them. */
#if SEASIM_SPECTRAL_OUTPUT && SEASIM_UWI_SPREAD
#define KD_FORWARD_SPECTRAL forward_spectral
#else
#define KD_FORWARD_SPECTRAL 0
#endif
#if SEASIM_LAYER_BANDS
#define KD_LAYER_BANDS layer_bands
#define KD_FORWARD_BANDS forward_bands
#else
#define KD_LAYER_BANDS 0
#define KD_FORWARD_BANDS 0
#endif
#if SEASIM_LAYER_VEILING_BANDS
#define KD_VEILING_BANDS veiling_bands
#else
#define KD_VEILING_BANDS 0
#endif
/* The froxel term of the pixel's whole column (froxel_lookup reads S >= z_far at z_far), for B∞. */
#if SEASIM_HAS_FROXEL
#define KD_FROXEL_AT_INFINITY froxel_lookup(fp, froxel_volume, x, y, p->width, p->height, UW_INFINITE)
#else
#define KD_FROXEL_AT_INFINITY ((float3)(0.0f, 0.0f, 0.0f))
#endif

static inline void kd_sums_zero(KdSums* s) {
  s->r = s->g = s->b = SPLATB(0.0f);
#if SEASIM_LAYER_FORMATION
  KD_ZERO3(*s, clear);
  KD_ZERO3(*s, direct);
  KD_ZERO3(*s, scatter);
  KD_ZERO3(*s, trans);
  KD_ZERO3(*s, weight);
  KD_ZERO3(*s, fwdl);
#endif
#if SEASIM_LAYER_VEILING
  KD_ZERO3(*s, veil);
#endif
#if SEASIM_UWI_SPREAD
  KD_ZERO3(*s, fwd);
  KD_ZERO3(*s, cnt);
  s->fwd_light_depth = SPLATB(0.0f);
#endif
}

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

#if SEASIM_LAYER_FORMATION
/* A step's layers of the hit, both models: clear, direct and the transmission e^{-c S} into the sums
 * (with the weight the transmission's fallback mean needs) and into the split per band, whose lamps
 * slot starts at 0 (underwater_lamps.cl adds into it). */
static inline void kd_add_hit_layers(realb clear, realb direct, realb trans, const KdStep* st, KdSums* s) {
  LAYER_ADD(clear, clear);
  LAYER_ADD(direct, direct);
  LAYER_ADD(trans, trans);
  LAYER_ADD(weight, SPLATB(1.0f));
  BAND_LAYER(0, clear);
  BAND_LAYER(1, direct);
  BAND_LAYER(3, SPLATB(0.0f));
  BAND_LAYER(4, trans);
}
#endif

#if SEASIM_UNDERWATER_MODEL == 1
/* sand_share.cl's lattice (SEASIM_SAND_SHARE_MAP): every step-th pixel's share, w x h of them, and where
 * this pixel is; its G-buffer distances tell which lattice pixels see the same surface. */
typedef struct {
  __global const float* map;
  int w, h, step;
  __global const float4* geom;
  int x, y;
} SandShareAt;

/* The kernel's lattice arguments, where it has them. */
#if SEASIM_SAND_SHARE_MAP
#define KD_SAND_MAP .map = sand_map, .w = sand_w, .h = sand_h, .step = sand_step
#else
#define KD_SAND_MAP .map = 0
#endif

#if SEASIM_SAND_SHARE_MAP
/* The objects' shares at the pixel from the lattice, (the sunlit sand's, the diffusely lit sand's, the light
 * from above's): the (up to) four lattice pixels around it whose hit lies within 5 % of the pixel's own
 * distance S (the same surface; open water: those without a hit either), weighted bilinearly by position;
 * -1 when none does (a silhouette: the caller evaluates the pixel itself). A lattice pixel reads its own
 * values, so there the shares are the per-pixel ones exactly. */
static inline float3 sand_share_from_map(const SandShareAt* a, __constant UwParams* p, float S) {
  const int open = !(S < 1.0e6f);
  const int i0 = a->x / a->step, j0 = a->y / a->step;
  const float fx = (float)(a->x - i0 * a->step) / a->step, fy = (float)(a->y - j0 * a->step) / a->step;
  const int plane = a->w * a->h;
  float3 sum = (float3)(0.0f, 0.0f, 0.0f);
  float wsum = 0.0f;
  for (int dj = 0; dj <= 1; ++dj)
    for (int di = 0; di <= 1; ++di) {
      const float w = (di ? fx : 1.0f - fx) * (dj ? fy : 1.0f - fy);
      const int i = min(i0 + di, a->w - 1), j = min(j0 + dj, a->h - 1);
      const float Sq = a->geom[min(j * a->step, p->height - 1) * p->width + min(i * a->step, p->width - 1)].x;
      const int same = open ? !(Sq < 1.0e6f) : Sq < 1.0e6f && fabs(Sq - S) <= 0.05f * S;
      if (!(w > 0.0f) || !same) continue;
      const int at = j * a->w + i;
      sum += w * (float3)(a->map[at], a->map[plane + at], a->map[2 * plane + at]);
      wsum += w;
    }
  return wsum > 0.0f ? sum / wsum : (float3)(-1.0f, -1.0f, -1.0f);
}
#endif

/* What the discrete-ordinates model reads of a pixel once besides KdPixel: the phase of the view and
 * (surface hits) of the reflected ray, the source table's and the aureole's nodes, the sand's share,
 * the mirrored object, the tilted plane table's nodes (uwi_pixel). */
typedef struct {
  UwiHitPixel hit;
  int row0, node, aureole_node;
  float phase, cos_dphi, aureole_frac, aureole_end, v_sand, v_diffuse, v_above, s_w_y;
  __global const float* albedo_m_row;
#if SEASIM_UWI_SPREAD
  float s_spread;
#endif
} UwiPixel;

static inline void uwi_pixel(__constant UwParams* p, __global const float* band_table, int stride,
                             __global const UwObject* objects, const SandShareAt* sand, const KdPixel* k, float3 d,
                             float3 n, float3 s_w, UwiPixel* q) {
  const int mat = k->mat;
  const float S = k->S;
  /* Its rows follow the objects' albedo rows; the phase of the view and (surface hits) of the reflected
   * ray (d.x, -d.y, d.z) once per pixel. */
  const int uwi_row0 = UW_ROWS + p->object_count;
  q->row0 = uwi_row0;
  q->s_w_y = s_w.y;
  const float cos_s = dot(d, s_w);
  q->phase = hg_phase(cos_s, p->g);
  const float cos_r = cos_s - 2.0f * d.y * s_w.y;
  const float phase_r = mat == UW_MAT_SURFACE ? hg_phase(cos_r, p->g) : 0.0f;
  /* The source table's nearest node in ν and the azimuth's cosine from the sun's, of the camera's ray's
   * photon (ν = d.y) and the reflected ray's (ν = -d.y). */
  q->node = uwi_source_node(d.y);
  const int node_r = uwi_source_node(-d.y);
  q->cos_dphi = uwi_cos_azimuth(cos_s, d.y, s_w.y);
  const float cos_dphi_r = uwi_cos_azimuth(cos_r, -d.y, s_w.y);
  /* The forward peak's aureole (uwi_aureole) of a ray looking up: its table's node, and where the ray ends
   * (the surface: 0, where every band's share is 1). */
  q->aureole_node = uwi_aureole_node(cos_s, &q->aureole_frac);
  q->aureole_end = mat == UW_MAT_SURFACE ? 0.0f : k->y_hit;
  const float3 cam = (float3)(p->cam_pos[0], p->cam_pos[1], p->cam_pos[2]);
  /* The shares of the sunlit and of the diffusely lit sand's light the ray gathers that no object hides or
   * shades (uwi_sand_shares), and of the light from above that the objects leave its in-scatter
   * (uwi_above_share; both with the first band's c' and k): from sand_share.cl's lattice where it can be,
   * else here. */
#if SEASIM_SAND_SHARE_MAP
  const float3 v_map = k->multiple ? sand_share_from_map(sand, p, S) : (float3)(1.0f, 1.0f, 1.0f);
#else
  const float3 v_map = k->multiple ? (float3)(-1.0f, -1.0f, -1.0f) : (float3)(1.0f, 1.0f, 1.0f);
#endif
  q->v_sand = v_map.x;
  q->v_diffuse = v_map.y;
  q->v_above = v_map.z;
  if (v_map.x < 0.0f) {
    q->v_sand = uwi_view_sand_shares(p, objects, band_table, stride, d, S, &q->v_diffuse);
    q->v_above = uwi_view_above_share(p, objects, band_table, stride, d, S);
  }
  /* The object the reflected ray meets first, if any (surface hits; uwi_mirror_hit). */
  int mat_m = UW_MAT_NONE;
  const UwiMirrorHit mirror =
      mat == UW_MAT_SURFACE ? uwi_mirror_hit(objects, p->object_count, cam, d, S, s_w, &mat_m) : uwi_no_mirror_object();
  q->albedo_m_row = band_table + (mat_m >= 0 ? UW_ROWS + mat_m : UW_ROW_BOTTOM_ALBEDO) * stride;
  const float n_m_dot_s = dot(mirror.n, s_w);
  /* The tilted plane table's node and azimuth of the object hit's normal and of the mirrored object's
   * (uwi_tilt_node, uwi_tilt_irradiance); the bottom reads E_d. */
  float frac, frac_m;
  const int tilt_node = uwi_tilt_node(n.y, &frac);
  const int tilt_node_m = uwi_tilt_node(mirror.n.y, &frac_m);
  const float cos_phi_n = uwi_cos_azimuth(k->n_dot_s, n.y, s_w.y);
  const float cos_phi_m = uwi_cos_azimuth(n_m_dot_s, mirror.n.y, s_w.y);
  /* The share of the sand an object's face sees that is sunlit (uwi_bottom_visibility; the mirrored
   * object's is taken as 1). */
  const float vis_b = mat >= 0 ? uwi_bottom_visibility(objects, p->object_count, p->bottom_depth, cam + S * d, n, s_w)
                               : 1.0f;
  const UwiHitPixel hp = {.mat = mat, .mirror_object = mat_m >= 0, .node_r = node_r, .tilt_node = tilt_node,
                          .tilt_node_m = tilt_node_m, .multiple = k->multiple, .sky_shape = k->sky_shape,
                          .cos_dphi_r = cos_dphi_r, .frac = frac, .frac_m = frac_m, .cos_phi_n = cos_phi_n,
                          .cos_phi_m = cos_phi_m, .phase_r = phase_r, .d_y = d.y, .ior = p->ior,
                          .bottom_depth = p->bottom_depth, .n_dot_s = k->n_dot_s, .n_m_dot_s = n_m_dot_s,
                          .vis = k->vis, .vis_b = vis_b, .mirror_s = mirror.s, .mirror_vis = mirror.vis};
  q->hit = hp;
#if SEASIM_UWI_SPREAD
  q->s_spread = fmin(S, 1e4f);
#endif
}

/* The in-scatter of the view ray to distance S_end (y_end its depth there; aureole_end the aureole's end)
 * for the step's lanes: L_MS by the discrete ordinates and the forward peak's light (uwi_forward_peak),
 * as uwi_band_radiance sums it. *multiple_part: L_MS alone, the share the point-spread divides. */
static inline realb uwi_step_inscatter(__constant UwParams* p, __global const float* band_table, int stride,
                                       const KdPixel* k, const UwiPixel* q, int i, const UwiLanes* v,
                                       const UwiWeights* w, const UwiStart* camera, float S_end, float y_end,
                                       float aureole_end, realb* multiple_part) {
  UwiEnds ends;
  uwi_ends(v, p->bottom_depth, S_end, y_end, k->single & k->multiple, &ends);
  realb strict;
  const realb L = k->multiple ? uwi_lanes_multiple(v, w, camera, &ends, q->phase, p->bottom_depth, S_end, k->d_y,
                                                   k->single, &strict)
                              : SPLATB(0.0f);
  *multiple_part = L;
  return k->multiple ? fmax(L + uwi_lanes_forward_peak(band_table, stride, q->row0, i, v, q->aureole_node,
                                                       q->aureole_frac, q->node, q->cos_dphi, q->phase, k->d_y, k->o_d,
                                                       aureole_end, q->s_w_y, strict),
                            SPLATB(0.0f))
                     : SPLATB(0.0f);
}

#if SEASIM_UWI_SPREAD
/* The step's share scattered by small angles (water_spread.h (1), (3)) and the in-scatter's ((4), (5)),
 * kept apart as moments for water_spread.cl to put back blurred; returns the light that stays in the
 * pixel. L: L_MS, the share the in-scatter's part is taken from. */
static inline realb uwi_step_spread(const UwiPixel* q, const UwiLanes* v, realb L, realb in_scatter, realb hit,
                                    realb direct, const KdStep* st, KdSums* s) {
  const realb delta = v->c - v->c_dm;
  const realb em = uws_expm1_neg_b(delta * q->s_spread);
  realb count_in, depth_in;
  const realb share_in = uws_inscatter_share_b(v->c_dm, delta, q->s_spread, em, &count_in, &depth_in);
  const realb fwd_hit = hit * uws_hit_share_b(em);
  const realb L_in_share = L * share_in;
  const realb fwd = fwd_hit + fmin(L_in_share, in_scatter);
  const realb cnt = hit * (delta * q->s_spread) + L * count_in;
  const realb fwd_depth = fwd_hit * q->s_spread + L * depth_in;
  s->fwd_r += fwd * st->w_r;
  s->fwd_g += fwd * st->w_g;
  s->fwd_b += fwd * st->w_b;
  s->cnt_r += cnt * st->w_r;
  s->cnt_g += cnt * st->w_g;
  s->cnt_b += cnt * st->w_b;
  s->fwd_light_depth += fwd_depth * (st->w_r + st->w_g + st->w_b);
#if SEASIM_LAYER_FORMATION
  /* The small-angle share of the in-scatter leaves the backscatter; water_spread.cl adds it (blurred)
   * to the forward layer with the hit's. */
  LAYER_ADD(scatter, in_scatter - fmin(L_in_share, in_scatter));
  LAYER_ADD(fwdl, hit - fwd_hit - direct);
  BAND_LAYER(2, in_scatter - fmin(L_in_share, in_scatter));
  BAND_FORWARD(hit - fwd_hit - direct);
#endif
#if SEASIM_SPECTRAL_OUTPUT
  store_lanes(fwd, st->forward_spectral + ((size_t)st->pixel * 2) * st->band_count + st->i, st->band_count - st->i);
  store_lanes(cnt, st->forward_spectral + ((size_t)st->pixel * 2 + 1) * st->band_count + st->i, st->band_count - st->i);
#endif
  return in_scatter + hit - fwd;
}
#endif

/* One step of bands of the discrete-ordinates model: T L_s + L_MS per band (without the light the
 * point-spread keeps apart), the layers' lanes added into `s`. */
static inline realb uwi_step(__constant UwParams* p, __global const float* band_table, int stride, const KdPixel* k,
                             const UwiPixel* q, const KdStep* st, KdSums* s) {
  const int i = st->i;
  UwiLanes v;
  uwi_lanes_load(band_table, stride, q->row0, i, &v);
  /* The in-scatter's integrals start at the camera (per-frame rows: o_d is the frame's) and end at the
   * hit, whose exps a Lambertian hit shares. */
  UwiStart camera;
  uwi_start_camera(band_table, stride, q->row0, i, &camera);
  UwiEnds ends;
  uwi_ends(&v, p->bottom_depth, k->S, k->y_hit, k->single & k->multiple, &ends);
  UwiWeights w;
  uwi_lanes_weights(band_table, stride, q->row0, i, q->node, q->cos_dphi, &w);
  if (q->v_sand < 1.0f || q->v_diffuse < 1.0f)
    uwi_lanes_hide_sand(band_table, stride, q->row0, i, q->node, q->v_sand, q->v_diffuse, &w);
  /* The source from above, both of its terms (uwi_multiple_sand). */
  w.w1 *= q->v_above;
  w.wp *= q->v_above;
  realb L;
  const realb in_scatter =
      uwi_step_inscatter(p, band_table, stride, k, q, i, &v, &w, &camera, k->S, k->y_hit, q->aureole_end, &L);
  /* the light of what the ray meets, T(S) included */
  const realb hit = uwi_lanes_hit(&q->hit, band_table, stride, q->row0, i, &v, &ends, ends.k, LOADB(k->albedo_row, i),
                                  LOADB(q->albedo_m_row, i));
  realb direct = SPLATB(0.0f);
#if SEASIM_LAYER_FORMATION
  /* clear: the same hit with S = 0 (its ends at the hit's depth without T; the surface's t_s = 1). */
  UwiEnds ends0;
  uwi_ends(&v, p->bottom_depth, 0.0f, k->y_hit, 0, &ends0);
  const realb clear = uwi_lanes_hit(&q->hit, band_table, stride, q->row0, i, &v, &ends0, SPLATB(1.0f),
                                    LOADB(k->albedo_row, i), LOADB(q->albedo_m_row, i));
  /* direct: clear through the whole extinction c (delta-M's c' < c keeps the small-angle light in hit). */
  const realb trans = exp(-v.c * k->S);
  direct = clear * trans;
  kd_add_hit_layers(clear, direct, trans, st, s);
#endif
#if SEASIM_LAYER_VEILING
  {
    /* B∞: the in-scatter of the same ray with S = ∞ (every far end 0; the aureole's end at the depth it
     * tends to). */
    const float y_inf = k->d_y < 0.0f ? UW_INFINITE : 0.0f;
    realb l_inf;
    const realb veil =
        uwi_step_inscatter(p, band_table, stride, k, q, i, &v, &w, &camera, UW_INFINITE, y_inf, y_inf, &l_inf);
    LAYER_ADD(veil, veil);
    BAND_VEILING(veil);
  }
#endif
#if SEASIM_UWI_SPREAD
  return uwi_step_spread(q, &v, L, in_scatter, hit, direct, st, s);
#else
#if SEASIM_LAYER_FORMATION
  LAYER_ADD(scatter, in_scatter);
  LAYER_ADD(fwdl, hit - direct);
  BAND_LAYER(2, in_scatter);
  BAND_FORWARD(hit - direct);
#endif
  return in_scatter + hit;
#endif
}
#endif /* SEASIM_UNDERWATER_MODEL == 1 */

/* One step of bands of the thesis's model: L = T(S) L_s + L_MS (002 eq. 2.7 with 4.7, T(S) folded into
 * L_s: common/underwater_bands.h), the layers' lanes added into `s`. */
static inline realb kd_thesis_step(__constant UwParams* p, __global const float* band_table, int stride,
                                   const KdPixel* k, const KdStep* st, KdSums* s) {
  const int i = st->i;
#define ROW(r) (band_table + (r) * stride)
  const realb c = LOADB(ROW(UW_ROW_C), i);
  const realb kd = LOADB(ROW(UW_ROW_KD), i);
  const realb k_beam = LOADB(ROW(UW_ROW_K_BEAM), i);
  const realb ms_total = LOADB(ROW(UW_ROW_MS_TOTAL), i);
  const realb ms_direct = LOADB(ROW(UW_ROW_MS_DIRECT), i);
  const int single = k->single, multiple = k->multiple;
  const float S = k->S;
  realb L = multiple ? uw_lanes_multiple(ms_total, ms_direct, kd, k_beam, c, single, k->d_y, k->o_d, S) : SPLATB(0.0f);
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
        multiple ? uw_lanes_multiple(ms_total, ms_direct, kd, k_beam, c, single, k->d_y, k->o_d, UW_INFINITE)
                 : SPLATB(0.0f);
    LAYER_ADD(veil, veil);
    BAND_VEILING(veil);
  }
#endif
  if (k->mat == UW_MAT_SURFACE) {
    const realb sky_l = kd_sky_lanes(band_table, stride, i, k->sky_shape);
    const realb surface = uw_lanes_surface(sky_l, ms_total, ms_direct, kd, k_beam, c, single, multiple, S, k->d_y,
                                           p->ior, p->bottom_depth);
    L += surface;
#if SEASIM_LAYER_FORMATION
    hit = surface;
    clear = uw_lanes_surface(sky_l, ms_total, ms_direct, kd, k_beam, c, single, multiple, 0.0f, k->d_y, p->ior,
                             p->bottom_depth);
#endif
  } else if (k->mat != UW_MAT_NONE) {
    /* Objects read their albedo row; the bottom (UW_MAT_BOTTOM) reads the bottom's. */
    const realb lambert = uw_lanes_lambert(LOADB(k->albedo_row, i), c, kd, k_beam, LOADB(ROW(UW_ROW_E_TOTAL), i),
                                           LOADB(ROW(UW_ROW_E_SUN), i), LOADB(ROW(UW_ROW_E_BEAM), i), single, S,
                                           k->y_hit, k->n_y, k->n_dot_s, k->vis);
    L += lambert;
#if SEASIM_LAYER_FORMATION
    hit = lambert;
    clear = uw_lanes_lambert(LOADB(k->albedo_row, i), c, kd, k_beam, LOADB(ROW(UW_ROW_E_TOTAL), i),
                             LOADB(ROW(UW_ROW_E_SUN), i), LOADB(ROW(UW_ROW_E_BEAM), i), single, 0.0f, k->y_hit, k->n_y,
                             k->n_dot_s, k->vis);
#endif
  }
#undef ROW
#if SEASIM_LAYER_FORMATION
  const realb trans = exp(-c * S);
  kd_add_hit_layers(clear, hit, trans, st, s);
  BAND_FORWARD(SPLATB(0.0f)); /* the thesis has no forward term */
#endif
  return L;
}

#if SEASIM_LAYER_FORMATION
/* The formation layers' sums into formation[pixel][12] (clear, direct, backscatter with the froxel term
 * ss, transmission) and forward_layer; lamps_layer starts at 0 (underwater_lamps.cl adds into it). */
static inline void kd_store_formation(const KdSums* s, int pixel, float3 ss, __global float* formation,
                                      __global float* forward_layer, __global float* lamps_layer) {
  LAYER_STORE(formation, 12, 0, clear);
  LAYER_STORE(formation, 12, 3, direct);
  LAYER_STORE(formation, 12, 6, scatter);
  LAYER_STORE(forward_layer, 3, 0, fwdl);
#if SEASIM_HAS_FROXEL
  formation[(size_t)pixel * 12 + 6] += ss.x;
  formation[(size_t)pixel * 12 + 7] += ss.y;
  formation[(size_t)pixel * 12 + 8] += ss.z;
#endif
  /* transmission per channel: direct/clear (so direct = clear x transmission), or where the hit sends no
   * light (open water, black objects) the sensor's mean of e^{-c S}. */
  const float cl[3] = {SUMB(s->clear_r), SUMB(s->clear_g), SUMB(s->clear_b)};
  const float di[3] = {SUMB(s->direct_r), SUMB(s->direct_g), SUMB(s->direct_b)};
  const float tw[3] = {SUMB(s->trans_r), SUMB(s->trans_g), SUMB(s->trans_b)};
  const float ww[3] = {SUMB(s->weight_r), SUMB(s->weight_g), SUMB(s->weight_b)};
  for (int k = 0; k < 3; ++k)
    formation[(size_t)pixel * 12 + 9 + k] = fabs(cl[k]) > 1e-30f ? di[k] / cl[k] : layer_weighted_mean(tw[k], ww[k]);
  lamps_layer[3 * pixel + 0] = 0.0f;
  lamps_layer[3 * pixel + 1] = 0.0f;
  lamps_layer[3 * pixel + 2] = 0.0f;
}
#endif

#if SEASIM_UWI_SPREAD
static inline void kd_store_forward(const KdSums* s, int pixel, __global float* forward_rgb,
                                    __global float* forward_depth) {
  forward_rgb[6 * pixel + 0] = SUMB(s->fwd_r);
  forward_rgb[6 * pixel + 1] = SUMB(s->fwd_g);
  forward_rgb[6 * pixel + 2] = SUMB(s->fwd_b);
  forward_rgb[6 * pixel + 3] = SUMB(s->cnt_r);
  forward_rgb[6 * pixel + 4] = SUMB(s->cnt_g);
  forward_rgb[6 * pixel + 5] = SUMB(s->cnt_b);
  forward_depth[2 * pixel + 0] = SUMB(s->fwd_light_depth);
  forward_depth[2 * pixel + 1] = SUMB(s->fwd_r) + SUMB(s->fwd_g) + SUMB(s->fwd_b); /* the sum of (w_r + w_g + w_b) F */
}
#endif

#if SEASIM_LAYER_VEILING
/* B∞ in sensor RGB: the in-scatter's sums with S = ∞ and the froxel term of the whole column. */
static inline void kd_store_veiling(const KdSums* s, int pixel, float3 ss_inf, __global float* veiling) {
  veiling[3 * pixel + 0] = SUMB(s->veil_r) + ss_inf.x;
  veiling[3 * pixel + 1] = SUMB(s->veil_g) + ss_inf.y;
  veiling[3 * pixel + 2] = SUMB(s->veil_b) + ss_inf.z;
}
#endif

__kernel void kd_multiple(__constant UwParams* p, __global const UwBand* bands, __global const float* albedo,
                          __global const float* band_table, __global const UwObject* objects,
                          __global const float4* geom, __global const int* material, __global const float* sun_vis,
                          __constant SkyParams* sky_params, __global const float* sky,
#if SEASIM_HAS_FROXEL
                          __constant FroxelParams* fp, __global const float* froxel_volume,
#endif
#if SEASIM_SAND_SHARE_MAP
                          __global const float* sand_map, int sand_w, int sand_h, int sand_step,
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
  const int x = get_global_id(0), y = get_global_id(1);
  if (x >= p->width || y >= p->height) return;
  const int pixel = y * p->width + x;
  const float3 d = uw_screen_dir(p, (x + 0.5f) / p->width, (y + 0.5f) / p->height);
  const float3 s_w = (float3)(p->sun_dir_water[0], p->sun_dir_water[1], p->sun_dir_water[2]);
  const float4 g = geom[pixel];
  const float3 n = (float3)(g.y, g.z, g.w);
  /* Sky and geometry once per pixel, then SEASIM_BAND_LANES bands per step (common/band_lanes.h), the
   * per-band values read from the band table with vector loads (uwi_step, kd_thesis_step). */
  const int stride = UW_BAND_STRIDE(p->band_count);
  KdPixel k = {.mat = material[pixel], .single = KD_SINGLE, .multiple = KD_MULTIPLE, .S = g.x, .d_y = d.y,
               .o_d = -p->cam_pos[1], .n_y = n.y, .n_dot_s = dot(n, s_w), .vis = sun_vis[pixel]};
  k.y_hit = fmax(k.o_d - k.S * d.y, 0.0f);
#if SEASIM_SKY_MODEL != SEASIM_SKY_UNIFORM
  k.sky_shape = k.mat == UW_MAT_SURFACE ? sky_view_shape(sky_params, sky, sky_window_air_dir(d, p->ior))
                                        : (float3)(0.0f, 0.0f, 0.0f);
#else
  k.sky_shape = (float3)(1.0f, 1.0f, 1.0f); /* unused: a uniform sky is the band's radiance */
#endif
  k.albedo_row = band_table + (k.mat >= 0 ? UW_ROWS + k.mat : UW_ROW_BOTTOM_ALBEDO) * stride;
#if SEASIM_UNDERWATER_MODEL == 1
  UwiPixel q;
  const SandShareAt sand = {.geom = geom, .x = x, .y = y, KD_SAND_MAP};
  uwi_pixel(p, band_table, stride, objects, &sand, &k, d, n, s_w, &q);
#endif
  KdSums s;
  kd_sums_zero(&s);
  KdStep st = {.pixel = pixel, .band_count = p->band_count, .forward_spectral = KD_FORWARD_SPECTRAL,
               .layer_bands = KD_LAYER_BANDS, .forward_bands = KD_FORWARD_BANDS, .veiling_bands = KD_VEILING_BANDS};
  for (int i = 0; i < st.band_count; i += SEASIM_BAND_LANES) {
    st.i = i;
    st.w_r = LOADB(band_table + UW_ROW_W_R * stride, i);
    st.w_g = LOADB(band_table + UW_ROW_W_G * stride, i);
    st.w_b = LOADB(band_table + UW_ROW_W_B * stride, i);
#if SEASIM_UNDERWATER_MODEL == 1
    const realb L = uwi_step(p, band_table, stride, &k, &q, &st, &s);
#else
    const realb L = kd_thesis_step(p, band_table, stride, &k, &st, &s);
#endif
    /* 002 eq. 4.8. */
    s.r += L * st.w_r;
    s.g += L * st.w_g;
    s.b += L * st.w_b;
#if SEASIM_SPECTRAL_OUTPUT
    store_lanes(L, spectral + (size_t)pixel * st.band_count + i, st.band_count - i);
#endif
  }
  float3 c = (float3)(SUMB(s.r), SUMB(s.g), SUMB(s.b));
#if SEASIM_HAS_FROXEL
  const float3 ss = froxel_lookup(fp, froxel_volume, x, y, p->width, p->height, k.S);
  c += ss;
#else
  const float3 ss = (float3)(0.0f, 0.0f, 0.0f); /* no froxel term */
#endif
  rgb[3 * pixel + 0] = c.x;
  rgb[3 * pixel + 1] = c.y;
  rgb[3 * pixel + 2] = c.z;
#if SEASIM_LAYER_FORMATION
  kd_store_formation(&s, pixel, ss, formation, forward_layer, lamps_layer);
#endif
#if SEASIM_LAYER_VEILING
  kd_store_veiling(&s, pixel, KD_FROXEL_AT_INFINITY, veiling);
#endif
#if SEASIM_UWI_SPREAD
  kd_store_forward(&s, pixel, forward_rgb, forward_depth);
#endif
}
