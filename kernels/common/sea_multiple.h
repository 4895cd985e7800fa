/* sea_multiple.h — sea.model = "multiple": a closed form per band for the water-leaving radiance of the
 * sea seen from above with all orders of scattering, in place of paper 000's eq. 5 + eq. 6–8 + eq. 9
 * (sea.model = "paper"). Needs compat.h, optics.h and sea_surface.h (hg_forward_fraction,
 * sea_single_scattering) before it. Shared by kernels/sea_single.cl, the host and
 * tests/unit/sea_multiple_test.cpp (float and double).
 *
 * Why (measured, results/sea_allorders/): paper 000's terms are 0.17–0.87 of all orders in image-mean
 * luminance outside deep clear water. Two things are missing:
 *  - the bottom: eq. 9 attenuates the sun with c down and up. At g = 0.9 almost all scattered light goes
 *    on forwards (c_f = 0.977) and still reaches the bottom, and the light the bottom reflects still
 *    reaches the surface; in Jerlov III at 2 m eq. 9's e^{-c H (sec + sec)} is 0.008 where the bottom's
 *    light really arrives at about 2/3.
 *  - the orders above 2 in turbid water, and the skylight in the water (no term in paper 000).
 *
 * The model: the quasi-single-scattering approximation (QSSA: light scattered forwards, into the
 * hemisphere ahead, is counted as not scattered) that paper 000's own eq. 5 uses, k = c (1 - ω₀ c_f) =
 * a + b_b with b_b = b (1 - c_f) the HG back-scattering coefficient, carried to every term, with the
 * semi-analytic shallow-water model of Lee et al. (1998, Appl. Opt. 37, 6329, eq. 9–12; 1999, Appl.
 * Opt. 38, 3831, eq. 4–7) for what the QSSA leaves: u = b_b / (a + b_b),
 *   column:  L_c = (L_sun + L_sky) orders(u), each its deep-water value times the depth factor
 *            1 - e^{-k H (1/μ_in + D_C/μ_v)} (μ_in: μ_s for the sun, μ_sky for the sky)
 *   bottom:  L_b = ρ/π E_d(H) e^{-k H D_B / μ_v},   E_d(H) = E_sun e^{-k H/μ_s} + E_sky e^{-k H/μ_sky}
 *   surface: the surface sends r_below of the upwelling light (column and bottom) back down, and
 *            the water returns it again (sea_multiple_surface_return; bottom–surface bounces included)
 *   D_C = 1.03 sqrt(1 + 2.4 u),  D_B = 1.04 sqrt(1 + 5.4 u)   (Lee 1999 eq. 6, 7: the upwelling light's
 *   path per metre of depth, longer than the view's 1/μ_v because it has been scattered).
 * L_sun is the sun's QSSA single scattering split into the unscattered beam (exact HG phase at the
 * pixel's angle, c on the way down) and the light already scattered forwards (b_b/(2π) per sr), each
 * with its own depth factor (sea_sun_backscatter); 000 eq. 5 gives all of it the beam's phase and k on
 * both legs, which was 0.74–0.82 of all orders in deep Jerlov II, III, 3C. L_sky the same QSSA single scattering of the diffuse skylight in the
 * water, E_sky = π L_sky (1 - r̄) (r̄ the uniform sky's mean Fresnel reflectance), arriving inside
 * Snell's window (mean cosine μ_sky = E_d/E_0 = (1 + cos θ_c)/2, exact for a uniform radiance over
 * the window's cone) and scattered back with b_b spread evenly over the upper hemisphere, b_b/(2π) per sr:
 *   L_sky(deep) = E_sky/μ_sky · b_b/(2π) / (k (1 + μ_v/μ_sky)).
 * orders(u, g) (sea_higher_orders): the higher orders relative to the first, put on top of the exact
 * HG first order; fitted on the uncapped path tracer for HG g = 0-0.95 (docs/journal/sea_all_orders.md).
 * Before, it was 1 + 0.6 (1 - e^{-30 u²}) for g = 0.9 on a path tracer capped at 64 vertices, and before that Lee's
 * 1 + 2.02 u ((0.084 + 0.170 u) u over its single-scattering limit 0.084 u, from Hydrolight with a
 * Petzold phase function).
 * Not in papers 000–004: Lee et al.'s D_C, D_B are an outside source (docs/models.md), and the orders'
 * three numbers are fitted here.
 * Everything here is below the surface; the caller applies T_o = (1 - R)/n² (the n² law), and the factor κ
 * of common/sea_ordinates.h, which holds the sum of the column, the bottom and the return to the
 * discrete-ordinates solution of the same flat layer (the spread term's isotropic back-scatter misses the
 * HG phase's rise towards 150°: 0.92–0.94 of all orders near the nadir in deep turbid water without it).
 *
 * Stiff cases: k -> 0 (clear water at long wavelengths is not that, but a = b = 0 is allowed): the
 * depth factors go through expm1_over_x; H < 0 means no bottom (infinitely deep): depth factors 1,
 * bottom 0; μ_v, μ_s clamped away from 0 by the caller (1e-4); u in [0, 1]: the square roots are of
 * numbers >= 1.
 */

