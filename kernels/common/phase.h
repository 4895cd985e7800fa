/* phase.h — measured and parameterised phase functions of water, beside Henyey–Greenstein (optics.h).
 * Every phase here is normalised over the sphere (∫ β̃ dΩ = 1, per sr). Written against compat.h; the
 * host compiles it in float and double (host/math/kernel_math.h); host/radiometry/phase_function.* builds
 * the tables and the parameters these functions read.
 *
 * Rayleigh-like (Mobley et al. 1993, "Comparison of numerical models for computing underwater light
 * fields", Appl. Opt. 32(36), problem 1): β̃ ∝ 1 + a cos²ψ with a = 0.835; ∫ (1 + a cos²ψ) dΩ = 4π (1 + a/3),
 * so β̃ = (1 + a cos²ψ) / (4π (1 + a/3)). Its Legendre moments: χ_0 = 1, χ_2 = 2a / (5 (3 + a)), the rest 0
 * (cos²ψ = (1 + 2 P_2) / 3).
 *
 * Fournier–Forand (Fournier & Forand 1994, "Analytic phase function for ocean water", Proc. SPIE 2258;
 * the form of Mobley, Sundman & Boss 2002, Appl. Opt. 41(6) eq. 4–6), with ν = (3 - μ)/2 (μ the Junge
 * slope), k = 4 / (3 (n - 1)²) (n the particles' index relative to water), δ = k sin²(ψ/2):
 *   β̃ = [ν(1 - δ) - (1 - δ^ν) + (δ(1 - δ^ν) - ν(1 - δ)) / sin²(ψ/2)] / (4π (1 - δ)² δ^ν)
 *       + (1 - δ_180^ν) / (16π (δ_180 - 1) δ_180^ν) (3 cos²ψ - 1),     δ_180 = k.
 * With 1/sin²(ψ/2) = k/δ the bracket is N = (k - 1)(1 - δ^ν) - ν (1 - δ)(k/δ - 1).
 * Stiff points:
 *   δ = 1 (ψ ≈ 10° at n = 1.1): N and (1 - δ)² vanish together (0/0). With x = 1 - δ, 1 - δ^ν =
 *     -Σ_j C(ν, j)(-x)^j and k/δ - 1 = (k - 1) + k Σ_{j≥1} x^j; the x terms cancel exactly, so
 *     N / x² = Σ_{j≥2} c_j x^{j-2},  c_j = -(k - 1)(-1)^j C(ν, j) - ν k,
 *     summed for |x| < 0.05 (14 terms: 0.05^14 < 1e-18; |C(ν, j)| <= 1 for ν in [-1, 0]). Outside it, N
 *     directly; the cancellation in N then costs at most eps/|x| = 20 eps.
 *   ψ -> 0: β̃ ~ -ν k δ^{-1-ν} / (4π) diverges (integrably, ν > -1); the argument is 1 - cos ψ (no
 *     cancellation at small ψ) clamped to >= 1e-30 (ψ >= 1.4e-15 rad), where β̃ is finite in float for
 *     every ν in [-1, 0) (δ >= 6.7e-29 at n = 1.1: k/δ <= 2e30 and δ^{-1-ν} <= 1.5e28 < FLT_MAX). The clamp
 *     sits far below any angle that matters: at b_b/b = 0.001 (ν = -0.03) the cumulative goes as ψ^{-2ν} =
 *     ψ^0.06, so a fifth of the scattering lies within 1e-12 rad and the host integrates that power law in
 *     closed form (phase_function.cpp) rather than by sampling the clamp.
 *   δ^ν = exp(ν ln δ) and its inverse: finite for δ >= k 5e-13 > 0.
 *
 * Tabulated values (the path tracer's next-event weights): a table of size V holds β̃ at 1 - cos ψ =
 * PHASE_OMC_MIN (2 / PHASE_OMC_MIN)^(i / (V - 1)), i = 0..V-1, log-spaced from 1e-9 (ψ = 2.6e-3°) to 2; between
 * nodes ln β̃ is linear in ln(1 - cos ψ) (power laws exactly), below the first node the first value holds.
 *
 * Tabulated inverse CDF (the path tracer's exact sampling of any phase): a table of size T holds
 * 1 - cos ψ at the cumulative probabilities u_i = i / (T - 1), i = 0..T-1 (first 0, last 2), built on the
 * host from the phase's fine quadrature. Between nodes the sample is geometric in 1 - cos ψ (linear in
 * ln(1 - cos ψ)), which follows a power-law forward peak (β̃ ∝ ψ^m) with no bias in a bin's median; the
 * first bin (from 0) is linear. The table's resolution is the sampler's only approximation (tested by
 * χ² against the phase itself, phase_function_test.cpp).
 */

#define PHASE_RAYLEIGH_LIKE_A R(0.835)
#define PHASE_OMC_MIN R(1e-9)
/* The path tracer's tables (reference.cl): PHASE_PT_VALUES values, then PHASE_PT_SAMPLES inverse-CDF entries. */
#define PHASE_PT_VALUES 1024
#define PHASE_PT_SAMPLES 8192

