/* sea_bottom_lanes.h — 000 §5.4's eq. 7 along the depth tables' sampling rays for SEASIM_BAND_LANES
 * sampling directions at once. common/band_lanes.h's realb holds a run of directions here, not of bands:
 * the height-field branch of sea_second.cl's scattering map reads a band's table row (a run of directions,
 * contiguous) with one vector load, where a lane per band would gather from a different table node per
 * band; PoCL does not vectorise the scalar direction loop itself. Needs compat.h, optics.h (the series of
 * expm1_over_x) and band_lanes.h. */

/* sea_path_integral's finite path (sea_second.h) for lanes of κ and of the optical path l >= 0, at one
 * a >= 0 (τ_k sec θ_io) with e_near = e^{-a}: e^{-(a + min(x, 0))} l φ(-|x|), x = κ l, which is
 * l e^{-a} φ(-x) in both signs (e^{-x} φ(x) = φ(-x)). For |x| >= 1/2 that is l (e^{-a} - e^{-(a + x)}) / x,
 * whose difference loses at most e^{1/2}/(1 - e^{-1/2}) ≈ 4 ulp, and below it e_near l φ(-x) by the series:
 * one exp per lane instead of two. a + x, the optical depth where the path ends plus its length, is >= 0,
 * so no exp overflows. */
SEASIM_FN realb sea_path_integral_finite_b(real e_near, real a, realb kappa, realb l) {
  const realb x = kappa * l;
  const maskb small = fabs(x) < R(0.5);
  const realb xs = SELECTB(small, SPLATB(R(1.0)), x);
  const realb direct = (e_near - exp(-(a + x))) / xs;
  const realb series = e_near * SEASIM_EXPM1_OVER_X_SERIES(-x);
  return l * SELECTB(small, series, direct);
}
