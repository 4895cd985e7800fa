/* shafts_intervals.h — the "intervals" method of the spotlight shafts: per pixel and
 * lamp, eq. 2 of paper 001 is integrated over the exact lit stretches of the view ray, found in
 * closed form, instead of being sampled by n planes with m shadow-map look-ups each (001 eq. 5–9).
 *
 *   I_s = ∫ H(t) I_l(t) F(α) ρ exp(-ρκ (s + t)) / s² dt                     (001 eq. 2, 3, 6)
 *
 * 1. Lit stretches. The ray's part inside the lamp's cone (shafts_cone_interval, common/shafts.h),
 *    up to the first surface, minus each object's shadow. The shadow volume of a convex object B
 *    from a point lamp l, S = {l + μ (x - l) : x ∈ B, μ >= 1}, is convex (a convex combination of
 *    two such points is l + M (x' - l) with M >= 1 and x' ∈ B), so the ray meets it in one interval:
 *      plane:  the half-space on the far side from the lamp;
 *      box:    the half-spaces behind its front faces and inside the planes through the lamp and
 *              its silhouette edges (at most 3 + 6);
 *      sphere: the tangent cone from the lamp, beyond the plane of its silhouette circle (the part
 *              of that region in front of the sphere's near cap is inside the sphere, which a view
 *              ray never reaches before its first hit).
 *    These are the shadows of exact shadow rays, the reference's H: no shadow map, no texels.
 * 2. The integral over each stretch, in the angle φ the lamp sees along the ray: t = a + r tan φ
 *    about the closest approach (a, h; r = max(h, s_min)), so that dt / s² = dφ / r when h >= r.
 *    The integrand is then smooth and bounded on (-π/2, π/2), and Gauss–Legendre panels (2 nodes,
 *    exact for cubics) of at most panel_rad integrate it up to K r past the closest approach; the
 *    rest, to the surface or to infinity, has the far-field closed form of common/shafts.h. The
 *    spotlight's fall-off is smooth inside the fall-off band and 1 inside the inner cone: stretches
 *    are split at the inner cone so that no panel straddles its kink. A light map varies on the
 *    scale of its texels: panels over it span at most map_panel_texels texels.
 *
 * Written against compat.h; no include guards, no #include (kernel_math.h orders the headers).
 * Needs optics.h and shafts.h before it.
 *
 * Stiff cases: a ray through the lamp (h -> 0): r = s_min, 1/s² clamped at s_min as in shafts_h;
 * ρκ = 0: the integrand tends to F(-1) ρ / r at φ -> π/2, finite; grazing a cone or a shadow
 * volume: an interval of zero length adds nothing; a lamp inside an object: everything shadowed.
 */

/* Half-spaces of one object's shadow volume: a box's 3 front faces and 6 silhouette edges. */
#define SHAFTS_OCC_PLANES 9
/* Lit stretches per pixel and lamp: each shadow interval removed splits at most one stretch in
 * two, so 1 + objects; the host allows at most SHAFTS_MAX_PIECES - 1 objects in this method. */
#define SHAFTS_MAX_PIECES 16
/* Panels per stretch at most: a bound on the work per pixel (π / 256 is 0.7 deg). */
#define SHAFTS_MAX_PANELS 256

/* A shadow volume as the host builds it: inside every half-space dot(n, p) <= b, and inside the
 * cone of apex `apex`, axis `axis`, cos_cone when has_cone. always = 1: the lamp is inside the
 * object, every point is in shadow; always = -1: nothing is (a lamp on a plane). */
typedef struct {
  real3 n[SHAFTS_OCC_PLANES];
  real b[SHAFTS_OCC_PLANES];
  real3 apex, axis;
  real cos_cone;
  int plane_count, has_cone, always;
} ShaftsShadowVolume;

/* Narrows [*lo, *hi] to the ray parameters t with dot(n, o + t d) <= b. Parallel rays (|n.d| below
 * 1e-20) keep or empty the interval; bounds are clamped to ±SHAFTS_T_INF (finite for relaxed maths). */
