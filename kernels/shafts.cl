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
 * `occluders`), SEASIM_SHAFTS_EXACT (g evaluated exactly, else from the 1-D and 2-D tables of eq. 6),
 * SEASIM_SHAFTS_HG (Henyey–Greenstein phase), SEASIM_HAS_OBJECTS, SEASIM_HAS_LIGHT_MAP.
 * Stiff cases: see common/shafts.h (s -> 0, ρκ = 0 and large, grazing planes); rays that hit
 * nothing have T = ∞ and no I_o term (so ρκ = 0 never forms 0·∞).
 */
#include "common/compat.h"
#include "common/optics.h"
#include "common/shafts.h"
#include "common/shafts_intervals.h"
#include "common/shafts_params.h"

#define SHAFTS_NO_HIT 1e30f

/* float[4] of any address space -> float3 */
#define v3(a) ((float3)((a)[0], (a)[1], (a)[2]))

/* First hit of the ray o + t d, t in (t_min, t_max); writes the normal (facing the ray) and the
 * object's index. Returns t or -1. */
static inline float scene_hit(__global const ShaftsObject* objects, int count, float3 o, float3 d, float t_min,
                              float t_max, float3* normal, int* which) {
  float best = t_max;
  int hit = -1;
  float3 nrm = (float3)(0.0f, 1.0f, 0.0f);
  for (int k = 0; k < count; ++k) {
    __global const ShaftsObject* ob = &objects[k];
    float t = -1.0f;
    int axis = 0;
    if (ob->type == SHAFTS_SPHERE) {
      t = ray_sphere(o, d, v3(ob->a), ob->a[3], t_min, best);
      if (t > 0.0f) nrm = normalize(o + t * d - v3(ob->a));
    } else if (ob->type == SHAFTS_BOX) {
      t = ray_box(o, d, v3(ob->a), v3(ob->b), t_min, best, &axis);
      if (t > 0.0f) nrm = box_normal(o + t * d, v3(ob->a), v3(ob->b), axis);
    } else {
      t = ray_plane(o, d, v3(ob->a), v3(ob->b), t_min, best);
      if (t > 0.0f) nrm = v3(ob->b);
    }
    if (t > 0.0f) {
      best = t;
      hit = k;
      if (normal) *normal = nrm;
    }
  }
  if (which) *which = hit;
  if (normal && hit >= 0 && dot(*normal, d) > 0.0f) *normal = -*normal;
  return hit >= 0 ? best : -1.0f;
}

/* Light-frame coordinates of a point: x, y across the beam, z along it. */
static inline float3 to_light(__global const ShaftsLight* L, float3 p) {
  float3 q = p - v3(L->position);
  return (float3)(dot(q, v3(L->right)), dot(q, v3(L->up)), dot(q, v3(L->direction)));
}

/* I_l towards a point with light-frame coordinates q at distance s, per R,G,B (W/sr). */
static inline float3 lamp_emission(__global const ShaftsLight* L, __global const float* light_maps, float3 q, float s) {
  if (q.z <= 0.0f || s <= 0.0f) return (float3)(0.0f);
  const float profile = shafts_cone_profile(q.z / s, L->cos_cone, L->cos_inner);
  if (profile <= 0.0f) return (float3)(0.0f);
  float3 e = v3(L->color) * profile;
#if SEASIM_HAS_LIGHT_MAP
  if (L->light_map_offset >= 0) {
    /* Projective texture (001 §4.2): the map covers [-tan_cone, tan_cone]² at unit distance,
     * top row towards the light's +up. Bilinear between texel centres, clamped at the border. */
    const float inv = 1.0f / (q.z * L->tan_cone);
    const float fu = (0.5f * (q.x * inv + 1.0f)) * L->light_map_width - 0.5f;
    const float fv = (0.5f * (1.0f - q.y * inv)) * L->light_map_height - 0.5f;
    const int w = L->light_map_width, h = L->light_map_height;
    const float cu = clamp(fu, 0.0f, (float)(w - 1)), cv = clamp(fv, 0.0f, (float)(h - 1));
    const int x0 = min((int)cu, w - 1), y0 = min((int)cv, h - 1);
    const int x1 = min(x0 + 1, w - 1), y1 = min(y0 + 1, h - 1);
    const float ax = cu - x0, ay = cv - y0;
    __global const float* m = light_maps + L->light_map_offset;
    float3 t00 = vload3(y0 * w + x0, m), t10 = vload3(y0 * w + x1, m);
    float3 t01 = vload3(y1 * w + x0, m), t11 = vload3(y1 * w + x1, m);
    e *= mix(mix(t00, t10, ax), mix(t01, t11, ax), ay);
  }
#endif
  return e;
}

