/* fourflow.h — the four-flow light field of shallow water (paper 003, Belyaev, "Real-time rendering
 * of shallow water"), per wavelength band, shared by kernels and host (kmath_f / kmath_d, unit-tested
 * in float and double against a numerical boundary-value solve of the ODEs in tests/unit/).
 * Needs optics.h (fresnel_reflectance, expm1_over_x) and gauss_legendre.h before it.
 *
 * The model (003 eq. 4), optical depth τ = ε z downwards from the surface, ε = χ + σ:
 *   dG+/dτ = -λ G+                       dG-/dτ =  λ G-                         λ = k + S1 + S2
 *   dF+/dτ = -(k+S) F+ + S F- + S1 G+ + S2 G-
 *   dF-/dτ =  (k+S) F- - S F+ - S1 G- - S2 G+
 * with k = χ/ε, S = σ/ε (1 - X1/2), S1 = σ/(2ε)(1 + X1), S2 = σ/(2ε)(1 - X1). X1 is the first
 * Legendre coefficient of the normalised phase function, taken here as its mean cosine g ∈ [-1, 1]
 * (so S1, S2 >= 0 and S1 + S2 = σ/ε, which makes λ = 1 as the paper states).
 * Boundary conditions (003 eq. 7) at the surface τ = 0 and the bottom τ0 = ε h:
 *   G+(0)  = T_dd E_sun + R~_dd G-(0)
 *   F+(0)  = T_df E_sun + T_ff E_sky + R~_df G-(0) + R~_ff F-(0)
 *   G-(τ0) = R^_dd G+(τ0)
 *   F-(τ0) = R^_df G+(τ0) + R^_ff F+(τ0)
 *
 * The paper's closed form (003 eq. 5, 8, 9) and why it is not evaluated as printed:
 *   - eq. 5 prints e^{-λ0 τ} for both C2 and C3; the diffuse system's modes are e^{-λ0 τ} with
 *     F-/F+ = A3 and e^{+λ0 τ} with F-/F+ = A4 = 1/A3, so C3 belongs to e^{+λ0 τ}. (Checked: the
 *     eigenvector of the diffuse matrix for -λ0 is (1, (k+S-λ0)/S) = (1, A3).)
 *   - eq. 8 is consistent with eq. 7 only if D = e^{+λτ0}; with D = e^{-λτ0} as printed it is
 *     C1 = T_dd E_sun / (1 - R^_dd R~_dd D²). Eq. 9's first row reads R_ff where R~_ff is meant.
 *   - deep water: e^{λ τ0} and e^{λ0 τ0} overflow (float at τ0 ≈ 88) and e^{-λτ0} underflows, and
 *     their products are what eq. 9 needs: 1/D0 · D0 = 1 computed as Inf · 0.
 *   - λ0 -> λ: A1, A2 = (...)/(λ0² - λ²) diverge. With X1 < 0 this happens inside the physical
 *     range (k = 1/(1 - X1)), where the forced solution becomes τ e^{-λτ} (resonance).
 *   - k -> 0 (no absorption): λ0 -> 0 and A3 -> 1, the two diffuse modes coalesce (a Jordan block:
 *     F± become linear in τ), so a basis (1, A3) e^{-λ0τ}, (A3, 1) e^{λ0τ} is singular there.
 * The rescaled form used below is the same solution, written so that none of that happens:
 *   - the upward beam is referred to the bottom: G-(τ) = C4s e^{-λ(τ0 - τ)} (C4s = C4 e^{λτ0});
 *   - the diffuse flows in sum and difference, s = F+ + F-, w = F+ - F-, for which eq. 4 reads
 *       s' = -a w + Δ (G+ - G-),   w' = -k s + Σ (G+ + G-),   a = k + 2S, Σ = S1 + S2, Δ = S1 - S2,
 *     so s'' = λ0² s with λ0² = k a;
 *   - homogeneous part in the two-point basis f(x) = sinh(λ0 x)/sinh(λ0 τ0) (1 at one end, 0 at
 *     the other): s_h(τ) = α f(τ0 - τ) + β f(τ), w_h = -s_h'/a. Written as e^{-λ0 (τ0 - x)} times a
 *     ratio of (1 - e^{-2λ0 x})/(2λ0) = x φ(-2λ0 x) (φ = expm1_over_x): every exponential has a
 *     non-positive argument (no overflow), and λ0 -> 0 gives x/τ0 (no 0/0);
 *   - particular part for G+ = e^{-λτ}: the paper's (A1, A2) e^{-λτ} minus the homogeneous solution
 *     with the same s-amplitude on the e^{-λ0 τ} mode. In s it is
 *       s_p(τ) = (λΔ + aΣ)/(λ0 + λ) · Φ(τ),   Φ(τ) = (e^{-λτ} - e^{-λ0τ})/(λ0 - λ) = τ e^{-mτ} φ(-|λ0-λ| τ)
 *     (m = min(λ, λ0)), a divided difference that tends to τ e^{-λτ} as λ0 -> λ instead of 0/0, and
 *       w_p(τ) = [(λ0 Σ + λ λ0 Δ/a) Φ(τ) - (Σ - λ0 Δ/a) e^{-λτ}] / (λ0 + λ).
 *     The G- forcing is its mirror image (τ -> τ0 - τ, F+ <-> F-: s unchanged, w negated).
 * The outgoing diffuse flows F-(0) and F+(τ0) come from adding the layer (its Kubelka–Munk reflectance
 * and transmittance, and the beams' emergent flows between black boundaries) to the two boundaries, a
 * 2×2 system whose determinant and right-hand sides are sums of non-negative terms (C² - E² = λ0²;
 * see ff_solve); α, β and the incoming flows then follow from the boundary conditions. This keeps a
 * small F-(0) (thin water over a dark bottom) to float's relative precision: 1e-6 relative in float
 * against the double reference over the test grids (tests/unit/fourflow_math_test.cpp).
 *
 * Stiff cases handled, each tested in tests/unit/fourflow_math_test.cpp:
 *   - τ0 = 50, 200, 1e4: no overflow, no Inf·0; F-(0) tends to the semi-infinite solution;
 *   - λ0 -> λ and λ0 = λ exactly: Φ is finite and continuous;
 *   - k = 0: λ0 = 0, f(x) = x/τ0; net flux is conserved;
 *   - τ0 -> 0: τ0 is clamped to FF_TAU0_MIN (an optical depth of 1e-12; the error this causes is of
 *     that relative order), so the upwelling is the bottom's reflection of the incoming light.
 * Requirement: a = k + 2S > 0 (always true for the paper's constants: a >= 1 when |X1| <= 1).
 */

