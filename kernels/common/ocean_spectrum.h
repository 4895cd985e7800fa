/* ocean_spectrum.h — the math of Tessendorf's FFT ocean (004 §3) that kernels/ocean.cl runs and the
 * host tests and the CPU reference (host/ocean/ocean_cpu.cpp) re-run in float and double:
 *   - a counter-based RNG (Philox4x32-10) and Box–Muller, keyed by (seed, integer wavenumber), so the
 *     same seed gives the same Gaussian draws on every device and for every grid size N (a finer
 *     grid adds short waves and keeps the long ones);
 *   - the Phillips spectrum with the |k̂·ŵ|^p directional factor and small-wave suppression
 *     (eq. 23–24) and the initial amplitudes h̃0 (eq. 25);
 *   - the dispersion relation, deep (eq. 14) and finite depth (eq. 15), and the quantised
 *     frequencies of a looping animation (eq. 17–18);
 *   - the time evolution h̃(k,t) (eq. 26);
 *   - the 2x2 Jacobian of the choppy map x -> x + λD, its eigenvalues J-, J+ and the eigenvector
 *     of J- (eq. 30–34).
 *
 * Normalisation of the spectrum. The paper folds the grid's wavenumber cell into its constant A.
 * We keep A dimensionless and independent of the patch: Ph(k) below is a density over k (m⁴), and
 * an amplitude on the lattice k = 2π(m, n)/L carries Ph(k) Δk², Δk = 2π/L. Then
 *   <h²> = Σ_k <|h̃(k,t)|²> = 2 Σ_k Ph(k) Δk² ≈ 2 ∫ Ph d²k = A π (V²/g)²      (p = 2, ℓ = 0)
 * (the radial integral ∫ e^{-1/(kLw)²} k⁻³ dk = Lw²/2, the angular one ∫ cos²θ dθ = π), so the
 * RMS height is √(Aπ) V²/g. A = 1.29e-3 (= α/2π with Phillips' α = 8.1e-3) gives a significant
 * wave height 4·RMS ≈ 0.25 V²/g, the fully developed sea of Pierson–Moskowitz.
 *
 * Stiff cases: wind speed 0 (Lw = 0: the spectrum is exactly 0, no 1/0), k = 0 (0), k Lw -> 0
 * (exp(-1/(kLw)²) underflows: returned as exactly 0 below a threshold instead of exp(-inf)),
 * depth -> 0 (tanh(kD) ≈ kD, ω -> k √(gD), no cancellation), |J_xz| = 0 with J_xx = J_zz (eq. 34
 * is 0/0: the eigenvector is taken from the better conditioned of the two matrix rows), J-/J+ by
 * the product form so neither loses digits when the other is large.
 */

#if !defined(__OPENCL_VERSION__) && !defined(__OPENCL_C_VERSION__)
/* Host: the std overloads keep float math in float inside seasim::kmath_f (real3_host.h lists the
 * others). */
using std::floor;
using std::tanh;
#endif

/* ---------------------------------------------------------------------------------------------
 * Philox4x32-10 (Salmon et al., "Parallel random numbers: as easy as 1, 2, 3", SC 2011): a
 * bijection of a 128-bit counter under a 64-bit key; 10 rounds pass BigCrush. Pure 32-bit integer
 * arithmetic, so it is bit-identical on every device and on the host.
 */
SEASIM_FN void philox4x32_10(unsigned int c[4], unsigned int k0, unsigned int k1) {
  for (int round = 0; round < 10; ++round) {
    unsigned long p0 = (unsigned long)0xD2511F53u * (unsigned long)c[0];
    unsigned long p1 = (unsigned long)0xCD9E8D57u * (unsigned long)c[2];
    unsigned int hi0 = (unsigned int)(p0 >> 32), lo0 = (unsigned int)p0;
    unsigned int hi1 = (unsigned int)(p1 >> 32), lo1 = (unsigned int)p1;
    unsigned int n0 = hi1 ^ c[1] ^ k0;
    unsigned int n2 = hi0 ^ c[3] ^ k1;
    c[0] = n0;
    c[1] = lo1;
    c[2] = n2;
    c[3] = lo0;
    k0 += 0x9E3779B9u;
    k1 += 0xBB67AE85u;
  }
}

/* A 32-bit draw -> uniform in (0, 1): the top 24 bits plus half a step, exactly representable in
 * float, so host and device agree bit for bit and log(u) never sees 0. */
