/* optics.h — the interface and medium optics every model shares: Fresnel reflectance, Snell
 * refraction, mirror reflection, phase functions (Henyey–Greenstein; the shafts paper's
 * 1 + 9 cos^16 lobe), Beer–Lambert transmittance, and the stable (e^x - 1)/x.
 *
 * Written against compat.h (real, real3, R(), MAKE_REAL3, SEASIM_FN); compiled as OpenCL C in the
 * kernels and as C++ in float and double on the host (host/math/kernel_math.h). No include guards
 * and no #include here on purpose (compat.h explains why).
 *
 * Conventions: directions are unit vectors pointing the way light travels; cosines are of angles
 * to the surface normal; eta = n1/n2 with n1 the medium the light arrives in.
 *
 * Stiff cases handled (DESIGN.md "Numerical stability"):
 *   - Fresnel at normal incidence: the sin/tan form of 004 eq. 44 is 0/0 at θ = 0 (the Tessendorf
 *     shader special-cases it); the amplitude form below in cos θi, cos θt has no 0/0 anywhere.
 *   - total internal reflection and the critical angle: R -> 1 continuously, R = 1 beyond.
 *   - grazing incidence: R -> 1.
 *   - Henyey–Greenstein with |g| -> 1: 1 - g^2 and the denominator written as sums of
 *     non-negative terms, so neither cancels near the forward/backward spike.
 *   - (e^x - 1)/x at x -> 0: a Taylor series instead of 0/0, selected without a branch.
 */

/* ---------------------------------------------------------------------------------------------
 * Snell's law (004 eq. 38–40): n1 sin θi = n2 sin θt, so
 *   cos²θt = 1 - eta² (1 - cos²θi),   eta = n1/n2.
 * Negative means no transmitted ray (total internal reflection). (1 - c)(1 + c) keeps sin²θi exact
 * to rounding near normal incidence, where 1 - c*c would lose half the digits.
 */
SEASIM_FN real snell_cos_t2(real cos_i, real eta) {
  real c = clamp(fabs(cos_i), R(0.0), R(1.0));
  real sin_i2 = (R(1.0) - c) * (R(1.0) + c);
  return R(1.0) - eta * eta * sin_i2;
}

/* Unpolarised Fresnel reflectance of a smooth dielectric interface for light arriving in medium
 * n1 and meeting medium n2, at cos θi = |cos_i| (either sign accepted; clamped to [0,1]).
 *
 * 004 eq. 44 writes R = ½ [sin²(θt-θi)/sin²(θt+θi) + tan²(θt-θi)/tan²(θt+θi)], which is 0/0 at
 * θi = 0. The same quantity in amplitude form (Fresnel's equations),
 *   r_s = (n1 cos θi - n2 cos θt) / (n1 cos θi + n2 cos θt)
 *   r_p = (n2 cos θi - n1 cos θt) / (n2 cos θi + n1 cos θt),   R = ½ (r_s² + r_p²),
 * has denominators > 0 whenever a transmitted ray exists (both cosines >= 0, not both 0), gives
 * ((n1-n2)/(n1+n2))² at θi = 0 exactly, and tends to 1 as cos θt -> 0 (critical angle) and as
 * cos θi -> 0 (grazing), so it joins the TIR branch (R = 1) continuously. T = 1 - R (004 eq. 43).
 */
SEASIM_FN real fresnel_reflectance(real cos_i, real n1, real n2) {
  real c_i = clamp(fabs(cos_i), R(0.0), R(1.0));
  real cos_t2 = snell_cos_t2(c_i, n1 / n2);
  /* cos θt = 0 counts as TIR (R = 1, the limit from both sides): with cos θi = 0 too (grazing
   * between equal indices) the amplitude form would be 0/0. */
  if (cos_t2 <= R(0.0)) return R(1.0);
  real c_t = sqrt(cos_t2);
  real rs = (n1 * c_i - n2 * c_t) / (n1 * c_i + n2 * c_t);
  real rp = (n2 * c_i - n1 * c_t) / (n2 * c_i + n1 * c_t);
  return R(0.5) * (rs * rs + rp * rp);
}

/* Mirror reflection of direction d about unit normal n (004 eq. 37); either orientation of n. */
SEASIM_FN real3 reflect_dir(real3 d, real3 n) { return d - (R(2.0) * dot(d, n)) * n; }