/* The thinnest water column solved (optical depth); see the header comment. */
#define FF_TAU0_MIN R(1e-12)

/* The ODE constants of 003 eq. 4 for one band. */
typedef struct {
  real k;  /* absorption over extinction, χ/ε */
  real S;  /* back-scattering of the diffuse flows */
  real S1; /* forward scattering of the directional flows into the diffuse flow of the same sense */
  real S2; /* backward scattering of the directional flows into the opposite diffuse flow */
} FfMedium;

/* 003 eq. 4 text: the constants from χ (absorption, m⁻¹), σ (scattering, m⁻¹) and X1 (mean cosine of
 * the phase function, [-1, 1]). ε = χ + σ must be > 0 (the caller's water always absorbs). */
SEASIM_FN FfMedium ff_medium(real chi, real sigma, real x1) {
  const real eps = chi + sigma;
  const real albedo = sigma / eps;
  FfMedium m;
  m.k = chi / eps;
  m.S = albedo * (R(1.0) - R(0.5) * x1);
  m.S1 = R(0.5) * albedo * (R(1.0) + x1);
  m.S2 = R(0.5) * albedo * (R(1.0) - x1);
  return m;
}

/* λ = k + S1 + S2 (= 1 for ff_medium's constants) and λ0 = sqrt(k (k + 2S)) (003 eq. 5). */
SEASIM_FN real ff_lambda(FfMedium m) { return m.k + m.S1 + m.S2; }
SEASIM_FN real ff_lambda0(FfMedium m) { return sqrt(m.k * (m.k + R(2.0) * m.S)); }

/* The paper's A1…A4 (003 eq. 5) as printed: singular at λ0 = λ (A1, A2) and A4 at S = 0. Used by the
 * tests to check that the rescaled solution is the paper's where the paper's is well conditioned. */
SEASIM_FN real ff_A1(FfMedium m) {
  const real l = ff_lambda(m), l0 = ff_lambda0(m);
  return (m.S * m.S2 + (l + m.k + m.S) * m.S1) / ((l0 - l) * (l0 + l));
}
SEASIM_FN real ff_A2(FfMedium m) {
  const real l = ff_lambda(m), l0 = ff_lambda0(m);
  return (m.S * m.S1 + (-l + m.k + m.S) * m.S2) / ((l0 - l) * (l0 + l));
}
SEASIM_FN real ff_A3(FfMedium m) {
  const real a = m.k + R(2.0) * m.S, l0 = ff_lambda0(m);
  return (a - l0) / (a + l0);
}
SEASIM_FN real ff_A4(FfMedium m) { return R(1.0) / ff_A3(m); }

/* Air–water coefficients of 003 eq. 6–7. "_w" is the paper's "~" (light meeting the surface from
 * below); R + T = 1 from each side (eq. 6), so only reflectances and the two transmittances that
 * enter eq. 7 are stored. */
typedef struct {
  real T_dd, T_df, T_ff;    /* air -> water: direct->direct, direct->diffuse, diffuse->diffuse */
  real Rw_dd, Rw_df, Rw_ff; /* water -> water (reflected back down from below the surface) */
} FfSurface;

/* Bottom reflectances of eq. 7 (R^): direct->direct (specular), direct->diffuse, diffuse->diffuse. */
typedef struct {
  real R_dd, R_df, R_ff;
} FfBottom;

/* The solved light field of one band (ff_solve); read it with ff_flows_at or the boundary values. */
typedef struct {
  FfMedium m;
  real tau0;            /* ε h, clamped to >= FF_TAU0_MIN */
  real C1;              /* G+(τ) = C1 e^{-λτ} */
  real C4s;             /* G-(τ) = C4s e^{-λ(τ0 - τ)} */
  real alpha, beta;     /* homogeneous s at the surface and at the bottom */
  real wh_top, wh_bot;  /* homogeneous w at the surface and at the bottom */
  real Fp_top, Fm_top;  /* F+(0), F-(0) */
  real Fp_bot, Fm_bot;  /* F+(τ0), F-(τ0) */
} FfSolution;

typedef struct {
  real Gp, Gm, Fp, Fm;
} FfFlows;

/* ---------------------------------------------------------------------------------------------
 * Building blocks, every exponential with a non-positive argument.
 *
 * Φ(x) = (e^{-λx} - e^{-λ0 x})/(λ0 - λ) = x e^{-m x} φ(-|λ0 - λ| x), m = min(λ, λ0): both orderings of
 * λ, λ0 give the same expression (factor e^{-m x} out, the rest is (1 - e^{-d x})/d), and λ0 = λ
 * gives x e^{-λ x}, the resonant solution. */
