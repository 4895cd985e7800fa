/* sea_second.cl — second-order scattering of sunlight under a flat sea by scattering maps
 * (000 §5.2, eq. 6–8), added to the image sea_single.cl wrote.
 *
 * The paper's GPU passes become four kernels, run in order for one frame:
 *   1. sea_second_vsf_map        the volume-scattering-function map: HG phase over the phase angle
 *                                 (parameter t = sin(alpha/2), common/sea_second.h)       [vsf_size]
 *   2. sea_second_radiance_map   the radiance map L^(1)(z_k, theta_m, phi_m) of eq. 7 per plane,
 *                                 direction and band, the direction table (omega, weight; over a
 *                                 height field the weight times the sun's phase) and the
 *                                 planes' depth weights d tau_k per band
 *                                                                          [n_z x n_d x bands]
 *   3. sea_second_scattering_map per plane k and sampling point s: G(z_k) sum_m beta(alpha'_m)
 *                                 L^(1)(z_k, m) sin(theta_m) dtheta dphi (eq. 8)  [n_z x M x M x bands]
 *   4. sea_second_accumulate     plane-wise accumulation along each pixel's refracted view ray:
 *                                 T_o sum_k map_k(pixel) dz_k sec(theta_ji), added into rgb.
 * The cost is n_z x M^2 x n_d x bands for the maps plus pixels x n_z x bands for the accumulation.
 *
 * Sampling points. The sampling points of plane k are where an M x M grid of view rays, spread evenly
 * over the image from the first to the last pixel centre, refracts through the surface and crosses
 * plane k: the plane's map in the camera's projection (what the paper's texture mapping of the planes
 * onto the view amounts to), so a pixel reads each map bilinearly at its own image position. Map rays
 * above the horizon are lowered to just below it (the in-water values are continuous there) so that
 * pixels next to the horizon interpolate towards the right limit.
 *
 * Units. Maps hold L^(2)(z_k)/c (eq. 8 divided by c) and the planes are placed in optical depth
 * tau = c z, per band (common/sea_second.h sea_plane_depth), so that nothing divides by c.
 *
 * Inputs: SeaSecondParams, SeaBand[band_count] (sea_params.h). Output: rgb[3 * pixels] += L^(2) in
 * sensor RGB; spectral[pixels * band_count] += L^(2) with SEASIM_SPECTRAL_OUTPUT.
 * Defines (host/plan): SEASIM_HAS_BOTTOM (flat bottom at bottom_depth), SEASIM_SPECTRAL_OUTPUT,
 * SEASIM_BOTTOM_HEIGHTFIELD (with SEASIM_HAS_BOTTOM: a height-field floor, below).
 *
 * Height-field floor (000 §5.4, common/sea_bottom.h). The planes still span [0, bottom_depth], the
 * deepest node of the floor, but
 *   0. sea_second_depth_table (once per scene; the pass caches it on disk) walks, from the sampling
 *      point of every map ray (i, j) at each of n_z + 1 table-node depths, every sampling direction
 *      to where it leaves the water (the floor, or the surface) and stores that distance in metres
 *                                       [(n_z + 1) x M x M x n_d, rows padded: sea_second_params.h];
 *   2. the radiance map is then per sampling point: the scattering-map kernel evaluates eq. 7 for
 *      each point, direction and band from the table, read linearly in depth between the nodes
 *      around the band's plane (the paper's interpolation between P_s and P'_s);
 *   4. the accumulation stops at the floor: plane k counts with the share of its depth cell above
 *      the pixel's own z_Q (its view ray walked to the floor).
 * Table nodes below a map ray's own floor point Q take the values of its last point in the water
 * (just above Q), so that the maps continue smoothly across the floor's edges for the pixels between.
 * Stiff cases: the 0/0 of eq. 7 at cos theta = cos theta_io and theta = pi/2 (common/sea_second.h);
 * sun below the horizon (sun_beam = 0: adds exactly 0); c = 0 (albedo 0: adds 0); grazing views
 * (cos theta_ji clamped away from 0, T_o -> 0).
 */
