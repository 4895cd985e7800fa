/* sky_table.h — an analytic sky (sky.h) tabulated for the directions the sea reflects. The
 * wave filter (sea_lean.h) asks for the sky at about ten facet directions per pixel, and the model's
 * two exps and acos per direction were half of sea_single's time under Preetham's sky.
 *
 * The CIE clear sky and Preetham's depend on a view d through two numbers alone: cos θ = d.y to the
 * zenith and cos γ = d · s to the sun s (sky_preetham_sun's for Preetham). The table holds the model's
 * own smooth quantities of the view — the CIE sky's φ(θ) f(γ) (in all three places), Preetham's Y, x, y
 * (three products of Perez's functions) — on an n × n grid of nodes u_i = i / (n − 1) = √(cos θ) and
 * v_j = j / (n − 1) = γ / π, row-major in i, SKY_TABLE_STRIDE reals per node (three, then one unused); a
 * read is bilinear between nodes, and sky_table_shape applies the model's conversion to the shape
 * (Preetham's chromaticity to the daylight basis, sky.h) after the read. That conversion amplifies the
 * chromaticity's errors (M1, M2 have coefficients near 30 over denominators near 0.2), so the nodes
 * crowd where the quantities bend: √(cos θ) puts them towards the horizon, where Perez's e^{B / cos θ}
 * turns, and γ itself (polynomial_trig.h's acos) keeps e^{Dγ} smooth at the sun and at the anti-sun,
 * where sin(γ/2) was singular. Tabulating the converted shape, or nodes uniform in cos θ and
 * sin(γ/2), was 1-5 % off near the horizon at n = 128. Every pair (cos θ, γ) is a node of the
 * formula, also pairs no direction takes (the model is evaluated there as written), so reads near the
 * sun's vertical plane interpolate a smooth function. A read costs a square root, the polynomial
 * acos and four nodes, against the model's two exps and acos.
 *
 * Its error against the exact shape is the bilinear interpolation's: at n = 256 within 5e-4 of the
 * shape's largest component for Preetham's sky (turbidity 1.7-10, any sun) and 1.5e-4 for the CIE
 * sky (tests/unit/sky_table_test.cpp, in float and double); results/BENCHMARKS.md states it in images
 * with the time it saves.
 *
 * Stiff cases: the zenith and the horizon (u = 1, 0: the last cell reads without leaving the table);
 * the sun itself and the anti-sun (v = 0, 1); a direction below the horizon reads the horizon
 * (cos θ clamped to 0, the models' own limit there). Needs compat.h, sky.h. */

#define SKY_TABLE_STRIDE 4
/* The table follows the sky model's own reals in sea_single's sky buffer, from this offset (the
 * Preetham sky packs 22, sky.h). */
#define SKY_TABLE_OFFSET 32

/* The node (i, j) of an n × n table: cos θ and cos γ. */
SEASIM_FN void sky_table_node(int i, int j, int n, real* cos_theta, real* cos_gamma) {
  const real u = (real)i / (real)(n - 1), v = (real)j / (real)(n - 1);
  *cos_theta = u * u;
  *cos_gamma = cos(SEASIM_PI * v);
}

/* The tabulated shape of the view with cos θ = cos_theta and cos γ = cos_gamma: bilinear between the
 * four nearest nodes. */
SEASIM_FN real3 sky_table_read(const SEASIM_GLOBAL real* table, int n, real cos_theta, real cos_gamma) {
  const real last = (real)(n - 1);
  const real u = sqrt(clamp(cos_theta, R(0.0), R(1.0))) * last;
  const real v = lookup_acos(clamp(cos_gamma, R(-1.0), R(1.0))) * (last / SEASIM_PI);
  const int iu = (int)u, iv = (int)v;
  const int i = iu < n - 2 ? iu : n - 2, j = iv < n - 2 ? iv : n - 2;
  const real tu = u - (real)i, tv = v - (real)j;
  const SEASIM_GLOBAL real* t00 = table + SKY_TABLE_STRIDE * (i * n + j);
  const SEASIM_GLOBAL real* t01 = t00 + SKY_TABLE_STRIDE;
  const SEASIM_GLOBAL real* t10 = t00 + SKY_TABLE_STRIDE * n;
  const SEASIM_GLOBAL real* t11 = t10 + SKY_TABLE_STRIDE;
  const real w00 = (R(1.0) - tu) * (R(1.0) - tv), w01 = (R(1.0) - tu) * tv, w10 = tu * (R(1.0) - tv), w11 = tu * tv;
  return MAKE_REAL3(w00 * t00[0] + w01 * t01[0] + w10 * t10[0] + w11 * t11[0],
                    w00 * t00[1] + w01 * t01[1] + w10 * t10[1] + w11 * t11[1],
                    w00 * t00[2] + w01 * t01[2] + w10 * t10[2] + w11 * t11[2]);
}

/* The scaled shape (sea_sky_shape's) of the view with cos θ = cos_theta and cos γ = cos_gamma from
 * the table: the model's conversion applied to the read. packed: the model's reals (sky.h). */
SEASIM_FN real3 sky_table_shape(int model, const SEASIM_GLOBAL real* packed, const SEASIM_GLOBAL real* table, int n,
                                real scale, real cos_theta, real cos_gamma) {
  const real3 t = sky_table_read(table, n, cos_theta, cos_gamma);
  if (model == SEASIM_SKY_PREETHAM) {
    const real v[3] = {t.x, t.y, t.z};
    return scale * sky_preetham_daylight_of_yxy(packed, v);
  }
  return MAKE_REAL3(scale * t.x, scale * t.x, scale * t.x);
}