SEASIM_FN real ff_divided_exp(real x, real l, real l0) {
  return x * exp(-fmin(l, l0) * x) * expm1_over_x(-fabs(l0 - l) * x);
}

/* f(x) = sinh(λ0 x)/sinh(λ0 τ0), 0 <= x <= τ0, τ0 > 0:
 *   sinh(λ0 x) = e^{λ0 x} λ0 x φ(-2λ0 x), so f = e^{-λ0 (τ0 - x)} x φ(-2λ0 x) / (τ0 φ(-2λ0 τ0)). */
SEASIM_FN real ff_sinh_ratio(real x, real l0, real tau0) {
  return exp(-l0 * (tau0 - x)) * (x * expm1_over_x(-R(2.0) * l0 * x)) / (tau0 * expm1_over_x(-R(2.0) * l0 * tau0));
}

/* c(x) = f'(x) = λ0 cosh(λ0 x)/sinh(λ0 τ0) = e^{-λ0(τ0 - x)} (1 + e^{-2λ0 x}) / (2 τ0 φ(-2λ0 τ0)). */
SEASIM_FN real ff_cosh_ratio(real x, real l0, real tau0) {
  return exp(-l0 * (tau0 - x)) * (R(1.0) + exp(-R(2.0) * l0 * x)) / (R(2.0) * tau0 * expm1_over_x(-R(2.0) * l0 * tau0));
}

/* The particular diffuse solution forced by G+ = e^{-λx} (s and w parts; see the header comment).
 * Its mirror (forced by G- = e^{-λ(τ0-τ)}) is s_p(τ0 - τ), -w_p(τ0 - τ). */
SEASIM_FN real ff_particular_s(FfMedium m, real x) {
  const real l = ff_lambda(m), l0 = ff_lambda0(m);
  const real a = m.k + R(2.0) * m.S;
  const real sig = m.S1 + m.S2, del = m.S1 - m.S2;
  return (l * del + a * sig) / (l0 + l) * ff_divided_exp(x, l, l0);
}
SEASIM_FN real ff_particular_w(FfMedium m, real x) {
  const real l = ff_lambda(m), l0 = ff_lambda0(m);
  const real a = m.k + R(2.0) * m.S;
  const real sig = m.S1 + m.S2, del = m.S1 - m.S2;
  const real r = l0 / a; /* = sqrt(k/a) */
  return ((l0 * sig + l * r * del) * ff_divided_exp(x, l, l0) - (sig - r * del) * exp(-l * x)) / (l0 + l);
}

/* Two non-negative gaps of the beam's divided exponential Φ = Φ(τ0) (ff_divided_exp), E = λ0/sinh(λ0 τ0):
 *   gap_e = 1 - E Φ = E ∫_0^τ0 [sinh(λ0 y) + e^{-λ0 y}(1 - e^{-λ(τ0 - y)})] dy,
 *   gap_p = Ψ - Φ = ∫_0^τ0 e^{-λ x}(1 - e^{-λ0 (τ0 - x)}) dx,   Ψ = (1 - e^{-λτ0})/λ.
 * In thin water both are O(τ0) differences of O(1) quantities; there ((λ + λ0) τ0 <= 1) they are
 * integrated from their non-negative integrands by 8-point Gauss–Legendre (entire integrands over a
 * range of at most one e-fold: error ~1e-13), elsewhere taken as the differences. */
SEASIM_FN void ff_beam_gaps(real t0, real l, real l0, real E, real* gap_e, real* gap_p) {
  const real phi = ff_divided_exp(t0, l, l0);
  if ((l + l0) * t0 > R(1.0)) {
    *gap_e = fmax(R(1.0) - E * phi, R(0.0));
    *gap_p = fmax(t0 * expm1_over_x(-l * t0) - phi, R(0.0));
    return;
  }
  real se = R(0.0), sp = R(0.0);
  for (int i = 0; i < 8; ++i) {
    real w;
    const real y = R(0.5) * t0 * (R(1.0) + gauss_legendre8_node(i, &w));
    const real z = t0 - y;
    /* sinh(λ0 y) = λ0 y (1 + e^{-2λ0 y})/2 ... written as e^{λ0 y} λ0 y φ(-2λ0 y) (no cancellation). */
    se += w * (exp(l0 * y) * l0 * y * expm1_over_x(-R(2.0) * l0 * y) + exp(-l0 * y) * l * z * expm1_over_x(-l * z));
    sp += w * exp(-l * y) * l0 * z * expm1_over_x(-l0 * z);
  }
  *gap_e = E * R(0.5) * t0 * se;
  *gap_p = R(0.5) * t0 * sp;
}

/* ---------------------------------------------------------------------------------------------
 * 003 eq. 7–9 solved for one band: bottom at optical depth tau0 = ε h, sun and sky irradiance on a
 * horizontal plane just above the surface (e_sun, e_sky). */
