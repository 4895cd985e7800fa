/* underwater_lamps.h — spotlights in the water's spectral medium: paper 001's sampling planes with
 * the water's per-band σ_s, σ_t and its Henyey–Greenstein phase function in place of 001 eq. 3–4,
 * shared by kernels/underwater_lamps.cl, the unit tests (float and double) and the kernel test's
 * double CPU evaluation.
 *
 * Along a view ray o + t d, per lamp with spectral intensity I(λ) (W sr⁻¹ nm⁻¹ on its axis) and
 * angular profile P (common/shafts.h, shafts_cone_profile), the light scattered once towards the eye is
 *   L_s(λ) = I(λ) ∫_{t0}^{t1} H(t) P(t) σ_s(λ) p_HG(cos α) e^{-σ_t(λ) (s + t)} / s² dt      (001 eq. 2–3)
 * over the exact part [t0, t1] of the ray inside the lamp's cone, up to the first surface (S from the
 * G-buffer). H is the visibility of the lamp (exact shadow rays), s the distance to the lamp, α the
 * scattering angle. The geometry (the planes, H P at the sub-samples, s, t, cos α) does not depend on
 * λ; only σ_s, σ_t and I do. So the planes are placed once per lamp and pixel (uw_lamp_span) and each
 * band costs one exp per plane (uw_lamp_plane_g): no 2-D h(s, t) table, which would have to be built
 * per band. Beyond K r past the closest approach (r its distance) the far field takes UW_LAMP_TAIL_SAMPLES
 * more samples, evenly in the angle the lamp sees (uw_lamp_tail_weight), whose band-free weights join the
 * planes' in the same band lanes. Air's closed form there (common/shafts.h, shafts_tail_from with ρ =
 * σ_s(λ), ρκ = σ_t(λ)) freezes the phase at the far field's middle angle and costs two exponential
 * integrals per band and end, scalar: in the water, with its bands, that was a quarter of the pass.
 *
 * A lit surface (an object or the bottom, albedo ρ_b(λ), normal n) adds the lamp's direct light:
 *   L_o(λ) = ρ_b(λ)/π I(λ) P H cos θ_n e^{-σ_t(λ) s} / s²  seen through e^{-σ_t(λ) S}   (001 eq. 1)
 * The lamp's light scattered more than once, and its reflection off the surface from below, are left
 * out; the path tracer (kernels/reference.cl) has them, so they are part of the measured error.
 *
 * Stiff cases: s -> 0 (1/s² clamped at s_min, the lamp's radius); σ_t (s + t) large (exp underflows to
 * 0); a cone of 0.1° (the interval is exact, so the planes still fall inside it); |g| -> 1 (hg_phase's
 * stable form, optics.h); a lamp inside an object (every shadow ray is blocked: H = 0).
 *
 * Written against compat.h; needs gauss_legendre.h, optics.h and shafts.h before it (kernel_math.h orders the
 * headers).
 */

/* One lamp along one view ray: the sampling-plane interval [ta, tp] and the far field [tp, tb]. */
typedef struct {
  real ta, tp, tb; /* ray parameters */
  real a, h, r;    /* closest approach: parameter, distance, max(h, s_min) */
  real dt;         /* plane spacing (tp - ta) / n */
  real phi_p, phi_b; /* far field: the angles the lamp sees its ends at */
  int tail;        /* 1: a far field [tp, tb] exists */
  int infinite;    /* 1: tb is infinite (the ray never leaves the cone and hits nothing) */
} UwLampSpan;

/* The span of one lamp on the ray o + t d, t in [0, t_end]; 0 when the ray misses the cone. */
SEASIM_FN int uw_lamp_span(real3 o, real3 d, real3 lamp, real3 axis, real cos_cone, real s_min, real t_end, int planes,
                           UwLampSpan* sp) {
  real ta, tb;
  if (!shafts_cone_interval(o, d, lamp, axis, cos_cone, &ta, &tb)) return 0;
  tb = fmin(tb, t_end);
  if (!(tb > ta)) return 0;
  real a, h;
  shafts_closest_approach(o, d, lamp, &a, &h);
  const real r = fmax(h, s_min);
  const real tp = fmin(tb, fmax(ta, a + (real)SHAFTS_TAIL_K * r));
  sp->ta = ta;
  sp->tp = tp;
  sp->tb = tb;
  sp->a = a;
  sp->h = h;
  sp->r = r;
  sp->dt = (tp - ta) / (real)planes;
  sp->tail = tb > tp;
  sp->infinite = tb >= (real)SHAFTS_T_INF;
  sp->phi_p = atan((tp - a) / r);
  sp->phi_b = sp->infinite ? R(0.5) * SEASIM_PI : atan((tb - a) / r);
  return 1;
}