SEASIM_FN real ocean_uniform(unsigned int x) {
  return ((real)(x >> 8) + R(0.5)) * R(5.9604644775390625e-8); /* 2^-24 */
}

/* Two independent standard normal draws for wavenumber (m, n) (integers, -N/2 <= m, n < N/2) by
 * Box–Muller (eq. 25's ξr, ξi). The counter is the signed wavenumber, not the array index, so the
 * draw for a given wave does not depend on N. */
SEASIM_FN void ocean_gaussian_pair(unsigned int seed, int m, int n, real* xi_r, real* xi_i) {
  unsigned int c[4];
  c[0] = (unsigned int)m;
  c[1] = (unsigned int)n;
  c[2] = 0x6F63656Eu; /* "ocen": separates this stream from any other use of the same key */
  c[3] = 0u;
  philox4x32_10(c, seed, 0x5EA51A00u);
  real u1 = ocean_uniform(c[0]);
  real u2 = ocean_uniform(c[1]);
  real r = sqrt(R(-2.0) * log(u1));
  real phi = R(2.0) * SEASIM_PI * u2;
  *xi_r = r * cos(phi);
  *xi_i = r * sin(phi);
}

/* ---------------------------------------------------------------------------------------------
 * Lattice index (0..N-1, FFT order) -> signed wavenumber integer: 0..N/2-1, then -N/2..-1.
 * The wavevector is k = (2π/L) (m, n) (004 §3.3). */
SEASIM_FN int ocean_wave_index(int i, int n) { return i < n / 2 ? i : i - n; }

/* Phillips spectrum (004 eq. 23) with small-wave suppression (eq. 24), as a density over k (m⁴):
 *   Ph(k) = A exp(-1/(k Lw)²) / k⁴ |k̂·ŵ|^p exp(-k² ℓ²),   Lw = V²/g.
 * (wx, wz) is the unit wind direction. Returns exactly 0 at k = 0, for V = 0, and where
 * 1/(k Lw)² > 80 (e^-80 = 1.8e-35: below float resolution of any amplitude that matters). */
SEASIM_FN real ocean_phillips(real kx, real kz, real wx, real wz, real wind_speed, real gravity,
                              real A, real p, real ell) {
  real k2 = kx * kx + kz * kz;
  real Lw = wind_speed * wind_speed / gravity;
  real kL2 = k2 * Lw * Lw;
  if (!(kL2 * R(80.0) > R(1.0))) return R(0.0); /* also k = 0, V = 0 and NaN */
  real k = sqrt(k2);
  real cos_w = (kx * wx + kz * wz) / k;
  /* pow(0, p) = 0 for p > 0, and p = 0 gives 1 (no directional preference). */
  real dir = p > R(0.0) ? pow(fabs(cos_w), p) : R(1.0);
  return A * exp(-R(1.0) / kL2 - k2 * ell * ell) / (k2 * k2) * dir;
}

/* h̃0(k) (004 eq. 25) on the lattice: (ξr + iξi)/√2 · √(Ph(k) Δk²), Δk = 2π/L. The Nyquist row and
 * column (m or n = -N/2) are left at 0: their ±k partners are themselves, and i k h̃ there would
 * make the slope and displacement spectra non-Hermitian (complex fields). */
SEASIM_FN void ocean_h0(int i, int j, int n, real patch_size, real wx, real wz, real wind_speed,
                        real gravity, real A, real p, real ell, unsigned int seed, real* re,
                        real* im) {
  *re = R(0.0);
  *im = R(0.0);
  if (i == n / 2 || j == n / 2) return;
  int m = ocean_wave_index(i, n), q = ocean_wave_index(j, n);
  real dk = R(2.0) * SEASIM_PI / patch_size;
  real P = ocean_phillips(dk * (real)m, dk * (real)q, wx, wz, wind_speed, gravity, A, p, ell);
  if (!(P > R(0.0))) return;
  real xr, xi;
  ocean_gaussian_pair(seed, m, q, &xr, &xi);
  real amp = sqrt(R(0.5) * P) * dk;
  *re = xr * amp;
  *im = xi * amp;
}

/* ---------------------------------------------------------------------------------------------
 * Dispersion: ω² = g k (deep water, 004 eq. 14) or ω² = g k tanh(k D) (bottom at depth D,
 * eq. 15). depth <= 0 means deep water. As D -> 0, tanh(kD) -> kD (tanh is accurate there, no
 * cancellation) and ω -> k √(gD), the shallow-water wave speed. */