SEASIM_FN FfSolution ff_solve(FfMedium m, FfSurface srf, FfBottom bot, real tau0, real e_sun, real e_sky) {
  FfSolution sol;
  sol.m = m;
  const real t0 = fmax(tau0, FF_TAU0_MIN);
  sol.tau0 = t0;
  const real l = ff_lambda(m), l0 = ff_lambda0(m);
  const real a = m.k + R(2.0) * m.S;

  /* Directional flows (eq. 8 with D = e^{-λτ0} <= 1): G-(τ0) = R^_dd G+(τ0), G+(0) = T_dd E_sun +
   * R~_dd G-(0) give C1 (1 - R~_dd R^_dd D²) = T_dd E_sun; the denominator is >= 1 - R R > 0. */
  const real D = exp(-l * t0);
  sol.C1 = srf.T_dd * e_sun / (R(1.0) - srf.Rw_dd * bot.R_dd * D * D);
  sol.C4s = bot.R_dd * D * sol.C1;
  const real gm_top = sol.C4s * D; /* G-(0) */
  const real gp_bot = sol.C1 * D;  /* G+(τ0) */

  /* Diffuse sources of the two boundary conditions. */
  const real src_top = srf.T_df * e_sun + srf.T_ff * e_sky + srf.Rw_df * gm_top;
  const real src_bot = bot.R_df * gp_bot;
  const real Rt = srf.Rw_ff, Rb = bot.R_ff;

  /* Particular solution at the two ends (Φ(0) = 0, so s_p has only the mirrored term at τ = 0). */
  const real sp_top = sol.C4s * ff_particular_s(m, t0);
  const real wp_top = sol.C1 * ff_particular_w(m, R(0.0)) - sol.C4s * ff_particular_w(m, t0);
  const real sp_bot = sol.C1 * ff_particular_s(m, t0);
  const real wp_bot = sol.C1 * ff_particular_w(m, t0) - sol.C4s * ff_particular_w(m, R(0.0));

  /* The outgoing diffuse flows u = F-(0) and v = F+(τ0) by adding the layer to its two boundaries
   * (the same solution as the 2×2 system for the homogeneous amplitudes, rearranged): the layer alone
   * reflects ρ = S/Q and transmits t = E/Q of a diffuse flow, Q = k + S + C, C = λ0 coth(λ0 τ0),
   * E = λ0 / sinh(λ0 τ0) (Kubelka–Munk, with C² - E² = λ0²), and the beams alone, between black
   * boundaries, send J_up up through the surface side and J_dn down onto the bottom. With the incoming
   * flows F+(0) = src_top + Rt u, F-(τ0) = src_bot + Rb v:
   *   u = ρ F+(0) + t F-(τ0) + J_up,   v = t F+(0) + ρ F-(τ0) + J_dn.
   * Why: reading u as (s(0) - src_top)/(1 + Rt) from the amplitude α lost the digits of a small F-(0)
   * under O(1) flows (4e-5 relative in float under a thin layer over a black bottom); here every piece
   * is a sum of non-negative terms except the beams' J, whose cancellation is bounded (measured in
   * tests/unit/fourflow_math_test.cpp). */
  const real Cm = ff_cosh_ratio(t0, l0, t0);  /* C */
  const real E = ff_cosh_ratio(R(0.0), l0, t0);
  /* C - E = (1 - e^{-λ0 τ0})² / (2 τ0 φ(-2 λ0 τ0)), exact and >= 0 (it -> 0 with λ0 τ0). */
  const real one_m = l0 * t0 * expm1_over_x(-l0 * t0);
  const real c_minus_e = one_m * one_m / (R(2.0) * t0 * expm1_over_x(-R(2.0) * l0 * t0));
  /* The beam G+ = e^{-λτ} between black boundaries (its mirror G- = e^{-λ(τ0-τ)} swaps up and down):
   *   2 Q J_up = -w_p(0) (a + C - E) + E dws
   *   2 Q J_dn = (k + C) s_p(τ0) + (a + C) [w_p(τ0) - w_p(0)] - (a + C - E)(-w_p(0))
   * with -w_p(0) = (Σ - rΔ)/(λ0 + λ) >= 0, r = λ0/a, and, from ff_particular_w and _s,
   *   w_p(τ0) - w_p(0) = [λ0 (Σ + λΔ/a) Φ(τ0) + (Σ - rΔ)(1 - e^{-λτ0})]/(λ0 + λ)   (both terms >= 0),
   *   dws = w_p(τ0) - w_p(0) - s_p(τ0) = [(Σ - rΔ)(1 - e^{-λτ0}) - (a - λ0)(Σ + λΔ/a) Φ(τ0)]/(λ0 + λ). */
  const real sig = m.S1 + m.S2, del = m.S1 - m.S2;
  const real r = l0 / a;
  const real inv_sum = R(1.0) / (l0 + l);
  const real phi0 = ff_divided_exp(t0, l, l0);
  const real beam_loss = l * t0 * expm1_over_x(-l * t0); /* 1 - e^{-λτ0} */
  const real w0n = (sig - r * del) * inv_sum;             /* -w_p(0) */
  const real gq = sig + l * del / a;
  const real dw = (l0 * gq * phi0 + (sig - r * del) * beam_loss) * inv_sum;
  const real sp1 = ff_particular_s(m, t0);
  const real ace = a + c_minus_e; /* a + C - E */
  /* Q J_up, rearranged with (a - λ0)(Σ + λΔ/a) = (Σ - rΔ)(a + λ) - 2 S2 (λ + λ0) into non-negative terms:
   *   2 Q J_up (λ0 + λ) = (Σ - rΔ)[a (1 - EΦ) + (C - E) + λ E (Ψ - Φ)] + 2 S2 (λ + λ0) E Φ;
   * the form above, -w_p(0)(a + C - E) + E dws, cancels in thin water to the single backscatter
   * S2 τ0 from terms of size Σ (a factor Σ/2S2 = 10 for X1 = 0.9). */
  real gap_e, gap_p;
  ff_beam_gaps(t0, l, l0, E, &gap_e, &gap_p);
  const real q_up = R(0.5) * ((sig - r * del) * (a * gap_e + c_minus_e + l * E * gap_p) * inv_sum +
                              R(2.0) * m.S2 * E * phi0); /* Q J_up for a unit G+ */
  /* Q J_dn two ways, equal in exact arithmetic: the first cancels in deep water ((a + C) dw and
   * (a + C - E)(-w_p(0)) agree to E/(a + C)), the second in thin water ((a + C) w_p(τ0) against
   * E w_p(0), both ~ 1/τ0); the one whose terms are smaller in magnitude is the one rounded least. */
  const real w1 = ff_particular_w(m, t0);
  const real dn_thin_a = (m.k + Cm) * sp1 + (a + Cm) * dw, dn_thin_b = ace * w0n;
  const real dn_deep_a = (m.k + Cm) * sp1 + E * w0n, dn_deep_b = (a + Cm) * w1;
  const real q_dn = R(0.5) * (fabs(dn_thin_a) + fabs(dn_thin_b) <= fabs(dn_deep_a) + fabs(dn_deep_b)
                                  ? dn_thin_a - dn_thin_b
                                  : dn_deep_a + dn_deep_b); /* Q J_dn for a unit G+ */
  const real qj_up = fmax(sol.C1 * q_up + sol.C4s * q_dn, R(0.0));
  const real qj_dn = fmax(sol.C1 * q_dn + sol.C4s * q_up, R(0.0));
  /* Q × the right-hand sides, and the 2×2 system times Q²: its determinant
   * (Q - S Rt)(Q - S Rb) - E² Rt Rb = C²(1 - Rt Rb) + C (p_t + p_b) + p_t p_b + λ0² Rt Rb,
   * p = k + S (1 - R), a sum of non-negative terms. */
  const real b1 = m.S * src_top + E * src_bot + qj_up;
  const real b2 = E * src_top + m.S * src_bot + qj_dn;
  const real pt = m.k + m.S * (R(1.0) - Rt), pb = m.k + m.S * (R(1.0) - Rb);
  const real det = Cm * Cm * (R(1.0) - Rt * Rb) + Cm * (pt + pb) + pt * pb + l0 * l0 * Rt * Rb;
  sol.Fm_top = fmax(((Cm + pb) * b1 + E * Rb * b2) / det, R(0.0));
  sol.Fp_bot = fmax((E * Rt * b1 + (Cm + pt) * b2) / det, R(0.0));
  sol.Fp_top = src_top + Rt * sol.Fm_top;
  sol.Fm_bot = src_bot + Rb * sol.Fp_bot;
  /* The homogeneous amplitudes of s at the two ends, for the interior flows (ff_flows_at). */
  sol.alpha = sol.Fp_top + sol.Fm_top - sp_top;
  sol.beta = sol.Fp_bot + sol.Fm_bot - sp_bot;
  /* w_h'' = λ0² w_h as well, so the interior w needs only its two end values; taking them from the
   * boundary flows avoids (α C - β E)/a, which cancels as τ0 -> 0 (C, E ~ 1/τ0, α ≈ β). */
  sol.wh_top = sol.Fp_top - sol.Fm_top - wp_top;
  sol.wh_bot = sol.Fp_bot - sol.Fm_bot - wp_bot;
  (void)l;
  return sol;
}

