/* sea_band_terms.h — one step of sea_single.cl's band loop: the radiance of SEASIM_BAND_LANES bands
 * (sea.model "paper", paper 000's eq. 5 and 9 plus the reflected sky and sun, on the lanes of
 * common/sea_bands.h; sea.model "multiple", common/sea_multiple.h's closed form on the lanes of
 * common/sea_multiple_bands.h held to the plane-parallel solution by common/sea_ordinates.h's κ; both
 * reading the band table of common/sea_band_table.h), and of the sky above the horizon. The
 * pixel's terms come from common/sea_view.h's SeaPixel; the operations are those of the kernel's former
 * single body, in the same order. tests/unit/sea_view_test.cpp holds these in float and double;
 * tests/kernels/sea_single_test.cpp the kernel to the double CPU reference.
 * Needs sea_view.h, band_lanes.h, band_lanes_math.h, sea_band_table.h, sea_bands.h, sea_multiple_bands.h,
 * sea_ordinates.h. */

/* Bands i .. i + SEASIM_BAND_LANES - 1 of the band table's row `row` (stride: SEA_BAND_STRIDE). */
#define SEA_TABLE_LANES(table, stride, row, i) LOADB((table) + (size_t)(row) * (stride), i)

/* The sky's radiance seen along a view above the horizon with shape sea_sky_shape, and the sun's disk
 * when the view sees it (sea_sees_sun). */
SEASIM_FN realb sea_sky_lanes_b(int sky_model, const SEASIM_GLOBAL real* table, int stride, int i, real3 shape,
                                int sees_sun, real sun_solid_angle) {
  const realb sky_l = sea_sky_band_b(sky_model, SEA_TABLE_LANES(table, stride, SEA_ROW_SKY, i),
                                     SEA_TABLE_LANES(table, stride, SEA_ROW_SKY_W_R, i),
                                     SEA_TABLE_LANES(table, stride, SEA_ROW_SKY_W_G, i),
                                     SEA_TABLE_LANES(table, stride, SEA_ROW_SKY_W_B, i), shape);
  return sees_sun ? sky_l + SEA_TABLE_LANES(table, stride, SEA_ROW_SUN, i) / sun_solid_angle : sky_l;
}

/* The reflected sky and sun: R times the sky (and the sun's disk where the reflected view sees it);
 * filtered, the Fresnel-weighted sky and the glint, R already in both. */
SEASIM_FN realb sea_reflection_lanes_b(SeaFeatures f, const SEASIM_GLOBAL real* table, int stride, int i,
                                       const SeaPixel* px, realb sun_e, real sun_solid_angle) {
  const realb sky_l = sea_sky_band_b(f.sky_model, SEA_TABLE_LANES(table, stride, SEA_ROW_SKY, i),
                                     SEA_TABLE_LANES(table, stride, SEA_ROW_SKY_W_R, i),
                                     SEA_TABLE_LANES(table, stride, SEA_ROW_SKY_W_G, i),
                                     SEA_TABLE_LANES(table, stride, SEA_ROW_SKY_W_B, i), px->reflected_shape);
  if (f.wave_filter) return sky_l + px->glint * sun_e;
  if (f.sun) return px->R_view * (px->reflects_sun ? sky_l + sun_e / sun_solid_angle : sky_l);
  return px->R_view * sky_l;
}

/* 000 eq. 5 through the surface: from the LUT (SEASIM_SEA_LUT, without beta and T_o, Catmull–Rom over
 * the pixel's taps) or exactly (sea_single_scattering_b, z_d from the bottom view). */
SEASIM_FN realb sea_scattering_lanes_b(SeaFeatures f, const SEASIM_GLOBAL real* table, int stride, int i,
                                       const SeaPixel* px, realb sun_e) {
  const realb scattering = SEA_TABLE_LANES(table, stride, SEA_ROW_B, i);
  if (f.lut)
    return scattering * px->phase * px->t_out *
           sea_lut_read_b(SEA_TABLE_LANES(table, stride, SEA_ROW_LUT + px->lut_jm, i),
                          SEA_TABLE_LANES(table, stride, SEA_ROW_LUT + px->lut_j, i),
                          SEA_TABLE_LANES(table, stride, SEA_ROW_LUT + px->lut_j + 1, i),
                          SEA_TABLE_LANES(table, stride, SEA_ROW_LUT + px->lut_jp, i), px->lut_t);
  const realb c = SEA_TABLE_LANES(table, stride, SEA_ROW_C, i);
  const realb albedo = SELECTB(c > R(0.0), scattering / c, SPLATB(R(0.0)));
  return sea_single_scattering_b(sun_e * px->sun_horizontal, px->t_in, px->t_out, scattering * px->phase, c, albedo,
                                 px->c_f, px->cos_io, px->cos_ji, px->z_d);
}

/* 000 eq. 9, times the caustics' focus; on a height field tilted by the floor's normal
 * (sea_bottom_reflection_tilted). */
SEASIM_FN realb sea_bottom_lanes_b(SeaFeatures f, const SEASIM_GLOBAL real* table, int stride, int i, const SeaPixel* px,
                                   realb sun_e) {
  const realb bottom = sea_bottom_reflection_b(sun_e * px->sun_horizontal, px->t_in, px->t_out,
                                               SEA_TABLE_LANES(table, stride, SEA_ROW_BOTTOM_ALBEDO, i),
                                               SEA_TABLE_LANES(table, stride, SEA_ROW_C, i), px->z_d, px->cos_io,
                                               px->cos_ji);
  if (f.bottom_heightfield) return px->focus * (bottom * (px->cos_gamma / px->cos_io));
  return px->focus * bottom;
}

