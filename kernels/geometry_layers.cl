/* geometry_layers.cl — the underwater frame's geometry layers (outputs.layers: range, depth, normal,
 * object_id, albedo) from raycast.cl's G-buffer, so they are the very hits the shading used.
 *
 * Inputs: UwParams (camera basis, band count), geom = (S, n) per pixel (S >= UW_INFINITE: open water),
 * material (object index or UW_MAT_*), the band table (common/underwater_band_table.h: the sensor's
 * weights and the albedo rows). Output: out[pixel * SEASIM_LAYER_CHANNELS + offset], each asked layer at
 * its offset.
 * Open water: range and depth +inf (written as such, the EXR keeps it), normal 0, object_id 0, albedo 0.
 * Built without -cl-fast-relaxed-math (its infinity must survive).
 * Defines (host/plan, LayerGeometryFeatures): SEASIM_LAYER_CHANNELS and each layer's channel offset,
 * -1 when not asked: SEASIM_LAYER_RANGE, SEASIM_LAYER_DEPTH, SEASIM_LAYER_NORMAL, SEASIM_LAYER_OBJECT_ID,
 * SEASIM_LAYER_ALBEDO; SEASIM_LAYER_ALBEDO_BANDS (with the albedo and spectral.exr): albedo_bands[pixel][band],
 * the albedo per band.
 */
#include "common/compat.h"
#include "common/optics.h"
#include "common/shafts.h"
#include "common/underwater_params.h"
#include "common/underwater.h"
#include "common/underwater_band_table.h"
#include "common/output_layers.h"
#ifndef SEASIM_LAYER_ALBEDO_BANDS
#define SEASIM_LAYER_ALBEDO_BANDS 0
#endif

__kernel void geometry_layers(__constant UwParams* p, __global const float4* geom, __global const int* material,
                              __global const float* band_table, __global float* out
#if SEASIM_LAYER_ALBEDO_BANDS
                              , __global float* albedo_bands
#endif
) {
  const int x = get_global_id(0);
  const int y = get_global_id(1);
  if (x >= p->width || y >= p->height) return;
  const int pixel = y * p->width + x;
  __global float* o = out + (size_t)pixel * SEASIM_LAYER_CHANNELS;
  const float4 g = geom[pixel];
  const int mat = material[pixel];
  const int hit = layer_hit(g.x);
#if SEASIM_LAYER_RANGE >= 0
  o[SEASIM_LAYER_RANGE] = hit ? g.x : INFINITY;
#endif
#if SEASIM_LAYER_DEPTH >= 0
  const float3 d = uw_screen_dir(p, (x + 0.5f) / p->width, (y + 0.5f) / p->height);
  const float3 fwd = (float3)(p->cam_forward[0], p->cam_forward[1], p->cam_forward[2]);
  o[SEASIM_LAYER_DEPTH] = hit ? layer_depth(g.x, d, fwd) : INFINITY;
#endif
#if SEASIM_LAYER_NORMAL >= 0
  o[SEASIM_LAYER_NORMAL + 0] = hit ? g.y : 0.0f;
  o[SEASIM_LAYER_NORMAL + 1] = hit ? g.z : 0.0f;
  o[SEASIM_LAYER_NORMAL + 2] = hit ? g.w : 0.0f;
#endif
#if SEASIM_LAYER_OBJECT_ID >= 0
  o[SEASIM_LAYER_OBJECT_ID] = (float)layer_object_id(mat);
#endif
#if SEASIM_LAYER_ALBEDO >= 0
  /* Objects and the bottom have an albedo row; water and the surface have none (0). */
  const int n = p->band_count;
  const int stride = UW_BAND_STRIDE(n);
  const int lambert = mat >= 0 || mat == UW_MAT_BOTTOM;
  __global const float* a = band_table + (mat >= 0 ? UW_ROWS + mat : UW_ROW_BOTTOM_ALBEDO) * stride;
  float aw_r = 0.0f, aw_g = 0.0f, aw_b = 0.0f, w_r = 0.0f, w_g = 0.0f, w_b = 0.0f;
  for (int i = 0; i < n; ++i) {
    const float albedo = lambert ? a[i] : 0.0f;
#if SEASIM_LAYER_ALBEDO_BANDS
    albedo_bands[(size_t)pixel * n + i] = albedo;
#endif
    const float wr = band_table[UW_ROW_W_R * stride + i], wg = band_table[UW_ROW_W_G * stride + i],
                wb = band_table[UW_ROW_W_B * stride + i];
    aw_r += albedo * wr;
    aw_g += albedo * wg;
    aw_b += albedo * wb;
    w_r += wr;
    w_g += wg;
    w_b += wb;
  }
  o[SEASIM_LAYER_ALBEDO + 0] = layer_weighted_mean(aw_r, w_r);
  o[SEASIM_LAYER_ALBEDO + 1] = layer_weighted_mean(aw_g, w_g);
  o[SEASIM_LAYER_ALBEDO + 2] = layer_weighted_mean(aw_b, w_b);
#endif
}
