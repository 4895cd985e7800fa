/* shafts_render.h — the terms of kernels/shafts.cl's shafts_render, per pixel (the method and paper
 * 001's equations are in shafts.cl's header comment): the first hit of the analytic objects, the
 * lamp's emission and shadow term, the F and ĥ tables, the surface's I_o under every spotlight, and
 * one lamp's I_s, either over sampling planes with the far-field tail (001 eq. 5–9) or over the exact
 * lit stretches of the ray (common/shafts_intervals.h). The kernel's compile-time choices arrive as
 * int arguments (constants there, so the compiler drops the branches not taken). The operations are
 * those of the kernel's former single body, in the same order, so the images are unchanged.
 * tests/unit/shafts_render_test.cpp holds these in float and double; tests/kernels/shafts_test.cpp
 * the kernel to the double CPU reference.
 * Needs compat.h, optics.h, shafts.h, shafts_intervals.h, shafts_params.h. */

/* float[4] of any address space -> real3 */
#define SHAFTS_V3(a) MAKE_REAL3((a)[0], (a)[1], (a)[2])

/* First hit of the ray o + t d, t in (t_min, t_max); writes the normal (facing the ray) and the
 * object's index. Returns t or -1. */
SEASIM_FN real shafts_scene_hit(SEASIM_GLOBAL const ShaftsObject* objects, int count, real3 o, real3 d, real t_min,
                                real t_max, real3* normal, int* which) {
  real best = t_max;
  int hit = -1;
  real3 nrm = MAKE_REAL3(R(0.0), R(1.0), R(0.0));
  for (int k = 0; k < count; ++k) {
    SEASIM_GLOBAL const ShaftsObject* ob = &objects[k];
    real t = R(-1.0);
    int axis = 0;
    if (ob->type == SHAFTS_SPHERE) {
      t = ray_sphere(o, d, SHAFTS_V3(ob->a), ob->a[3], t_min, best);
      if (t > R(0.0)) nrm = normalize(o + t * d - SHAFTS_V3(ob->a));
    } else if (ob->type == SHAFTS_BOX) {
      t = ray_box(o, d, SHAFTS_V3(ob->a), SHAFTS_V3(ob->b), t_min, best, &axis);
      if (t > R(0.0)) nrm = box_normal(o + t * d, SHAFTS_V3(ob->a), SHAFTS_V3(ob->b), axis);
    } else {
      t = ray_plane(o, d, SHAFTS_V3(ob->a), SHAFTS_V3(ob->b), t_min, best);
      if (t > R(0.0)) nrm = SHAFTS_V3(ob->b);
    }
    if (t > R(0.0)) {
      best = t;
      hit = k;
      if (normal) *normal = nrm;
    }
  }
  if (which) *which = hit;
  if (normal && hit >= 0 && dot(*normal, d) > R(0.0)) *normal = -*normal;
  return hit >= 0 ? best : R(-1.0);
}

/* Light-frame coordinates of a point: x, y across the beam, z along it. */
SEASIM_FN real3 shafts_to_light(SEASIM_GLOBAL const ShaftsLight* L, real3 p) {
  const real3 q = p - SHAFTS_V3(L->position);
  return MAKE_REAL3(dot(q, SHAFTS_V3(L->right)), dot(q, SHAFTS_V3(L->up)), dot(q, SHAFTS_V3(L->direction)));
}

/* Texel i of an RGB map. */
SEASIM_FN real3 shafts_rgb_texel(SEASIM_GLOBAL const float* m, int i) {
  return MAKE_REAL3(m[3 * i], m[3 * i + 1], m[3 * i + 2]);
}

/* I_l towards a point with light-frame coordinates q at distance s, per R,G,B (W/sr); with the light
 * map (has_light_map) the projective texture of 001 §4.2: the map covers [-tan_cone, tan_cone]² at
 * unit distance, top row towards the light's +up, bilinear between texel centres, clamped at the border. */
