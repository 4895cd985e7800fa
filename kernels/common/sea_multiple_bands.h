/* sea_multiple_bands.h — sea_multiple.h's closed form (sea.model "multiple": QSSA with Lee et al.'s
 * factors, the skylight in the water, the bottom, the surface's return) for SEASIM_BAND_LANES bands at
 * once (common/band_lanes.h), the band loop of sea_single.cl for SEASIM_SEA_MODEL 1. The same formulas,
 * in the same order of operations, as sea_multiple.h (whose comments give the physics and the fits),
 * rewritten on realb because OpenCL C has no templates. The band's factors (b_b, k, u, D_C, D_B, the
 * higher orders) are computed once per step and shared by the column, the bottom and the return, which
 * the scalar functions each compute again. tests/unit/sea_multiple_bands_test.cpp holds these to
 * sea_multiple.h's scalar functions in float and double; tests/kernels/sea_single_test.cpp the kernel to
 * the double CPU reference.
 * Needs compat.h, band_lanes.h, band_lanes_math.h (expm1_over_x_b), sea_multiple.h. */

/* sea_depth_factor for the lanes' k and secants: 1 - e^{-k H secants}, 1 without a bottom (H < 0). */
SEASIM_FN realb sea_depth_factor_b(realb k, real H, realb secants) {
  const realb x = k * fmax(H, R(0.0)) * secants;
  return H < R(0.0) ? SPLATB(R(1.0)) : x * expm1_over_x_b(-x);
}

/* sea_sky_backscatter_deep for the lanes' e_sky, b_b and k. */
SEASIM_FN realb sea_sky_backscatter_deep_b(realb e_sky, real mu_sky, realb bb, realb k, real cos_ji) {
  return e_sky / mu_sky * bb / (R(2.0) * SEASIM_PI) / fmax(k * (R(1.0) + cos_ji / mu_sky), R(1e-30));
}

/* sea_higher_orders for the lanes' u. */
SEASIM_FN realb sea_higher_orders_b(realb u, real c_f) {
  const real h = fmax(R(2.0) * c_f - R(1.0), R(0.0));
  const realb u2 = u * u;
  return R(1.0) + R(0.52) * u * (R(0.5) + u) + R(0.636) * h * u2 / (u2 + R(0.0397));
}

/* SeaMultipleFactors for the lanes' bands. */
typedef struct {
  realb bb, k, u, d_c, d_b, orders;
} SeaMultipleFactorsB;

SEASIM_FN SeaMultipleFactorsB sea_multiple_factors_b(realb a, realb b, real c_f) {
  SeaMultipleFactorsB f;
  f.bb = b * (R(1.0) - c_f);
  f.k = a + f.bb;
  const maskb absorbs = f.k > R(0.0);
  f.u = SELECTB(absorbs, f.bb / SELECTB(absorbs, f.k, SPLATB(R(1.0))), SPLATB(R(0.0)));
  f.d_c = R(1.03) * sqrt(R(1.0) + R(2.4) * f.u);
  f.d_b = R(1.04) * sqrt(R(1.0) + R(5.4) * f.u);
  f.orders = sea_higher_orders_b(f.u, c_f);
  return f;
}

/* sea_sun_backscatter for the lanes (e_sun_in = E t_in, b, b_b, c, k and D_C per band). */
SEASIM_FN realb sea_sun_backscatter_b(realb e_sun_in, realb b, real phase, realb bb, realb c, realb k, real H,
                                      real cos_io, real cos_ji, realb d_c) {
  const realb bf = fmax(c - k, R(0.0));
  const realb to_beam = fmax(c * cos_ji + k * cos_io, R(1e-30));
  const realb to_all = fmax(k * (cos_io + cos_ji), R(1e-30));
  const realb B = bb / (R(2.0) * SEASIM_PI) / to_beam;
  const realb spread_deep = bb / (R(2.0) * SEASIM_PI) * bf * cos_ji / (to_all * to_beam);
  const realb beam_depth = sea_depth_factor_b(SPLATB(R(1.0)), H, c / cos_io + k * d_c / cos_ji);
  const realb all_depth = sea_depth_factor_b(k, H, R(1.0) / cos_io + d_c / cos_ji);
  const realb spread = fmax((spread_deep + B) * all_depth - B * beam_depth, R(0.0));
  return e_sun_in * (b * phase / to_beam * beam_depth + spread);
}