/* Ray parameter of sub-sample j (of m) of plane interval i (001 eq. 7–9). */
SEASIM_FN real uw_lamp_subsample_t(const UwLampSpan* sp, int i, int j, int m) {
  return sp->ta + (real)i * sp->dt + ((real)j + R(0.5)) * sp->dt / (real)m;
}

/* The lamp's profile P towards a point p (0 outside the cone or behind the lamp). */
SEASIM_FN real uw_lamp_profile(real3 p, real3 lamp, real3 axis, real cos_cone, real cos_inner) {
  const real3 q = p - lamp;
  const real s = length(q);
  if (!(s > R(0.0))) return R(0.0);
  const real c = dot(q, axis) / s;
  if (c <= R(0.0)) return R(0.0);
  return shafts_cone_profile(c, cos_cone, cos_inner);
}

/* Distance to the lamp and cosine of the scattering angle at ray parameter t (cos α = 1: the lamp's
 * light travels straight on towards the eye). */
SEASIM_FN void uw_lamp_at(real3 o, real3 d, real3 lamp, real t, real* s, real* cos_alpha) {
  const real3 w = o + t * d - lamp;
  *s = length(w);
  *cos_alpha = *s > R(0.0) ? dot(w, -d) / *s : R(1.0);
}

/* The band-free part of uw_lamp_plane_g (001 eq. 3's g): p_HG(cos α) / max(s, s_min)², so
 * that a kernel can sum the planes of all bands at once (kernels/underwater_lamps.cl, lamp_beam_block). */
SEASIM_FN real uw_lamp_plane_weight(real hg_g, real s, real cos_alpha, real s_min) {
  const real sc = fmax(s, s_min);
  return hg_phase(cos_alpha, hg_g) / (sc * sc);
}

/* g of 001 eq. 3 in water for one band: σ_s p_HG(cos α) e^{-σ_t (s + t)} / max(s, s_min)², sr⁻¹ m⁻³. */
SEASIM_FN real uw_lamp_plane_g(real sigma_s, real sigma_t, real hg_g, real s, real t, real cos_alpha, real s_min) {
  return uw_lamp_plane_weight(hg_g, s, cos_alpha, s_min) * shafts_h_scaled(s, t, sigma_s, sigma_t);
}

/* The far field [tp, tb] by 8-point Gauss–Legendre in the angle φ the lamp sees (t = a + r tan φ, φ_p to
 * φ_b; φ_b = π/2 for an infinite ray): sample j (0..UW_LAMP_TAIL_SAMPLES - 1) lies at *t and has the
 * band-free weight
 *   p_HG(cos α_j) (dt/dφ) Δφ_j / s_j² = p_HG(cos α_j) r (1 + tan² φ_j) Δφ_j / s_j²
 * (times its H P), Δφ_j the rule's weight over the range, and its path length s_j + t_j into *x; the
 * band's part is σ_s e^{-σ_t x}, as a plane's. Every sample lies K r or more past the closest approach,
 * so s_j >= K r >= s_min and nothing is clamped. In φ the integrand, e^{-σ_t r (sec φ + tan φ)} times a
 * slowly turning phase, is smooth and falls to 0 with every derivative at π/2; against the closed form
 * under an isotropic phase the rule is within 1e-4 of the whole ray's in-scatter (underwater_lamps_math_test).
 */
