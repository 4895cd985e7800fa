/* froxel.cl — single scattering of the refracted sun beam under a flat surface by froxels (002 §5.1,
 * eq. 5.2, §5.2), with the scrolling caustic textures of 002 §5.3. The math is common/froxel.h.
 *
 *   L_SS = ∫_0^S e^{-σ_t z} σ_s p_HG(s_w·d, g) E_beam(y) V C dz,  E_beam(y) = e_beam0 e^{-σ_t y/μ_w}
 *
 * Kernels, in order:
 *   froxel_shadow_map  the sun's orthographic depth map along -s_w over the spheres and boxes (planes
 *                      are unbounded and tested exactly in froxel_inject): per texel the distance to the
 *                      first object below the surface, UW_INFINITE where none. Only with objects.
 *   froxel_inject      per column (i, j), for each froxel k front to back, the band-independent part of
 *                      the in-scatter at its centre:
 *                      V (shadow map, 2×2 PCF, times the exact plane test) × C (caustic_modulation at
 *                      the surface point the refracted sun ray through the froxel came from, when
 *                      SEASIM_CAUSTICS == UW_CAUSTICS_TEXTURE, its feature points read from
 *                      caustic_table (caustic_fill_table, filled once by the host) instead of hashed;
 *                      1 otherwise — the caustic map of UW_CAUSTICS_MAP is not read here). 0 above the
 *                      surface; the caustic is not evaluated where V = 0.
 *   froxel_column_extent  (before froxel_inject, when the pass is given the G-buffer) per pixel, the last
 *                      slice its read needs in each column it reads: froxels beyond are not evaluated.
 *   froxel_integrate   per column, front to back (002 eq. 5.2, common/froxel.h): per band and slice
 *                      σ_s p V C e_beam0 e^{-σ_t P} integrated exactly over the slice (P the light's
 *                      path from the surface to the camera, linear along the column; V·C from
 *                      froxel_inject), accumulated into sensor RGB with the band's w_r, w_g, w_b.
 *   froxel_resolve     per pixel, the volume read at the pixel's G-buffer distance (froxel_lookup);
 *                      kd_multiple.cl does the same read inline, this kernel serves tests and tools.
 *
 * Inputs: UwParams, FroxelParams, UwObject[object_count], bands: UwBand[band_count] (spectral
 * injection) or the three RGB pseudo-bands (host/reference/froxel_reference.h). Outputs: light (1 float
 * per froxel), volume (4 floats per froxel, common/froxel_params.h), rgb (3 floats per pixel).
 * caustic_table: CAUSTIC_TABLE_REALS
 * floats (common/caustic_texture.h caustic_fill_table), read only with SEASIM_CAUSTICS == UW_CAUSTICS_TEXTURE.
 * column_last: 1 int per column (froxel_column_extent). column_dy: 1 float per column, its ray's d_y
 * (froxelColumnDy, filled by the host).
 * Defines (host/plan): SEASIM_HAS_OBJECTS, SEASIM_CAUSTICS (UW_CAUSTICS_*), SEASIM_SPECTRAL_INJECTION
 * (1: the n wavelength bands, p->band_count of them; 0: the three RGB pseudo-bands).
 * Stiff cases: E_beam and the transmittance underflow to 0 at great depth and distance (camera at
 * 1000 m, 9C water over 60 m) — every factor is <= 1 except L_i d, so nothing overflows and no 0·∞
 * forms; slices of any optical depth are integrated exactly (φ = expm1_over_x); the sun's refracted
 * μ_w >= 0.66 (Snell), clamped at 1e-4 all the same.
 */
#include "common/compat.h"
#include "common/optics.h"
#include "common/shafts.h"
#include "common/underwater_params.h"
#include "common/underwater.h"
#include "common/froxel_params.h"
#include "common/froxel.h"
#if SEASIM_CAUSTICS == UW_CAUSTICS_TEXTURE
#include "common/caustic_texture.h"
#endif
#if SEASIM_CAUSTICS == UW_CAUSTICS_MAP
#include "common/caustic_map.h"
#endif

#ifndef SEASIM_HAS_OBJECTS
#define SEASIM_HAS_OBJECTS 1
#endif
#ifndef SEASIM_SPECTRAL_INJECTION
#define SEASIM_SPECTRAL_INJECTION 1
#endif

