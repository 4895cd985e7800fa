/* shafts.cl — spotlight shafts of light in a uniform medium (paper 001), per pixel on the device.
 *
 *   I_v = I_o exp(-ρκT) + I_s                                        (001 eq. 1)
 *   I_s = ∫_0^T H(t) I_l(t) g(α, s, t) dt                             (001 eq. 2)
 *   g   = ρ F(α) exp(-ρκ(s + t)) / s²  = F(α) h(s, t)                 (001 eq. 3, 6)
 *   I_s ≈ Σ_i J_i g(α_i, s_i, t_i) Δt_i,  J_i = (1/m) Σ_j H(u_j) I_l(u_j) (001 eq. 5, 7–9)
 *
 * Per lamp, eq. 2 runs over the exact part of the view ray inside the lamp's cone, from the camera
 * to the first surface or to infinity. n sampling intervals, equal in t (and so in camera depth:
 * planes parallel to the screen within that part), cover it up to K r past the ray's closest
 * approach to the lamp (r: its distance); m sub-sample planes per interval average the shadow term
 * H (from the shadow map) times the lamp's emission I_l (projected light map, or the cone fall-off)
 * before multiplying by g, which varies slowly. Beyond K r the lamp sees the rest of the ray within
 * atan(1/K): there eq. 2 has a closed form in exponential integrals (common/shafts.h,
 * shafts_tail_from) with H I_l averaged over m directions and F taken in the middle one; exact for
 * a uniform cone and an isotropic phase function.
 * F is 001 eq. 4 normalised to ∫F dΩ = 1 (optics.h), or Henyey–Greenstein. ρ acts as the
 * scattering coefficient (1/m) and ρκ as the extinction coefficient. Light adds up per lamp.
 *
 * Kernels:
 *   shafts_shadow_map  one depth map per light: distance from the lamp to the first object along
 *                      each texel's ray, the texels spanning [-tan_cone, tan_cone]² in the light's
 *                      projective plane (x/z, y/z); 1e30 where nothing is hit.
 *   shafts_render      per pixel: ray cast of the analytic objects (sphere, box, plane), I_o by
 *                      Lambertian shading under every spotlight with exact shadow rays, then I_s.
 * Inputs: ShaftsParams, ShaftsLight[light_count], ShaftsObject[object_count], light maps (RGB
 * floats), F table [table_size] over α ∈ [0, π] and ĥ = s² h table [table_size²] over
 * (s, t) ∈ [0, s_max] × [0, t_max] (table mode). Output: rgb[3 * pixels], linear RGB radiance.
 * Defines: SEASIM_SHAFTS_INTERVALS (I_s integrated over the exact lit stretches of the ray,
 * common/shafts_intervals.h, with exact g and no shadow maps; the objects' shadow volumes come in
 * `occluders`), SEASIM_SHAFTS_MARCH (I_s by ShaftsParams.march_steps midpoint steps in the lamp's angle
 * with an exact shadow ray at each, common/shafts_render.h shafts_lamp_march), SEASIM_SHAFTS_EXACT (g evaluated exactly, else from the 1-D and 2-D tables of eq. 6),
 * SEASIM_SHAFTS_HG (Henyey–Greenstein phase), SEASIM_HAS_OBJECTS, SEASIM_HAS_LIGHT_MAP.
 * Stiff cases: see common/shafts.h (s -> 0, ρκ = 0 and large, grazing planes); rays that hit
 * nothing have T = ∞ and no I_o term (so ρκ = 0 never forms 0·∞).
 */
#include "common/compat.h"
#include "common/optics.h"
#include "common/shafts.h"
#include "common/shafts_intervals.h"
#include "common/shafts_params.h"
#include "common/shafts_render.h"

#define SHAFTS_NO_HIT 1e30f

/* float[4] of any address space -> float3 */
#define v3(a) ((float3)((a)[0], (a)[1], (a)[2]))

