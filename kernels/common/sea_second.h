/* sea_second.h — second-order scattering under a flat sea (000 §5.2, eq. 6–8), the math shared by
 * kernels/sea_second.cl, host/reference/sea_second_reference.cpp and the unit tests. Needs compat.h
 * and optics.h (hg_phase, expm1_over_x).
 *
 * Everything is written in optical depth tau = c z (and optical path c l), so that no term divides
 * by c: c -> 0 (b -> 0 too) is finite, and one set of formulas serves every wavelength band.
 *
 * Conventions. theta is the angle of a sampling direction omega (the way P_k LOOKS, light travels
 * -omega) from the upward vertical: theta <= pi/2 looks up to the surface, theta > pi/2 down to the
 * bottom. cos_io > 0 is the refracted sun's angle to the downward vertical; e_beam is the sun's beam
 * irradiance just below the surface, E_h T_i / cos_io (E_h: irradiance on the horizontal surface, the
 * L_sun of 000 eq. 5, see sea_surface.h). tau_d < 0 means no bottom (infinitely deep water).
 *
 * Stiff cases handled:
 *   - 1 - sec(theta_io) cos(theta) -> 0 (looking back up the sun beam), where 000 eq. 7's L* has 0/0:
 *     the path integral is written as l (1 - e^{-kappa l}) / (kappa l) through expm1_over_x;
 *   - theta -> pi/2 from both sides: the sampling ray becomes infinitely long (exactly infinite at
 *     cos theta = 0) and both branches of eq. 7 tend to L*(theta) e^{-c z sec theta_io};
 *   - kappa < 0 (theta < theta_io): e^{-a} e^{-kappa l} is combined into one exponent so that neither
 *     factor overflows or underflows alone;
 *   - sun below the horizon: e_beam = 0 gives exactly 0.
 */

/* int_0^l_max exp(-a - kappa l) dl, l_max < 0 meaning infinity (then kappa > 0 is required; kappa <= 0
 * returns 0, the b = c = 0 limit of the callers). Two forms, each free of overflow and 0/0:
 *   kappa l >= 0:  e^{-a} l (1 - e^{-kappa l})/(kappa l)
 *   kappa l <  0:  e^{-(a + kappa l)} l (1 - e^{kappa l})/(-kappa l)     (same value, e^{-kappa l} > 1
 * folded into the exponent, which is the attenuation at the far end and never positive here).
 * Both are e^{-(a + min(x, 0))} l φ(-|x|), written so, with the infinite path selected at the end:
 * one exp, one φ and no branch in the direction and band loops that call this. */
SEASIM_FN real sea_path_integral(real a, real kappa, real l_max) {
  const int infinite = l_max < R(0.0);
  const real x = infinite ? R(0.0) : kappa * l_max;
  const real e = exp(-(a + fmin(x, R(0.0))));
  const real finite_path = e * l_max * expm1_over_x(-fabs(x));
  const real infinite_path = kappa > R(0.0) ? e / fmax(kappa, R(1e-30)) : R(0.0);
  return infinite ? infinite_path : finite_path;
}

/* The radiance map of 000 eq. 7: single-scattered sunlight L^(1)(z_k, theta, phi) arriving at depth
 * z_k (optical depth tau_k = c z_k) from the sampling direction omega with cos_theta = omega.y.
 * phase = p(alpha), the normalised phase function between the sun beam and the light's travel
 * direction -omega; albedo = b/c. With l the optical path from P_k along omega,
 *   L^(1) = e_beam albedo phase int_0^{l_max} exp(-tau_k sec_io - l (1 - cos_theta sec_io)) dl
 * (depth along the ray tau_k - l cos_theta; the beam is e_beam e^{-tau sec_io} at tau). This is
 * eq. 7 exactly: L* = L_sun T beta / (c (1 - sec_io cos theta)) times
 *   theta <= pi/2: l_max = tau_k sec theta (the surface):
 *                  e^{-c z_k sec_io} - e^{-c z_k sec theta}
 *   theta >  pi/2: l_max = (tau_d - tau_k)/|cos theta| (the bottom):
 *                  e^{-c z_k sec_io} - e^{-c (z_d sec_io - (z_d - z_k) sec theta)}
 * but in the stable form of sea_path_integral (0/0 at cos theta = cos_io removed). The bottom's own
 * reflection is not a source here, as in the paper. */