SEASIM_FN void shafts_clip_halfspace(real3 o, real3 d, real3 n, real b, real* lo, real* hi) {
  const real nd = dot(n, d), excess = dot(n, o) - b;
  if (fabs(nd) < R(1e-20)) {
    if (excess > R(0.0)) *lo = SHAFTS_T_INF;
    return;
  }
  const real t = clamp(-excess / nd, -SHAFTS_T_INF, SHAFTS_T_INF);
  if (nd > R(0.0)) *hi = fmin(*hi, t);
  else *lo = fmax(*lo, t);
}

/* A shadow volume from `lamp` with no planes, no cone and nothing always in shadow (what each object's
 * constructor below starts from), its cone axis `axis`. */
SEASIM_FN ShaftsShadowVolume shafts_shadow_volume_empty(real3 lamp, real3 axis) {
  ShaftsShadowVolume v;
  v.plane_count = 0;
  v.has_cone = 0;
  v.always = 0;
  v.cos_cone = R(0.0);
  v.apex = lamp;
  v.axis = axis;
  return v;
}

/* The shadow volume of the plane through p with normal nrm, lit from `lamp`: the half-space on the
 * other side (empty when the lamp lies on the plane: a shadow ray ending on it is not blocked). */
SEASIM_FN ShaftsShadowVolume shafts_plane_shadow(real3 lamp, real3 p, real3 nrm) {
  ShaftsShadowVolume v = shafts_shadow_volume_empty(lamp, nrm);
  const real side = dot(nrm, lamp - p);
  if (side != R(0.0)) {
    const real3 m = side > R(0.0) ? nrm : -nrm; /* points towards the lamp */
    v.n[0] = m;
    v.b[0] = dot(m, p);
    v.plane_count = 1;
  } else {
    v.always = -1;
  }
  return v;
}

/* The shadow volume of the sphere (centre c, radius rad) from `lamp`. */
SEASIM_FN ShaftsShadowVolume shafts_sphere_shadow(real3 lamp, real3 c, real rad) {
  const real3 w = c - lamp;
  const real dist = length(w);
  ShaftsShadowVolume v = shafts_shadow_volume_empty(lamp, dist > R(0.0) ? w / dist : MAKE_REAL3(0, 0, 1));
  if (dist <= rad) {
    v.always = 1;
    return v;
  }
  const real tangent2 = (dist - rad) * (dist + rad); /* dist² - rad², without cancellation */
  v.cos_cone = sqrt(tangent2) / dist;
  v.has_cone = 1;
  /* Beyond the silhouette circle's plane: dot(axis, p - lamp) >= tangent2 / dist. */
  v.n[0] = -v.axis;
  v.b[0] = -(dot(v.axis, lamp) + tangent2 / dist);
  v.plane_count = 1;
  return v;
}