/* H: 1 when the point (light frame q, distance s) is nearer the lamp than the shadow map's depth. */
static inline float shadow_term(__global const ShaftsLight* L, __global const float* shadow, int size, float3 q, float s) {
#if SEASIM_HAS_OBJECTS
  const float inv = 1.0f / (q.z * L->tan_cone);
  const int ix = clamp((int)(0.5f * (q.x * inv + 1.0f) * size), 0, size - 1);
  const int iy = clamp((int)(0.5f * (q.y * inv + 1.0f) * size), 0, size - 1);
  const float depth = shadow[L->shadow_offset + iy * size + ix];
  return s < depth ? 1.0f : 0.0f;
#else
  return 1.0f;
#endif
}

__kernel void shafts_shadow_map(__constant ShaftsParams* p, __global const ShaftsLight* lights,
                                __global const ShaftsObject* objects, __global float* shadow) {
  const int x = get_global_id(0), y = get_global_id(1), l = get_global_id(2);
  const int size = p->shadow_map_size;
  if (x >= size || y >= size || l >= p->light_count) return;
  __global const ShaftsLight* L = &lights[l];
  const float a = ((x + 0.5f) / size * 2.0f - 1.0f) * L->tan_cone;
  const float b = ((y + 0.5f) / size * 2.0f - 1.0f) * L->tan_cone;
  const float3 d = normalize(v3(L->direction) + a * v3(L->right) + b * v3(L->up));
  const float t = scene_hit(objects, p->object_count, v3(L->position), d, 0.0f, SHAFTS_NO_HIT, 0, 0);
  shadow[L->shadow_offset + y * size + x] = t > 0.0f ? t : SHAFTS_NO_HIT;
}

#if !SEASIM_SHAFTS_EXACT
/* Linear interpolation in the 1-D F table over α ∈ [0, π] (001 eq. 6). */
static inline float phase_table(__global const float* F, int n, float cos_alpha) {
  const float x = acos(clamp(cos_alpha, -1.0f, 1.0f)) * (float)(n - 1) / M_PI_F;
  const int i = min((int)x, n - 2);
  const float f = x - i;
  return mix(F[i], F[i + 1], f);
}
/* Bilinear interpolation in the 2-D table of ĥ = s² h over (s, t). */
static inline float h_table(__global const float* H, int n, float s_max, float t_max, float s, float t) {
  const float xs = clamp(s / s_max, 0.0f, 1.0f) * (n - 1), xt = clamp(t / t_max, 0.0f, 1.0f) * (n - 1);
  const int i = min((int)xs, n - 2), j = min((int)xt, n - 2);
  const float fs = xs - i, ft = xt - j;
  const float a = mix(H[j * n + i], H[j * n + i + 1], fs), b = mix(H[(j + 1) * n + i], H[(j + 1) * n + i + 1], fs);
  return mix(a, b, ft);
}
#endif

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
  const float T = scene_hit(objects, p->object_count, eye, d, 0.0f, SHAFTS_NO_HIT, &n, &which);
  if (T > 0.0f) {
    /* I_o: Lambertian surface under each spotlight, exact shadow ray, Beer–Lambert lamp -> surface. */
    const float3 P = eye + T * d;
    const float3 albedo = v3(objects[which].albedo);
    float3 Io = (float3)(0.0f);
    for (int l = 0; l < p->light_count; ++l) {
      __global const ShaftsLight* L = &lights[l];
      const float3 to_lamp = v3(L->position) - P;
      const float s = length(to_lamp);
      const float3 wl = to_lamp / fmax(s, 1e-20f);
      const float cos_n = dot(n, wl);
      if (cos_n <= 0.0f) continue;
      const float3 e = lamp_emission(L, light_maps, to_light(L, P), s);
      if (e.x + e.y + e.z <= 0.0f) continue;
      const float eps = 1e-4f * fmax(1.0f, T);
      if (scene_hit(objects, p->object_count, P + eps * n, wl, 0.0f, s - 2.0f * eps, 0, 0) > 0.0f) continue;
      const float sc = fmax(s, p->s_min);
      Io += e * (cos_n * exp(-p->sigma_t * s) / (sc * sc));
    }
    result = Io * (albedo * (1.0f / M_PI_F)) * exp(-p->sigma_t * T); /* 001 eq. 1, first term */
    t_end = T;
  }
