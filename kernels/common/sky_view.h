/* sky_view.h — one sky for every model that looks at it (issue 19): the shape of the scene's [sky]
 * towards a direction in air, the share of it one band takes, and the direction in air that a ray
 * leaving the water upwards through a flat surface sees (Snell's window). The sea from above reads the
 * same shapes through sea_single.cl's own copy (it keeps its SeaParams); the underwater model
 * (kd_multiple.cl) and the host (host/sky/sky_light.*) read them here. Needs compat.h, sky.h and
 * sky_params.h.
 *
 * A band's sky radiance towards d is L_sky(λ) · sky_view_band(w_λ, shape(d)), L_sky(λ) the uniform
 * level ([sky] radiance × D65 shape) and w_λ the band's weights (common/sky.h: R, G, B shares for the
 * image, CIE daylight basis S_k(λ) / D65(λ) for the spectral Preetham sky); the shape includes the
 * scale, so that the cosine-weighted mean over the upper hemisphere is 1 for every model (the
 * luminance's mean for the image and Preetham skies).
 * The model is SEASIM_SKY_MODEL when a kernel is built with it (the branch folds away), else
 * p->model (the host). */

#ifdef SEASIM_SKY_MODEL
#define SKY_VIEW_MODEL(p) SEASIM_SKY_MODEL
#else
#define SKY_VIEW_MODEL(p) ((p)->model)
#endif

/* The sky's shape towards unit d (grey for the uniform and CIE skies: x = y = z), scale included.
 * sky: the image's texels (model 2) or Preetham's 22 reals (model 3, sky_preetham_daylight); unread
 * otherwise. */
SEASIM_FN real3 sky_view_shape(const SEASIM_CONSTANT SkyParams* p, const SEASIM_GLOBAL real* sky, real3 d) {
  const int model = SKY_VIEW_MODEL(p);
  const real3 sun = MAKE_REAL3(p->sun_dir[0], p->sun_dir[1], p->sun_dir[2]);
  const real scale = (real)p->scale;
  if (model == SEASIM_SKY_ANALYTIC) {
    const real v = scale * sky_cie_clear_shape(d, sun);
    return MAKE_REAL3(v, v, v);
  }
  if (model == SEASIM_SKY_IMAGE) return scale * sky_latlong_rgb(sky, p->width, p->height, d);
  if (model == SEASIM_SKY_PREETHAM) return scale * sky_preetham_daylight(sky, d, sun);
  return MAKE_REAL3(R(1.0), R(1.0), R(1.0));
}

/* The share of a shape one band takes: its weights w (R, G, B; the daylight basis for Preetham) for
 * the image and Preetham skies, the grey value for the others (a grey shape is spectrally flat: no
 * weighting). Linear in the shape, but held at 0: with the sun near the horizon Preetham's x, y reach
 * about 0.46–0.49 near the sun, warmer than the daylight basis's 4000 K end and off its locus, and
 * the spectrum S0 + M1 S1 + M2 S2 dips below 0 in the violet; at T = 10 it does at 360–380 nm even
 * with the sun high (tests/unit/sky_daylight_test.cpp). */
SEASIM_FN real sky_view_band(int model, real3 w, real3 shape) {
  if (model == SEASIM_SKY_IMAGE || model == SEASIM_SKY_PREETHAM) return fmax(dot(w, shape), R(0.0));
  return shape.x;
}

/* The direction in air seen from below through a flat surface along the upward unit direction d
 * (d.y > 0), relative index ior = n_water / n_air (Snell, 004 eq. 40–44): the horizontal part grows by
 * ior and the vertical one follows from |a| = 1, exactly unit for a unit d. Outside Snell's window
 * (total internal reflection, where 1 - F = 0 and the sky is not seen) the horizon's direction, so
 * the shape stays finite. */
SEASIM_FN real3 sky_window_air_dir(real3 d, real ior) {
  const real h2 = ior * ior * (R(1.0) - d.y * d.y);
  if (h2 >= R(1.0)) {
    const real h = sqrt(fmax(d.x * d.x + d.z * d.z, R(1e-30)));
    return MAKE_REAL3(d.x / h, R(0.0), d.z / h);
  }
  return MAKE_REAL3(ior * d.x, sqrt(R(1.0) - h2), ior * d.z);
}

/* Sensor RGB of the sky for a shape (scale included): rgb_c = m_c · shape, m three rows of 4 (R, G, B
 * over the shape's x, y, z; 4th unused) that the host sums over the bands, m_ck = Σ_λ to_c(λ) L_sky(λ)
 * w_k(λ) (host/sky: skyRgbMatrix); the grey models put Σ_λ to_c(λ) L_sky(λ) in column 0 alone. */
SEASIM_FN real3 sky_view_rgb(const SEASIM_CONSTANT float* m, real3 shape) {
  return MAKE_REAL3((real)m[0] * shape.x + (real)m[1] * shape.y + (real)m[2] * shape.z,
                    (real)m[4] * shape.x + (real)m[5] * shape.y + (real)m[6] * shape.z,
                    (real)m[8] * shape.x + (real)m[9] * shape.y + (real)m[10] * shape.z);
}