/* The shadow volume of the axis-aligned box [bmin, bmax] from `lamp`. */
SEASIM_FN ShaftsShadowVolume shafts_box_shadow(real3 lamp, real3 bmin, real3 bmax) {
  ShaftsShadowVolume v = shafts_shadow_volume_empty(lamp, MAKE_REAL3(0, 0, 1));
  const real l[3] = {lamp.x, lamp.y, lamp.z};
  const real mn[3] = {bmin.x, bmin.y, bmin.z}, mx[3] = {bmax.x, bmax.y, bmax.z};
  /* front[k][0]: the face at bmin[k] faces the lamp; front[k][1]: the face at bmax[k]. */
  int front[3][2];
  int inside = 1;
  for (int k = 0; k < 3; ++k) {
    front[k][0] = l[k] < mn[k];
    front[k][1] = l[k] > mx[k];
    if (front[k][0] || front[k][1]) inside = 0;
  }
  if (inside) {
    v.always = 1;
    return v;
  }
  const real3 centre = R(0.5) * (bmin + bmax);
  for (int k = 0; k < 3; ++k) {
    const real3 e = k == 0 ? MAKE_REAL3(1, 0, 0) : (k == 1 ? MAKE_REAL3(0, 1, 0) : MAKE_REAL3(0, 0, 1));
    if (front[k][0]) { /* behind the face: p_k >= bmin_k */
      v.n[v.plane_count] = -e;
      v.b[v.plane_count] = -mn[k];
      ++v.plane_count;
    }
    if (front[k][1]) { /* p_k <= bmax_k */
      v.n[v.plane_count] = e;
      v.b[v.plane_count] = mx[k];
      ++v.plane_count;
    }
  }
  /* Silhouette edges: the edge along axis k between face (i, si) and face (j, sj) is on the
   * silhouette when exactly one of the two faces is front-facing. The plane through the lamp and
   * the edge bounds the cone over the box; the box's centre is on its inner side. */
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    for (int si = 0; si < 2; ++si)
      for (int sj = 0; sj < 2; ++sj) {
        if (front[i][si] == front[j][sj]) continue;
        real p0[3], p1[3];
        p0[i] = p1[i] = si ? mx[i] : mn[i];
        p0[j] = p1[j] = sj ? mx[j] : mn[j];
        p0[k] = mn[k];
        p1[k] = mx[k];
        const real3 e0 = MAKE_REAL3(p0[0], p0[1], p0[2]), e1 = MAKE_REAL3(p1[0], p1[1], p1[2]);
        real3 m = cross(e1 - e0, e0 - lamp);
        if (dot(m, centre - lamp) > R(0.0)) m = -m;
        v.n[v.plane_count] = m;
        v.b[v.plane_count] = dot(m, lamp);
        ++v.plane_count;
      }
  }
  return v;
}

/* The ray parameters [*lo, *hi] of o + t d inside the shadow volume; returns 0 when it misses. */
SEASIM_FN int shafts_shadow_interval(ShaftsShadowVolume v, real3 o, real3 d, real* lo, real* hi) {
  *lo = -SHAFTS_T_INF;
  *hi = SHAFTS_T_INF;
  if (v.always < 0) return 0;
  if (v.always > 0) return 1;
  for (int k = 0; k < v.plane_count; ++k) shafts_clip_halfspace(o, d, v.n[k], v.b[k], lo, hi);
  if (v.has_cone && *hi > *lo) { /* (shafts_cone_interval keeps t >= 0: the view ray's part) */
    real c0, c1;
    if (!shafts_cone_interval(o, d, v.apex, v.axis, v.cos_cone, &c0, &c1)) return 0;
    *lo = fmax(*lo, c0);
    *hi = fmin(*hi, c1);
  }
  return *hi > *lo;
}

/* shafts_shadow_interval on a volume packed as the kernel's buffer holds it (common/shafts_params.h,
 * ShaftsOccluder): planes[k] = n.xyz, b, one row of four per plane (rows, not a flat float pointer
 * into the struct's 2-D array: indexing past the first row through such a pointer is outside its
 * array in C, and Oclgrind reports it). It narrows the caller's [*lo, *hi] (the lit
 * range the shadow could touch) plane by plane and stops at the first that leaves it empty, as most
 * rays miss most shadows. */
SEASIM_FN int shafts_shadow_interval_packed(SEASIM_GLOBAL const float (*planes)[4], int plane_count, int has_cone,
                                            int always, real3 apex, real3 axis, real cos_cone, real3 o, real3 d,
                                            real* lo, real* hi) {
  if (always < 0) return 0;
  if (always > 0) return 1;
  for (int k = 0; k < plane_count; ++k) {
    const real3 n = MAKE_REAL3(planes[k][0], planes[k][1], planes[k][2]);
    shafts_clip_halfspace(o, d, n, (real)planes[k][3], lo, hi);
    if (!(*hi > *lo)) return 0;
  }
  if (has_cone) {
    real c0, c1;
    if (!shafts_cone_interval(o, d, apex, axis, cos_cone, &c0, &c1)) return 0;
    *lo = fmax(*lo, c0);
    *hi = fmin(*hi, c1);
  }
  return *hi > *lo;
}

