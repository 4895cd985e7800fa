/* gauss_legendre.h — the 8-point Gauss–Legendre rule on [-1, 1] (Abramowitz & Stegun, Handbook of
 * Mathematical Functions, table 25.4), exact for polynomials of degree 15: the Beckmann facets' ranges of
 * the sea's wave filter (sea_lean.h), the four-flow beam's gaps (fourflow.h) and the lamps' far field
 * in the water (underwater_lamps.h). Written against compat.h; the host compiles it in float and double.
 */

/* Node i (0..7, in increasing order) and its weight. */
SEASIM_FN real gauss_legendre8_node(int i, real* weight) {
  const real x[4] = {R(0.1834346424956498), R(0.5255324099163290), R(0.7966664774136267), R(0.9602898564975363)};
  const real w[4] = {R(0.3626837833783620), R(0.3137066458778873), R(0.2223810344533745), R(0.1012285362903763)};
  const int k = i < 4 ? 3 - i : i - 4;
  *weight = w[k];
  return i < 4 ? -x[k] : x[k];
}