SEASIM_FN real3 shafts_lamp_emission(int has_light_map, SEASIM_GLOBAL const ShaftsLight* L,
                                     SEASIM_GLOBAL const float* light_maps, real3 q, real s) {
  if (q.z <= R(0.0) || s <= R(0.0)) return MAKE_REAL3(R(0.0), R(0.0), R(0.0));
  const real profile = shafts_cone_profile(q.z / s, L->cos_cone, L->cos_inner);
  if (profile <= R(0.0)) return MAKE_REAL3(R(0.0), R(0.0), R(0.0));
  real3 e = SHAFTS_V3(L->color) * profile;
  if (has_light_map && L->light_map_offset >= 0) {
    const real inv = R(1.0) / (q.z * L->tan_cone);
    const real fu = (R(0.5) * (q.x * inv + R(1.0))) * L->light_map_width - R(0.5);
    const real fv = (R(0.5) * (R(1.0) - q.y * inv)) * L->light_map_height - R(0.5);
    const int w = L->light_map_width, h = L->light_map_height;
    const real cu = clamp(fu, R(0.0), (real)(w - 1)), cv = clamp(fv, R(0.0), (real)(h - 1));
    const int x0 = (int)cu < w - 1 ? (int)cu : w - 1, y0 = (int)cv < h - 1 ? (int)cv : h - 1;
    const int x1 = x0 + 1 < w - 1 ? x0 + 1 : w - 1, y1 = y0 + 1 < h - 1 ? y0 + 1 : h - 1;
    const real ax = cu - x0, ay = cv - y0;
    SEASIM_GLOBAL const float* m = light_maps + L->light_map_offset;
    const real3 t00 = shafts_rgb_texel(m, y0 * w + x0), t10 = shafts_rgb_texel(m, y0 * w + x1);
    const real3 t01 = shafts_rgb_texel(m, y1 * w + x0), t11 = shafts_rgb_texel(m, y1 * w + x1);
    e = e * mix(mix(t00, t10, ax), mix(t01, t11, ax), ay);
  }
  return e;
}

/* H: 1 when the point (light frame q, distance s) is nearer the lamp than the shadow map's depth;
 * always 1 without objects. */
SEASIM_FN real shafts_shadow_term(int has_objects, SEASIM_GLOBAL const ShaftsLight* L, SEASIM_GLOBAL const float* shadow,
                                  int size, real3 q, real s) {
  if (!has_objects) return R(1.0);
  const real inv = R(1.0) / (q.z * L->tan_cone);
  const int ix = clamp((int)(R(0.5) * (q.x * inv + R(1.0)) * size), 0, size - 1);
  const int iy = clamp((int)(R(0.5) * (q.y * inv + R(1.0)) * size), 0, size - 1);
  const real depth = shadow[L->shadow_offset + iy * size + ix];
  return s < depth ? R(1.0) : R(0.0);
}

/* Linear interpolation in the 1-D F table over α ∈ [0, π] (001 eq. 6). */
SEASIM_FN real shafts_phase_table(SEASIM_GLOBAL const float* F, int n, real cos_alpha) {
  const real x = acos(clamp(cos_alpha, R(-1.0), R(1.0))) * (real)(n - 1) / SEASIM_PI;
  const int i = (int)x < n - 2 ? (int)x : n - 2;
  const real f = x - i;
  return mix((real)F[i], (real)F[i + 1], f);
}

/* Bilinear interpolation in the 2-D table of ĥ = s² h over (s, t). */
SEASIM_FN real shafts_h_table(SEASIM_GLOBAL const float* H, int n, real s_max, real t_max, real s, real t) {
  const real xs = clamp(s / s_max, R(0.0), R(1.0)) * (n - 1), xt = clamp(t / t_max, R(0.0), R(1.0)) * (n - 1);
  const int i = (int)xs < n - 2 ? (int)xs : n - 2, j = (int)xt < n - 2 ? (int)xt : n - 2;
  const real fs = xs - i, ft = xt - j;
  const real a = mix((real)H[j * n + i], (real)H[j * n + i + 1], fs);
  const real b = mix((real)H[(j + 1) * n + i], (real)H[(j + 1) * n + i + 1], fs);
  return mix(a, b, ft);
}

/* 001 eq. 1's first term at the surface point P = eye + T d (normal n, object `which`): a Lambertian
 * surface under each spotlight, exact shadow ray, Beer–Lambert lamp -> surface and surface -> eye. */
