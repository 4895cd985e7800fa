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

__kernel void sand_share(__constant UwParams* p, __global const float* band_table, __global const UwObject* objects,
                         __global const float4* geom, int step, int map_w, int map_h, __global float* map) {
  const int i = get_global_id(0), j = get_global_id(1);
  if (i >= map_w || j >= map_h) return;
  const int x = min(i * step, p->width - 1), y = min(j * step, p->height - 1);
  const float3 d = uw_screen_dir(p, (x + 0.5f) / p->width, (y + 0.5f) / p->height);
  const int stride = UW_BAND_STRIDE(p->band_count);
  const float S = geom[y * p->width + x].x;
  float v_diffuse;
  const int plane = map_w * map_h;
  map[j * map_w + i] = uwi_view_sand_shares(p, objects, band_table, stride, d, S, &v_diffuse);
  map[plane + j * map_w + i] = v_diffuse;
  map[2 * plane + j * map_w + i] = uwi_view_above_share(p, objects, band_table, stride, d, S);
}