/* Refraction of the unit direction `incident` through a surface with unit normal `normal`
 * (either orientation: it is turned to face the incoming light), eta = n1/n2 (004 eq. 41–42):
 *   t = eta d + (eta cos θi - cos θt) n,   cos θi = -d·n >= 0.
 * |t|² = eta² sin²θi + cos²θt = 1 by Snell, so t is unit without renormalising.
 * Returns 1 and writes t to *out; on total internal reflection returns 0 and writes the mirror
 * direction instead, so *out is always a valid direction.
 */
/* The same through a normal n already facing the incoming light, cos_i = -incident·n in [0, 1] given: a
 * caller whose normal faces by construction (a normal bent to grazing, sea_waves.h) passes its own
 * cos_i, clamped at 0, so that rounding cannot turn n over. */
SEASIM_FN int refract_facing_dir(real3 incident, real3 n, real cos_i, real eta, real3* out) {
  real cos_t2 = snell_cos_t2(cos_i, eta);
  if (cos_t2 < R(0.0)) {
    *out = reflect_dir(incident, n);
    return 0;
  }
  real cos_t = sqrt(cos_t2);
  *out = eta * incident + (eta * cos_i - cos_t) * n;
  return 1;
}

SEASIM_FN int refract_dir(real3 incident, real3 normal, real eta, real3* out) {
  real cos_i = -dot(incident, normal);
  real3 n = normal;
  if (cos_i < R(0.0)) {
    n = -normal;
    cos_i = -cos_i;
  }
  return refract_facing_dir(incident, n, fmin(cos_i, R(1.0)), eta, out);
}

/* ---------------------------------------------------------------------------------------------
 * Henyey–Greenstein phase function, normalised over the sphere (∫ p dΩ = 1), mean cosine g:
 *   p(cos θ) = (1 - g²) / (4π (1 + g² - 2 g cos θ)^{3/2}).
 * Near |g| = 1 both numerator and denominator cancel catastrophically if written as above. We use
 *   1 - g² = (1 - g)(1 + g)
 *   1 + g² - 2 g c = (1 - g)² + 2 g (1 - c)        for g >= 0
 *                  = (1 + g)² + 2 (-g) (1 + c)     for g <  0
 * each a sum of non-negative terms, so the only 0/0 left is the spike itself (|g| = 1 and
 * cos θ = sign g), where p is a delta. cos_theta is clamped to [-1, 1].
 */
SEASIM_FN real hg_phase(real cos_theta, real g) {
  real c = clamp(cos_theta, R(-1.0), R(1.0));
  real num = (R(1.0) - g) * (R(1.0) + g);
  real den;
  if (g >= R(0.0)) {
    den = (R(1.0) - g) * (R(1.0) - g) + R(2.0) * g * (R(1.0) - c);
  } else {
    den = (R(1.0) + g) * (R(1.0) + g) - R(2.0) * g * (R(1.0) + c);
  }
  return num / (R(4.0) * SEASIM_PI * den * sqrt(den));
}

/* ---------------------------------------------------------------------------------------------
 * The shafts paper's particle phase function (001 eq. 4): F(α) = K (1 + 9 cos^16(α/2)), α the
 * phase angle. The paper leaves K to the user as an intensity scale; we fix K so that F is a
 * normalised phase function (∫ F dΩ = 1) and let the scene's scattering coefficient carry the
 * intensity. Derivation, with u = cos α and cos²(α/2) = (1 + u)/2:
 *   ∫ F dΩ = 2π K ∫_{-1}^{1} (1 + 9 ((1+u)/2)^8) du
 *          = 2π K (2 + 9 · 2 ∫_0^1 v^8 dv)          (v = (1+u)/2, du = 2 dv)
 *          = 2π K (2 + 2) = 8π K   =>   K = 1/(8π).
 * So F(0) = 10/(8π), F(π) = 1/(8π), F(0)/F(π) = 10.
 */
#define SEASIM_SHAFTS_K (R(1.0) / (R(8.0) * SEASIM_PI))

/* F from cos α: cos^16(α/2) = ((1 + cos α)/2)^8 by three squarings (no pow, exact at α = π). */
SEASIM_FN real shafts_phase_cos(real cos_alpha) {
  real h = clamp(R(0.5) * (R(1.0) + cos_alpha), R(0.0), R(1.0)); /* cos²(α/2) */
  real h2 = h * h;
  real h4 = h2 * h2;
  real h8 = h4 * h4;
  return SEASIM_SHAFTS_K * (R(1.0) + R(9.0) * h8);
}

/* F from the angle α itself (001 eq. 4 as written). */
SEASIM_FN real shafts_phase(real alpha) {
  real c = cos(R(0.5) * alpha); /* cos(α/2) */
  real c2 = c * c;
  real c4 = c2 * c2;
  real c8 = c4 * c4;
  return SEASIM_SHAFTS_K * (R(1.0) + R(9.0) * c8 * c8);
}

