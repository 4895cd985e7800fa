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
#include "common/optics.h"
#include "common/fourflow_params.h"
#include "common/fourflow.h"

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

/* The real-time path: bilinear table lookup and the blend of eq. 22 per pixel. */
__kernel void ff_table_blend(__constant FfParams* p, __global const float* table, __global const float* path_l,
                             __global const float* depth_h, __global const float* tex, __global float* out_rgb, int n) {
  const int i = get_global_id(0);
  if (i >= n) return;
  real rgb[3];
  ff_table_rgb(*p, table, path_l[i], depth_h[i], tex[i], rgb);
  vstore3((float3)(rgb[0], rgb[1], rgb[2]), i, out_rgb);
}