#define SUN_DIR_WATER(p) ((float3)((p)->sun_dir_water[0], (p)->sun_dir_water[1], (p)->sun_dir_water[2]))

__kernel void froxel_shadow_map(__constant UwParams* p, __constant FroxelParams* fp, __global const UwObject* objects,
                                __global float* map) {
  const int i = get_global_id(0), j = get_global_id(1);
  const int n = fp->shadow_size;
  if (i >= n || j >= n) return;
  map[j * n + i] = froxel_shadow_texel(fp, objects, p->object_count, SUN_DIR_WATER(p), i, j);
}

/* V·C of one froxel with centre q (see the top): 0 above the surface. */
float froxel_injected(__constant UwParams* p, __constant FroxelParams* fp, __global const UwObject* objects,
                      __global const float* map, __global const float* caustic_maps,
                      __global const float* caustic_table, float3 s_w, float3 q, float caustic_rho) {
  if (q.y > 0.0f) return 0.0f; /* above the surface: no water, no beam */
  float v = 1.0f;
#if SEASIM_HAS_OBJECTS
  v = froxel_shadow_visibility(fp, map, s_w, q) * froxel_plane_visibility(objects, p->object_count, s_w, q);
#endif
#if SEASIM_CAUSTICS == UW_CAUSTICS_TEXTURE
  /* Where the refracted sun ray through q crossed the surface (as raycast.cl does for surfaces), kept
   * by rho where the froxel stands for the texture's mean over many cells (froxel_caustic_correlation);
   * not evaluated where v = 0 or rho is too small (froxel_caustic_evaluated). */
  if (v > 0.0f && froxel_caustic_evaluated(caustic_rho)) {
    const float t_up = -q.y / fmax(s_w.y, 1e-4f);
    v *= froxel_kept_caustic(caustic_modulation_table(q.x + t_up * s_w.x, q.z + t_up * s_w.z, p->time,
                                                      p->caustic_period, p->caustic_speed, caustic_table),
                             caustic_rho);
  }
#endif
#if SEASIM_CAUSTICS == UW_CAUSTICS_MAP
  v *= caustic_map_sample(caustic_maps, p->caustic_map_size, p->caustic_layers, p->caustic_extent, p->caustic_depth_max,
                          q.x, -q.y, q.z);
#endif
  return v;
}

/* Per pixel of the G-buffer (raycast.cl's geom: S in .x): raises column_last of the up to four columns
 * its froxel_lookup reads (froxel_pixel_column) to the slice it reads there (froxel_read_slice; the last
 * slice for a ray to the surface, which reads its columns whole). The
 * host sets column_last to -1 first; atomic_max makes the result independent of the order. */
__kernel void froxel_column_extent(__constant FroxelParams* fp, __global const float* column_dy,
                                   __global const float4* geom, int width, int height, __global int* column_last) {
  const int x = get_global_id(0), y = get_global_id(1);
  if (x >= width || y >= height) return;
  const int nx = fp->nx, ny = fp->ny;
  const float gx = froxel_pixel_column(x, width, nx), gy = froxel_pixel_column(y, height, ny);
  const int i0 = (int)gx, j0 = (int)gy;
  const int i1 = i0 + 1 < nx ? i0 + 1 : nx - 1, j1 = j0 + 1 < ny ? j0 + 1 : ny - 1;
  const float S = geom[y * width + x].x;
  /* froxel_lookup's test for a ray to the surface on the same columns' d_y (the table the volume
   * stores), with twice its tolerance: every pixel it reads whole is marked whole here, whatever the
   * rounding of the bilinear weights. */
  const float d_y = froxel_pixel_dy(column_dy[j0 * nx + i0], column_dy[j0 * nx + i1], column_dy[j1 * nx + i0],
                                    column_dy[j1 * nx + i1], gx - (float)i0, gy - (float)j0);
  const int k = S > 0.0f && froxel_reads_whole_columns(fp, d_y, S, 2e-3f) ? fp->nz - 1 : froxel_read_slice(fp, S);
  if (k < 0) return;
  atomic_max(&column_last[j0 * nx + i0], k);
  atomic_max(&column_last[j0 * nx + i1], k);
  atomic_max(&column_last[j1 * nx + i0], k);
  atomic_max(&column_last[j1 * nx + i1], k);
}