/* ---------------------------------------------------------------------------------------------
 * Beer–Lambert transmittance through a homogeneous medium: T = exp(-σ d), σ in m⁻¹, d in m.
 * σ d -> ∞ underflows to 0 (never NaN for finite inputs); σ = 0 or d = 0 gives exactly 1.
 */
SEASIM_FN real beer_lambert(real sigma, real distance) { return exp(-(sigma * distance)); }

/* φ(x) = (e^x - 1)/x with its removable singularity at 0 filled (φ(0) = 1), for closed forms such as
 * 002 eq. 4.7, 000 eq. 5 and the froxel slices of 002 eq. 5.2, where the exponent can vanish.
 *
 * Branch-free, because it sits in the band loops of every model: both sides are computed and one is
 * selected, so a vectorising compiler (PoCL's work-group vectoriser, a GPU warp) runs one straight
 * line, and only exp is called (PoCL's expm1 is a scalar library call, about 12x its exp).
 *   |x| <  0.5: the Taylor series φ(x) = Σ_{n>=0} x^n/(n+1)!, by Horner. Truncated after x^7 in float
 *               (next term 0.5^8/9! = 1.1e-8 of φ >= 0.79) and after x^13 in double (0.5^14/15! =
 *               4.7e-17); the precision is a compile-time constant (sizeof), so one of the two
 *               polynomials is dead code.
 *   |x| >= 0.5: (e^x - 1)/x. e^x - 1 cancels at most by e^0.5/(e^0.5 - 1) = 2.5 there (0.5 ulp of e^x
 *               become 1.3 ulp of φ) and the subtraction itself is exact (Sterbenz), so a few ulp.
 * The discarded side is kept finite: exp sees 1 where |x| < 0.5 (no 0/0 at x = 0).
 * Large |x|: x -> -∞ gives -1/x -> +0 (exp underflows to 0); e^x overflows to +Inf at the same x as
 * expm1 does (e^x - 1 rounds to e^x there), ~88.7 in float and ~709.8 in double, so no input that
 * gave a finite φ before gives Inf now. Every model calls it with x <= 0.
 */
/* The Taylor series of (e^x - 1)/x that expm1_over_x uses below |x| = 0.5 (13 terms in double, 8 in
 * float), as a macro so that the band-vector version (band_lanes_math.h, expm1_over_x_b) shares it. */
#define SEASIM_EXPM1_OVER_X_SERIES(x) \
  (sizeof(real) > 4 \
   ? R(1.0) + \
   (x) * (R(1.0) / R(2.0) + \
   (x) * (R(1.0) / R(6.0) + \
   (x) * (R(1.0) / R(24.0) + \
   (x) * (R(1.0) / R(120.0) + \
   (x) * (R(1.0) / R(720.0) + \
   (x) * (R(1.0) / R(5040.0) + \
   (x) * (R(1.0) / R(40320.0) + \
   (x) * (R(1.0) / R(362880.0) + \
   (x) * (R(1.0) / R(3628800.0) + \
   (x) * (R(1.0) / R(39916800.0) + \
   (x) * (R(1.0) / R(479001600.0) + \
   (x) * (R(1.0) / R(6227020800.0) + \
   (x) * (R(1.0) / R(87178291200.0)))))))))))))) \
   : R(1.0) + \
   (x) * (R(1.0) / R(2.0) + \
   (x) * (R(1.0) / R(6.0) + \
   (x) * (R(1.0) / R(24.0) + \
   (x) * (R(1.0) / R(120.0) + \
   (x) * (R(1.0) / R(720.0) + (x) * (R(1.0) / R(5040.0) + (x) * (R(1.0) / R(40320.0)))))))))

SEASIM_FN real expm1_over_x(real x) {
  const real series = SEASIM_EXPM1_OVER_X_SERIES(x);
  const int small = fabs(x) < R(0.5);
  const real xs = small ? R(1.0) : x;
  const real direct = (exp(xs) - R(1.0)) / xs;
  return small ? series : direct;
}

/* 1 - e^{-y} for y >= 0 (finite), without cancellation as y -> 0: y φ(-y), which is -expm1(-y) to a
 * few ulp, through the branch-free expm1_over_x instead of PoCL's scalar expm1 call. 0 at y = 0,
 * -> 1 as y grows (φ(-y) = 1/y to rounding once e^{-y} underflows). */
SEASIM_FN real one_minus_exp_neg(real y) { return y * expm1_over_x(-y); }