/* All four flows at optical depth τ ∈ [0, τ0] (003 eq. 5 in the rescaled form). */
SEASIM_FN FfFlows ff_flows_at(FfSolution sol, real tau) {
  const FfMedium m = sol.m;
  const real t0 = sol.tau0;
  const real t = clamp(tau, R(0.0), t0);
  const real l = ff_lambda(m), l0 = ff_lambda0(m);
  FfFlows f;
  f.Gp = sol.C1 * exp(-l * t);
  f.Gm = sol.C4s * exp(-l * (t0 - t));
  const real s = sol.alpha * ff_sinh_ratio(t0 - t, l0, t0) + sol.beta * ff_sinh_ratio(t, l0, t0) +
                 sol.C1 * ff_particular_s(m, t) + sol.C4s * ff_particular_s(m, t0 - t);
  const real w = sol.wh_top * ff_sinh_ratio(t0 - t, l0, t0) + sol.wh_bot * ff_sinh_ratio(t, l0, t0) +
                 sol.C1 * ff_particular_w(m, t) - sol.C4s * ff_particular_w(m, t0 - t);
  f.Fp = R(0.5) * (s + w);
  f.Fm = R(0.5) * (s - w);
  return f;
}

/* ---------------------------------------------------------------------------------------------
 * Flat-surface coefficients (003 eq. 6 and the text after eq. 9: for a water mirror the dd terms are
 * the Fresnel term and the ff terms its hemispherical average, eq. 10 with a single flat facet and a
 * uniform sky B). A flat surface turns no direct light into diffuse: T_df = R_df = 0, so eq. 6 is
 * R_dd + T_dd = 1 and R_ff + T_ff = 1 exactly.
 *
 * Diffuse reflectance for Lambertian light arriving in n1 at a surface to n2:
 *   R = ∫ F(μ) 2μ dμ over μ = cos θ ∈ [0, 1].
 * From the denser side F = 1 below the critical cosine μc = sqrt(1 - (n2/n1)²), which contributes μc²
 * exactly; above it F has a square-root corner at μc, removed by μ = μc + (1 - μc) t² (dμ = 2(1-μc) t dt),
 * after which the integrand is smooth and composite Simpson with FF_FRESNEL_INTERVALS converges fast
 * (error ~1e-10 at 256 intervals: the unit test compares with 4096 intervals and checks 1 - R~_ff = (1 - R_ff)/n², the
 * Lambertian form of the n² radiance law). */
