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
 */
#include "common/compat.h"
#include "common/optics.h"
#include "common/shafts.h"
#include "common/underwater_params.h"
#include "common/underwater.h"
#if SEASIM_CAUSTICS == 1
#include "common/caustic_texture.h"
#endif
#if SEASIM_CAUSTICS == 2
#include "common/caustic_map.h"
#endif

__kernel void raycast(__constant UwParams* p, __global const UwObject* objects, __global const float* caustic_maps,
                      __global float4* geom, __global int* material, __global float* sun_vis) {
  const int x = get_global_id(0);
  const int y = get_global_id(1);
  if (x >= p->width || y >= p->height) return;
  const int pixel = y * p->width + x;

  const float3 o = (float3)(p->cam_pos[0], p->cam_pos[1], p->cam_pos[2]);
  const float3 d = uw_screen_dir(p, (x + 0.5f) / p->width, (y + 0.5f) / p->height);

#if SEASIM_HAS_OBJECTS
  const int count = p->object_count;
#else
  const int count = 0;
#endif
  float3 n;
  int mat;
  const float S = uw_scene_hit(objects, count, p->bottom_depth, o, d, 0.0f, &n, &mat);

  float vis = 0.0f;
#if SEASIM_HAS_SUN
  if (mat >= 0 || mat == UW_MAT_BOTTOM) {
    const float3 s_w = (float3)(p->sun_dir_water[0], p->sun_dir_water[1], p->sun_dir_water[2]);
    const float3 hit = o + S * d;
    vis = 1.0f;
#if SEASIM_HAS_OBJECTS
    vis = uw_sun_visibility(objects, count, hit, n, s_w);
#endif
#if SEASIM_CAUSTICS == 1
    /* Where the refracted sun ray through this point crossed the surface. */
    const float t_up = -hit.y / s_w.y;
    vis *= caustic_modulation(hit.x + t_up * s_w.x, hit.z + t_up * s_w.z, p->time, p->caustic_period,
                              p->caustic_speed);
#endif
#if SEASIM_CAUSTICS == 2
    /* The maps were splatted along the refracted rays already: read them where the point is. */
    vis *= caustic_map_sample(caustic_maps, p->caustic_map_size, p->caustic_layers, p->caustic_extent,
                              p->caustic_depth_max, hit.x, -hit.y, hit.z);
#endif
  }
#endif
  geom[pixel] = (float4)(S, n.x, n.y, n.z);
  material[pixel] = mat;
  sun_vis[pixel] = vis;
}
