/* sea_bottom_lanes.h — the second order over a height field (000 §5.4) in vector lanes (common/band_lanes.h's
 * realb), for sea_second.cl:
 *   - eq. 7 along the depth tables' sampling rays for SEASIM_BAND_LANES sampling directions at once: realb
 *     holds a run of directions here, not of bands. The scattering map reads a band's table row (a run of
 *     directions, contiguous) with one vector load, where a lane per band would gather from a different
 *     table node per band;
 *   - the planes' shares above a pixel's floor for SEASIM_BAND_LANES bands at once (the accumulation,
 *     whose maps hold the bands of a map point contiguously).
 * PoCL does not vectorise the scalar loops themselves. Needs compat.h, optics.h, band_lanes.h and
 * band_lanes_math.h. */

/* sea_path_integral's finite path (sea_second.h) for lanes of κ and of the optical path l >= 0, at one
 * a >= 0 (τ_k sec θ_io) with e_near = e^{-a}: e^{-(a + min(x, 0))} l φ(-|x|), x = κ l, which is
 * l e^{-a} φ(-x) in both signs (e^{-x} φ(x) = φ(-x)). For |x| >= 1/2 that is l (e^{-a} - e^{-(a + x)}) / x,
 * whose difference loses at most e^{1/2}/(1 - e^{-1/2}) ≈ 4 ulp, and below it e_near l φ(-x) by the series:
 * one exp per lane instead of two. a + x, the optical depth where the path ends plus its length, is >= 0,
 * so no exp overflows. inv_kappa: 1/κ where κ != 0 (any finite value where κ = 0, whose x takes the series),
 * which the caller has per direction: the finite path l (e^{-a} - e^{-(a + x)}) / x is (e^{-a} - e^{-(a + x)})
 * / κ, one product per lane where a division was the loop's dearest step after the exp. */
SEASIM_FN realb sea_path_integral_finite_b(real e_near, real a, realb kappa, realb inv_kappa, realb l) {
  const realb x = kappa * l;
  const maskb small = fabs(x) < R(0.5);
  const realb direct = (e_near - exp(-(a + x))) * inv_kappa;
  const realb series = l * e_near * SEASIM_EXPM1_OVER_X_SERIES(-x);
  return SELECTB(small, series, direct);
}

/* sea_plane_share_above (sea_bottom.h) for lanes of bands: tau_d >= 0 (a floor) and tau_q per lane. */
SEASIM_FN realb sea_plane_share_above_b(int k, int n_z, real cos_io, realb tau_d, realb tau_q) {
  const real s = R(1.0) + R(1.0) / cos_io;
  const realb y_d = s * tau_d, y_q = s * fmax(tau_q, R(0.0));
  const realb span = y_d * expm1_over_x_b(-y_d), q = y_q * expm1_over_x_b(-y_q); /* one_minus_exp_neg */
  const realb top = (R(k) / R(n_z)) * span, bottom = (R(k + 1) / R(n_z)) * span;
  const maskb empty = bottom <= top; /* tau_d = 0 (c = 0 or no water): the planes weigh nothing */
  const realb share = clamp((q - top) / SELECTB(empty, SPLATB(R(1.0)), bottom - top), R(0.0), R(1.0));
  return SELECTB(empty, SPLATB(R(0.0)), share);
}