/* The water-leaving and reflected radiance of bands i .. i + SEASIM_BAND_LANES - 1 (sea.model "single"). */
SEASIM_FN realb sea_band_lanes_b(SeaFeatures f, const SEASIM_GLOBAL real* table, int stride, int i, const SeaPixel* px,
                                 real sun_solid_angle) {
  const realb sun_e = SEA_TABLE_LANES(table, stride, SEA_ROW_SUN, i);
  realb L = SPLATB(R(0.0));
  if (f.reflection) L += sea_reflection_lanes_b(f, table, stride, i, px, sun_e, sun_solid_angle);
  if (f.single_scattering) L += sea_scattering_lanes_b(f, table, stride, i, px, sun_e);
  if (f.bottom) L += sea_bottom_lanes_b(f, table, stride, i, px, sun_e);
  return L;
}

/* The lanes' κ (common/sea_ordinates.h) bilinear in zenith and azimuth on the depth layer from `row`. */
SEASIM_FN realb sea_ordinates_layer_b(const SEASIM_GLOBAL real* table, int stride, int i, int row, real tz, real ta) {
  const int r = SEA_ROW_ORDINATES + row;
  const realb near_zenith =
      (R(1.0) - ta) * SEA_TABLE_LANES(table, stride, r, i) + ta * SEA_TABLE_LANES(table, stride, r + 1, i);
  const realb next_zenith = (R(1.0) - ta) * SEA_TABLE_LANES(table, stride, r + SEA_ORD_AZIMUTHS, i) +
                            ta * SEA_TABLE_LANES(table, stride, r + SEA_ORD_AZIMUTHS + 1, i);
  return (R(1.0) - tz) * near_zenith + tz * next_zenith;
}

/* The lanes' factor κ at the pixel: one layer, or two blended in depth over a height field (depth_grid). */
SEASIM_FN realb sea_ordinates_factor_b(const SEASIM_GLOBAL real* table, int stride, int i, const SeaPixel* px,
                                       int depth_grid) {
  const realb kappa = sea_ordinates_layer_b(table, stride, i, px->ord_row0, px->ord_tz, px->ord_ta);
  if (!depth_grid) return kappa;
  return (R(1.0) - px->ord_td) * kappa +
         px->ord_td * sea_ordinates_layer_b(table, stride, i, px->ord_row1, px->ord_tz, px->ord_ta);
}

/* Bands i .. i + SEASIM_BAND_LANES - 1 of sea.model "multiple" from the band table: the reflection as
 * sea.model "paper" has it (the sun's disk where px->reflects_sun), then all orders in closed form
 * (sea_multiple.h: the column, the bottom and the surface's return, with the bands' factors computed
 * once) held to the plane-parallel solution by κ (sea_ordinates.h), through the surface with T_o =
 * (1 - R)/n². The sky's irradiance below the surface: π L_sky (1 - r̄), L_sky the band's cosine-weighted
 * mean sky radiance (the shape is normalised to mean 1). */
SEASIM_FN realb sea_multiple_lanes_b(SeaFeatures f, SEASIM_CONSTANT const SeaParams* p, const SEASIM_GLOBAL real* table,
                                     int stride, int i, const SeaPixel* px) {
  const realb sun = SEA_TABLE_LANES(table, stride, SEA_ROW_SUN, i);
  realb L = SPLATB(R(0.0));
  if (f.reflection) L += sea_reflection_lanes_b(f, table, stride, i, px, sun, p->sun_solid_angle);
  if (!f.single_scattering && !f.bottom) return L;
  const realb e_sky = SEASIM_PI *
                      sea_sky_band_b(f.sky_model, SEA_TABLE_LANES(table, stride, SEA_ROW_SKY, i),
                                     SEA_TABLE_LANES(table, stride, SEA_ROW_SKY_W_R, i),
                                     SEA_TABLE_LANES(table, stride, SEA_ROW_SKY_W_G, i),
                                     SEA_TABLE_LANES(table, stride, SEA_ROW_SKY_W_B, i), MAKE_REAL3(1.0, 1.0, 1.0)) *
                      (R(1.0) - p->sky_fresnel_mean);
  const realb e_sun = sun * px->sun_horizontal;
  const realb a = SEA_TABLE_LANES(table, stride, SEA_ROW_A, i), b = SEA_TABLE_LANES(table, stride, SEA_ROW_B, i);
  const realb albedo = SEA_TABLE_LANES(table, stride, SEA_ROW_BOTTOM_ALBEDO, i);
  const SeaMultipleFactorsB factors = sea_multiple_factors_b(a, b, px->c_f);
  realb below = SPLATB(R(0.0));
  if (f.single_scattering)
    below += sea_multiple_column_b(&factors, e_sun, px->t_in, e_sky, a, b, px->z_d, px->cos_io, px->cos_ji, px->phase,
                                   px->mu_sky);
  if (f.bottom)
    below += sea_multiple_bottom_b(&factors, e_sun, px->t_in, e_sky, albedo, px->z_d, px->cos_io, px->cos_ji,
                                   px->mu_sky, px->focus);
  below += sea_multiple_surface_return_b(&factors, e_sun, px->t_in, e_sky, albedo, px->z_d, px->cos_io, px->cos_ji,
                                         px->mu_sky, px->focus, px->r_below, px->mu_ret, f.single_scattering,
                                         px->hemisphere);
  return L + px->t_out * sea_ordinates_factor_b(table, stride, i, px, f.bottom_heightfield) * below;
}