#define FF_FRESNEL_INTERVALS 256
SEASIM_FN real ff_diffuse_reflectance(real n1, real n2, int intervals) {
  const real ratio = n2 / n1;
  const real mu_c = ratio < R(1.0) ? sqrt((R(1.0) - ratio) * (R(1.0) + ratio)) : R(0.0);
  const int nseg = intervals + (intervals & 1); /* Simpson needs an even count */
  const real h = R(1.0) / (real)nseg;
  real sum = R(0.0);
  for (int i = 0; i <= nseg; ++i) {
    const real t = h * (real)i;
    const real mu = mu_c + (R(1.0) - mu_c) * t * t;
    const real g = fresnel_reflectance(mu, n1, n2) * R(2.0) * mu * R(2.0) * (R(1.0) - mu_c) * t;
    const real wgt = (i == 0 || i == nseg) ? R(1.0) : ((i & 1) ? R(4.0) : R(2.0));
    sum += wgt * g;
  }
  return mu_c * mu_c + sum * h / R(3.0);
}

/* The surface of eq. 7 for a flat water mirror: sun at cos θ = mu_sun (from the zenith, in air),
 * water index n_water. R~_dd is the Fresnel term of the refracted sun direction seen from below,
 * equal to the one from above (Fresnel reflectance is the same for both directions of a refracted
 * pair), so the upward beam leaves with the same T. */
SEASIM_FN FfSurface ff_flat_surface(real mu_sun, real n_water) {
  FfSurface s;
  const real f_sun = fresnel_reflectance(mu_sun, R(1.0), n_water);
  s.T_dd = R(1.0) - f_sun;
  s.T_df = R(0.0);
  s.T_ff = R(1.0) - ff_diffuse_reflectance(R(1.0), n_water, FF_FRESNEL_INTERVALS);
  s.Rw_dd = f_sun;
  s.Rw_df = R(0.0);
  s.Rw_ff = ff_diffuse_reflectance(n_water, R(1.0), FF_FRESNEL_INTERVALS);
  return s;
}

/* A Lambertian bottom of albedo r (003 eq. 11: R^_dd ≈ 0, R^_df = R^_ff = R^). */
SEASIM_FN FfBottom ff_lambert_bottom(real r) {
  FfBottom b;
  b.R_dd = R(0.0);
  b.R_df = r;
  b.R_ff = r;
  return b;
}

/* 003 eq. 11–12: light reaching the bottom, G+(τ0) + F+(τ0) (times R^(x) gives E_bottom), and the
 * upwelling diffuse flow under the surface, E_scatter = F-(0). */
SEASIM_FN real ff_bottom_irradiance(FfSolution sol) {
  return sol.C1 * exp(-ff_lambda(sol.m) * sol.tau0) + sol.Fp_bot;
}
SEASIM_FN real ff_upwelling(FfSolution sol) { return sol.Fm_top; }

/* ---------------------------------------------------------------------------------------------
 * Per band and per pixel (003 eq. 1–3, 11–13, 20–23), on the FfBand / FfParams blocks of
 * fourflow_params.h. The light field is solved for the texture's mean bottom albedo R̄ (eq. 12: the
 * "average color bottom"); the bottom point seen reflects it with its own albedo (eq. 11). */

/* What eq. 20 needs from the light field at bottom depth h (m): the light reaching the bottom,
 * G+(τ0) + F+(τ0), and the upwelling under the surface, F-(0). */
typedef struct {
  real down_bottom, up_surface;
} FfBandTerms;

SEASIM_FN FfBandTerms ff_band_terms(FfBand b, real h) {
  FfMedium m;
  m.k = b.k, m.S = b.S, m.S1 = b.S1, m.S2 = b.S2;
  FfSurface s;
  s.T_dd = b.T_dd, s.T_df = b.T_df, s.T_ff = b.T_ff, s.Rw_dd = b.Rw_dd, s.Rw_df = b.Rw_df, s.Rw_ff = b.Rw_ff;
  const FfSolution sol = ff_solve(m, s, ff_lambert_bottom(b.rho_mean), (real)b.eps * h, b.e_sun, b.e_sky);
  FfBandTerms t;
  t.down_bottom = ff_bottom_irradiance(sol);
  t.up_surface = ff_upwelling(sol);
  return t;
}

/* 003 eq. 20 with α_l = e^{-ε l} (eq. 3): E_refr = α_l R̂ (G+ + F+)(τ0) + (1 - α_l) F-(0). */
SEASIM_FN real ff_refracted(FfBandTerms t, real alpha_l, real rho) {
  return alpha_l * rho * t.down_bottom + (R(1.0) - alpha_l) * t.up_surface;
}

/* The bottom albedo of band b where the texture mixes material b with weight tex ∈ [0, 1]. */
SEASIM_FN real ff_bottom_albedo(FfBand b, real tex) { return (R(1.0) - tex) * b.rho_a + tex * b.rho_b; }

/* The exact path: eq. 20 per band, summed into linear RGB through the bands' sensor weights. */
SEASIM_FN void ff_exact_rgb(const SEASIM_GLOBAL FfBand* bands, int n_bands, real l, real h, real tex, real* rgb) {
  rgb[0] = rgb[1] = rgb[2] = R(0.0);
  for (int i = 0; i < n_bands; ++i) {
    const FfBand b = bands[i];
    const real e = ff_refracted(ff_band_terms(b, h), exp(-(real)b.eps * l), ff_bottom_albedo(b, tex));
    rgb[0] += b.rgb[0] * e;
    rgb[1] += b.rgb[1] * e;
    rgb[2] += b.rgb[2] * e;
  }
}

/* One (l, h) table cell of 003 eq. 22–24, written to cell[0 .. FF_TABLE_STRIDE - 1]:
 *   [0..2]  T0 = Φ(E_refr over a white bottom)      "the colour of water for the specified bottom" once
 *                                                    multiplied by the bottom texture's RGB;
 *   [3]     a  = 1 - (1 - mean_λ e^{-ε l})^γ        eq. 23 (the paper's (1/400)∫_380^780 is the band mean);
 *   [4..6]  T1 = Φ(E_refr over the mean bottom R̄)  "the water colour for some average bottom";
 *   [8..10] T_α = Φ(α_l) under the incoming light    eq. 24's pre-converted transmittance (Σ w α E / Σ w E);
 *   [12..14] Φ(G+ + F+)(τ0), [16..18] Φ(F-(0))      eq. 24's T0(h), T1(h); the other slots 0.
 * Φ here is the linear band -> RGB map; the display transform comes after the blend. */
