/* whitecaps.cl — sea-surface foam over the sea seen from above: where the FFT ocean's Jacobian
 * (004 §3.7, eq. 30) falls below the threshold that makes the foam cover Monahan &
 * O'Muircheartaigh's (1980) whitecap fraction, a Lambertian layer of Koepke's (1984) effective
 * reflectance is composited over the sea's radiance (common/whitecaps.h derives each step).
 *
 * Inputs: WhitecapsParams (camera, image and tile sizes, the foam's radiance in sensor RGB); the
 * ocean's Jacobian map (N x N floats, texel (i, j) at x = iL/N, z = jL/N); the threshold J_th (the
 * W-quantile of that map, from the host) and rank_j[WHITECAPS_RANK_NODES], J at evenly spaced ranks
 * among the foam texels (the foam's age, common/whitecaps.h); foam_bands[band_count], the foam's radiance per band, W m^-2
 * sr^-1 nm^-1 (SEASIM_SPECTRAL_OUTPUT).
 * Outputs: mips, the foam's opacity and its mip chain (whitecaps_level_offset); rgb[3 * pixels] and, with
 * SEASIM_SPECTRAL_OUTPUT, spectral[band_count * pixels], the sea's radiance, updated in place.
 * Three kernels, run in this order: whitecaps_mask_texels (level 0), whitecaps_downsample once per
 * further level, whitecaps_over_sea per pixel.
 * Stiff cases (common/whitecaps.h): no wind leaves the image bit for bit; rays at or above the
 * horizon are untouched; grazing rays read the top level; f in [0, 1] keeps every value finite. */
#include "common/compat.h"
#include "common/whitecaps_params.h"
#include "common/whitecaps.h"

#ifndef SEASIM_SPECTRAL_OUTPUT
#define SEASIM_SPECTRAL_OUTPUT 0
#endif

/* Level 0: the foam's opacity at each texel of the Jacobian map. */
__kernel void whitecaps_mask_texels(__constant WhitecapsParams* p, __global const float* jacobian, float threshold,
                                    __global const float* rank_j, __global float* mips) {
  const int i = get_global_id(0), j = get_global_id(1);
  const int n = p->ocean_n;
  if (i >= n || j >= n) return;
  mips[j * n + i] = whitecaps_mask(jacobian[j * n + i], threshold, rank_j);
}

/* Level `level` + 1 from level `level`: the mean of each 2 x 2 block. */
__kernel void whitecaps_downsample(__constant WhitecapsParams* p, __global float* mips, int level) {
  const int i = get_global_id(0), j = get_global_id(1);
  const int n = p->ocean_n;
  const int nl = n >> level, m = nl >> 1;
  if (i >= m || j >= m) return;
  __global const float* src = mips + whitecaps_level_offset(n, level);
  __global float* dst = mips + whitecaps_level_offset(n, level + 1);
  dst[j * m + i] = whitecaps_box(src[2 * j * nl + 2 * i], src[2 * j * nl + 2 * i + 1], src[(2 * j + 1) * nl + 2 * i],
                                 src[(2 * j + 1) * nl + 2 * i + 1]);
}

/* L = L_sea + f (L_f - L_sea) per pixel, f the foam fraction of the pixel's footprint on the sea. */
__kernel void whitecaps_over_sea(__constant WhitecapsParams* p, __global const float* mips,
                                 __global const float* foam_bands, __global float* rgb, __global float* spectral) {
  const int x = get_global_id(0), y = get_global_id(1);
  if (x >= p->width || y >= p->height) return;
  float hx, hz, dir_x, dir_z, minor, major;
  if (!whitecaps_pixel_footprint(p, x, y, &hx, &hz, &dir_x, &dir_z, &minor, &major)) return;
  const float f = whitecaps_footprint(mips, p->ocean_n, p->ocean_patch, hx, hz, dir_x, dir_z, minor, major);
  const size_t pixel = (size_t)y * (size_t)p->width + (size_t)x;
  for (int c = 0; c < 3; ++c) rgb[3 * pixel + c] = whitecaps_composite(rgb[3 * pixel + c], f, p->foam_rgb[c]);
#if SEASIM_SPECTRAL_OUTPUT
  __global float* bands = spectral + pixel * (size_t)p->band_count;
  for (int i = 0; i < p->band_count; ++i) bands[i] = whitecaps_composite(bands[i], f, foam_bands[i]);
#endif
}
