/* band_lanes_math.h — the pieces that both band-lane loops (kd_multiple.cl through
 * common/underwater_bands.h, sea_single.cl through common/sea_bands.h) share, for SEASIM_BAND_LANES bands
 * at once (common/band_lanes.h): optics.h's expm1_over_x and sky_view.h's sky_view_band, lane by lane.
 * Needs compat.h, band_lanes.h, optics.h (SEASIM_EXPM1_OVER_X_SERIES) and sky.h (the model numbers). */

/* expm1_over_x of optics.h, lane by lane (the same series and switch at |x| = 0.5, branch-free). */
SEASIM_FN realb expm1_over_x_b(realb x) {
  const realb series = SEASIM_EXPM1_OVER_X_SERIES(x);
  const maskb small = fabs(x) < R(0.5);
  const realb xs = SELECTB(small, SPLATB(R(1.0)), x);
  const realb direct = (exp(xs) - R(1.0)) / xs;
  return SELECTB(small, series, direct);
}

/* sky_view_band of sky_view.h for the lanes' weights (w_r, w_g, w_b) and one shape. */
SEASIM_FN realb sky_view_band_b(int model, realb w_r, realb w_g, realb w_b, real3 shape) {
  if (model == SEASIM_SKY_IMAGE || model == SEASIM_SKY_PREETHAM)
    return fmax(w_r * shape.x + w_g * shape.y + w_b * shape.z, R(0.0));
  return SPLATB(shape.x);
}