SEASIM_FN void ff_table_cell(const SEASIM_GLOBAL FfBand* bands, int n_bands, real gamma, real l, real h, real* cell) {
  for (int q = 0; q < FF_TABLE_STRIDE; ++q) cell[q] = R(0.0);
  real alpha_sum = R(0.0), light_w[3] = {R(0.0), R(0.0), R(0.0)};
  for (int i = 0; i < n_bands; ++i) {
    const FfBand b = bands[i];
    const FfBandTerms t = ff_band_terms(b, h);
    const real alpha = exp(-(real)b.eps * l);
    const real e_white = ff_refracted(t, alpha, R(1.0));
    const real e_mean = ff_refracted(t, alpha, (real)b.rho_mean);
    const real light = (real)b.e_sun + (real)b.e_sky;
    for (int c = 0; c < 3; ++c) {
      const real w = (real)b.rgb[c];
      cell[c] += w * e_white;
      cell[4 + c] += w * e_mean;
      cell[8 + c] += w * alpha * light;
      light_w[c] += w * light;
      cell[12 + c] += w * t.down_bottom;
      cell[16 + c] += w * t.up_surface;
    }
    alpha_sum += alpha;
  }
  const real mean_alpha = n_bands > 0 ? alpha_sum / (real)n_bands : R(0.0);
  cell[3] = R(1.0) - pow(fmax(R(1.0) - mean_alpha, R(0.0)), gamma);
  for (int c = 0; c < 3; ++c) cell[8 + c] = light_w[c] > R(0.0) ? cell[8 + c] / light_w[c] : R(0.0);
}

/* The table node (l, h) stands for: l_max (i/(n_l - 1))², h_max j/(n_h - 1). The nodes along l are
 * dense near l = 0 because e^{-ε l} changes fastest there (red bands: ε ~ 0.4 m⁻¹ while l_max is set by
 * the clearest band, hundreds of m); uniform nodes left the first metres between two nodes (the sweep
 * measured no convergence up to 128 nodes). */
SEASIM_FN real ff_table_l(FfParams p, int i) {
  const real t = (real)i / (real)(p.n_l - 1);
  return (real)p.l_max * t * t;
}
SEASIM_FN real ff_table_h(FfParams p, int j) { return (real)p.h_max * (real)j / (real)(p.n_h - 1); }

/* The real-time path per pixel: bilinear lookup (in √l and h) of the cell at (l, h), clamped to the table's
 * range (beyond l_max the view ray has left the table: e^{-ε l_max} should be ~0 there, which the
 * planner's l_max ensures), then 003 eq. 22: T_refr = a T0 T_bottom + (1 - a) T1 (or eq. 24 when eq24), with T_bottom the
 * linear RGB reflectance of the texture at the pixel. table[(j n_l + i) FF_TABLE_STRIDE + c]. */
SEASIM_FN void ff_table_rgb(FfParams p, const SEASIM_GLOBAL float* table, real l, real h, real tex, int eq24, real* rgb) {
  const real fl = sqrt(clamp(l / (real)p.l_max, R(0.0), R(1.0))) * (real)(p.n_l - 1);
  const real fh = clamp(h / (real)p.h_max, R(0.0), R(1.0)) * (real)(p.n_h - 1);
  const int il = (int)fl, jh = (int)fh;
  const int i0 = il < p.n_l - 2 ? il : p.n_l - 2, j0 = jh < p.n_h - 2 ? jh : p.n_h - 2;
  const real u = fl - (real)i0, v = fh - (real)j0;
  real c[FF_TABLE_STRIDE];
  for (int q = 0; q < FF_TABLE_STRIDE; ++q) {
    const real c00 = table[((j0 + 0) * p.n_l + i0 + 0) * FF_TABLE_STRIDE + q];
    const real c10 = table[((j0 + 0) * p.n_l + i0 + 1) * FF_TABLE_STRIDE + q];
    const real c01 = table[((j0 + 1) * p.n_l + i0 + 0) * FF_TABLE_STRIDE + q];
    const real c11 = table[((j0 + 1) * p.n_l + i0 + 1) * FF_TABLE_STRIDE + q];
    c[q] = (R(1.0) - v) * ((R(1.0) - u) * c00 + u * c10) + v * ((R(1.0) - u) * c01 + u * c11);
  }
  const real a = c[3];
  for (int ch = 0; ch < 3; ++ch) {
    const real t_bottom = (R(1.0) - tex) * (real)p.rgb_a[ch] + tex * (real)p.rgb_b[ch];
    /* eq. 24, which the paper reports worse than eq. 22 (RGB conversion before the blend):
     * T_α T_bottom T0(h) + (1 - T_α) T1(h). */
    rgb[ch] = eq24 ? c[8 + ch] * t_bottom * c[12 + ch] + (R(1.0) - c[8 + ch]) * c[16 + ch]
                   : a * c[ch] * t_bottom + (R(1.0) - a) * c[4 + ch];
  }
}