/* Removes [a, b] from the sorted, disjoint stretches lo[0..n), hi[0..n); returns the new count.
 * A stretch that would not fit (more than SHAFTS_MAX_PIECES) is dropped: the host keeps the object
 * count below that bound, so this never happens in a planned render. */
SEASIM_FN int shafts_pieces_subtract(real* lo, real* hi, int n, real a, real b) {
  if (!(b > a)) return n;
  real nlo[SHAFTS_MAX_PIECES], nhi[SHAFTS_MAX_PIECES];
  int m = 0;
  for (int k = 0; k < n; ++k) {
    if (b <= lo[k] || a >= hi[k]) { /* untouched */
      if (m < SHAFTS_MAX_PIECES) { nlo[m] = lo[k]; nhi[m] = hi[k]; ++m; }
      continue;
    }
    if (a > lo[k] && m < SHAFTS_MAX_PIECES) { nlo[m] = lo[k]; nhi[m] = a; ++m; }
    if (b < hi[k] && m < SHAFTS_MAX_PIECES) { nlo[m] = b; nhi[m] = hi[k]; ++m; }
  }
  for (int k = 0; k < m; ++k) {
    lo[k] = nlo[k];
    hi[k] = nhi[k];
  }
  return m;
}

/* A spotlight as the integrator sees it: frame (axis = light +z, right = +x, up = +y), cone,
 * fall-off, and its light map's size (map_w = 0: none). */
typedef struct {
  real3 pos, axis, right, up;
  real cos_cone, cos_inner, tan_cone;
  int map_w, map_h;
} ShaftsLamp;

/* The light map's RGB at the light-frame point q (q.z > 0), bilinear between texel centres and
 * clamped at the border, as common/shafts_render.h's shafts_lamp_emission (001 §4.2). */
SEASIM_FN real3 shafts_light_map_rgb(ShaftsLamp L, SEASIM_GLOBAL const float* map, real3 q) {
  const real inv = R(1.0) / (q.z * L.tan_cone);
  const real fu = (R(0.5) * (q.x * inv + R(1.0))) * (real)L.map_w - R(0.5);
  const real fv = (R(0.5) * (R(1.0) - q.y * inv)) * (real)L.map_h - R(0.5);
  const real cu = clamp(fu, R(0.0), (real)(L.map_w - 1)), cv = clamp(fv, R(0.0), (real)(L.map_h - 1));
  const int x0 = (int)cu < L.map_w - 1 ? (int)cu : L.map_w - 1, y0 = (int)cv < L.map_h - 1 ? (int)cv : L.map_h - 1;
  const int x1 = x0 + 1 < L.map_w ? x0 + 1 : x0, y1 = y0 + 1 < L.map_h ? y0 + 1 : y0;
  const real ax = cu - (real)x0, ay = cv - (real)y0;
  const int i00 = 3 * (y0 * L.map_w + x0), i10 = 3 * (y0 * L.map_w + x1);
  const int i01 = 3 * (y1 * L.map_w + x0), i11 = 3 * (y1 * L.map_w + x1);
  const real3 t00 = MAKE_REAL3(map[i00], map[i00 + 1], map[i00 + 2]);
  const real3 t10 = MAKE_REAL3(map[i10], map[i10 + 1], map[i10 + 2]);
  const real3 t01 = MAKE_REAL3(map[i01], map[i01 + 1], map[i01 + 2]);
  const real3 t11 = MAKE_REAL3(map[i11], map[i11 + 1], map[i11 + 2]);
  const real3 top = t00 + ax * (t10 - t00), bottom = t01 + ax * (t11 - t01);
  return top + ay * (bottom - top);
}

/* At φ given by cp = cos φ > 0, sp = sin φ (t = a + r tan φ): returns V F, the cone profile times
 * the light map (RGB) times the phase function F(α), and writes to *kern the rest of eq. 2's
 * integrand per dφ, ρ exp(-ρκ (s + t)) dt/dφ / max(s, s_min)² (001 eq. 3, 6). */