/* Mean cosine E_d / E_0 (to the downward vertical) of a uniform sky refracted into water of index ior:
 * the radiance fills Snell's cone of half-angle θ_c, sin θ_c = 1/ior, so E_d = π L sin² θ_c and
 * E_0 = 2π L (1 - cos θ_c), whose ratio is (1 + cos θ_c)/2. E_d decays at first as e^{-k y/μ}. */
SEASIM_FN real sea_sky_mean_cosine(real ior) {
  const real s = R(1.0) / fmax(ior, R(1.0));
  return R(0.5) * (R(1.0) + sqrt(fmax(R(1.0) - s * s, R(0.0))));
}

/* The surface's reflectance, seen from below, for a uniform (Lambertian) upwelling radiance:
 * r_below = 1 - (1 - r_above)/n², r_above the same for a uniform sky from above (the cosine-weighted
 * mean Fresnel reflectance, skyFresnelMean). Exact by reciprocity: a direction pair across the surface
 * has one F, and n² cos θ_w dω_w = cos θ_a dω_a, so the flux a uniform L_w sends out is π L_w (1 -
 * r_above)/n²; the rest, total internal reflection included, goes back down (0.47 at n = 1.333). */
SEASIM_FN real sea_surface_reflectance_below(real r_above, real ior) {
  return R(1.0) - (R(1.0) - r_above) / (ior * ior);
}

/* 1 - e^{-k H secants}, or 1 without a bottom (H < 0): as x φ(-x), φ = expm1_over_x, exact as k -> 0. */
SEASIM_FN real sea_depth_factor(real k, real H, real secants) {
  const real x = k * fmax(H, R(0.0)) * secants;
  return H < R(0.0) ? R(1.0) : x * expm1_over_x(-x);
}

/* The skylight's QSSA single scattering back along the view in infinitely deep water (see the top),
 * below the surface: e_sky the diffuse irradiance just below the surface, mu_sky its mean cosine, bb
 * the back-scattering coefficient, k = a + b_b, cos_ji the refracted view's cosine. */
SEASIM_FN real sea_sky_backscatter_deep(real e_sky, real mu_sky, real bb, real k, real cos_ji) {
  return e_sky / mu_sky * bb / (R(2.0) * SEASIM_PI) / fmax(k * (R(1.0) + cos_ji / mu_sky), R(1e-30));
}

