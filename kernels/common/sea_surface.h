/* sea_surface.h — flat-sea terms of paper 000, per wavelength band. Needs compat.h and optics.h.
 * Stiff cases: sun at or below the horizon (no transmitted sun), grazing view (cos -> 0 terms are
 * clamped), no bottom (z_d -> infinity), c -> 0 (1 - exp(-x))/c form through expm1. */

/* Forward-scattering fraction of Henyey–Greenstein: 2*pi * int_0^{pi/2} p(alpha) sin(alpha) dalpha,
 * the c_f of 000 eq. 5 divided by b. The integral is (1 - g^2)/(2g) * (1/(1 - g) - 1/sqrt(1 + g^2)),
 * which cancels catastrophically as g -> 0 (0/0). Using sqrt(1+g^2) - (1-g) = g + g^2/(1+sqrt(1+g^2))
 * it becomes (1 + g)(1 + g/(1 + s)) / (2 s), s = sqrt(1 + g^2): no cancellation for any |g| < 1. */
SEASIM_FN real hg_forward_fraction(real g) {
  real s = sqrt(R(1.0) + g * g);
  return (R(1.0) + g) * (R(1.0) + g / (R(1.0) + s)) / (R(2.0) * s);
}

/* Single scattering of sunlight along the refracted view ray down to depth z_d (000 eq. 5).
 * sun_irradiance is the sun's irradiance on the horizontal surface (L_sun of eq. 5): the refracted
 * beam then carries E T_i / cos_io, and integrating beta * beam * exp(-k z (sec_io + sec_ji)) dz/cos_ji
 * over depth gives exactly eq. 5 (host/reference/sea_reference.cpp does that integral numerically):
 *   L_s = E T_i T_o beta / ((cos_io + cos_ji) c (1 - w0 c_f)) * (1 - exp(-z_d c (1 - w0 c_f)(sec_ji + sec_io)))
 * cos_io: refracted sun angle to the downward vertical, cos_ji: refracted view angle, both > 0.
 * z_d < 0 means no bottom (infinite depth). */
SEASIM_FN real sea_single_scattering(real sun_irradiance, real t_in, real t_out, real beta, real c,
                                     real albedo, real c_f, real cos_io, real cos_ji, real z_d) {
  real k = c * (R(1.0) - albedo * c_f);          /* effective attenuation */
  real sec_sum = R(1.0) / cos_ji + R(1.0) / cos_io;
  /* (1 - exp(-k X)) / k with X = z_d sec_sum, written X * expm1_over_x(-k X): finite as k -> 0. */
  real path = (z_d < R(0.0)) ? R(1.0) / fmax(k, R(1e-30)) : z_d * sec_sum * expm1_over_x(-k * z_d * sec_sum);
  return sun_irradiance * t_in * t_out * beta * path / (cos_io + cos_ji);
}

/* Sunlight reflected by a flat Lambertian bottom at depth z_d back along the refracted view ray
 * (000 eq. 9): L_r = T_o L'_sun K_d cos(gamma) exp(-c z_d sec(theta_ji)). With sun_irradiance the
 * irradiance on the horizontal sea surface (as in eq. 5), the beam in the water carries
 * E T_i / cos_io, so L'_sun cos(gamma) = E T_i exp(-c z_d sec(theta_io)) on a flat bottom
 * (cos(gamma) = cos_io); the paper's reflectance K_d is taken as a Lambertian BRDF albedo/pi.
 * The two legs' attenuations, down along the sun and up along the view, are one exp: the sun leg's
 * e^{-c z_d sec(theta_io)} is the same for every pixel of a band, and folded into the view leg's
 * exponent it costs nothing (a per-band table would cost a buffer and still one exp per pixel).
 * Both exponents are <= 0, so the sum underflows to 0 exactly where the product did. */
SEASIM_FN real sea_bottom_reflection(real sun_irradiance, real t_in, real t_out, real bottom_albedo,
                                     real c, real z_d, real cos_io, real cos_ji) {
  const real attenuation = exp(-c * z_d * (R(1.0) / cos_io + R(1.0) / cos_ji));
  return t_out * sun_irradiance * t_in * (bottom_albedo / SEASIM_PI) * attenuation;
}
