/* polynomial_trig.h — atan2, acos and sin/cos as short polynomials, for lookups and quadrature nodes
 * where an error of a few 1e-8 rad does not show and the library call dominates: the latitude–longitude
 * sky image (sky.h), read once per wave facet in the sea's filter (on PoCL the scalar atan2 was 21 % of
 * wavy_sea_image_sky's frame and the lookup around it 26 %), and the lamps' order-1 edge line
 * (underwater_lamps_ms.h: the sin and cos of its 12 deflections, with PoCL's argument reduction, were a
 * fifth of the lattice's time on rov_lights). Written against compat.h; the host compiles it in float
 * and double.
 *
 * Abramowitz & Stegun, Handbook of Mathematical Functions (1964):
 *   4.4.49  atan x = x (1 + a2 x² + … + a16 x^16),  0 <= x <= 1;  A&S bound 2e-8, measured 1.4e-8;
 *   4.4.46  acos x = sqrt(1 - x) (a0 + a1 x + … + a7 x^7),  0 <= x <= 1;  A&S bound 2e-8, measured 2.2e-8
 * (measured on 2,000,001 points of [0, 1] in double); sin and cos on [0, π] from their Taylor series
 * (A&S 4.3.65–66) about π/2, truncated below 7e-10 and 6.4e-9. Outside [0, 1] by the identities
 * atan x = π/2 - atan(1/x), acos(-x) = π - acos x, and atan2's quadrants. A&S print 10 digits, so the
 * polynomials carry 2e-8 rad in double too: the callers use lookup_atan2, lookup_acos and
 * kernel_sincos_0_pi, which are the polynomials in kernels and the library's functions on the host, so
 * the host's double evaluation stays the exact reference the kernels are tested against (the difference
 * is ≤ 1e-7 relative, inside every kernel test's float tolerance); tests/unit/polynomial_trig_test.cpp
 * checks the polynomials themselves in float and double. */

/* atan2(y, x) in [-π, π]; atan2(0, 0) = 0 as the library's. The sign of a zero is not kept
 * (atan2(-0, -1) = π here, -π in the library; atan2(0, -0) = 0 here, π there): the same direction. */
SEASIM_FN real polynomial_atan2(real y, real x) {
  const real ax = fabs(x), ay = fabs(y);
  const real hi = fmax(ax, ay), lo = fmin(ax, ay);
  const real t = hi > R(0.0) ? lo / hi : R(0.0); /* in [0, 1] */
  const real t2 = t * t;
  real p = R(0.0028662257);
  p = p * t2 + R(-0.0161657367);
  p = p * t2 + R(0.0429096138);
  p = p * t2 + R(-0.0752896400);
  p = p * t2 + R(0.1065626393);
  p = p * t2 + R(-0.1420889944);
  p = p * t2 + R(0.1999355085);
  p = p * t2 + R(-0.3333314528);
  p = p * t2 + R(1.0);
  real a = t * p;                                   /* atan(lo / hi) in [0, π/4] */
  if (ay > ax) a = R(0.5) * SEASIM_PI - a;          /* atan(ay / ax) */
  if (x < R(0.0)) a = SEASIM_PI - a;
  return y < R(0.0) ? -a : a;
}

/* acos(x) for x in [-1, 1] (the caller clamps). */
SEASIM_FN real polynomial_acos(real x) {
  const real ax = fabs(x);
  real p = R(-0.0012624911);
  p = p * ax + R(0.0066700901);
  p = p * ax + R(-0.0170881256);
  p = p * ax + R(0.0308918810);
  p = p * ax + R(-0.0501743046);
  p = p * ax + R(0.0889789874);
  p = p * ax + R(-0.2145988016);
  p = p * ax + R(1.5707963050);
  const real a = sqrt(fmax(R(1.0) - ax, R(0.0))) * p;
  return x < R(0.0) ? SEASIM_PI - a : a;
}

/* sin x, and cos x into *cos_x, for x in [0, π] (the caller keeps it there): with y = x - π/2 in
 * [-π/2, π/2], sin x = cos y and cos x = -sin y, each a Taylor polynomial in y² (to y^12 and y^13; the
 * first terms left out are below 6.4e-9 and 6.7e-10 at y = ±π/2). No argument reduction. */
SEASIM_FN real polynomial_sincos_0_pi(real x, real* cos_x) {
  const real y = x - R(0.5) * SEASIM_PI, y2 = y * y;
  real s = R(1.6059043836821615e-10); /* sin y / y: 1/13!, -1/11!, …, 1 */
  s = s * y2 + R(-2.5052108385441719e-08);
  s = s * y2 + R(2.7557319223985891e-06);
  s = s * y2 + R(-1.9841269841269841e-04);
  s = s * y2 + R(8.3333333333333332e-03);
  s = s * y2 + R(-1.6666666666666666e-01);
  s = s * y2 + R(1.0);
  real c = R(2.0876756987868099e-09); /* cos y: 1/12!, -1/10!, …, 1 */
  c = c * y2 + R(-2.7557319223985888e-07);
  c = c * y2 + R(2.4801587301587302e-05);
  c = c * y2 + R(-1.3888888888888889e-03);
  c = c * y2 + R(4.1666666666666664e-02);
  c = c * y2 + R(-0.5);
  c = c * y2 + R(1.0);
  *cos_x = -y * s;
  return c;
}

/* The polynomials above in kernels, the library on the host (header). */
SEASIM_FN real lookup_atan2(real y, real x) {
#if defined(__OPENCL_VERSION__) || defined(__OPENCL_C_VERSION__)
  return polynomial_atan2(y, x);
#else
  return atan2(y, x);
#endif
}

SEASIM_FN real lookup_acos(real x) {
#if defined(__OPENCL_VERSION__) || defined(__OPENCL_C_VERSION__)
  return polynomial_acos(x);
#else
  return acos(x);
#endif
}

/* sin x and cos x for x in [0, π]: polynomial_sincos_0_pi in kernels, the library on the host. */
SEASIM_FN real kernel_sincos_0_pi(real x, real* cos_x) {
#if defined(__OPENCL_VERSION__) || defined(__OPENCL_C_VERSION__)
  return polynomial_sincos_0_pi(x, cos_x);
#else
  *cos_x = cos(x);
  return sin(x);
#endif
}