/* The higher orders relative to this model's QSSA first order, by u = b_b/(a + b_b) and the HG g (through
 * c_f = hg_forward_fraction(g), which the callers already have; h = 2 c_f - 1 is 0 at g = 0 and -> 1 as
 * g -> 1, smooth in g; g < 0, back-scattering, not met in water, is taken as g = 0's):
 *   orders(u, g) = 1 + 0.52 u (1/2 + u) + 0.636 h u² / (u² + 0.0397)
 * the first part what isotropic-ish water (g = 0) needs, the second what forward water adds and that
 * levels off once u passes about 0.2. Fitted (three numbers, tests/perf/sea_orders_fit_g.py)
 * on the path tracer of kernels/reference.cl without its bounce cap (--max-bounces 2048; 8192 gave the
 * same image) and without internal reflection over the first order alone (sea.model = "multiple" with
 * orders 1 and no surface return; the sky's reflection subtracted from both), 30 deep one-grey-band
 * cases, g = 0, 0.5, 0.8, 0.9, 0.95 at u = 0.05-0.7, the view of tests/perf/sea_allorders.sh
 * (tests/perf/sea_orders_fit.sh, results/sea_allorders/orders_fit_g.csv): RMS 1.7 %, worst 5.4 % (g 0.95
 * at u 0.05, where the path tracer needs 0.997, less than the first order; else within 4.2 %); at g 0.9
 * within 1.7 % for u = 0.05-0.7. Checked, not fitted, on uncapped references (results/sea_allorders/
 * README.md): one grey band, deep, g 0.9, internal reflection included, u 0.35 / 0.45 / 0.62:
 * 0.985 / 1.010 / 1.070 of all orders (the g = 0.9 factor 0.968 / 0.924 / 0.854); Jerlov III and 3C at 10 m
 * and deep, I deep, 16 bands: 0.973-1.000 (g = 0.9 factor 0.974-1.004; III closer by 1 %, 3C further by 2 %).
 * Before, it was 1 + 0.6 (1 - e^{-30 u²}) for g = 0.9 alone, fitted on a path tracer capped at 64
 * scattering vertices, which made the factor level at 1.6: uncapped it rises on, 1.90 at u = 0.6; and
 * before that Lee 1999 eq. 5's 1 + 2.02 u (Hydrolight, Petzold phase function), too bright for u >= 0.35.
 * Exactly 1 at u = 0; rising in u (every term is, for h >= 0); at most 2.39 for u in [0, 1]; one
 * division and no exp (expm1 here made the whole kernel 5x slower on PoCL, measured). */
SEASIM_FN real sea_higher_orders(real u, real c_f) {
  const real h = fmax(R(2.0) * c_f - R(1.0), R(0.0));
  const real u2 = u * u;
  return R(1.0) + R(0.52) * u * (R(0.5) + u) + R(0.636) * h * u2 / (u2 + R(0.0397));
}

/* The band's factors (see the top): k = a + b_b, u = b_b / k, D_C, D_B (Lee 1999), sea_higher_orders
 * (of u and c_f = hg_forward_fraction(g)). */
typedef struct {
  real bb, k, u, d_c, d_b, orders;
} SeaMultipleFactors;

SEASIM_FN SeaMultipleFactors sea_multiple_factors(real a, real b, real c_f) {
  SeaMultipleFactors f;
  f.bb = b * (R(1.0) - c_f);
  f.k = a + f.bb;                                             /* = c (1 - ω₀ c_f), 000 eq. 5 */
  f.u = f.k > R(0.0) ? f.bb / f.k : R(0.0);
  f.d_c = R(1.03) * sqrt(R(1.0) + R(2.4) * f.u);              /* Lee 1999 eq. 6 */
  f.d_b = R(1.04) * sqrt(R(1.0) + R(5.4) * f.u);              /* Lee 1999 eq. 7 */
  f.orders = sea_higher_orders(f.u, c_f);
  return f;
}