/* One work-item per column (i, j), front to back: the column's ray and each slice end are computed
 * once (slice k starts where k - 1 ended), V·C at the same points as froxel_center. Froxels past
 * column_last[j nx + i] + 1 are written 0 without evaluating them: no pixel reads them, not even
 * through the running integral (froxel_column_extent; one slice of margin against a rounding
 * difference between froxel_read_slice here and in kd_multiple.cl). column_last = nz - 1 everywhere:
 * every froxel. */
__kernel void froxel_inject(__constant UwParams* p, __constant FroxelParams* fp, __global const UwObject* objects,
                            __global const float* map, __global const float* caustic_maps, __global float* light,
                            __global const float* caustic_table, __global const int* column_last) {
  const int i = get_global_id(0), j = get_global_id(1);
  if (i >= fp->nx || j >= fp->ny) return;
  const int last = column_last[j * fp->nx + i] + 1;
  const float3 s_w = SUN_DIR_WATER(p);
  const float3 o = (float3)(p->cam_pos[0], p->cam_pos[1], p->cam_pos[2]);
  const float3 d = froxel_column_dir(p, fp, i, j);
  const float t_surface = froxel_surface_distance(-p->cam_pos[1], d.y);
  float t0 = 0.0f;
  for (int k = 0; k < fp->nz; ++k) {
    const float t1 = froxel_slice_end(k, fp->nz, fp->z_near, fp->z_far, fp->log_far_near);
    const float t = froxel_sample_t(t0, t1, t_surface);
#if SEASIM_CAUSTICS == UW_CAUSTICS_TEXTURE
    const float rho = froxel_caustic_correlation(p, fp, d, s_w, t0, fmax(t0, fmin(t1, t_surface)),
                                                 caustic_integral_scale(p->caustic_period));
#else
    const float rho = 1.0f;
#endif
    light[(k * fp->ny + j) * fp->nx + i] =
        k <= last ? froxel_injected(p, fp, objects, map, caustic_maps, caustic_table, s_w, o + t * d, rho) : 0.0f;
    t0 = t1;
  }
}

__kernel void froxel_integrate(__constant UwParams* p, __constant FroxelParams* fp, __global const UwBand* bands,
                               __global const float* light, __global float* volume, __global const float* column_dy) {
  const int i = get_global_id(0), j = get_global_id(1);
  if (i >= fp->nx || j >= fp->ny) return;
#if SEASIM_SPECTRAL_INJECTION
  const int band_count = p->band_count;
#else
  const int band_count = 3;
#endif
  froxel_integrate_column(p, fp, bands, band_count, light, volume, column_dy[j * fp->nx + i], i, j);
}

__kernel void froxel_resolve(__constant FroxelParams* fp, __global const float* volume, __global const float4* geom,
                             int width, int height, __global float* rgb) {
  const int x = get_global_id(0), y = get_global_id(1);
  if (x >= width || y >= height) return;
  const int pixel = y * width + x;
  const float3 ss = froxel_lookup(fp, volume, x, y, width, height, geom[pixel].x);
  rgb[3 * pixel + 0] = ss.x;
  rgb[3 * pixel + 1] = ss.y;
  rgb[3 * pixel + 2] = ss.z;
}

// The froxel term of one wavelength band (a volume integrated for that band alone, its value in R)
// added into a per-band image: values[pixel * stride + offset] += the volume read at geom[pixel].x.
// The stride and offset pick the band's slot in the spectral image or a layer's slot of the band
// layers (kd_multiple.cl's header gives their layouts).
__kernel void froxel_resolve_add(__constant FroxelParams* fp, __global const float* volume,
                                 __global const float4* geom, int width, int height, int stride, int offset,
                                 __global float* values) {
  const int x = get_global_id(0), y = get_global_id(1);
  if (x >= width || y >= height) return;
  const int pixel = y * width + x;
  const float3 ss = froxel_lookup(fp, volume, x, y, width, height, geom[pixel].x);
  values[(size_t)pixel * (size_t)stride + (size_t)offset] += ss.x;
}
