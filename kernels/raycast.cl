/* raycast.cl — the underwater G-buffer (002 §4.3.2: deferred shading): per pixel, the first hit of the
 * view ray among the analytic objects, the flat bottom and the water surface (common/underwater.h
 * uw_scene_hit), and the direct sun's visibility at that point (an exact shadow ray along the refracted
 * sun direction to the surface, times the caustic modulation when caustics are on).
 *
 * Inputs: UwParams, UwObject[object_count], caustic_maps (SEASIM_CAUSTICS == 2: common/caustic_map.h;
 * otherwise unused, one float). Outputs per pixel: geom = (S, n.x, n.y, n.z) with S the hit
 * distance in m (>= UW_INFINITE: deep water), material (object index or UW_MAT_*), sun_vis in [0, ∞)
 * (0 in shadow; caustics redistribute light, so > 1 occurs).
 * Defines (host/plan): SEASIM_HAS_OBJECTS, SEASIM_HAS_SUN (shadow rays are needed only with a sun),
 * SEASIM_CAUSTICS (UW_CAUSTICS_*).
 * Each work-item casts UW_RAYCAST_PIXELS pixels of a row in lanes (common/underwater_hit_lanes.h): PoCL does
 * not vectorise the scalar cast across work-items, and this is most of the frame's cost that does not
 * depend on the band count. The host launches ceil(width / UW_RAYCAST_PIXELS) x height work-items. The caustic
 * texture is read in the same lanes (common/caustic_texture_lanes.h); the caustic maps' reads stay per lane.
 */
#include "common/compat.h"
#include "common/optics.h"
#include "common/shafts.h"
#include "common/underwater_params.h"
#include "common/underwater.h"
#define SEASIM_BAND_LANES UW_RAYCAST_PIXELS /* pixel lanes, not bands: the lanes' types and macros */
#include "common/band_lanes.h"
#include "common/underwater_hit_lanes.h"
#if SEASIM_CAUSTICS == 1
#include "common/caustic_texture.h"
#include "common/caustic_texture_lanes.h"
#endif
#if SEASIM_CAUSTICS == 2
#include "common/caustic_map.h"
#endif

__kernel void raycast(__constant UwParams* p, __global const UwObject* objects, __global const float* caustic_maps,
                      __global float4* geom, __global int* material, __global float* sun_vis) {
  const int x0 = get_global_id(0) * UW_RAYCAST_PIXELS;
  const int y = get_global_id(1);
  if (x0 >= p->width || y >= p->height) return;

  /* The view directions of the row's pixels x0 .. x0 + UW_RAYCAST_PIXELS - 1. */
  const real3b d = uw_screen_dir_b(p, (lane_offsets() + ((float)x0 + 0.5f)) / (float)p->width, (y + 0.5f) / p->height);
  const real3b o_b = uw_splat3b((float3)(p->cam_pos[0], p->cam_pos[1], p->cam_pos[2]));

#if SEASIM_HAS_OBJECTS
  const int count = p->object_count;
#else
  const int count = 0;
#endif
  real3b n;
  realb mat;
  const realb S = uw_scene_hit_b(objects, count, p->bottom_depth, o_b, d, SPLATB(0.0f), &n, &mat);

  realb vis = SPLATB(0.0f);
#if SEASIM_HAS_SUN
  const float3 s_w = (float3)(p->sun_dir_water[0], p->sun_dir_water[1], p->sun_dir_water[2]);
  const real3b hit = uw_along3b(o_b, S, d);
  const maskb lit = (mat >= 0.0f) | (mat == (float)UW_MAT_BOTTOM);
#if SEASIM_HAS_OBJECTS
  vis = SELECTB(lit, uw_sun_visibility_b(objects, count, hit, n, s_w), vis);
#else
  vis = SELECTB(lit, SPLATB(1.0f), vis);
#endif
#if SEASIM_CAUSTICS == 1
  /* The caustic texture where the refracted sun ray through each lit hit crossed the surface, in the lanes. */
  const maskb sunlit = vis > 0.0f;
  if (ANYB(sunlit)) {
    const realb t_up = -hit.y / s_w.y;
    const realb m = caustic_modulation_b(hit.x + t_up * s_w.x, hit.z + t_up * s_w.z, p->time, p->caustic_period,
                                         p->caustic_speed);
    vis = SELECTB(sunlit, vis * m, vis);
  }
#endif
#endif

  /* The lanes out to the row, the pixels past its end left alone. */
  float S_l[UW_RAYCAST_PIXELS] __attribute__((aligned(4 * UW_RAYCAST_PIXELS)));
  float nx[UW_RAYCAST_PIXELS] __attribute__((aligned(4 * UW_RAYCAST_PIXELS)));
  float ny[UW_RAYCAST_PIXELS] __attribute__((aligned(4 * UW_RAYCAST_PIXELS)));
  float nz[UW_RAYCAST_PIXELS] __attribute__((aligned(4 * UW_RAYCAST_PIXELS)));
  float m_l[UW_RAYCAST_PIXELS] __attribute__((aligned(4 * UW_RAYCAST_PIXELS)));
  float v_l[UW_RAYCAST_PIXELS] __attribute__((aligned(4 * UW_RAYCAST_PIXELS)));
  *(realb*)S_l = S;
  *(realb*)nx = n.x;
  *(realb*)ny = n.y;
  *(realb*)nz = n.z;
  *(realb*)m_l = mat;
  *(realb*)v_l = vis;
  const int count_x = min(UW_RAYCAST_PIXELS, p->width - x0);
  for (int q = 0; q < count_x; ++q) {
    const int pixel = y * p->width + x0 + q;
    float vq = v_l[q];
#if SEASIM_HAS_SUN && SEASIM_CAUSTICS == 2
    if (vq > 0.0f) {
      /* The maps were splatted along the refracted rays already: read them where the lane's hit is. */
      const float3 hq = (float3)(((const float*)&hit.x)[q], ((const float*)&hit.y)[q], ((const float*)&hit.z)[q]);
      vq *= caustic_map_sample(caustic_maps, p->caustic_map_size, p->caustic_layers, p->caustic_extent,
                               p->caustic_depth_max, hq.x, -hq.y, hq.z);
    }
#endif
    geom[pixel] = (float4)(S_l[q], nx[q], ny[q], nz[q]);
    material[pixel] = (int)m_l[q];
    sun_vis[pixel] = vq;
  }
}
