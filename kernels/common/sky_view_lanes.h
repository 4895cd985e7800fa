/* sky_view_lanes.h — sky_view.h's sky_view_band for SEASIM_BAND_LANES bands at once (common/band_lanes.h),
 * for the band-lane loops that see the sky (kd_multiple.cl through common/underwater_bands.h, sea_single.cl
 * through common/sea_bands.h).
 * Needs compat.h, band_lanes.h and sky.h (the model numbers). */

/* sky_view_band of sky_view.h for the lanes' weights (w_r, w_g, w_b) and one shape. */
SEASIM_FN realb sky_view_band_b(int model, realb w_r, realb w_g, realb w_b, real3 shape) {
  if (model == SEASIM_SKY_IMAGE || model == SEASIM_SKY_PREETHAM)
    return fmax(w_r * shape.x + w_g * shape.y + w_b * shape.z, R(0.0));
  return SPLATB(shape.x);
}