/* The sun's light scattered back towards the eye below the surface (no T_o, no higher orders), the
 * QSSA downwelling split in two:
 *  - the unscattered beam, E_n e^{-c y/μ_s}, scattered into the view with the exact HG phase at the
 *    pixel's angle (the true first order: only unscattered light keeps the sun's direction);
 *  - the light already scattered forwards, E_n (e^{-k y/μ_s} - e^{-c y/μ_s}) (the QSSA's total minus the
 *    beam), whose directions have spread around the sun's, scattered back evenly over the upper
 *    hemisphere, b_b/(2π) per sr, as the skylight is.
 * Paper 000's eq. 5 gives the whole QSSA flux the beam's phase; at g = 0.9 and the sun behind the
 * camera the view sees HG near 180°, 0.6x its mean over the back hemisphere, and that is most of what
 * it missed in turbid water (results/sea_allorders/: deep Jerlov III 0.74 -> 0.95 of all orders).
 * Both parts go back up with k. In deep water (H < 0), with E_n = E/μ_s and ∫ dy/μ_v:
 *   beam   = E b p / (c μ_v + k μ_s)
 *   spread = E b_b/(2π) (1/(k (μ_s + μ_v)) - 1/(c μ_v + k μ_s)) = E b_b/(2π) b_f μ_v / (k (μ_s + μ_v) (c μ_v + k μ_s))
 * with b_f = c - k, the forward scattering; over a bottom at H each part times its depth factor, the
 * view leg stretched by d_c (Lee 1999, as for the sky): 1 - e^{-x_c} and 1 - e^{-x_k}, x_c = H (c/μ_s
 * + k d_c/μ_v), x_k = H k (1/μ_s + d_c/μ_v); the spread is A (1 - e^{-x_k}) - B (1 - e^{-x_c}), A and B
 * its two deep terms, whose difference cancels only where the spread is small beside the beam (b_f H
 * small): an absolute error of a float ulp of the beam's size, and clamped at 0.
 * e_sun_in: E t_in, the sun's irradiance on the horizontal just below the surface. */
SEASIM_FN real sea_sun_backscatter(real e_sun_in, real b, real phase, real bb, real c, real k, real H, real cos_io,
                                   real cos_ji, real d_c) {
  const real bf = fmax(c - k, R(0.0));
  const real to_beam = fmax(c * cos_ji + k * cos_io, R(1e-30));
  const real to_all = fmax(k * (cos_io + cos_ji), R(1e-30));
  const real B = bb / (R(2.0) * SEASIM_PI) / to_beam;
  const real spread_deep = bb / (R(2.0) * SEASIM_PI) * bf * cos_ji / (to_all * to_beam); /* A - B */
  const real beam_depth = sea_depth_factor(R(1.0), H, c / cos_io + k * d_c / cos_ji);
  const real all_depth = sea_depth_factor(k, H, R(1.0) / cos_io + d_c / cos_ji);
  const real spread = fmax((spread_deep + B) * all_depth - B * beam_depth, R(0.0));
  return e_sun_in * (b * phase / to_beam * beam_depth + spread);
}

/* The water column's radiance just below the surface towards the eye (no T_o): the sun's part
 * (sea_sun_backscatter) and the skylight's back-scattering in deep water times its depth factor, both
 * times the higher orders. e_sun: the sun's irradiance on the horizontal surface above the water (eq.
 * 5's L_sun), t_in its Fresnel transmittance; e_sky = π L_sky (1 - r̄) just below the surface; a, b the
 * water's IOPs, c_f = hg_forward_fraction(g); H the bottom depth (< 0: none); cos_io, cos_ji the
 * refracted sun's and view's cosines to the vertical (> 0); phase the HG phase at the pixel's
 * scattering angle (sun beam into the view); mu_sky from sea_sky_mean_cosine. */
SEASIM_FN real sea_multiple_column(real e_sun, real t_in, real e_sky, real a, real b, real c_f, real H, real cos_io,
                                   real cos_ji, real phase, real mu_sky) {
  const SeaMultipleFactors f = sea_multiple_factors(a, b, c_f);
  const real sun = sea_sun_backscatter(e_sun * t_in, b, phase, f.bb, a + b, f.k, H, cos_io, cos_ji, f.d_c);
  const real sky = sea_sky_backscatter_deep(e_sky, mu_sky, f.bb, f.k, cos_ji) *
                   sea_depth_factor(f.k, H, R(1.0) / mu_sky + f.d_c / cos_ji);
  return (sun + sky) * f.orders;
}

