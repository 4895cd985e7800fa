/* sand_share.cl — the discrete-ordinates model's shares that the objects leave a view ray: of the sunlit and of
 * the diffusely lit sand's light (common/underwater_ordinates.h, uwi_view_sand_shares) and of the light from
 * above in its in-scatter (uwi_view_above_share), on a lattice of every `step`-th pixel in x and y, the pixel
 * (i step, j step) at map[k map_w map_h + j map_w + i], plane k = 0, 1, 2 (clamped to the image's last row
 * and column).
 * kd_multiple.cl (SEASIM_SAND_SHARE_MAP) interpolates it to the pixels between, where the lattice's hits
 * lie at the pixel's own distance, and evaluates the rest itself: the share is smooth along a surface and
 * jumps at its silhouettes. Its rays (UWI_SAND_POINTS points x UWI_SAND_RAYS rays, their shadow rays and
 * the diffuse share's up-rays; UWI_ABOVE_POINTS x UWI_ABOVE_RAYS up-rays; against every object) are the model's fixed cost per pixel; a lattice of step 2 pays about a
 * quarter of it (results/BENCHMARKS.md).
 *
 * Each work-item evaluates UW_SAND_SHARE_PIXELS lattice pixels of a row in lanes
 * (common/underwater_ordinates_lanes.h): PoCL does not vectorise the scalar form across work-items (its loops
 * over rays and objects are control flow). The host launches ceil(map_w / UW_SAND_SHARE_PIXELS) x map_h.
 *
 * Inputs: UwParams, the band table (the first band's c', k, albedos), the objects, raycast.cl's G-buffer
 * distances (geom.x). Output: map[3 * map_w * map_h].
 */
#include "common/compat.h"
#include "common/optics.h"
#include "common/shafts.h"
#include "common/underwater_params.h"
#include "common/underwater.h"
#include "common/underwater_band_table.h"
#include "common/underwater_ordinates_params.h"
#include "common/underwater_ordinates.h"
#define SEASIM_BAND_LANES UW_SAND_SHARE_PIXELS /* pixel lanes, not bands: the lanes' types and macros */
#include "common/band_lanes.h"
#include "common/underwater_hit_lanes.h"
#include "common/underwater_ordinates_lanes.h"

__kernel void sand_share(__constant UwParams* p, __global const float* band_table, __global const UwObject* objects,
                         __global const float4* geom, int step, int map_w, int map_h, __global float* map) {
  const int i0 = get_global_id(0) * UW_SAND_SHARE_PIXELS, j = get_global_id(1);
  if (i0 >= map_w || j >= map_h) return;
  const int y = min(j * step, p->height - 1);
  /* The lanes' pixels (i step, y), clamped to the last column as the lattice is; lanes past the lattice's end
   * repeat its last pixel and are not written. */
  float S_l[UW_SAND_SHARE_PIXELS] __attribute__((aligned(4 * UW_SAND_SHARE_PIXELS)));
  float x_l[UW_SAND_SHARE_PIXELS] __attribute__((aligned(4 * UW_SAND_SHARE_PIXELS)));
  for (int q = 0; q < UW_SAND_SHARE_PIXELS; ++q) {
    const int x = min(min(i0 + q, map_w - 1) * step, p->width - 1);
    x_l[q] = x + 0.5f;
    S_l[q] = geom[y * p->width + x].x;
  }
  const real3b d = uw_screen_dir_b(p, *(realb*)x_l / (float)p->width, (y + 0.5f) / p->height);
  const realb S = *(realb*)S_l;
  const int stride = UW_BAND_STRIDE(p->band_count);
  realb v_diffuse;
  float sand[UW_SAND_SHARE_PIXELS] __attribute__((aligned(4 * UW_SAND_SHARE_PIXELS)));
  float diffuse[UW_SAND_SHARE_PIXELS] __attribute__((aligned(4 * UW_SAND_SHARE_PIXELS)));
  float above[UW_SAND_SHARE_PIXELS] __attribute__((aligned(4 * UW_SAND_SHARE_PIXELS)));
  *(realb*)sand = uwi_view_sand_shares_b(p, objects, band_table, stride, d, S, &v_diffuse);
  *(realb*)diffuse = v_diffuse;
  *(realb*)above = uwi_view_above_share_b(p, objects, band_table, stride, d, S);
  const int plane = map_w * map_h;
  for (int q = 0; q < min(UW_SAND_SHARE_PIXELS, map_w - i0); ++q) {
    const int i = i0 + q;
    map[j * map_w + i] = sand[q];
    map[plane + j * map_w + i] = diffuse[q];
    map[2 * plane + j * map_w + i] = above[q];
  }
}