__kernel void shafts_shadow_map(__constant ShaftsParams* p, __global const ShaftsLight* lights,
                                __global const ShaftsObject* objects, __global float* shadow) {
  const int x = get_global_id(0), y = get_global_id(1), l = get_global_id(2);
  const int size = p->shadow_map_size;
  if (x >= size || y >= size || l >= p->light_count) return;
  __global const ShaftsLight* L = &lights[l];
  const float a = ((x + 0.5f) / size * 2.0f - 1.0f) * L->tan_cone;
  const float b = ((y + 0.5f) / size * 2.0f - 1.0f) * L->tan_cone;
  const float3 d = normalize(v3(L->direction) + a * v3(L->right) + b * v3(L->up));
  const float t = shafts_scene_hit(objects, p->object_count, v3(L->position), d, 0.0f, SHAFTS_NO_HIT, 0, 0);
  shadow[L->shadow_offset + y * size + x] = t > 0.0f ? t : SHAFTS_NO_HIT;
}

#ifndef SEASIM_SHAFTS_INTERVALS
#define SEASIM_SHAFTS_INTERVALS 0
#endif
#ifndef SEASIM_SHAFTS_MARCH
#define SEASIM_SHAFTS_MARCH 0
#endif
#ifndef SEASIM_SHAFTS_EXACT
#define SEASIM_SHAFTS_EXACT 0
#endif
#ifndef SEASIM_SHAFTS_HG
#define SEASIM_SHAFTS_HG 0
#endif
#ifndef SEASIM_HAS_OBJECTS
#define SEASIM_HAS_OBJECTS 0
#endif
#ifndef SEASIM_HAS_LIGHT_MAP
#define SEASIM_HAS_LIGHT_MAP 0
#endif

/* Per pixel: the eye ray, I_o at the first surface (common/shafts_render.h, shafts_surface_radiance),
 * then I_s lamp by lamp (shafts_lamp_intervals, shafts_lamp_march or shafts_lamp_planes) up to that surface. */
__kernel void shafts_render(__constant ShaftsParams* p, __global const ShaftsLight* lights,
                            __global const ShaftsObject* objects, __global const float* shadow,
                            __global const float* light_maps, __global const float* F_table,
                            __global const float* h_tab, __global const ShaftsOccluder* occluders,
                            __global float* rgb) {
  const int x = get_global_id(0), y = get_global_id(1);
  if (x >= p->width || y >= p->height) return;
  const int pixel = y * p->width + x;

  const float u = (2.0f * (x + 0.5f) / p->width - 1.0f) * p->tan_half_fov_y * p->aspect;
  const float v = (1.0f - 2.0f * (y + 0.5f) / p->height) * p->tan_half_fov_y;
  const float3 eye = v3(p->cam_pos), fwd = v3(p->cam_forward);
  const float3 d = normalize(fwd + u * v3(p->cam_right) + v * v3(p->cam_up));

  float3 result = (float3)(0.0f);
  float t_end = SHAFTS_T_INF; /* the first surface on the ray, or none */
#if SEASIM_HAS_OBJECTS
  float3 n;
  int which;
  const float T = shafts_scene_hit(objects, p->object_count, eye, d, 0.0f, SHAFTS_NO_HIT, &n, &which);
  if (T > 0.0f) {
    result = shafts_surface_radiance(SEASIM_HAS_LIGHT_MAP, p, lights, objects, light_maps, eye, d, T, n, which);
    t_end = T;
  }
#endif
  for (int l = 0; l < p->light_count; ++l) {
#if SEASIM_SHAFTS_INTERVALS
    result += shafts_lamp_intervals(SEASIM_HAS_OBJECTS, SEASIM_HAS_LIGHT_MAP, SEASIM_SHAFTS_HG, p, &lights[l], l,
                                    occluders, light_maps, eye, d, t_end);
#elif SEASIM_SHAFTS_MARCH
    result += shafts_lamp_march(SEASIM_HAS_OBJECTS, SEASIM_HAS_LIGHT_MAP, SEASIM_SHAFTS_HG, p, &lights[l], objects,
                                light_maps, eye, d, t_end, p->march_steps);
#else
    result += shafts_lamp_planes(SEASIM_HAS_OBJECTS, SEASIM_HAS_LIGHT_MAP, SEASIM_SHAFTS_EXACT, SEASIM_SHAFTS_HG, p,
                                 &lights[l], shadow, light_maps, F_table, h_tab, eye, d, t_end);
#endif
  }
  vstore3(result, pixel, rgb);
}