/* The Lambertian bottom's radiance just below the surface towards the eye (no T_o), 0 without a bottom
 * (H < 0): ρ/π E_d(H) e^{-k H D_B / cos_ji}, E_d(H) = focus E_sun t_in e^{-k H/cos_io} + E_sky
 * e^{-k H/μ_sky}; focus the caustic factor on the sun's light (1 without caustics), albedo ρ. The light
 * that comes back after the surface reflects the bottom's (and the column's) upwelling light down is
 * sea_multiple_surface_return's. */
SEASIM_FN real sea_multiple_bottom(real e_sun, real t_in, real e_sky, real a, real b, real c_f, real albedo, real H,
                                   real cos_io, real cos_ji, real mu_sky, real focus) {
  const SeaMultipleFactors f = sea_multiple_factors(a, b, c_f);
  const real depth = fmax(H, R(0.0));
  const real e_direct = focus * e_sun * t_in * exp(-f.k * depth / cos_io) + e_sky * exp(-f.k * depth / mu_sky);
  const real v = albedo / SEASIM_PI * e_direct * exp(-f.k * depth * f.d_b / cos_ji);
  return H < R(0.0) ? R(0.0) : v;
}

/* Mean cosine (to the downward vertical) of the light a flat surface reflects back down from a uniform
 * upwelling radiance L: μ' = ∫F μ dμ / ∫F dμ over the upward cosines μ in [0, 1]. Outside Snell's
 * window (μ < μ_c = sqrt(1 - 1/n²)) F = 1 (total internal reflection), so ∫_0^{μ_c} F μ dμ = μ_c²/2 and
 * ∫_0^{μ_c} F dμ = μ_c exactly; the window's part of ∫F μ dμ is (r_below - μ_c²)/2 exactly (r_below =
 * 2∫F μ dμ, sea_surface_reflectance_below), and its part of ∫F dμ is taken at the window's mean cosine
 * (1 + μ_c)/2 (it is 3 % of the whole at n = 1.333; F rises towards the critical angle, so μ' comes
 * out 0.4 % high in water, 2.5 % at n = 1.05: tests/unit/sea_multiple_test.cpp). 0.347 in water: the
 * reflected light runs at about 70° from the vertical, absorbed near the surface, seen at a slant. */
SEASIM_FN real sea_reflected_mean_cosine(real r_below, real ior) {
  const real n = fmax(ior, R(1.0));
  const real mu_c = sqrt(fmax(R(1.0) - R(1.0) / (n * n), R(0.0)));
  const real window = fmax(r_below - mu_c * mu_c, R(0.0)) * R(0.5);     /* ∫_{μ_c}^1 F μ dμ */
  const real int_f = mu_c + window / (R(0.5) * (R(1.0) + mu_c));        /* ∫_0^1 F dμ */
  return fmax(R(0.5) * r_below / fmax(int_f, R(1e-30)), R(1e-4));
}

/* The column's irradiance reflectance E_u(0)/E_d(0) just below the surface for a downwelling
 * irradiance of mean cosine mu, in this model's own terms: its radiance back up per unit E_d is
 * b_b/(2π k (μ + μ_v)) × orders (as sea_sky_backscatter_deep), whose integral over the upper
 * hemisphere, ∫ 2π μ_v dμ_v, is u orders (1 - μ ln(1 + 1/μ)) (sea_column_hemisphere; 0.333 u orders for the sun at μ = 0.875:
 * Gordon's 0.33 b_b/(a + b_b)); over a bottom at H (< 0: none) times the depth factor with the upwelling
 * light's mean secant 2, as the bottom's diffuse light (sea_bottom_surface_reflectance). */