SEASIM_FN real ocean_omega(real k, real gravity, real depth) {
  if (depth > R(0.0)) return sqrt(gravity * k * tanh(k * depth));
  return sqrt(gravity * k);
}

/* Phase ω t of a wave at time t. With a loop period T > 0 the frequency is quantised to
 * ω̄ = [[ω/ω0]] ω0, ω0 = 2π/T (004 eq. 17–18), and the phase is taken as 2π·frac(m τ) with
 * m = [[ω/ω0]] and τ = frac(t/T) (computed by the host in double): every quantity is then exactly
 * periodic in t with period T, also in float. */
SEASIM_FN real ocean_phase(real omega, real time, real loop_period, real loop_phase) {
  if (loop_period > R(0.0)) {
    real m = floor(omega * loop_period / (R(2.0) * SEASIM_PI));
    real cycles = m * loop_phase;
    return R(2.0) * SEASIM_PI * (cycles - floor(cycles));
  }
  return omega * time;
}

/* h̃(k,t) = h̃0(k) e^{iωt} + h̃0*(-k) e^{-iωt} (004 eq. 26), with (h0r, h0i) = h̃0(k) and
 * (h0mr, h0mi) = h̃0(-k). Preserves h̃*(k,t) = h̃(-k,t), so the height field is real. */
SEASIM_FN void ocean_evolve(real h0r, real h0i, real h0mr, real h0mi, real phase, real* hr,
                            real* hi) {
  real c = cos(phase), s = sin(phase);
  *hr = (h0r + h0mr) * c - (h0i + h0mi) * s;
  *hi = (h0r - h0mr) * s + (h0i - h0mi) * c;
}

/* ---------------------------------------------------------------------------------------------
 * Folding (004 eq. 30–34). The Jacobian matrix of x -> x + λD(x) is
 *   [J_xx J_xz; J_xz J_zz],  J_xx = 1 + λ ∂Dx/∂x,  J_zz = 1 + λ ∂Dz/∂z,  J_xz = λ ∂Dx/∂z = λ ∂Dz/∂x,
 * J = J_xx J_zz - J_xz² (eq. 30). Eigenvalues J± = (J_xx + J_zz)/2 ± √(((J_xx - J_zz)/2)² + J_xz²)
 * (eq. 32): the one whose sign matches the mean is computed directly, the other as J / that one
 * (no cancellation). The unit eigenvector of J- (eq. 33–34 write (1, q)/√(1+q²),
 * q = (J- - J_xx)/J_xz, which is 0/0 when J_xz = 0) is taken as the longer of the two rows of
 * (J - J- I) rotated by 90°; when both vanish (isotropic: any direction) it is (1, 0). */
SEASIM_FN void ocean_jacobian_eigen(real jxx, real jzz, real jxz, real* j_minus, real* j_plus,
                                    real* ex, real* ez) {
  real mean = R(0.5) * (jxx + jzz);
  real half_diff = R(0.5) * (jxx - jzz); /* not "half": a type in OpenCL C */
  real r = sqrt(half_diff * half_diff + jxz * jxz);
  real det = jxx * jzz - jxz * jxz;
  real lo, hi;
  if (mean >= R(0.0)) {
    hi = mean + r;
    lo = hi > R(0.0) ? det / hi : mean - r;
  } else {
    lo = mean - r;
    hi = det / lo;
  }
  /* Rounding in det/hi can put lo a hair above hi when r ≈ 0. */
  if (lo > hi) lo = hi;
  *j_minus = lo;
  *j_plus = hi;
  /* Rows of (J - lo I): (jxx - lo, jxz) and (jxz, jzz - lo); the eigenvector is orthogonal to
   * both, i.e. (jxz, -(jxx - lo)) or (-(jzz - lo), jxz) — pick the longer one. */
  real ax = jxz, az = lo - jxx;
  real bx = lo - jzz, bz = jxz;
  real la = ax * ax + az * az, lb = bx * bx + bz * bz;
  real vx = la >= lb ? ax : bx;
  real vz = la >= lb ? az : bz;
  real len2 = la >= lb ? la : lb;
  if (!(len2 > R(0.0))) {
    *ex = R(1.0);
    *ez = R(0.0);
    return;
  }
  real inv = R(1.0) / sqrt(len2);
  /* Orientation is arbitrary; fix the sign so that ex >= 0 (ez >= 0 when ex == 0). */
  if (vx < R(0.0) || (vx == R(0.0) && vz < R(0.0))) {
    vx = -vx;
    vz = -vz;
  }
  *ex = vx * inv;
  *ez = vz * inv;
}
