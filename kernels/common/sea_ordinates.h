/* sea_ordinates.h — sea.model = "multiple" held to the plane-parallel radiative transfer: the grid of the
 * factor κ = L_ordinates / L_closed by which the band's water-leaving radiance below the surface (the closed
 * form's column, bottom and surface return, common/sea_multiple.h) is scaled, per band, bottom depth H,
 * and direction of the upwelling light; and the taps a pixel reads it with. Shared by kernels/sea_single.cl
 * (rows SEA_ROW_ORDINATES + node of the band table, common/sea_band_table.h), the host that builds it
 * (host/passes/sea_ordinates_table.cpp) and the double reference (host/reference/sea_reference.cpp).
 *
 * Why: the closed form's back-scatter of the light already scattered forwards is isotropic (b_b/2π per sr)
 * and its higher orders one factor of u and g. In deep turbid water that misses the HG phase's rise
 * from 180° towards 150°: near the nadir its radiance was 0.92–0.94 of the all-orders path tracer's
 * (Jerlov II, III, 3C deep, docs/journal/beyond_the_grids.md). The discrete-ordinates solution of the
 * same flat layer (host/underwater/ordinates_high_order.h: 16 streams, azimuth modes 0–2, the beam's
 * single scattering with the exact phase, the surface's Fresnel reflection from below, a Lambertian
 * bottom) is the radiative transfer equation's answer for that layer: against the slab Monte Carlo
 * (host/reference/sea_slab_mc.h, a 0.07, b 1.07, g 0.9, sun 40°) 0.999–1.004 from the nadir to 75° in
 * deep water, 1.002–1.008 over a 5 m bottom of albedo 0.3. The closed form keeps what the flat layer
 * does not have (waves' normals, a height-field floor, caustics, the sky's shape) and takes the layer's
 * level and angular shape from κ; κ is the ratio of the two in the same azimuth modes, so the modes
 * the solution leaves out cancel.
 *
 * The grid, nodes in one flat row each (SEA_ORD_ROW):
 *   bottom depth: over a height field 0.25 · 2^(j/2) m for j = 0..18 (0.25–128 m), then no bottom (j = 19);
 *     below 0.25 m the first node, beyond 128 m blended towards no bottom by 128/H. Otherwise the scene has
 *     one depth (a flat bottom's, or none) and one layer (j = 0) holds κ at exactly that depth:
 *     SEA_ORD_LAYER nodes, 4 taps a pixel.
 *   the upwelling light's angle θ from the zenith in the water: 10 nodes uniform in sqrt(1 - cos θ) from
 *     the zenith to 81° (0°, 8.3°, 16.6°, 25.0°, ..., 70.5°, 81°; held at 81° beyond).
 *   its azimuth φ from the refracted sun's direction of travel: 7 nodes uniform in cos φ from 1 to -1.
 * Linear in each (in log H for the depth).
 */
#ifndef SEASIM_SEA_ORDINATES_H /* also included by host/math/kernel_math.h, twice (float and double) */
#define SEA_ORD_DEPTHS 20   /* 19 bottom depths, then no bottom */
#define SEA_ORD_ZENITHS 10  /* from the zenith to 81°, 8–10° apart */
#define SEA_ORD_AZIMUTHS 7  /* uniform in the cosine of the azimuth from the sun's */
#define SEA_ORD_LAYER (SEA_ORD_ZENITHS * SEA_ORD_AZIMUTHS) /* nodes of one depth */
#define SEA_ORD_NODES (SEA_ORD_DEPTHS * SEA_ORD_LAYER)      /* nodes of the depth grid */
#define SEA_ORD_ROW(depth, zenith, azimuth) \
  (((depth) * SEA_ORD_ZENITHS + (zenith)) * SEA_ORD_AZIMUTHS + (azimuth))
#define SEA_ORD_TAPS 8 /* rows a pixel blends on the depth grid (sea_ord_taps); 4 on one layer */
#endif
#define SEASIM_SEA_ORDINATES_H

/* Depth node j < SEA_ORD_DEPTHS - 1, m. */
SEASIM_FN real sea_ord_depth_node(int j) {
  return R(0.25) * exp2(R(0.5) * (real)j);
}

/* Zenith node j as the upwelling light's cosine with the zenith: uniform in sqrt(1 - cos), about uniform in
 * the angle (2 asin(x/√2)) and without an acos per pixel; from the zenith to 81° (x up to sqrt(1 - cos 81°)). */
#define SEA_ORD_ZENITH_X_MAX R(0.918458)
SEASIM_FN real sea_ord_zenith_cosine(int j) {
  const real x = (real)j * (SEA_ORD_ZENITH_X_MAX / (real)(SEA_ORD_ZENITHS - 1));
  return R(1.0) - x * x;
}
/* Azimuth node j as its cosine, uniform from 1 (towards the sun's travel) to -1 (against it): the azimuth
 * modes 0-2 κ is made of are polynomials in cos φ (cos 2φ = 2 cos² φ - 1). */