SEASIM_FN real sea_radiance_map(real e_beam, real albedo, real phase, real cos_io, real cos_theta, real tau_k,
                                real tau_d) {
  real kappa = (cos_io - cos_theta) / cos_io; /* 1 - sec(theta_io) cos(theta), one rounding */
  real l_max;
  if (cos_theta > R(0.0)) {
    l_max = tau_k / cos_theta;
  } else if (cos_theta < R(0.0) && tau_d >= R(0.0)) {
    l_max = fmax(tau_d - tau_k, R(0.0)) / (-cos_theta);
  } else {
    l_max = R(-1.0); /* horizontal ray, or looking down into bottomless water */
  }
  return e_beam * albedo * phase * sea_path_integral(tau_k / cos_io, kappa, l_max);
}

/* The volume-scattering-function map (000 §5.2): the phase function tabulated over the phase angle.
 * The table's parameter is t = sin(alpha/2) = sqrt((1 - cos alpha)/2) in [0, 1], uniform steps: it
 * is ~alpha/2 near the forward peak (resolving HG spikes that a table uniform in cos alpha would
 * miss) and needs no acos. beta = b * sea_vsf_value. */
SEASIM_FN real sea_vsf_param(real cos_alpha) {
  return sqrt(clamp(R(0.5) * (R(1.0) - cos_alpha), R(0.0), R(1.0)));
}
SEASIM_FN real sea_vsf_value(real t, real g) { return hg_phase(R(1.0) - R(2.0) * t * t, g); }

/* The attenuation map G of 000 eq. 6: exp(-c z_k sec theta_ji), from P_k up to the surface. */
SEASIM_FN real sea_attenuation(real tau_k, real cos_ji) { return exp(-tau_k / cos_ji); }

/* The depths of the n_z sampling planes (the paper leaves them open). The view-ray integrand
 * G J behaves like exp(-tau (sec_ji + sec_io)) with sec_ji >= 1, so the planes are midpoints in the
 * transmittance u = exp(-s tau), s = 1 + sec_io, over [exp(-s tau_d), 1] (tau_d < 0: [0, 1], no
 * cut-off depth needed for bottomless water). Returns tau_k and writes the quadrature weight
 * d tau = du / (s u) to *weight, so that int_0^{tau_d} f dtau ~= sum_k f(tau_k) weight_k. */
SEASIM_FN real sea_plane_depth(int k, int n_z, real cos_io, real tau_d, real* weight) {
  real s = R(1.0) + R(1.0) / cos_io;
  real span = tau_d < R(0.0) ? R(1.0) : one_minus_exp_neg(s * tau_d); /* 1 - u_min */
  real frac = (R(k) + R(0.5)) / R(n_z) * span;             /* 1 - u_k */
  real u = R(1.0) - frac;
  *weight = span / (R(n_z) * s * u);
  return -log1p(-frac) / s;
}

/* Sampling direction m of n_theta x n_phi (000 eq. 8): midpoints theta_j = (j + 1/2) pi / n_theta,
 * phi_i = (i + 1/2) 2 pi / n_phi, m = j n_phi + i; y is up. Returns the weight sin(theta) dtheta dphi. */
SEASIM_FN real sea_direction(int m, int n_theta, int n_phi, real3* omega) {
  int j = m / n_phi;
  int i = m - j * n_phi;
  real d_theta = SEASIM_PI / R(n_theta);
  real d_phi = R(2.0) * SEASIM_PI / R(n_phi);
  real theta = (R(j) + R(0.5)) * d_theta;
  real phi = (R(i) + R(0.5)) * d_phi;
  real st = sin(theta);
  *omega = MAKE_REAL3(st * cos(phi), cos(theta), st * sin(phi));
  return st * d_theta * d_phi;
}