#include "common/compat.h"
#include "common/optics.h"
#include "common/sea_params.h"
#include "common/sea_second_params.h"
#include "common/sea_second.h"
#include "common/sea_surface.h"
#include "common/sea_bottom_params.h"
#include "common/sea_bottom.h"

#ifndef SEASIM_BOTTOM_HEIGHTFIELD
#define SEASIM_BOTTOM_HEIGHTFIELD 0
#endif

/* Directions per block of the height field's scattering map: a multiple of SEASIM_BAND_LANES (and of the
 * rows' padding), its band-free factors held in two private arrays of this size. */
#define SEA_SECOND_DIR_BLOCK (8 * SEASIM_BAND_LANES)
#include "common/band_lanes.h"
#include "common/band_lanes_math.h"
#include "common/sea_bottom_lanes.h"

#define SEA_SECOND_CHUNK 32 /* bands accumulated per pass over the directions (private registers) */

/* World view direction through image position (fx, fy) in pixels (pixel centres at x + 0.5). */
static inline float3 view_dir(__constant SeaSecondParams* p, float fx, float fy) {
  const float u = (2.0f * fx / p->width - 1.0f) * p->tan_half_fov_y * p->aspect;
  const float v = (1.0f - 2.0f * fy / p->height) * p->tan_half_fov_y;
  const float3 right = (float3)(p->cam_right[0], p->cam_right[1], p->cam_right[2]);
  const float3 up = (float3)(p->cam_up[0], p->cam_up[1], p->cam_up[2]);
  const float3 fwd = (float3)(p->cam_forward[0], p->cam_forward[1], p->cam_forward[2]);
  return normalize(fwd + u * right + v * up);
}

static inline float optical_bottom(const __global SeaBand* band, __constant SeaSecondParams* p) {
#if SEASIM_HAS_BOTTOM
  return band->c * p->bottom_depth;
#else
  return -1.0f; /* no bottom */
#endif
}

__kernel void sea_second_vsf_map(__constant SeaSecondParams* p, __global float* vsf) {
  const int i = get_global_id(0);
  if (i >= p->vsf_size) return;
  vsf[i] = sea_vsf_value((float)i / (float)(p->vsf_size - 1), p->g);
}

/* Over a height field it also writes, per plane k and band, what the scattering map needs of them at every map
 * point: plane_bands[k * SEA_SECOND_STRIDE(band_count) + band] = (τ_k, the table node's interpolation weight, the
 * node, e^{-τ_k sec θ_io}); four log1p per band that each of the map's points would otherwise repeat. */
__kernel void sea_second_radiance_map(__constant SeaSecondParams* p, __global const SeaBand* bands,
                                      __global float4* dirs, __global float* radiance, __global float* plane_w,
                                      __global float4* plane_bands) {
  const int m = get_global_id(0);
  const int k = get_global_id(1);
  const int n_d = p->n_theta * p->n_phi;
  if (m >= SEA_SECOND_STRIDE(n_d) || k >= p->n_z) return;
  if (m >= n_d) { /* a padded direction: weight 0 */
    if (k == 0) dirs[m] = (float4)(0.0f, 1.0f, 0.0f, 0.0f);
    return;
  }
  float3 omega;
  const float weight = sea_direction(m, p->n_theta, p->n_phi, &omega);
  const float3 sun = (float3)(p->sun_in_water[0], p->sun_in_water[1], p->sun_in_water[2]);
  const float phase = hg_phase(dot(sun, -omega), p->g); /* first scattering: sun beam -> -omega */
  /* Over a height field the scattering map evaluates eq. 7 itself and takes the sun's phase with the weight. */
  if (k == 0) dirs[m] = (float4)(omega.x, omega.y, omega.z, SEASIM_BOTTOM_HEIGHTFIELD ? weight * phase : weight);
  __global float* w_row = plane_w + k * SEA_SECOND_STRIDE(p->band_count); /* d tau of plane k, for the accumulation */
  for (int i = 0; i < p->band_count; ++i) {
    const __global SeaBand* band = &bands[i];
    const float albedo = band->c > 0.0f ? band->b / band->c : 0.0f;
    const float tau_d = optical_bottom(band, p);
    float w;
    const float tau_k = sea_plane_depth(k, p->n_z, p->cos_io, tau_d, &w);
    if (m == 0) w_row[i] = w;
#if SEASIM_BOTTOM_HEIGHTFIELD
    if (m == 0) {
      const float z_k = band->c > 0.0f ? tau_k / band->c : 0.0f;
      float node_w;
      const int node = sea_table_node_interval(z_k, p->n_z, p->cos_io, p->table_c, p->bottom_depth, &node_w);
      plane_bands[k * SEA_SECOND_STRIDE(p->band_count) + i] = (float4)(tau_k, node_w, (float)node, exp(-tau_k / p->cos_io));
    }
#endif
    radiance[((size_t)k * n_d + m) * p->band_count + i] =
        sea_radiance_map(band->sun_irradiance * p->sun_beam, albedo, phase, p->cos_io, omega.y, tau_k, tau_d);
  }
  if (m == 0)
    for (int i = p->band_count; i < SEA_SECOND_STRIDE(p->band_count); ++i) { /* padded bands */
      w_row[i] = 0.0f;
      plane_bands[k * SEA_SECOND_STRIDE(p->band_count) + i] = (float4)(0.0f, 0.0f, 0.0f, 1.0f);
    }
}

