/* underwater_bands.h — underwater.h's band radiance for SEASIM_BAND_LANES bands at once, the
 * band loop of kd_multiple.cl. The same formulas (002 eq. 2.7, 4.7; the comments of underwater.h),
 * rewritten on realb (common/band_lanes.h) because OpenCL C has no templates; the per-band values that
 * do not depend on the pixel come precomputed from the band table (common/underwater_band_table.h):
 * σ_t/μ_w and σ_s/(4π) E_0 are no longer divided per pixel. tests/unit/underwater_bands_test.cpp holds
 * these to underwater.h's scalar functions in float and double, tests/kernels/underwater_kd_test.cpp
 * the kernel to the double CPU evaluation.
 * One exp fewer than underwater.h per lit band: T(S) = e^{-σ_t S} is folded into the exps of the
 * irradiance at depth, e^{-σ_t S} e^{-k y} = e^{-(k y + σ_t S)} (and the clamp at 0 commutes with the
 * positive factor).
 * Needs compat.h, band_lanes.h, band_lanes_math.h (expm1_over_x_b), sky_view_lanes.h (sky_view_band_b), optics.h
 * (fresnel), underwater_band_table.h, underwater.h (UW_INFINITE). */

/* kd_exp_integral of underwater.h for the lanes' attenuations k and extinctions c, on one ray
 * (d_y, o_d, S shared): e^{-k o_d} ∫_0^S e^{(k d_y - c) z} dz = S e^{max(t, 0) - k o_d} φ(-|t|). */
SEASIM_FN realb kd_exp_integral_b(realb k, realb c, real d_y, real o_d, real S) {
  const realb x = k * d_y - c;
  const maskb diverges = (SPLATB(S) >= UW_INFINITE) & (x >= R(0.0));
  const realb t = SELECTB(diverges, SPLATB(R(0.0)), x * S);
  const realb v = S * exp(fmax(t, R(0.0)) - k * o_d) * expm1_over_x_b(-fabs(t));
  return SELECTB(diverges, SPLATB(R(0.0)), v);
}

/* kd_exp_integral_b with both ends of the integrand given: a = e^{-k o_d} where the ray starts (per band
 * and frame for the camera's rays, whose depth o_d is the frame's: common/underwater_band_table.h) and
 * b = e^{-(k y(S) + c S)} where it ends (the exp that a hit's irradiance takes anyway, so shared with
 * it: common/underwater_ordinates_bands.h). No exp of its own. With x = k d_y - c and t = x S,
 *   e^{-k o_d} ∫_0^S e^{x z} dz = (b - a) / x          (b = e^{t - k o_d}: y(S) = o_d - S d_y)
 * and a S φ(t) (the series of expm1_over_x) where |t| < 0.5 and the difference would cancel. No
 * overflow: a, b <= 1 for a ray in the water. A camera so deep that a underflows (k o_d > 87 in float)
 * loses only what is below float's range (with t > 0, b carries the value); the clamp at 0 keeps the
 * sign where both underflow with different roundings. S = ∞ (t < 0, b = 0) gives a / (c - k d_y), the
 * divergent case 0, as kd_exp_integral_b. */
SEASIM_FN realb kd_exp_integral_ends_b(realb k, realb c, realb a, realb b, real d_y, real S) {
  const realb x = k * d_y - c;
  const maskb diverges = (SPLATB(S) >= UW_INFINITE) & (x >= R(0.0));
  const realb t = SELECTB(diverges, SPLATB(R(0.0)), x * S);
  const maskb small = fabs(t) < R(0.5);
  const realb xs = SELECTB(small, SPLATB(R(1.0)), x);
  const realb ends = fmax((b - a) / xs, R(0.0));
  const realb v = SELECTB(small, (a * S) * SEASIM_EXPM1_OVER_X_SERIES(t), ends);
  return SELECTB(diverges, SPLATB(R(0.0)), v);
}

/* L_MS along the ray (d_y, o_d) to distance S (002 eq. 4.7; kd_multiple_scattering of underwater.h):
 * ms_total = σ_s/(4π) (e_sky0 + e_sun0), ms_direct = σ_s/(4π) e_sun0; single_scattering (a constant
 * in the kernel, so the second integral folds away without it) takes the direct beam out. */
SEASIM_FN realb uw_lanes_multiple(realb ms_total, realb ms_direct, realb kd, realb k_beam, realb c,
                                  int single_scattering, real d_y, real o_d, real S) {
  const realb total = ms_total * kd_exp_integral_b(kd, c, d_y, o_d, S);
  const realb v = single_scattering ? total - ms_direct * kd_exp_integral_b(k_beam, c, d_y, o_d, S) : total;
  return fmax(v, R(0.0));
}

/* T(S) L_s of a Lambertian hit at distance S and depth y (uw_lambert_radiance times e^{-σ_t S}):
 * ρ/π (E_dif(y) (1 + n_y)/2 + E_beam(y) max(n·s_w, 0) vis) e^{-σ_t S}, n_dot_s = n·s_w. */
SEASIM_FN realb uw_lanes_lambert(realb albedo, realb c, realb kd, realb k_beam, realb e_total, realb e_sun,
                                 realb e_beam, int single_scattering, real S, real y, real n_y, real n_dot_s,
                                 real vis) {
  const realb c_s = c * S;
  const realb diffuse_t = e_total * exp(-(kd * y + c_s));
  if (!single_scattering) return albedo / SEASIM_PI * (fmax(diffuse_t, R(0.0)) * (R(0.5) * (R(1.0) + n_y)));
  const realb beam_t = exp(-(k_beam * y + c_s));
  const realb diffuse = fmax(diffuse_t - e_sun * beam_t, R(0.0)) * (R(0.5) * (R(1.0) + n_y));
  const realb direct = e_beam * beam_t * (fmax(n_dot_s, R(0.0)) * vis);
  return albedo / SEASIM_PI * (diffuse + direct);
}

/* T(S) L_s of the water surface seen from below along d_y > 0 (uw_band_surface_sky times e^{-σ_t S}):
 * e^{-σ_t S} (n² (1 - F) L_sky + F L_MS(reflected ray)), the reflected ray going down from depth 0
 * to the bottom (bottom_depth > 0) or deep water; sky_l the lanes' sky radiance in air along the
 * refracted view. */
SEASIM_FN realb uw_lanes_surface(realb sky_l, realb ms_total, realb ms_direct, realb kd, realb k_beam, realb c,
                                 int single_scattering, int multiple, real S, real d_y, real ior,
                                 real bottom_depth) {
  const real s_r = bottom_depth > R(0.0) ? bottom_depth / fmax(d_y, R(1e-6)) : UW_INFINITE;
  const realb l_r = multiple ? uw_lanes_multiple(ms_total, ms_direct, kd, k_beam, c, single_scattering, -d_y,
                                                 R(0.0), s_r)
                             : SPLATB(R(0.0));
  const real f = fresnel_reflectance(d_y, ior, R(1.0));
  return exp(-c * S) * (ior * ior * (R(1.0) - f) * sky_l + f * l_r);
}