SEASIM_FN real3 shafts_surface_radiance(int has_light_map, SEASIM_CONSTANT const ShaftsParams* p,
                                        SEASIM_GLOBAL const ShaftsLight* lights, SEASIM_GLOBAL const ShaftsObject* objects,
                                        SEASIM_GLOBAL const float* light_maps, real3 eye, real3 d, real T, real3 n,
                                        int which) {
  const real3 P = eye + T * d;
  const real3 albedo = SHAFTS_V3(objects[which].albedo);
  real3 Io = MAKE_REAL3(R(0.0), R(0.0), R(0.0));
  for (int l = 0; l < p->light_count; ++l) {
    SEASIM_GLOBAL const ShaftsLight* L = &lights[l];
    const real3 to_lamp = SHAFTS_V3(L->position) - P;
    const real s = length(to_lamp);
    const real3 wl = to_lamp / fmax(s, R(1e-20));
    const real cos_n = dot(n, wl);
    if (cos_n <= R(0.0)) continue;
    const real3 e = shafts_lamp_emission(has_light_map, L, light_maps, shafts_to_light(L, P), s);
    if (e.x + e.y + e.z <= R(0.0)) continue;
    const real eps = R(1e-4) * fmax(R(1.0), T);
    if (shafts_scene_hit(objects, p->object_count, P + eps * n, wl, R(0.0), s - R(2.0) * eps, 0, 0) > R(0.0)) continue;
    const real sc = fmax(s, p->s_min);
    Io = Io + e * (cos_n * exp(-p->sigma_t * s) / (sc * sc));
  }
  return Io * (albedo * (R(1.0) / SEASIM_PI)) * exp(-p->sigma_t * T);
}

/* One lamp's I_s over the lit stretches of the ray inside its cone (common/shafts_intervals.h): the
 * cone's part up to the first surface t_end, minus each object's shadow interval, integrated in the
 * lamp's angle with the far-field closed form beyond K r. */
SEASIM_FN real3 shafts_lamp_intervals(int has_objects, int has_light_map, int use_hg,
                                      SEASIM_CONSTANT const ShaftsParams* p, SEASIM_GLOBAL const ShaftsLight* Lg, int l,
                                      SEASIM_GLOBAL const ShaftsOccluder* occluders, SEASIM_GLOBAL const float* light_maps,
                                      real3 eye, real3 d, real t_end) {
  const real3 none = MAKE_REAL3(R(0.0), R(0.0), R(0.0));
  ShaftsLamp L;
  L.pos = SHAFTS_V3(Lg->position);
  L.axis = SHAFTS_V3(Lg->direction);
  L.right = SHAFTS_V3(Lg->right);
  L.up = SHAFTS_V3(Lg->up);
  L.cos_cone = Lg->cos_cone;
  L.cos_inner = Lg->cos_inner;
  L.tan_cone = Lg->tan_cone;
  L.map_w = 0;
  L.map_h = 0;
  if (has_light_map && Lg->light_map_offset >= 0) {
    L.map_w = Lg->light_map_width;
    L.map_h = Lg->light_map_height;
  }
  real lo[SHAFTS_MAX_PIECES], hi[SHAFTS_MAX_PIECES];
  if (!shafts_cone_interval(eye, d, L.pos, L.axis, L.cos_cone, &lo[0], &hi[0])) return none;
  hi[0] = fmin(hi[0], t_end);
  if (!(hi[0] > lo[0])) return none;
  int n = 1;
  for (int k = 0; has_objects && k < p->object_count && n > 0; ++k) {
    SEASIM_GLOBAL const ShaftsOccluder* oc = &occluders[l * p->object_count + k];
    real s0 = lo[0], s1 = hi[n - 1]; /* the shadow matters only where the ray is lit */
    if (shafts_shadow_interval_packed(oc->planes, oc->plane_count, oc->has_cone, oc->always, SHAFTS_V3(oc->apex),
                                      SHAFTS_V3(oc->axis), oc->axis[3], eye, d, &s0, &s1))
      n = shafts_pieces_subtract(lo, hi, n, s0, s1);
  }
  if (n == 0) return none;
  real ti0 = R(0.0), ti1 = R(0.0);
  const int has_inner = shafts_cone_interval(eye, d, L.pos, L.axis, L.cos_inner, &ti0, &ti1);
  SEASIM_GLOBAL const float* map = light_maps + (Lg->light_map_offset > 0 ? Lg->light_map_offset : 0);
  return SHAFTS_V3(Lg->color) * shafts_interval_airlight(lo, hi, n, has_inner, ti0, ti1, eye, d, L, map, p->rho,
                                                          p->sigma_t, p->s_min, use_hg, p->hg_g, p->panel_rad,
                                                          p->map_panel_texels);
}