/* Mobley et al. 1993 problem 1's phase at cos ψ. */
SEASIM_FN real phase_rayleigh_like(real cos_psi) {
  const real c = clamp(cos_psi, R(-1.0), R(1.0));
  return (R(1.0) + PHASE_RAYLEIGH_LIKE_A * c * c) / (R(4.0) * SEASIM_PI * (R(1.0) + PHASE_RAYLEIGH_LIKE_A / R(3.0)));
}

/* N / (1 - δ)² of the Fournier–Forand bracket (see the top), for δ = 1 - x with |x| < 0.05: the series. */
SEASIM_FN real phase_ff_bracket_series(real x, real nu, real k) {
  real binom = nu * (nu - R(1.0)) / R(2.0); /* C(ν, j), from j = 2 */
  real sign = R(1.0);                        /* (-1)^j */
  real xp = R(1.0);                          /* x^{j-2} */
  real sum = R(0.0);
  for (int j = 2; j < 16; ++j) {
    sum += (-(k - R(1.0)) * sign * binom - nu * k) * xp;
    binom *= (nu - (real)j) / (real)(j + 1);
    sign = -sign;
    xp *= x;
  }
  return sum;
}

/* The Fournier–Forand phase at 1 - cos ψ (in [0, 2]), with ν in [-1, 0) and k = 4 / (3 (n - 1)²) > 1. */
SEASIM_FN real phase_fournier_forand(real one_minus_cos, real nu, real k) {
  const real omc = clamp(one_minus_cos, R(1e-30), R(2.0));
  const real delta = k * R(0.5) * omc; /* k sin²(ψ/2) */
  const real x = R(1.0) - delta;
  const real ln_delta = log(delta);
  const real inv_delta_nu = exp(-nu * ln_delta); /* δ^-ν */
  real bracket_over_delta_nu;
  if (fabs(x) < R(0.05)) {
    bracket_over_delta_nu = phase_ff_bracket_series(x, nu, k) * inv_delta_nu;
  } else {
    /* N / δ^ν = (k - 1)(δ^-ν - 1) - ν (1 - δ)(k/δ - 1) δ^-ν, divided by x². */
    const real n_over = (k - R(1.0)) * (inv_delta_nu - R(1.0)) - nu * x * (k / delta - R(1.0)) * inv_delta_nu;
    bracket_over_delta_nu = n_over / (x * x);
  }
  const real cos_psi = R(1.0) - omc;
  const real k_nu = exp(nu * log(k)); /* δ_180^ν */
  const real back = (R(1.0) - k_nu) / (R(16.0) * SEASIM_PI * (k - R(1.0)) * k_nu);
  return bracket_over_delta_nu / (R(4.0) * SEASIM_PI) + back * (R(3.0) * cos_psi * cos_psi - R(1.0));
}

/* The Fournier–Forand backscattering ratio b_b/b (Mobley et al. 2002 eq. 6), δ_90 = k/2. */
SEASIM_FN real phase_fournier_forand_bb(real nu, real k) {
  const real d90 = R(0.5) * k;
  const real d_nu = exp(nu * log(d90));
  return R(1.0) - (R(1.0) - d_nu * d90 - R(0.5) * (R(1.0) - d_nu)) / ((R(1.0) - d90) * d_nu);
}

/* 1 - cos ψ of a sample of a tabulated phase: `table` holds `size` >= 2 values of 1 - cos ψ at u_i =
 * i / (size - 1) (see the top). u in [0, 1]. */
SEASIM_FN real phase_table_sample_omc(SEASIM_GLOBAL const real* table, int size, real u) {
  const real s = clamp(u, R(0.0), R(1.0)) * (real)(size - 1);
  int i = (int)floor(s);
  if (i > size - 2) i = size - 2;
  if (i < 0) i = 0;
  const real t = s - (real)i;
  const real lo = table[i], hi = table[i + 1];
  if (lo > R(0.0) && hi > lo) return lo * exp(t * log(hi / lo));
  return lo + t * (hi - lo);
}

/* β̃ at 1 - cos ψ from `table` (size >= 2 values at log-spaced 1 - cos ψ, see the top). */
SEASIM_FN real phase_table_value(SEASIM_GLOBAL const real* table, int size, real one_minus_cos) {
  const real omc = clamp(one_minus_cos, PHASE_OMC_MIN, R(2.0));
  const real s = log(omc / PHASE_OMC_MIN) / log(R(2.0) / PHASE_OMC_MIN) * (real)(size - 1);
  int i = (int)floor(s);
  if (i > size - 2) i = size - 2;
  if (i < 0) i = 0;
  const real t = clamp(s - (real)i, R(0.0), R(1.0));
  const real lo = table[i], hi = table[i + 1];
  if (lo > R(0.0) && hi > R(0.0)) return lo * exp(t * log(hi / lo));
  return lo + t * (hi - lo);
}
