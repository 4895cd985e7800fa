/* shafts.h — the math of spotlight shafts (paper 001) that the kernel (kernels/shafts.cl) and the
 * double CPU reference (host/reference/shafts_reference.cpp) share: the attenuation factor
 * h(s,t) of 001 eq. 6, the phase function choice of eq. 4, the spotlight's cone fall-off, the
 * exact part of a view ray inside a lamp's cone, the closed-form far-field tail of eq. 2, and ray
 * intersections with the scene's analytic objects.
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

/* A ray parameter standing for "no end": the ray leaves through the far side of the cone never, or
 * hits nothing. Finite, so relaxed-math builds compare it safely. */
#define SHAFTS_T_INF 1e30f

/* The far field starts at K r past the closest approach (r = max(h, s_min)): there the lamp sees the
 * rest of the ray within atan(1/K) = 7.1 deg, and the series of shafts_tail_from converges fast. */
#define SHAFTS_TAIL_K 8.0f

/* The part of the ray o + t d (d unit), t >= 0, inside a lamp's solid cone {q : q.axis >= cos_cone |q|,
 * q.axis > 0}, q = p - lamp. A cone of half-angle <= 90 deg is convex, so the part is one interval
 * [*t0, *t1]; *t1 = SHAFTS_T_INF when the ray never leaves. Returns 0 when the ray misses the cone.
 *   f(t) = (q.axis)^2 - cos^2 |q|^2 = A t^2 + 2 B t + C >= 0 is the double cone; the forward nappe is
 * the half-line q.axis = qa + t da > 0. With A > 0 (d inside the double cone's directions) f >= 0 off
 * (r0, r1), and the apex plane (where f = -cos^2 |q|^2 <= 0) separates the two pieces: the forward one
 * is [r1, inf) for da > 0, (-inf, r0] for da < 0. With A < 0 f >= 0 on [r0, r1]. Roots by the stable
 * form q = -(B + sign(B) sqrt(B^2 - A C)), t = q / A and C / q. A = 0 (d along the cone's surface, or a
 * 90 deg cone seen side-on) leaves the linear condition 2 B t + C >= 0. */
SEASIM_FN int shafts_cone_interval(real3 o, real3 d, real3 lamp, real3 axis, real cos_cone, real* t0, real* t1) {
  /* Solved in x = t - a about the closest approach a: there q0 = o + a d - lamp is the perpendicular
   * offset (|q0| = h), so the coefficients scale with h and not with the distance to the lamp. A ray
   * passing near the apex has two close roots; about the eye, float would lose them to cancellation
   * in B^2 - A C (an error of sqrt(eps) times the distance: 0.3 mm at 1 m, 0.2 % of the airlight). */
  real a = dot(lamp - o, d);
  real3 q0 = o + a * d - lamp;
  real da = dot(d, axis), qa = dot(q0, axis);
  real c2 = cos_cone * cos_cone;
  real A = da * da - c2, B = qa * da - c2 * dot(q0, d), C = qa * qa - c2 * dot(q0, q0);
  real lo = -a, hi = SHAFTS_T_INF; /* t >= 0 */
  if (da > R(0.0)) lo = fmax(lo, -qa / da); /* forward nappe */
  else if (da < R(0.0)) hi = fmin(hi, -qa / da);
  else if (qa <= R(0.0)) return 0;
  real disc = B * B - A * C;
  if (A == R(0.0)) {
    if (B > R(0.0)) lo = fmax(lo, -C / (R(2.0) * B));
    else if (B < R(0.0)) hi = fmin(hi, -C / (R(2.0) * B));
    else if (C < R(0.0)) return 0;
  } else if (disc <= R(0.0)) {
    if (A < R(0.0)) return 0; /* f < 0 except at one point */
    /* A > 0: f >= 0 on the whole line; the forward nappe alone decides */
  } else {
    real sq = sqrt(disc);
    real q = B >= R(0.0) ? -(B + sq) : -(B - sq);
    real r0 = q / A, r1 = C / q;
    if (r0 > r1) {
      real tmp = r0;
      r0 = r1;
      r1 = tmp;
    }
    if (A < R(0.0)) {
      lo = fmax(lo, r0);
      hi = fmin(hi, r1);
    } else if (da > R(0.0)) {
      lo = fmax(lo, r1);
    } else {
      hi = fmin(hi, r0);
    }
  }
  if (!(hi > lo)) return 0;
  *t0 = fmax(a + lo, R(0.0));
  *t1 = hi >= SHAFTS_T_INF ? SHAFTS_T_INF : a + hi;
  return *t1 > *t0;
}