SEASIM_FN real sea_ord_azimuth_cosine_node(int j) {
  return R(1.0) - (real)j * (R(2.0) / (real)(SEA_ORD_AZIMUTHS - 1));
}

/* The two depth nodes around a bottom depth H (< 0: no bottom) on the depth grid, and the weight of the
 * second. */
SEASIM_FN real sea_ord_depth_taps(real H, int* d0, int* d1) {
  const int deep = SEA_ORD_DEPTHS - 1;
  const real h_last = sea_ord_depth_node(deep - 1);
  if (H < R(0.0)) {
    *d0 = *d1 = deep;
    return R(0.0);
  }
  if (H >= h_last) { /* towards no bottom as 1 - 128/H: the bottom's light fades as it recedes */
    *d0 = deep - 1;
    *d1 = deep;
    return R(1.0) - h_last / H;
  }
  const real x = fmax(R(2.0) * log2(fmax(H, R(0.25)) * R(4.0)), R(0.0));
  const int j = (int)x < deep - 2 ? (int)x : deep - 2;
  *d0 = j;
  *d1 = j + 1;
  return fmin(x - (real)j, R(1.0));
}

/* The node below x (a position in node units, >= 0, clamped to count - 1) and the weight of the next. */
SEASIM_FN real sea_ord_axis_taps(real x, int count, int* j0) {
  const real xc = clamp(x, R(0.0), (real)(count - 1));
  const int j = (int)xc < count - 2 ? (int)xc : count - 2;
  *j0 = j;
  return xc - (real)j;
}

/* Where a pixel reads κ: at a bottom depth H (< 0: none), the upwelling light's cosine cos_up with the
 * zenith (the refracted view's with the downward vertical) and the cosine cos_phi of its azimuth from the
 * refracted sun's travel. row0, row1: the nodes (z0, a0) of the two depth layers around H (the same layer
 * without depth_grid, which is a height field's: then the table has one layer); td, tz, ta: the weights of
 * the second node in depth, zenith and azimuth. The pixel then blends rows row + {0, 1, SEA_ORD_AZIMUTHS,
 * SEA_ORD_AZIMUTHS + 1} of each layer (sea_ord_taps). Scalars, not arrays, so that a kernel keeps them in
 * registers. */
SEASIM_FN void sea_ord_corner(real H, int depth_grid, real cos_up, real cos_phi, int* row0, int* row1, real* td,
                              real* tz, real* ta) {
  int d0 = 0, d1 = 0, z0, a0;
  *td = depth_grid ? sea_ord_depth_taps(H, &d0, &d1) : R(0.0);
  const real x_zenith = sqrt(R(1.0) - clamp(cos_up, R(0.0), R(1.0)));
  *tz = sea_ord_axis_taps(x_zenith * ((real)(SEA_ORD_ZENITHS - 1) / SEA_ORD_ZENITH_X_MAX), SEA_ORD_ZENITHS, &z0);
  *ta = sea_ord_axis_taps((R(1.0) - clamp(cos_phi, R(-1.0), R(1.0))) * (R(0.5) * (real)(SEA_ORD_AZIMUTHS - 1)),
                          SEA_ORD_AZIMUTHS, &a0);
  *row0 = SEA_ORD_ROW(d0, z0, a0);
  *row1 = SEA_ORD_ROW(d1, z0, a0);
}

/* The same as 8 rows and weights (the last 4 weigh 0 without depth_grid): the host's and the tests' form. */
SEASIM_FN void sea_ord_taps(real H, int depth_grid, real cos_up, real cos_phi, int* rows, real* weights) {
  int row0, row1;
  real td, tz, ta;
  sea_ord_corner(H, depth_grid, cos_up, cos_phi, &row0, &row1, &td, &tz, &ta);
  for (int c = 0; c < SEA_ORD_TAPS; ++c) {
    const int dd = (c >> 2) & 1, dz = (c >> 1) & 1, da = c & 1;
    rows[c] = (dd ? row1 : row0) + dz * SEA_ORD_AZIMUTHS + da;
    weights[c] = (dd ? td : R(1.0) - td) * (dz ? tz : R(1.0) - tz) * (da ? ta : R(1.0) - ta);
  }
}

/* The cosine of the upwelling light's azimuth from the refracted sun's travel, from view_x, view_z, the
 * horizontal part of the refracted view's direction of travel (down, away from the eye), and sun_x, sun_z,
 * that of the direction towards the sun. The light towards the eye travels against the view and the sun's
 * light away from the sun, so the two reversals cancel. 1 where either is vertical (κ's azimuths agree
 * there). */
SEASIM_FN real sea_ord_azimuth_cosine(real view_x, real view_z, real sun_x, real sun_z) {
  const real n = sqrt((view_x * view_x + view_z * view_z) * (sun_x * sun_x + sun_z * sun_z));
  return n > R(1e-12) ? (view_x * sun_x + view_z * sun_z) / n : R(1.0);
}