SEASIM_FN real3 shafts_interval_vf(real cp, real sp, real3 o, real3 d, ShaftsLamp L, SEASIM_GLOBAL const float* map,
                                   real a, real h, real r, real rho, real sigma_t, real s_min, int use_hg, real hg_g,
                                   real* kern) {
  const real x = r * sp / cp;                      /* t - a */
  const real s2 = x * x + h * h, s = sqrt(s2);     /* distance to the lamp */
  const real3 w = o + (a + x) * d - L.pos;         /* lamp -> sample */
  const real qz = dot(w, L.axis);
  *kern = rho * exp(-(sigma_t * (s + a + x))) * r / (cp * cp * fmax(s2, s_min * s_min)); /* r sec²φ / max(s, s_min)² */
  const real profile = s > R(0.0) ? shafts_cone_profile(qz / s, L.cos_cone, L.cos_inner) : R(0.0);
  if (profile <= R(0.0)) return MAKE_REAL3(0, 0, 0);
  const real cos_alpha = s > R(0.0) ? -x / s : R(1.0); /* dot(w, -d) / s */
  const real vf = profile * shafts_phase_fn(cos_alpha, use_hg, hg_g);
  if (L.map_w > 0) return vf * shafts_light_map_rgb(L, map, MAKE_REAL3(dot(w, L.right), dot(w, L.up), qz));
  return MAKE_REAL3(vf, vf, vf);
}

/* Panels for the φ range [phi0, phi1]: of at most panel_rad and, over a light map, at most
 * map_panel_texels of its texels (a texel spans 2 tan_cone / map_w in tan of the angle off the
 * axis, which is at least the angle it spans); between 1 and SHAFTS_MAX_PANELS. */
SEASIM_FN int shafts_interval_panels(real phi0, real phi1, ShaftsLamp L, real panel_rad, real map_panel_texels) {
  real width = panel_rad;
  if (L.map_w > 0)
    width = fmin(width, map_panel_texels * R(2.0) * L.tan_cone / (real)(L.map_w > L.map_h ? L.map_w : L.map_h));
  const real wanted = (phi1 - phi0) / width; /* ceil, clamped */
  int panels = wanted < (real)SHAFTS_MAX_PANELS ? (int)wanted : SHAFTS_MAX_PANELS;
  if ((real)panels < wanted && panels < SHAFTS_MAX_PANELS) ++panels;
  return panels < 1 ? 1 : panels;
}

/* ∫ over the stretch [t0, t1] of the ray (t1 may be SHAFTS_T_INF) of eq. 2 per unit lamp colour.
 *   Near part, x = t - a < K r (φ < atan K = 82.9°): 2-node Gauss–Legendre panels in φ
 *   (shafts_interval_panels).
 *   Far part, x >= K r: there ρκ r small makes exp(-ρκ (s + t)) fall from 1 to 0 in the last few
 *   thousandths of a radian before φ = π/2, which panels cannot follow; its integral has the closed
 *   form of common/shafts.h (shafts_tail_from, exponential integrals), multiplied by V F averaged
 *   over Gauss–Legendre nodes in φ (exact for a uniform V F; F changes by < 1 % beyond 82.9°). */
