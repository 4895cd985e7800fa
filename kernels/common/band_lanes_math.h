/* band_lanes_math.h — optics.h's expm1_over_x for SEASIM_BAND_LANES bands at once (common/band_lanes.h),
 * shared by the band-lane loops (kd_multiple.cl through common/underwater_bands.h, sea_single.cl through
 * common/sea_bands.h, sea_second.cl through common/sea_bottom_lanes.h).
 * Needs compat.h, band_lanes.h and optics.h (SEASIM_EXPM1_OVER_X_SERIES). */

/* expm1_over_x of optics.h, lane by lane (the same series and switch at |x| = 0.5, branch-free). */
SEASIM_FN realb expm1_over_x_b(realb x) {
  const realb series = SEASIM_EXPM1_OVER_X_SERIES(x);
  const maskb small = fabs(x) < R(0.5);
  const realb xs = SELECTB(small, SPLATB(R(1.0)), x);
  const realb direct = (exp(xs) - R(1.0)) / xs;
  return SELECTB(small, series, direct);
}
