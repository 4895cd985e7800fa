/* sea_bands.h — sea_single.cl's band terms (paper 000's eq. 5 and 9, the sky and its reflection) for
 * SEASIM_BAND_LANES bands at once (common/band_lanes.h), the band loop of sea_single.cl for
 * sea.model "single" (SEASIM_SEA_MODEL 0). The same formulas, in the same order of operations, as
 * sea_surface.h, sea_bottom.h and sea_band_terms.h's one-band step (their comments give the physics), on
 * realb because OpenCL C has no templates; the per-band values come from the band table
 * (common/sea_band_table.h), whose eq. 5 LUT is band-contiguous, so the LUT's four Catmull–Rom taps
 * are found once per pixel and read as four vector loads. tests/unit/sea_bands_test.cpp holds these to
 * the scalar functions in float and double; tests/kernels/sea_single_test.cpp the kernel to the double
 * CPU reference, with band counts that do not fill the lanes.
 * Needs compat.h, band_lanes.h, band_lanes_math.h, sky_view_lanes.h, optics.h, sea_surface.h. */

/* The taps of sea_single.cl's Catmull–Rom read of an n-entry LUT (n >= 2) at fractional index x in
 * [0, n-1], indices mirrored at both ends (the factors are even about 0 and pi/2): entries jm, j, j+1,
 * jp and the fraction t it returns. The same for every band of a pixel. */
SEASIM_FN real sea_lut_taps(int n, real x, int* jm, int* j, int* jp) {
  const int i = (int)x;
  const int j0 = i < 0 ? 0 : (i > n - 2 ? n - 2 : i);
  *jm = j0 > 0 ? j0 - 1 : 1;
  *j = j0;
  *jp = j0 + 2 < n ? j0 + 2 : n - 2;
  return x - (real)j0;
}

/* The Catmull–Rom interpolation at fraction t between the lanes' entries p1 and p2 (p0, p3 beyond). */
SEASIM_FN realb sea_lut_read_b(realb p0, realb p1, realb p2, realb p3, real t) {
  return p1 + R(0.5) * t *
                  (p2 - p0 + t * (R(2.0) * p0 - R(5.0) * p1 + R(4.0) * p2 - p3 + t * (R(3.0) * (p1 - p2) + p3 - p0)));
}

/* sea_single_scattering of sea_surface.h (000 eq. 5) for the lanes' sun irradiance (on the horizontal
 * surface), beta, c and albedo; the angles, T_i, T_o, c_f and z_d (< 0: no bottom) are the pixel's. */
SEASIM_FN realb sea_single_scattering_b(realb sun_irradiance, real t_in, real t_out, realb beta, realb c,
                                        realb albedo, real c_f, real cos_io, real cos_ji, real z_d) {
  const realb k = c * (R(1.0) - albedo * c_f);
  const real sec_sum = R(1.0) / cos_ji + R(1.0) / cos_io;
  const realb path = (z_d < R(0.0)) ? R(1.0) / fmax(k, R(1e-30)) : z_d * sec_sum * expm1_over_x_b(-k * z_d * sec_sum);
  return sun_irradiance * t_in * t_out * beta * path / (cos_io + cos_ji);
}

/* sea_bottom_reflection of sea_surface.h (000 eq. 9, one exp for both legs) for the lanes' sun
 * irradiance (on the horizontal surface), bottom albedo and c. */
SEASIM_FN realb sea_bottom_reflection_b(realb sun_irradiance, real t_in, real t_out, realb bottom_albedo, realb c,
                                        real z_d, real cos_io, real cos_ji) {
  const realb attenuation = exp(-c * z_d * (R(1.0) / cos_io + R(1.0) / cos_ji));
  return t_out * sun_irradiance * t_in * (bottom_albedo / SEASIM_PI) * attenuation;
}

/* The lanes' sky radiance for one shape (sea_view.h's sea_sky_band): the uniform level times the band's
 * share of the shape (sky_view_band_b), model = SEASIM_SKY_MODEL. */
SEASIM_FN realb sea_sky_band_b(int model, realb sky_radiance, realb w_r, realb w_g, realb w_b, real3 shape) {
  return sky_radiance * sky_view_band_b(model, w_r, w_g, w_b, shape);
}
