/* fourflow_waves.h — the air–water coefficients of the four-flow model over a wavy surface (003 eq. 10),
 * per facet of the FFT ocean's patch; the host (host/underwater/fourflow_waves.cpp) averages them over
 * the patch. Needs optics.h (fresnel_reflectance) and fourflow.h (FfSurface) before it.
 *
 * 003 eq. 10: R_ff = Σ_ij ∫ B F(α(ω, n_ij)) cos θ dω / (N² ∫ B cos θ dω), B the light arriving from
 * direction ω (θ from the zenith), α the angle between ω and the facet normal n_ij. (The paper writes
 * dθ dφ; the solid angle is sin θ dθ dφ, used here.) Our reading of the terms:
 *   - ff (uniform sky, B = const): the integral above. Light that would meet a facet from behind
 *     (ω·n < 0 while ω is above the horizon) is counted with F(cos α = 0) = 1, the limit of grazing
 *     incidence: it skims off (no shadowing or masking model; with the patch's slopes it is a small
 *     share of the sky);
 *   - dd (the sun, B = a delta at ω_sun): R_dd = Σ w_ij F(ω_sun·n_ij) / Σ w_ij with w_ij =
 *     max(ω_sun·n_ij, 0) / n_y,ij, the sunlight a facet intercepts per unit horizontal area;
 *   - df: 0. Where a tilted facet sends the refracted sun is not a quantity of the four-flow model
 *     (its directional flow G+ is attenuated by λ = 1 whatever its direction), so all of the sun's
 *     transmitted light stays directional. Eq. 6 then reads R_dd + T_dd = 1 and R_ff + T_ff = 1;
 *   - "~" (from below): the same integrals with the light in the water (n1 = n_water, n2 = 1, total
 *     internal reflection included), the ff term for an upwelling uniform radiance, the dd term for
 *     the upward beam, the flat-surface refracted sun mirrored into the up direction.
 *
 * The ff integral for one facet depends only on the facet's tilt β (cos β = n_y). Written around n,
 * ω = c n + s (cos ψ e1 + sin ψ e2), c = cos α, s = sin α, e1 in the plane of n and the zenith, the
 * weight is max(ω·y, 0) = max(A + B cos ψ, 0), A = c cos β, B = s sin β, whose integral over ψ is
 *   I(c) = 2π A (A >= B),  0 (A <= -B),  2 (A ψ0 + B sin ψ0), ψ0 = acos(-A/B), in between,
 * so R_ff(β) = (1/π) ∫_{-1}^{1} F(max(c, 0)) I(c) dc, a 1-D integral. Its integrand has corners at
 * c = ± sin β (I), at c = 0 (F), and at the critical cosine (F from below); the integral is split there
 * and each piece integrated by Simpson's rule in t with c = a + (b - a)(3t² - 2t³), which makes the
 * integrand's square-root corners at both ends smooth. At β = 0, I = 2π max(c, 0) and R_ff is the flat
 * hemispherical average ∫ F(μ) 2μ dμ of fourflow.h's ff_diffuse_reflectance.
 */

#define FF_WAVE_INTERVALS 128 /* Simpson intervals per piece: error ~h⁴, measured 2e-8 at a flat facet from below */

/* ∫_0^{2π} max(A + B cos ψ, 0) dψ, B >= 0. */
SEASIM_FN real ff_wave_azimuth_weight(real A, real B) {
  if (A >= B) return R(2.0) * SEASIM_PI * A;
  if (A <= -B) return R(0.0);
  const real psi0 = acos(clamp(-A / B, R(-1.0), R(1.0)));
  return R(2.0) * (A * psi0 + B * sin(psi0));
}

/* The integrand F(max(c, 0)) I(c) of R_ff(β) for light in n1 meeting a surface to n2. */
SEASIM_FN real ff_wave_integrand(real c, real cos_b, real sin_b, real n1, real n2) {
  const real s = sqrt(fmax((R(1.0) - c) * (R(1.0) + c), R(0.0)));
  return fresnel_reflectance(fmax(c, R(0.0)), n1, n2) * ff_wave_azimuth_weight(c * cos_b, s * sin_b);
}

/* ∫_a^b of the integrand, Simpson in t with c = a + (b - a)(3t² - 2t³). */
SEASIM_FN real ff_wave_piece(real a, real b, real cos_b, real sin_b, real n1, real n2, int intervals) {
  if (!(b > a)) return R(0.0);
  const int nseg = intervals + (intervals & 1);
  const real h = R(1.0) / (real)nseg;
  real sum = R(0.0);
  for (int i = 0; i <= nseg; ++i) {
    const real t = h * (real)i;
    const real c = a + (b - a) * t * t * (R(3.0) - R(2.0) * t);
    const real dc = (b - a) * R(6.0) * t * (R(1.0) - t);
    const real wgt = (i == 0 || i == nseg) ? R(1.0) : ((i & 1) ? R(4.0) : R(2.0));
    sum += wgt * ff_wave_integrand(c, cos_b, sin_b, n1, n2) * dc;
  }
  return sum * h / R(3.0);
}

/* R_ff of one facet tilted by β (cos_b = n_y > 0) under a uniform radiance from the side of n1. */
SEASIM_FN real ff_facet_diffuse_reflectance(real cos_b, real n1, real n2, int intervals) {
  const real cb = clamp(cos_b, R(0.0), R(1.0));
  const real sb = sqrt(fmax((R(1.0) - cb) * (R(1.0) + cb), R(0.0)));
  const real ratio = n2 / n1;
  const real mu_c = ratio < R(1.0) ? sqrt((R(1.0) - ratio) * (R(1.0) + ratio)) : R(0.0);
  /* Break points in ascending order: -sin β, 0, sin β, μc (the ones inside (-1, 1)). */
  real pts[6];
  int n = 0;
  pts[n++] = -sb;
  pts[n++] = R(0.0);
  const real lo = fmin(sb, mu_c), hi = fmax(sb, mu_c);
  if (lo > R(0.0)) pts[n++] = lo;
  if (hi > lo) pts[n++] = hi;
  pts[n++] = R(1.0);
  real sum = R(0.0);
  for (int i = 0; i + 1 < n; ++i) sum += ff_wave_piece(pts[i], pts[i + 1], cb, sb, n1, n2, intervals);
  return sum / SEASIM_PI;
}

/* Eq. 6 from the facet averages (see the header comment): r_sky, r_sun from above; rw_sky, rw_beam from below. */
SEASIM_FN FfSurface ff_wave_surface(real r_sky, real r_sun, real rw_sky, real rw_beam) {
  FfSurface s;
  s.T_dd = R(1.0) - r_sun;
  s.T_df = R(0.0);
  s.T_ff = R(1.0) - r_sky;
  s.Rw_dd = rw_beam;
  s.Rw_df = R(0.0);
  s.Rw_ff = rw_sky;
  return s;
}