/* sea_multiple_column for the lanes: f the bands' factors (of a, b, c_f), e_sun and e_sky per band. */
SEASIM_FN realb sea_multiple_column_b(const SeaMultipleFactorsB* f, realb e_sun, real t_in, realb e_sky, realb a,
                                      realb b, real H, real cos_io, real cos_ji, real phase, real mu_sky) {
  const realb sun = sea_sun_backscatter_b(e_sun * t_in, b, phase, f->bb, a + b, f->k, H, cos_io, cos_ji, f->d_c);
  const realb sky = sea_sky_backscatter_deep_b(e_sky, mu_sky, f->bb, f->k, cos_ji) *
                    sea_depth_factor_b(f->k, H, R(1.0) / mu_sky + f->d_c / cos_ji);
  return (sun + sky) * f->orders;
}

/* sea_multiple_bottom for the lanes (0 without a bottom, H < 0). */
SEASIM_FN realb sea_multiple_bottom_b(const SeaMultipleFactorsB* f, realb e_sun, real t_in, realb e_sky, realb albedo,
                                      real H, real cos_io, real cos_ji, real mu_sky, real focus) {
  const real depth = fmax(H, R(0.0));
  const realb e_direct = focus * e_sun * t_in * exp(-f->k * depth / cos_io) + e_sky * exp(-f->k * depth / mu_sky);
  const realb v = albedo / SEASIM_PI * e_direct * exp(-f->k * depth * f->d_b / cos_ji);
  return H < R(0.0) ? SPLATB(R(0.0)) : v;
}

/* sea_column_reflectance for the lanes' factors at one mean cosine, whose sea_column_hemisphere the caller has
 * (once per frame: SeaParams.column_hemisphere; a scalar log1p call per pixel was a fifth of flat_sea's frame). */
SEASIM_FN realb sea_column_reflectance_b(const SeaMultipleFactorsB* f, real H, real mu, real hemisphere) {
  const real m = fmax(mu, R(1e-4));
  return f->u * f->orders * hemisphere * sea_depth_factor_b(f->k, H, SPLATB(R(1.0) / m + R(2.0)));
}

/* sea_bottom_surface_reflectance for the lanes' k and albedo. */
SEASIM_FN realb sea_bottom_surface_reflectance_b(realb k, realb albedo, real H, real mu) {
  const real depth = fmax(H, R(0.0));
  return H < R(0.0) ? SPLATB(R(0.0)) : albedo * exp(-k * depth * (R(1.0) / fmax(mu, R(1e-4)) + R(2.0)));
}

/* sea_multiple_surface_return for the lanes; hemisphere: sea_column_hemisphere of cos_io, mu_sky and mu_ret. */
SEASIM_FN realb sea_multiple_surface_return_b(const SeaMultipleFactorsB* f, realb e_sun, real t_in, realb e_sky,
                                              realb albedo, real H, real cos_io, real cos_ji, real mu_sky, real focus,
                                              real r_below, real mu_ret, int with_column, const real* hemisphere) {
  const real col = with_column ? R(1.0) : R(0.0);
  const realb e_up = e_sun * t_in * (col * sea_column_reflectance_b(f, H, cos_io, hemisphere[0]) +
                                     focus * sea_bottom_surface_reflectance_b(f->k, albedo, H, cos_io)) +
                     e_sky * (col * sea_column_reflectance_b(f, H, mu_sky, hemisphere[1]) +
                              sea_bottom_surface_reflectance_b(f->k, albedo, H, mu_sky));
  const realb r_water = col * sea_column_reflectance_b(f, H, mu_ret, hemisphere[2]) +
                        sea_bottom_surface_reflectance_b(f->k, albedo, H, mu_ret);
  const realb e_down = r_below * e_up / (R(1.0) - fmin(r_below * r_water, R(0.999)));
  const realb column = col * sea_sky_backscatter_deep_b(SPLATB(R(1.0)), mu_ret, f->bb, f->k, cos_ji) *
                       sea_depth_factor_b(f->k, H, R(1.0) / mu_ret + f->d_c / cos_ji) * f->orders;
  const real depth = fmax(H, R(0.0));
  const realb bottom = H < R(0.0) ? SPLATB(R(0.0))
                                  : albedo / SEASIM_PI * exp(-f->k * depth * (R(1.0) / mu_ret + f->d_b / cos_ji));
  return e_down * (column + bottom);
}