/* World view direction of map sampling point (i, j), lowered just below the horizon when above it. */
static inline float3 map_view_dir(__constant SeaSecondParams* p, int i, int j) {
  const int M = p->map_size;
  const float fx = M > 1 ? 0.5f + (float)i * (p->width - 1) / (M - 1) : 0.5f * p->width;
  const float fy = M > 1 ? 0.5f + (float)j * (p->height - 1) / (M - 1) : 0.5f * p->height;
  float3 d = view_dir(p, fx, fy);
  if (d.y > -1e-3f) d = normalize((float3)(d.x, -1e-3f, d.z)); /* lowered below the horizon */
  return d;
}

/* Refracted view direction and cos(theta_ji) at a map sampling point (i, j). */
static inline float3 map_view_in_water(__constant SeaSecondParams* p, int i, int j, float* cos_ji) {
  const float3 d = map_view_dir(p, i, j);
  float3 v;
  refract_dir(d, (float3)(0.0f, 1.0f, 0.0f), 1.0f / p->ior, &v);
  *cos_ji = fmax(-v.y, 1e-4f);
  return v;
}

#if SEASIM_BOTTOM_HEIGHTFIELD
/* Where the view ray d from the camera meets the mean surface y = 0 (P of 000 Fig. 5). */
static inline float3 surface_point(__constant SeaSecondParams* p, float3 d) {
  const float t = p->cam_pos[1] / -d.y;
  return (float3)(p->cam_pos[0] + t * d.x, 0.0f, p->cam_pos[2] + t * d.z);
}

/* 000 §5.4's depth tables: table[((t * M + j) * M + i) * SEA_SECOND_STRIDE(n_d) + m] = the distance (m) from map ray
 * (i, j)'s sampling point at table-node depth z_t along sampling direction m to where it leaves the
 * water: the floor, or the surface when nothing is in the way. */
__kernel void sea_second_depth_table(__constant SeaSecondParams* p, __constant SeaHeightField* hf,
                                     __global const float* hf_depth, __global float* table) {
  const int i = get_global_id(0);
  const int j = get_global_id(1);
  const int t = get_global_id(2);
  const int M = p->map_size;
  if (i >= M || j >= M || t > p->n_z) return;
  const int n_d = p->n_theta * p->n_phi;
  float cos_ji;
  const float3 v = map_view_in_water(p, i, j, &cos_ji);
  const float3 P = surface_point(p, map_view_dir(p, i, j));
  float t_q;
  float3 n_q;
  sea_hf_intersect(hf, hf_depth, P, v, 1e30f, &t_q, &n_q); /* the map ray's own floor point Q */
  const float dz = -v.y;                                   /* depth per metre along v, > 0.66 */
  const float z_q = dz * t_q;
  /* Nodes at or below Q sit in the floor: use the ray's last point in the water, just above Q. */
  const float z_max_here = fmax(z_q - 2e-4f * fmax(1.0f, z_q), 0.0f);
  const float z_node = fmin(sea_table_node_depth(t, p->n_z, p->cos_io, p->table_c, p->bottom_depth), z_max_here);
  const float3 Ps = P + (z_node / dz) * v;
  const int n_rows = SEA_SECOND_STRIDE(n_d);
  __global float* out = table + (((size_t)t * M + j) * M + i) * n_rows;
  for (int m = n_d; m < n_rows; ++m) out[m] = 0.0f; /* padded directions: no water */
  for (int m = 0; m < n_d; ++m) {
    float3 omega;
    sea_direction(m, p->n_theta, p->n_phi, &omega);
    float l;
    float3 n;
    /* Upwards the surface ends the ray unless the floor comes first; downwards the floor always does. */
    sea_hf_intersect(hf, hf_depth, Ps, omega, omega.y > 0.0f ? z_node / omega.y : 1e30f, &l, &n);
    out[m] = l;
  }
}
#endif

