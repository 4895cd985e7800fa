/* shafts.h — the math of spotlight shafts (paper 001) that the kernel (kernels/shafts.cl) and the
 * double CPU reference (host/reference/shafts_reference.cpp) share: the attenuation factor
 * h(s,t) of 001 eq. 6, the phase function choice of eq. 4, the spotlight's cone fall-off, the
 * sampling-plane intervals of eq. 5/7–9, and ray intersections with the scene's analytic objects.
 *
 * Written against compat.h (real, real3, R(), SEASIM_FN); no include guards, no #include
 * (kernel_math.h orders the headers). Needs optics.h (shafts_phase_cos, hg_phase) before it.
 *
 * Stiff cases:
 *   - s -> 0 (a sample at the lamp): 1/s² is clamped at s_min (the lamp's radius), so a sample on
 *     the lamp is large but finite; the phase angle at s = 0 is taken as forward (cos α = 1).
 *   - ρκ (s + t) large: exp underflows to 0, never NaN; ρκ = 0: exactly no attenuation.
 *   - grazing planes (a view ray almost parallel to the screen): the interval length Δz / cos θ
 *     is finite for cos θ > 0, which every pixel of a pinhole camera with fov < 180° has.
 */

/* 001 eq. 6: h(s, t) = ρ exp(-ρκ (s + t)) / s², with s clamped at s_min. */
SEASIM_FN real shafts_h(real s, real t, real rho, real sigma_t, real s_min) {
  real sc = fmax(s, s_min);
  return rho * exp(-(sigma_t * (s + t))) / (sc * sc);
}

/* s² h(s, t) = ρ exp(-ρκ (s + t)): smooth in s, what the 2-D table stores (dividing by s² after
 * the lookup keeps the 1/s² spike exact instead of interpolating it linearly). */
SEASIM_FN real shafts_h_scaled(real s, real t, real rho, real sigma_t) {
  return rho * exp(-(sigma_t * (s + t)));
}

/* The phase function: 001 eq. 4 normalised (optics.h), or Henyey–Greenstein with asymmetry g
 * when use_hg != 0. cos_alpha is the cosine of the scattering angle (1: light travelling straight
 * on towards the eye). */
SEASIM_FN real shafts_phase_fn(real cos_alpha, int use_hg, real hg_g) {
  return use_hg ? hg_phase(cos_alpha, hg_g) : shafts_phase_cos(cos_alpha);
}

/* The spotlight's angular profile from the cosine of the angle to its axis: 1 inside
 * cos_inner = cos(cone - falloff), 0 outside cos_cone = cos(cone), smoothstep between (zero
 * falloff: a hard edge). */
SEASIM_FN real shafts_cone_profile(real cos_axis, real cos_cone, real cos_inner) {
  if (cos_axis <= cos_cone) return R(0.0);
  if (cos_axis >= cos_inner) return R(1.0);
  real x = (cos_axis - cos_cone) / (cos_inner - cos_cone);
  return x * x * (R(3.0) - R(2.0) * x);
}

/* Sampling interval i of n (001 eq. 5 and §4.3): planes parallel to the screen at camera depths
 * z_i = z_near + (i + 1/2) Δz, Δz = (z_far - z_near)/n, interval i = [z_i - Δz/2, z_i + Δz/2]
 * clipped to the visible depth z_end (the first surface on the ray). Writes the clipped interval
 * to *za, *zb; returns 0 when it is empty. Clipping the last interval at the surface (instead of
 * dropping or keeping it whole, as a depth test would) removes the O(Δz) error at object edges. */
SEASIM_FN int shafts_interval(int i, int n, real z_near, real z_far, real z_end, real* za, real* zb) {
  real dz = (z_far - z_near) / (real)n;
  real a = z_near + (real)i * dz;
  real b = a + dz;
  if (b > z_end) b = z_end;
  *za = a;
  *zb = b;
  return b > a;
}

/* ---- ray vs analytic objects: return the ray parameter of the first hit in (t_min, t_max), or
 * -1 when there is none. d is unit. ---- */

SEASIM_FN real ray_sphere(real3 o, real3 d, real3 c, real r, real t_min, real t_max) {
  real3 oc = o - c;
  real b = dot(oc, d);
  real cc = dot(oc, oc) - r * r;
  real disc = b * b - cc;
  if (disc < R(0.0)) return R(-1.0);
  real sq = sqrt(disc);
  /* Stable roots: q = -(b + sign(b) sq), t = q and cc/q. */
  real q = b >= R(0.0) ? -(b + sq) : -(b - sq);
  real t0 = q, t1 = q != R(0.0) ? cc / q : R(0.0);
  if (t0 > t1) {
    real tmp = t0;
    t0 = t1;
    t1 = tmp;
  }
  if (t0 > t_min && t0 < t_max) return t0;
  if (t1 > t_min && t1 < t_max) return t1;
  return R(-1.0);
}

SEASIM_FN real ray_plane(real3 o, real3 d, real3 p, real3 n, real t_min, real t_max) {
  real dn = dot(d, n);
  if (fabs(dn) < R(1e-12)) return R(-1.0);
  real t = dot(p - o, n) / dn;
  return (t > t_min && t < t_max) ? t : R(-1.0);
}

/* Slab test; *axis gets the axis (0,1,2) of the face hit, for the normal. */
SEASIM_FN real ray_box(real3 o, real3 d, real3 bmin, real3 bmax, real t_min, real t_max, int* axis) {
  real lo = -R(1e30), hi = R(1e30);
  int ax_lo = 0, ax_hi = 0;
  real oo[3] = {o.x, o.y, o.z}, dd[3] = {d.x, d.y, d.z};
  real mn[3] = {bmin.x, bmin.y, bmin.z}, mx[3] = {bmax.x, bmax.y, bmax.z};
  for (int k = 0; k < 3; ++k) {
    if (fabs(dd[k]) < R(1e-20)) {
      if (oo[k] < mn[k] || oo[k] > mx[k]) return R(-1.0);
      continue;
    }
    real inv = R(1.0) / dd[k];
    real ta = (mn[k] - oo[k]) * inv, tb = (mx[k] - oo[k]) * inv;
    if (ta > tb) {
      real tmp = ta;
      ta = tb;
      tb = tmp;
    }
    if (ta > lo) {
      lo = ta;
      ax_lo = k;
    }
    if (tb < hi) {
      hi = tb;
      ax_hi = k;
    }
  }
  if (lo > hi) return R(-1.0);
  if (lo > t_min && lo < t_max) {
    *axis = ax_lo;
    return lo;
  }
  if (hi > t_min && hi < t_max) {
    *axis = ax_hi;
    return hi;
  }
  return R(-1.0);
}

/* Outward normal of an axis-aligned box at a point p on its face `axis`. */
SEASIM_FN real3 box_normal(real3 p, real3 bmin, real3 bmax, int axis) {
  real c = axis == 0 ? p.x - R(0.5) * (bmin.x + bmax.x)
                     : (axis == 1 ? p.y - R(0.5) * (bmin.y + bmax.y) : p.z - R(0.5) * (bmin.z + bmax.z));
  real s = c >= R(0.0) ? R(1.0) : R(-1.0);
  return axis == 0 ? MAKE_REAL3(s, 0, 0) : (axis == 1 ? MAKE_REAL3(0, s, 0) : MAKE_REAL3(0, 0, s));
}