SEASIM_FN real3 shafts_interval_stretch(real t0, real t1, real3 o, real3 d, ShaftsLamp L, SEASIM_GLOBAL const float* map,
                                        real a, real h, real r, real rho, real sigma_t, real s_min, int use_hg, real hg_g,
                                        real panel_rad, real map_panel_texels) {
  const real half_pi = R(0.5) * SEASIM_PI;
  const real tc = a + SHAFTS_TAIL_K * r; /* start of the far part */
  real3 sum = MAKE_REAL3(0, 0, 0);
  real kern;
  const real tn = fmin(t1, tc);
  if (tn > t0) {
    const real phi0 = atan2(t0 - a, r), phi1 = atan2(tn - a, r);
    const int panels = shafts_interval_panels(phi0, phi1, L, panel_rad, map_panel_texels);
    const real dphi = (phi1 - phi0) / (real)panels;
    const real node = R(0.28867513459481288) * dphi; /* GL nodes at mid ± dphi / (2 sqrt 3) */
    /* The nodes' (cos, sin) advance by a rotation of dphi per panel: no sin/cos in the loop. */
    const real cd = cos(dphi), sd = sin(dphi);
    const real first = phi0 + R(0.5) * dphi - node;
    real ca = cos(first), sa = sin(first), cb = cos(first + R(2.0) * node), sb = sin(first + R(2.0) * node);
    real3 near = MAKE_REAL3(0, 0, 0);
    for (int k = 0; k < panels; ++k) {
      real3 vf = shafts_interval_vf(ca, sa, o, d, L, map, a, h, r, rho, sigma_t, s_min, use_hg, hg_g, &kern);
      near = near + vf * kern;
      vf = shafts_interval_vf(cb, sb, o, d, L, map, a, h, r, rho, sigma_t, s_min, use_hg, hg_g, &kern);
      near = near + vf * kern;
      const real ca1 = ca * cd - sa * sd, cb1 = cb * cd - sb * sd;
      sa = sa * cd + ca * sd;
      sb = sb * cd + cb * sd;
      ca = ca1;
      cb = cb1;
    }
    sum = near * (R(0.5) * dphi);
  }
  const real tf = fmax(t0, tc);
  if (t1 > tf) {
    const int infinite = t1 >= SHAFTS_T_INF;
    const real phi0 = atan2(tf - a, r), phi1 = infinite ? half_pi : atan2(t1 - a, r);
    const int panels = shafts_interval_panels(phi0, phi1, L, panel_rad, map_panel_texels);
    const real dphi = (phi1 - phi0) / (real)panels;
    const real node = R(0.28867513459481288) * dphi;
    real3 mean = MAKE_REAL3(0, 0, 0);
    for (int k = 0; k < panels; ++k) {
      const real mid = phi0 + ((real)k + R(0.5)) * dphi;
      mean = mean + shafts_interval_vf(cos(mid - node), sin(mid - node), o, d, L, map, a, h, r, rho, sigma_t, s_min,
                                       use_hg, hg_g, &kern);
      mean = mean + shafts_interval_vf(cos(mid + node), sin(mid + node), o, d, L, map, a, h, r, rho, sigma_t, s_min,
                                       use_hg, hg_g, &kern);
    }
    real tail = shafts_tail_from(tf - a, a, h, rho, sigma_t);
    if (!infinite) tail -= shafts_tail_from(t1 - a, a, h, rho, sigma_t);
    sum = sum + mean * (fmax(tail, R(0.0)) / (R(2.0) * (real)panels));
  }
  return sum;
}

/* ∫ over the lit stretches lo[0..n), hi[0..n) (sorted, inside the lamp's cone), each split at the
 * inner cone [ti0, ti1] (has_inner = 0: the ray misses it) so no panel straddles the fall-off's
 * kink. Per unit lamp colour (the caller multiplies by I_l's RGB). */
SEASIM_FN real3 shafts_interval_airlight(const real* lo, const real* hi, int n, int has_inner, real ti0, real ti1,
                                         real3 o, real3 d, ShaftsLamp L, SEASIM_GLOBAL const float* map, real rho,
                                         real sigma_t, real s_min, int use_hg, real hg_g, real panel_rad,
                                         real map_panel_texels) {
  real a, h;
  shafts_closest_approach(o, d, L.pos, &a, &h);
  const real r = fmax(h, s_min);
  real3 acc = MAKE_REAL3(0, 0, 0);
  for (int k = 0; k < n; ++k) {
    real cuts[4];
    int c = 0;
    cuts[c++] = lo[k];
    if (has_inner && ti0 > lo[k] && ti0 < hi[k]) cuts[c++] = ti0;
    if (has_inner && ti1 > lo[k] && ti1 < hi[k]) cuts[c++] = ti1;
    cuts[c++] = hi[k];
    for (int j = 0; j + 1 < c; ++j)
      acc = acc + shafts_interval_stretch(cuts[j], cuts[j + 1], o, d, L, map, a, h, r, rho, sigma_t, s_min, use_hg, hg_g,
                                     panel_rad, map_panel_texels);
  }
  return acc;
}