#endif

#if SEASIM_SHAFTS_INTERVALS
  /* I_s, lamp by lamp, over the lit stretches of the ray inside the lamp's cone (common/shafts_intervals.h):
   * the cone's part up to the first surface, minus each object's shadow interval, integrated in the
   * lamp's angle with the far-field closed form beyond K r. */
  for (int l = 0; l < p->light_count; ++l) {
    __global const ShaftsLight* Lg = &lights[l];
    ShaftsLamp L;
    L.pos = v3(Lg->position);
    L.axis = v3(Lg->direction);
    L.right = v3(Lg->right);
    L.up = v3(Lg->up);
    L.cos_cone = Lg->cos_cone;
    L.cos_inner = Lg->cos_inner;
    L.tan_cone = Lg->tan_cone;
    L.map_w = 0;
    L.map_h = 0;
#if SEASIM_HAS_LIGHT_MAP
    if (Lg->light_map_offset >= 0) {
      L.map_w = Lg->light_map_width;
      L.map_h = Lg->light_map_height;
    }
#endif
    float lo[SHAFTS_MAX_PIECES], hi[SHAFTS_MAX_PIECES];
    if (!shafts_cone_interval(eye, d, L.pos, L.axis, L.cos_cone, &lo[0], &hi[0])) continue;
    hi[0] = fmin(hi[0], t_end);
    if (!(hi[0] > lo[0])) continue;
    int n = 1;
#if SEASIM_HAS_OBJECTS
    for (int k = 0; k < p->object_count && n > 0; ++k) {
      __global const ShaftsOccluder* oc = &occluders[l * p->object_count + k];
      float s0 = lo[0], s1 = hi[n - 1]; /* the shadow matters only where the ray is lit */
      if (shafts_shadow_interval_packed(oc->planes, oc->plane_count, oc->has_cone, oc->always, v3(oc->apex),
                                        v3(oc->axis), oc->axis[3], eye, d, &s0, &s1))
        n = shafts_pieces_subtract(lo, hi, n, s0, s1);
    }
#endif
    if (n == 0) continue;
    float ti0 = 0.0f, ti1 = 0.0f;
    const int has_inner = shafts_cone_interval(eye, d, L.pos, L.axis, L.cos_inner, &ti0, &ti1);
    __global const float* map = light_maps + max(Lg->light_map_offset, 0);
    result += v3(Lg->color) * shafts_interval_airlight(lo, hi, n, has_inner, ti0, ti1, eye, d, L, map, p->rho,
                                                       p->sigma_t, p->s_min, SEASIM_SHAFTS_HG, p->hg_g, p->panel_rad,
                                                       p->map_panel_texels);
  }
