/* band_lanes_math.h — optics.h's expm1_over_x and hg_phase for SEASIM_BAND_LANES values at once
 * (common/band_lanes.h), shared by the band-lane loops (kd_multiple.cl through common/underwater_bands.h,
 * sea_single.cl through common/sea_bands.h, sea_second.cl through common/sea_bottom_lanes.h) and the lamps'
 * node loops (underwater_lamps_ms.h).
 * Needs compat.h, band_lanes.h and optics.h (SEASIM_EXPM1_OVER_X_SERIES). */

/* expm1_over_x of optics.h, lane by lane (the same series and switch at |x| = 0.5, branch-free). */
SEASIM_FN realb expm1_over_x_b(realb x) {
  const realb series = SEASIM_EXPM1_OVER_X_SERIES(x);
  const maskb small = fabs(x) < R(0.5);
  const realb xs = SELECTB(small, SPLATB(R(1.0)), x);
  const realb direct = (exp(xs) - R(1.0)) / xs;
  return SELECTB(small, series, direct);
}

/* hg_phase of optics.h for lanes of cosines under one g: the same stable form and clamp. */
SEASIM_FN realb hg_phase_b(realb cos_theta, real g) {
  const realb c = clamp(cos_theta, R(-1.0), R(1.0));
  const real num = (R(1.0) - g) * (R(1.0) + g);
  realb den;
  if (g >= R(0.0)) {
    den = (R(1.0) - g) * (R(1.0) - g) + R(2.0) * g * (R(1.0) - c);
  } else {
    den = (R(1.0) + g) * (R(1.0) + g) - R(2.0) * g * (R(1.0) + c);
  }
  return num / (R(4.0) * SEASIM_PI * den * sqrt(den));
}