/* The ray's closest approach to the lamp: *a = (lamp - o).d (the ray parameter there), *h = |(lamp - o) x d|
 * (the distance; the cross product keeps it accurate for rays aimed near the lamp). */
SEASIM_FN void shafts_closest_approach(real3 o, real3 d, real3 lamp, real* a, real* h) {
  real3 q = lamp - o;
  *a = dot(q, d);
  *h = length(cross(q, d));
}

/* e^z E_n(z), z >= 0, n >= 2: the exponential integral E_n(z) = int_1^inf e^{-z u} u^{-n} du scaled so
 * it neither overflows nor underflows (it lies between 1/(z + n) and 1/(z + n - 1)). z > 1: the
 * continued fraction of E_n evaluated by the modified Lentz method (it yields e^z E_n directly);
 * z <= 1: the power series (Abramowitz & Stegun 5.1.12), whose terms fall as z^k / k!. */
SEASIM_FN real shafts_expint_scaled(int n, real z) {
  const real eps = sizeof(real) == 8 ? R(1e-15) : R(1e-7);
  if (z <= R(0.0)) return R(1.0) / (real)(n - 1);
  if (z > R(1.0)) {
    real b = z + (real)n, c = R(1e30), d = R(1.0) / b, h = d;
    for (int i = 1; i <= 300; ++i) {
      real an = -(real)i * (real)(n - 1 + i);
      b += R(2.0);
      d = R(1.0) / (an * d + b);
      c = b + an / c;
      real del = c * d;
      h *= del;
      if (fabs(del - R(1.0)) < eps) break;
    }
    return h;
  }
  const real euler = R(0.57721566490153286);
  int nm1 = n - 1;
  real sum = R(1.0) / (real)nm1, fact = R(1.0);
  for (int i = 1; i <= 100; ++i) {
    fact *= -z / (real)i;
    real del;
    if (i != nm1) {
      del = -fact / (real)(i - nm1);
    } else {
      real psi = -euler;
      for (int k = 1; k <= nm1; ++k) psi += R(1.0) / (real)k;
      del = fact * (psi - log(z));
    }
    sum += del;
    if (i > nm1 && fabs(del) < fabs(sum) * eps) break;
  }
  return exp(z) * sum;
}

/* The far-field airlight of one lamp per unit H I_l F (001 eq. 2-3 with those three frozen):
 *   rho int_x^inf exp(-sigma_t (s + t)) / s^2 dx',  x = t - a >= SHAFTS_TAIL_K h,
 * where a, h are the closest approach (shafts_closest_approach), s = sqrt(x^2 + h^2), t = a + x.
 * With w = x + s (so s + t = a + w, x = (w^2 - h^2) / 2w, s = (w^2 + h^2) / 2w, dt / s^2 = 2 dw / (w^2 + h^2)):
 *   = 2 rho exp(-sigma_t (s + t)) int_0^inf exp(-sigma_t v) / ((w + v)^2 + h^2) dv
 *   = 2 rho exp(-sigma_t (s + t)) [e^z E_2(z) / w - h^2 e^z E_4(z) / w^3 + ...],  z = sigma_t w,
 * from 1/(w^2 + h^2) = 1/w^2 - h^2/w^4 + h^4/w^6 ...; w >= 2 K h drops terms below (1/2K)^4 = 1.5e-5 of it.
 * sigma_t = 0: e^0 E_n(0) = 1/(n - 1), the 1/w form. Never NaN/Inf: x > 0, w > 0. */
SEASIM_FN real shafts_tail_from(real x, real a, real h, real rho, real sigma_t) {
  real s = sqrt(x * x + h * h);
  real w = x + s;
  real z = sigma_t * w;
  real inv = R(1.0) / w;
  return R(2.0) * rho * exp(-(sigma_t * (s + a + x))) *
         (shafts_expint_scaled(2, z) * inv - h * h * inv * inv * inv * shafts_expint_scaled(4, z));
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