/* One lamp's I_s by ray marching, the method of the CPU reference (host/reference/shafts_reference.h,
 * renderShaftsReference) in the kernel's precision: `steps` midpoint steps uniform in the lamp's angle
 * φ = atan((t - a)/r) over the cone's part of [0, t_end] (a: the ray parameter of the closest approach to
 * the lamp, r = max(its distance, s_min); t = ∞ is φ = π/2, so an unbounded ray is a finite interval and
 * the integrand g dt/dφ = g r sec²φ stays bounded), at each the lamp's emission, an exact shadow ray to the
 * lamp (has_objects) and g = F h (001 eq. 2–4). It converges to the exact I_s as steps grows and shares
 * neither planes, tables nor shadow maps with the other methods. */
SEASIM_FN real3 shafts_lamp_march(int has_objects, int has_light_map, int use_hg, SEASIM_CONSTANT const ShaftsParams* p,
                                  SEASIM_GLOBAL const ShaftsLight* L, SEASIM_GLOBAL const ShaftsObject* objects,
                                  SEASIM_GLOBAL const float* light_maps, real3 eye, real3 d, real t_end, int steps) {
  const real3 none = MAKE_REAL3(R(0.0), R(0.0), R(0.0));
  const real3 pos = SHAFTS_V3(L->position);
  real ta = R(0.0), tb = R(0.0);
  if (!shafts_cone_interval(eye, d, pos, SHAFTS_V3(L->direction), L->cos_cone, &ta, &tb)) return none;
  const int unbounded = tb >= SHAFTS_T_INF && t_end >= SHAFTS_T_INF;
  tb = fmin(tb, t_end);
  if (!(tb > ta) || steps < 1) return none;
  real a = R(0.0), h = R(0.0);
  shafts_closest_approach(eye, d, pos, &a, &h);
  const real r = fmax(h, (real)p->s_min);
  const real phi_a = atan((ta - a) / r);
  const real phi_b = unbounded ? R(0.5) * SEASIM_PI : atan((tb - a) / r);
  const real dphi = (phi_b - phi_a) / (real)steps;
  real3 sum = none;
  for (int i = 0; i < steps; ++i) {
    const real tan_phi = tan(phi_a + ((real)i + R(0.5)) * dphi);
    const real t = a + r * tan_phi;
    const real3 P = eye + t * d;
    const real3 w = P - pos;
    const real s = length(w);
    const real3 e = shafts_lamp_emission(has_light_map, L, light_maps, shafts_to_light(L, P), s);
    if (!(e.x + e.y + e.z > R(0.0))) continue;
    if (has_objects && s > R(0.0) && shafts_scene_hit(objects, p->object_count, P, -(w / s), R(0.0), s, 0, 0) > R(0.0))
      continue; /* H = 0 */
    const real cos_alpha = s > R(0.0) ? dot(w, -d) / s : R(1.0);
    const real g = shafts_phase_fn(cos_alpha, use_hg, (real)p->hg_g) * shafts_h(s, t, (real)p->rho, (real)p->sigma_t,
                                                                               (real)p->s_min); /* 001 eq. 3 */
    sum = sum + e * (g * r * (R(1.0) + tan_phi * tan_phi) * dphi);
  }
  return sum;
}

/* The sum of H I_l over m points eye + t d (001 eq. 9's J, not yet divided by m). t of point j:
 * t0 + (j + 0.5) dt in a plane interval, or in the far field a + r tan(phi_p + (j + 0.5) (phi_b - phi_p) / m). */
SEASIM_FN real3 shafts_lit_sum(int has_objects, int has_light_map, SEASIM_CONSTANT const ShaftsParams* p,
                               SEASIM_GLOBAL const ShaftsLight* L, SEASIM_GLOBAL const float* shadow,
                               SEASIM_GLOBAL const float* light_maps, real3 eye, real3 d, int m, int far_field,
                               real t0, real dt, real a, real r, real phi_p, real phi_b) {
  const real3 lamp = SHAFTS_V3(L->position);
  real3 J = MAKE_REAL3(R(0.0), R(0.0), R(0.0));
  for (int j = 0; j < m; ++j) {
    const real t = !far_field ? t0 + (j + R(0.5)) * dt : a + r * tan(phi_p + (j + R(0.5)) * (phi_b - phi_p) / m);
    const real3 P = eye + t * d;
    const real3 q = shafts_to_light(L, P);
    const real s = length(P - lamp);
    const real3 e = shafts_lamp_emission(has_light_map, L, light_maps, q, s);
    if (e.x + e.y + e.z > R(0.0)) J = J + e * shafts_shadow_term(has_objects, L, shadow, p->shadow_map_size, q, s);
  }
  return J;
}