__kernel void sea_second_scattering_map(__constant SeaSecondParams* p, __global const SeaBand* bands,
                                        __global const float4* dirs, __global const float* vsf,
                                        __global const float* radiance, __global float* maps
#if SEASIM_BOTTOM_HEIGHTFIELD
                                        , __global const float* table, __global const float4* plane_bands
#endif
) {
  const int i = get_global_id(0);
  const int j = get_global_id(1);
  const int k = get_global_id(2);
  const int M = p->map_size;
  if (i >= M || j >= M || k >= p->n_z) return;
  const int n_d = p->n_theta * p->n_phi;
  const int nb = p->band_count;
  float cos_ji;
  const float3 v = map_view_in_water(p, i, j, &cos_ji);
  const size_t out = (((size_t)k * M + j) * M + i) * SEA_SECOND_STRIDE(nb);
  for (int b = nb; b < SEA_SECOND_STRIDE(nb); ++b) maps[out + b] = 0.0f; /* padded bands */
  for (int b0 = 0; b0 < nb; b0 += SEA_SECOND_CHUNK) {
    const int count = min(SEA_SECOND_CHUNK, nb - b0);
    float acc[SEA_SECOND_CHUNK];
    for (int c = 0; c < count; ++c) acc[c] = 0.0f;
#if SEASIM_BOTTOM_HEIGHTFIELD
    /* Per band: its plane's optical depth and the table nodes around its geometric depth (plane_bands). */
    float node_w[SEA_SECOND_CHUNK], source[SEA_SECOND_CHUNK], c_band[SEA_SECOND_CHUNK];
    float a_band[SEA_SECOND_CHUNK], near_band[SEA_SECOND_CHUNK]; /* tau_k sec(theta_io) and its e^{-a} */
    int node[SEA_SECOND_CHUNK];
    for (int c = 0; c < count; ++c) {
      const __global SeaBand* band = &bands[b0 + c];
      const float4 plane = plane_bands[k * SEA_SECOND_STRIDE(nb) + b0 + c];
      node_w[c] = plane.y;
      node[c] = (int)plane.z;
      source[c] = band->sun_irradiance * p->sun_beam * (band->c > 0.0f ? band->b / band->c : 0.0f);
      c_band[c] = band->c;
      a_band[c] = plane.x / p->cos_io;
      near_band[c] = plane.w;
    }
    const int n_rows = SEA_SECOND_STRIDE(n_d);
    const size_t node_stride = (size_t)M * M * n_rows;
    const __global float* ends = table + ((size_t)j * M + i) * n_rows;
    /* The directions in blocks of SEA_SECOND_DIR_BLOCK (the rows padded with directions of weight 0): their
     * band-free factors once per block (the VSF towards the eye times the weight and the sun's phase, which
     * the direction table holds, and κ), then per band eq. 7 for SEASIM_BAND_LANES directions at a time
     * (sea_bottom_lanes.h), one vector load of each table node's row, summed across the block's runs in the
     * lanes and only then across them (one horizontal sum per band and block, not per run). */
    for (int m0 = 0; m0 < n_rows; m0 += SEA_SECOND_DIR_BLOCK) {
      const int m_count = min(SEA_SECOND_DIR_BLOCK, n_rows - m0);
      float blk_w[SEA_SECOND_DIR_BLOCK] __attribute__((aligned(4 * SEASIM_BAND_LANES)));
      float blk_kappa[SEA_SECOND_DIR_BLOCK] __attribute__((aligned(4 * SEASIM_BAND_LANES)));
      float blk_inv_kappa[SEA_SECOND_DIR_BLOCK] __attribute__((aligned(4 * SEASIM_BAND_LANES)));
      for (int q = 0; q < m_count; ++q) {
        const float4 dw = dirs[m0 + q];
        const float t = sea_vsf_param(dw.x * v.x + dw.y * v.y + dw.z * v.z) * (p->vsf_size - 1);
        const int t0 = min((int)t, p->vsf_size - 2);
        const float f = t - (float)t0;
        blk_w[q] = (vsf[t0] + f * (vsf[t0 + 1] - vsf[t0])) * dw.w;
        blk_kappa[q] = (p->cos_io - dw.y) / p->cos_io; /* 1 - sec(theta_io) cos(theta) */
        blk_inv_kappa[q] = blk_kappa[q] != 0.0f ? 1.0f / blk_kappa[q] : 0.0f;
      }
      for (int c = 0; c < count; ++c) {
        const __global float* row = ends + node[c] * node_stride + m0;
        realb sum = SPLATB(R(0.0));
        for (int r = 0; r < m_count; r += SEASIM_BAND_LANES) {
          const realb l0 = LOADB(row, r), l1 = LOADB(row + node_stride, r);
          const realb l = fmax(c_band[c] * (l0 + node_w[c] * (l1 - l0)), R(0.0));
          sum += LOADB(blk_w, r) *
                 sea_path_integral_finite_b(near_band[c], a_band[c], LOADB(blk_kappa, r), LOADB(blk_inv_kappa, r), l);
        }
        acc[c] += source[c] * SUMB(sum);
      }
    }
#else
    for (int m = 0; m < n_d; ++m) {
      const float4 dw = dirs[m];
      /* Second scattering: light travelling -omega turned towards the eye (-v): cos alpha' = omega.v */
      const float t = sea_vsf_param(dw.x * v.x + dw.y * v.y + dw.z * v.z) * (p->vsf_size - 1);
      const int t0 = min((int)t, p->vsf_size - 2);
      const float f = t - (float)t0;
      const float pw = (vsf[t0] + f * (vsf[t0 + 1] - vsf[t0])) * dw.w;
      const __global float* L1 = radiance + ((size_t)k * n_d + m) * nb + b0;
      for (int c = 0; c < count; ++c) acc[c] += pw * L1[c];
    }
#endif
    for (int c = 0; c < count; ++c) {
      const __global SeaBand* band = &bands[b0 + c];
      const float albedo = band->c > 0.0f ? band->b / band->c : 0.0f;
#if SEASIM_BOTTOM_HEIGHTFIELD
      const float tau_k = plane_bands[k * SEA_SECOND_STRIDE(nb) + b0 + c].x;
#else
      float w;
      const float tau_k = sea_plane_depth(k, p->n_z, p->cos_io, optical_bottom(band, p), &w);
#endif
      maps[out + b0 + c] = sea_attenuation(tau_k, cos_ji) * albedo * acc[c]; /* eq. 8 / c */
    }
  }
}