#define UW_LAMP_TAIL_SAMPLES 8
SEASIM_FN real uw_lamp_tail_weight(const UwLampSpan* sp, int j, real hg_g, real3 o, real3 d, real3 lamp, real* t,
                                   real* x) {
  real w;
  const real half_range = R(0.5) * (sp->phi_b - sp->phi_p);
  const real tan_phi = tan(sp->phi_p + half_range * (R(1.0) + gauss_legendre8_node(j, &w)));
  *t = sp->a + sp->r * tan_phi;
  real s, c;
  uw_lamp_at(o, d, lamp, *t, &s, &c);
  *x = s + *t;
  return hg_phase(c, hg_g) * sp->r * (R(1.0) + tan_phi * tan_phi) * half_range * w / fmax(s * s, R(1e-30));
}

/* L_s per unit I(λ) for one band without shadows (H = 1): n planes, m sub-samples, the far field's
 * samples. The
 * kernel runs the same steps with H from shadow rays and the bands innermost; tests use this one. */
SEASIM_FN real uw_lamp_inscatter(real3 o, real3 d, real3 lamp, real3 axis, real cos_cone, real cos_inner, real s_min,
                                 real t_end, real sigma_s, real sigma_t, real hg_g, int planes, int m) {
  UwLampSpan sp;
  if (!uw_lamp_span(o, d, lamp, axis, cos_cone, s_min, t_end, planes, &sp)) return R(0.0);
  real acc = R(0.0);
  for (int i = 0; i < planes && sp.dt > R(0.0); ++i) {
    real J = R(0.0);
    for (int j = 0; j < m; ++j) J += uw_lamp_profile(o + uw_lamp_subsample_t(&sp, i, j, m) * d, lamp, axis, cos_cone, cos_inner);
    if (J <= R(0.0)) continue;
    real s, c;
    const real t = sp.ta + ((real)i + R(0.5)) * sp.dt;
    uw_lamp_at(o, d, lamp, t, &s, &c);
    acc += J / (real)m * uw_lamp_plane_g(sigma_s, sigma_t, hg_g, s, t, c, s_min) * sp.dt;
  }
  for (int j = 0; sp.tail && j < UW_LAMP_TAIL_SAMPLES; ++j) {
    real t, x;
    const real w = uw_lamp_tail_weight(&sp, j, hg_g, o, d, lamp, &t, &x);
    const real P = uw_lamp_profile(o + t * d, lamp, axis, cos_cone, cos_inner);
    if (P > R(0.0)) acc += P * w * sigma_s * exp(-(sigma_t * x));
  }
  return acc;
}

/* The band-free part of uw_lamp_surface: P H cos θ_n / (π max(s, s_min)²), with the lamp's distance s
 * into *s_out (0 and 0 where no light arrives). A band loop takes it once and one exp per band. */
SEASIM_FN real uw_lamp_surface_geometry(real3 p, real3 n, real3 lamp, real3 axis, real cos_cone, real cos_inner,
                                        real s_min, real vis, real* s_out) {
  const real3 to_lamp = lamp - p;
  const real s = length(to_lamp);
  *s_out = R(0.0);
  if (!(s > R(0.0)) || vis <= R(0.0)) return R(0.0);
  const real cos_n = dot(n, to_lamp) / s;
  if (cos_n <= R(0.0)) return R(0.0);
  const real profile = uw_lamp_profile(p, lamp, axis, cos_cone, cos_inner);
  if (profile <= R(0.0)) return R(0.0);
  const real sc = fmax(s, s_min);
  *s_out = s;
  return vis * profile * cos_n / (SEASIM_PI * sc * sc);
}

/* The lamp's direct light on a Lambertian point at distance S from the eye, per unit I(λ) and albedo:
 * P H cos θ_n e^{-σ_t (s + S)} / (π max(s, s_min)²), cos θ_n the cosine between the normal and the
 * lamp (0 when the lamp is behind the surface). `vis` is H. */
SEASIM_FN real uw_lamp_surface(real3 p, real3 n, real S, real3 lamp, real3 axis, real cos_cone, real cos_inner,
                               real s_min, real sigma_t, real vis) {
  real s;
  const real geometry = uw_lamp_surface_geometry(p, n, lamp, axis, cos_cone, cos_inner, s_min, vis, &s);
  return geometry > R(0.0) ? geometry * exp(-(sigma_t * (s + S))) : R(0.0);
}