/* F(α): exactly (shafts_phase_fn) or from the 1-D table. */
SEASIM_FN real shafts_phase_at(int exact, int use_hg, SEASIM_CONSTANT const ShaftsParams* p,
                               SEASIM_GLOBAL const float* F_table, real cos_alpha) {
  if (exact) return shafts_phase_fn(cos_alpha, use_hg, p->hg_g);
  return shafts_phase_table(F_table, p->table_size, cos_alpha);
}

/* One lamp's I_s over the exact part of the view ray inside its cone, from the camera to the first
 * surface t_end or to infinity: n sampling intervals (001 eq. 5) with m sub-samples each (001 eq.
 * 7–9) up to K r past the closest approach to the lamp; beyond, the closed-form far field
 * (shafts_tail_from) with H I_l averaged over m directions spread evenly in the angle the lamp sees
 * (dt / s² is uniform in it), and F at the middle one. g exactly (001 eq. 3, 6) or from the tables. */
SEASIM_FN real3 shafts_lamp_planes(int has_objects, int has_light_map, int exact, int use_hg,
                                   SEASIM_CONSTANT const ShaftsParams* p, SEASIM_GLOBAL const ShaftsLight* L,
                                   SEASIM_GLOBAL const float* shadow, SEASIM_GLOBAL const float* light_maps,
                                   SEASIM_GLOBAL const float* F_table, SEASIM_GLOBAL const float* h_tab, real3 eye,
                                   real3 d, real t_end) {
  const int n_planes = p->planes, m = p->subplanes;
  const real3 lamp = SHAFTS_V3(L->position);
  real3 acc = MAKE_REAL3(R(0.0), R(0.0), R(0.0));
  real ta, tb;
  if (!shafts_cone_interval(eye, d, lamp, SHAFTS_V3(L->direction), L->cos_cone, &ta, &tb)) return acc;
  tb = fmin(tb, t_end);
  if (!(tb > ta)) return acc;
  real a, h;
  shafts_closest_approach(eye, d, lamp, &a, &h);
  const real r = fmax(h, p->s_min);
  const real tp = fmin(tb, fmax(ta, a + SHAFTS_TAIL_K * r)); /* planes on [ta, tp], far field on [tp, tb] */
  const real dt = (tp - ta) / n_planes;
  for (int i = 0; i < n_planes && dt > R(0.0); ++i) {
    const real za = ta + i * dt;
    real3 J = shafts_lit_sum(has_objects, has_light_map, p, L, shadow, light_maps, eye, d, m, 0, za, dt / m, R(0.0),
                             R(0.0), R(0.0), R(0.0));
    if (J.x + J.y + J.z <= R(0.0)) continue;
    J = J * (R(1.0) / m);
    const real t = za + R(0.5) * dt; /* g at the plane (the interval's midpoint) */
    const real3 w = eye + t * d - lamp;
    const real s = length(w);
    const real cos_alpha = s > R(0.0) ? dot(w, -d) / s : R(1.0);
    real g;
    if (exact) {
      g = shafts_phase_fn(cos_alpha, use_hg, p->hg_g) * shafts_h(s, t, p->rho, p->sigma_t, p->s_min);
    } else {
      const real sc = fmax(s, p->s_min);
      g = shafts_phase_table(F_table, p->table_size, cos_alpha) *
          shafts_h_table(h_tab, p->table_size, p->table_s_max, p->table_t_max, s, t) / (sc * sc);
    }
    acc = acc + J * (g * dt);
  }
  if (tb > tp) {
    const int infinite = tb >= SHAFTS_T_INF;
    const real phi_p = atan((tp - a) / r), phi_b = infinite ? R(0.5) * SEASIM_PI : atan((tb - a) / r);
    const real3 J =
        shafts_lit_sum(has_objects, has_light_map, p, L, shadow, light_maps, eye, d, m, 1, R(0.0), R(0.0), a, r,
                       phi_p, phi_b);
    if (J.x + J.y + J.z > R(0.0)) {
      const real3 w = eye + (a + r * tan(R(0.5) * (phi_p + phi_b))) * d - lamp;
      const real F = shafts_phase_at(exact, use_hg, p, F_table, dot(w, -d) / length(w));
      real tail = shafts_tail_from(tp - a, a, h, p->rho, p->sigma_t);
      if (!infinite) tail -= shafts_tail_from(tb - a, a, h, p->rho, p->sigma_t);
      acc = acc + J * (F * fmax(tail, R(0.0)) / m);
    }
  }
  return acc;
}