__kernel void sea_second_accumulate(__constant SeaSecondParams* p, __global const SeaBand* bands,
                                    __global const float* maps, __global const float* plane_w, __global float* rgb
#if SEASIM_SPECTRAL_OUTPUT
                                    , __global float* spectral
#endif
#if SEASIM_BOTTOM_HEIGHTFIELD
                                    , __constant SeaHeightField* hf, __global const float* hf_depth
#endif
) {
  const int x = get_global_id(0);
  const int y = get_global_id(1);
  if (x >= p->width || y >= p->height) return;
  const float3 d = view_dir(p, x + 0.5f, y + 0.5f);
  if (d.y >= 0.0f) return; /* sky: no water along this ray */
  const int pixel = y * p->width + x;
  /* T_o with the n² law (radiance / n² conserved across the surface; sea_single.cl, docs/radiometry.md) */
  const float t_out = (1.0f - fresnel_reflectance(-d.y, 1.0f, p->ior)) / (p->ior * p->ior);
  float3 v;
  refract_dir(d, (float3)(0.0f, 1.0f, 0.0f), 1.0f / p->ior, &v);
  const float cos_ji = fmax(-v.y, 1e-4f);
#if SEASIM_BOTTOM_HEIGHTFIELD
  /* 000 §5.4: this pixel's view ray sees water down to its own floor point Q only. */
  float t_q;
  float3 n_q;
  sea_hf_intersect(hf, hf_depth, surface_point(p, d), v, 1e30f, &t_q, &n_q);
  const float z_q = fmax(-v.y, 0.0f) * t_q;
#endif

  /* Bilinear position of this pixel in every plane's map. */
  const int M = p->map_size;
  float mx = 0.0f, my = 0.0f;
  if (M > 1) {
    mx = p->width > 1 ? (float)x * (M - 1) / (p->width - 1) : 0.0f;
    my = p->height > 1 ? (float)y * (M - 1) / (p->height - 1) : 0.0f;
  }
  const int i0 = M > 1 ? min((int)mx, M - 2) : 0;
  const int j0 = M > 1 ? min((int)my, M - 2) : 0;
  const int di = M > 1 ? 1 : 0;
  const float fx = mx - i0, fy = my - j0;
  const int nb = p->band_count;

  float r = 0.0f, g = 0.0f, b = 0.0f;
  /* The bands in runs of SEASIM_BAND_LANES: a map point's bands are contiguous, the rows padded with
   * bands of c = 0 and no sensor weight. */
  const int stride = SEA_SECOND_STRIDE(nb);
  for (int b0 = 0; b0 < stride; b0 += SEASIM_BAND_LANES) {
    float run_c[SEASIM_BAND_LANES], run_r[SEASIM_BAND_LANES], run_g[SEASIM_BAND_LANES], run_b[SEASIM_BAND_LANES];
    for (int q = 0; q < SEASIM_BAND_LANES; ++q) {
      const __global SeaBand* band = &bands[b0 + q];
      run_c[q] = band->c, run_r[q] = band->w_r, run_g[q] = band->w_g, run_b[q] = band->w_b;
    }
    const realb c = LOADB(run_c, 0);
    realb sum = SPLATB(0.0f);
    for (int k = 0; k < p->n_z; ++k) { /* plane by plane, front to back */
#if SEASIM_BOTTOM_HEIGHTFIELD
      const realb w = LOADB(plane_w + k * stride, b0) * sea_plane_share_above_b(k, p->n_z, p->cos_io, c * p->bottom_depth, c * z_q);
#else
      const realb w = LOADB(plane_w + k * stride, b0);
#endif
      const __global float* map = maps + (size_t)k * M * M * stride + b0;
      const realb a00 = LOADB(map, ((size_t)j0 * M + i0) * stride), a10 = LOADB(map, ((size_t)j0 * M + i0 + di) * stride);
      const realb a01 = LOADB(map, ((size_t)(j0 + di) * M + i0) * stride), a11 = LOADB(map, ((size_t)(j0 + di) * M + i0 + di) * stride);
      const realb top = a00 + fx * (a10 - a00), bottom = a01 + fx * (a11 - a01);
      sum += (top + fy * (bottom - top)) * w;
    }
    const realb L = t_out * sum / cos_ji; /* dz sec(theta_ji) = dtau sec(theta_ji) / c */
    r += SUMB(L * LOADB(run_r, 0)), g += SUMB(L * LOADB(run_g, 0)), b += SUMB(L * LOADB(run_b, 0));
#if SEASIM_SPECTRAL_OUTPUT
    __global float* out = spectral + (size_t)pixel * nb + b0; /* spectral.exr's rows are not padded */
    store_lanes(load_lanes(out, nb - b0) + L, out, nb - b0);
#endif
  }
  rgb[3 * pixel + 0] += r;
  rgb[3 * pixel + 1] += g;
  rgb[3 * pixel + 2] += b;
}