#else
  /* I_s, lamp by lamp, over the exact part of the view ray inside the lamp's cone, from the camera to
   * the first surface or to infinity (no near or far cut). n sampling intervals (001 eq. 5) with m
   * sub-samples each (001 eq. 7–9) cover it up to K r past the closest approach to the lamp; beyond,
   * the closed-form far field (common/shafts.h, shafts_tail_from) with H I_l averaged over m
   * directions spread evenly in the angle the lamp sees, and F at the middle one. */
  const int n_planes = p->planes, m = p->subplanes;
  for (int l = 0; l < p->light_count; ++l) {
    __global const ShaftsLight* L = &lights[l];
    const float3 lamp = v3(L->position);
    float ta, tb;
    if (!shafts_cone_interval(eye, d, lamp, v3(L->direction), L->cos_cone, &ta, &tb)) continue;
    tb = fmin(tb, t_end);
    if (!(tb > ta)) continue;
    float a, h;
    shafts_closest_approach(eye, d, lamp, &a, &h);
    const float r = fmax(h, p->s_min);
    const float tp = fmin(tb, fmax(ta, a + SHAFTS_TAIL_K * r)); /* planes on [ta, tp], far field on [tp, tb] */
    float3 acc = (float3)(0.0f);
    const float dt = (tp - ta) / n_planes;
    for (int i = 0; i < n_planes && dt > 0.0f; ++i) {
      const float za = ta + i * dt;
      /* J_i: average of H I_l over m sub-sample planes in the interval (001 eq. 9). */
      float3 J = (float3)(0.0f);
      const float dts = dt / m;
      for (int j = 0; j < m; ++j) {
        const float3 P = eye + (za + (j + 0.5f) * dts) * d;
        const float3 q = to_light(L, P);
        const float s = length(P - lamp);
        const float3 e = lamp_emission(L, light_maps, q, s);
        if (e.x + e.y + e.z > 0.0f) J += e * shadow_term(L, shadow, p->shadow_map_size, q, s);
      }
      if (J.x + J.y + J.z <= 0.0f) continue;
      J *= 1.0f / m;
      /* g at the plane (the interval's midpoint): 001 eq. 3, 6. */
      const float t = za + 0.5f * dt;
      const float3 w = eye + t * d - lamp;
      const float s = length(w);
      const float cos_alpha = s > 0.0f ? dot(w, -d) / s : 1.0f;
#if SEASIM_SHAFTS_EXACT
      const float g = shafts_phase_fn(cos_alpha, SEASIM_SHAFTS_HG, p->hg_g) * shafts_h(s, t, p->rho, p->sigma_t, p->s_min);
#else
      const float sc = fmax(s, p->s_min);
      const float g = phase_table(F_table, p->table_size, cos_alpha) *
                      h_table(h_tab, p->table_size, p->table_s_max, p->table_t_max, s, t) / (sc * sc);
#endif
      acc += J * (g * dt);
    }
    if (tb > tp) {
      /* Far field: x = t - a >= K r. The lamp sees [tp, tb] over the angles [phi_p, phi_b],
       * phi = atan(x / r); dt / s^2 is uniform in phi, so H I_l is averaged evenly in phi. */
      const int infinite = tb >= SHAFTS_T_INF;
      const float phi_p = atan((tp - a) / r), phi_b = infinite ? 0.5f * M_PI_F : atan((tb - a) / r);
      float3 J = (float3)(0.0f);
      for (int j = 0; j < m; ++j) {
        const float3 P = eye + (a + r * tan(phi_p + (j + 0.5f) * (phi_b - phi_p) / m)) * d;
        const float3 q = to_light(L, P);
        const float s = length(P - lamp);
        const float3 e = lamp_emission(L, light_maps, q, s);
        if (e.x + e.y + e.z > 0.0f) J += e * shadow_term(L, shadow, p->shadow_map_size, q, s);
      }
      if (J.x + J.y + J.z > 0.0f) {
        const float3 w = eye + (a + r * tan(0.5f * (phi_p + phi_b))) * d - lamp;
        const float cos_alpha = dot(w, -d) / length(w);
#if SEASIM_SHAFTS_EXACT
        const float F = shafts_phase_fn(cos_alpha, SEASIM_SHAFTS_HG, p->hg_g);
#else
        const float F = phase_table(F_table, p->table_size, cos_alpha);
#endif
        float tail = shafts_tail_from(tp - a, a, h, p->rho, p->sigma_t);
        if (!infinite) tail -= shafts_tail_from(tb - a, a, h, p->rho, p->sigma_t);
        acc += J * (F * fmax(tail, 0.0f) / m);
      }
    }
    result += acc;
  }
#endif
  vstore3(result, pixel, rgb);
}