/* ---------------------------------------------------------------------------------------------
 * The procedural bottom texture: the share tex ∈ [0, 1] of the dark material at (x, z) (m). Value noise
 * (a hashed lattice, smoothstep-interpolated, two octaves) in [0, 1], turned into patches:
 * tex = clamp(3 (n - 1/2) + (dark_fraction - 1/2) 3 + 1/2, 0, 1), which for noise symmetric about 1/2
 * has a mean near dark_fraction; the host measures the exact mean (the "average bottom" R̄ of eq. 12)
 * with this same function. Generated, so nothing needs a licence. */
SEASIM_FN real ff_lattice(int i, int j) {
  unsigned int h = (unsigned int)i * 73856093u ^ (unsigned int)j * 19349663u;
  h ^= h >> 13;
  h *= 0x5bd1e995u;
  h ^= h >> 15;
  return (real)(h & 0xffffu) / R(65535.0);
}
SEASIM_FN real ff_value_noise(real x, real z) {
  /* floor without the C library (an int cast truncates towards 0); |x| stays far below 2^31 here. */
  const int i = (int)x - (x < (real)(int)x ? 1 : 0), j = (int)z - (z < (real)(int)z ? 1 : 0);
  const real fx = (real)i, fz = (real)j;
  real u = x - fx, v = z - fz;
  u = u * u * (R(3.0) - R(2.0) * u);
  v = v * v * (R(3.0) - R(2.0) * v);
  const real a = ff_lattice(i, j), b = ff_lattice(i + 1, j), c = ff_lattice(i, j + 1), d = ff_lattice(i + 1, j + 1);
  return (a + u * (b - a)) + v * ((c + u * (d - c)) - (a + u * (b - a)));
}
SEASIM_FN real ff_bottom_texture(real x, real z, real scale, real dark_fraction) {
  const real n = R(0.65) * ff_value_noise(x / scale, z / scale) + R(0.35) * ff_value_noise(R(2.7) * x / scale + R(17.0), R(2.7) * z / scale - R(5.0));
  return clamp(R(3.0) * (n - R(0.5)) + R(3.0) * (dark_fraction - R(0.5)) + R(0.5), R(0.0), R(1.0));
}

/* ---------------------------------------------------------------------------------------------
 * The frame's per-pixel steps (kernels/fourflow.cl ff_render; tests/kernels/fourflow_test.cpp runs
 * them in double on the host): the camera ray, its entry into the water, and the pixel's colour once
 * the bottom point C (path l through the water, depth h) is known. */

/* The unit view direction of pixel (x, y) (pixel centres, y down), the pinhole camera of the sea model. */
SEASIM_FN real3 ff_camera_dir(FfView v, int x, int y) {
  const real sx = ((real)x + R(0.5)) / (real)v.width, sy = ((real)y + R(0.5)) / (real)v.height;
  const real3 right = MAKE_REAL3(v.cam_right[0], v.cam_right[1], v.cam_right[2]);
  const real3 up = MAKE_REAL3(v.cam_up[0], v.cam_up[1], v.cam_up[2]);
  const real3 fwd = MAKE_REAL3(v.cam_forward[0], v.cam_forward[1], v.cam_forward[2]);
  return normalize(fwd + ((R(2.0) * sx - R(1.0)) * (real)v.tan_half_fov_y * (real)v.aspect) * right +
                   ((R(1.0) - R(2.0) * sy) * (real)v.tan_half_fov_y) * up);
}

/* A ray from o (above the water) along d meets the flat surface y = 0 at *b when d.y < 0: returns 1
 * with the Fresnel term *F (003 eq. 1) and the refracted direction *dw; 0 when it sees the sky. */
SEASIM_FN int ff_enter_water(FfView v, real3 o, real3 d, real3* b, real* F, real3* dw) {
  if (!(d.y < R(0.0))) return 0;
  *b = o + (o.y / -d.y) * d;
  *F = fresnel_reflectance(-d.y, R(1.0), (real)v.ior);
  refract_dir(d, MAKE_REAL3(R(0.0), R(1.0), R(0.0)), R(1.0) / (real)v.ior, dw);
  return 1;
}

/* One band's radiance at the pixel (the spectral EXR): eq. 1 with eq. 20 for that band alone,
 * F L_sky + (1 - F) E_refr / (π n²), L_sky = e_sky / π (a uniform sky). The exact path's RGB is the
 * sum of these through the bands' rgb weights. */
SEASIM_FN real ff_band_radiance(FfBand b, real ior, real F, real l, real h, real tex) {
  const real e = ff_refracted(ff_band_terms(b, h), exp(-(real)b.eps * l), ff_bottom_albedo(b, tex));
  return (F * (real)b.e_sky + (R(1.0) - F) * fmax(e, R(0.0)) / (ior * ior)) / SEASIM_PI;
}

/* The pixel (003 eq. 1): F L_sky + (1 - F) E_refr / (π n²), E_refr (eq. 20) at bottom point c, path l,
 * depth h, by the exact band sum (mode 0), the tables with eq. 22 (mode 1) or eq. 24 (mode 2). */
SEASIM_FN void ff_shade(FfView v, const SEASIM_GLOBAL FfBand* bands, FfParams p, const SEASIM_GLOBAL float* table,
                        int mode, real F, real l, real h, real3 c, real* rgb) {
  const real tex = ff_bottom_texture(c.x, c.z, (real)v.texture_scale, (real)v.dark_fraction);
  real refr[3];
  if (mode == 0) {
    ff_exact_rgb(bands, p.n_bands, l, h, tex, refr);
  } else {
    ff_table_rgb(p, table, l, h, tex, mode == 2, refr);
  }
  const real k = (R(1.0) - F) / (SEASIM_PI * (real)v.ior * (real)v.ior);
  for (int ch = 0; ch < 3; ++ch) rgb[ch] = F * (real)v.sky_rgb[ch] + k * fmax(refr[ch], R(0.0));
}