SEASIM_FN real sea_column_hemisphere(real mu) {
  const real m = fmax(mu, R(1e-4));
  return R(1.0) - m * log1p(R(1.0) / m);
}
SEASIM_FN real sea_column_reflectance(SeaMultipleFactors f, real H, real mu) {
  const real m = fmax(mu, R(1e-4));
  return f.u * f.orders * sea_column_hemisphere(mu) * sea_depth_factor(f.k, H, R(1.0) / m + R(2.0));
}

/* The bottom's share of E_u(0)/E_d(0) for a downwelling irradiance of mean cosine mu: ρ e^{-k H/μ} down
 * and e^{-2 k H} back up (a diffuse flux, mean secant 2), with the QSSA k; 0 without a bottom (H < 0). */
SEASIM_FN real sea_bottom_surface_reflectance(real k, real albedo, real H, real mu) {
  const real depth = fmax(H, R(0.0));
  return H < R(0.0) ? R(0.0) : albedo * exp(-k * depth * (R(1.0) / fmax(mu, R(1e-4)) + R(2.0)));
}

/* The light the surface sends back down into the water, and what the water returns of it towards the
 * eye, below the surface (no T_o). The surface reflects r_below of the upwelling irradiance
 * E_u(0) (sea_surface_reflectance_below: a uniform upwelling radiance; mostly total internal
 * reflection) down again, with mean cosine mu_ret (sea_reflected_mean_cosine); the water (column and
 * bottom) returns R' = sea_column_reflectance + sea_bottom_surface_reflectance of it at mu_ret, of which
 * the surface again reflects r_below, ...:
 *   E_u1 = e_sun t_in (R_col(μ_s) + focus R_bot(μ_s)) + e_sky (R_col(μ_sky) + R_bot(μ_sky))
 *   E'   = r_below E_u1 / (1 - r_below R'(mu_ret))            (the whole series of bounces)
 *   L    = E' [b_b/(2π k (mu_ret + μ_v)) orders depth(1/mu_ret + D_C/μ_v) + ρ/π e^{-k H (1/mu_ret + D_B/μ_v)}]
 * the column's and the bottom's radiance for that light, as for the skylight. Measured against the path
 * tracer with and without the internal reflection (results/sea_allorders/README.md): 10 % of the image
 * in deep water with u = 0.26 (Jerlov III near 550 nm), 2 % at u = 0.07. with_column 0 leaves out the
 * column's parts (sea.single_scattering = false); the bottom's then remain (over a bottom at depth 0 the
 * old bottom–surface series ρ/π E/(1 - ρ r_below)). Arguments as sea_multiple_bottom's. */
SEASIM_FN real sea_multiple_surface_return(real e_sun, real t_in, real e_sky, real a, real b, real c_f, real albedo,
                                           real H, real cos_io, real cos_ji, real mu_sky, real focus, real r_below,
                                           real mu_ret, int with_column) {
  const SeaMultipleFactors f = sea_multiple_factors(a, b, c_f);
  const real col = with_column ? R(1.0) : R(0.0);
  const real e_up = e_sun * t_in * (col * sea_column_reflectance(f, H, cos_io) +
                                    focus * sea_bottom_surface_reflectance(f.k, albedo, H, cos_io)) +
                    e_sky * (col * sea_column_reflectance(f, H, mu_sky) +
                             sea_bottom_surface_reflectance(f.k, albedo, H, mu_sky));
  const real r_water = col * sea_column_reflectance(f, H, mu_ret) + sea_bottom_surface_reflectance(f.k, albedo, H, mu_ret);
  const real e_down = r_below * e_up / (R(1.0) - fmin(r_below * r_water, R(0.999)));
  const real column = col * sea_sky_backscatter_deep(R(1.0), mu_ret, f.bb, f.k, cos_ji) *
                      sea_depth_factor(f.k, H, R(1.0) / mu_ret + f.d_c / cos_ji) * f.orders;
  const real depth = fmax(H, R(0.0));
  const real bottom = H < R(0.0) ? R(0.0)
                                 : albedo / SEASIM_PI * exp(-f.k * depth * (R(1.0) / mu_ret + f.d_b / cos_ji));
  return e_down * (column + bottom);
}
