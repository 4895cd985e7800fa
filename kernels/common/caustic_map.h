/* caustic_map.h — reading the flux-conservation caustic maps of the FFT ocean (004 §5.2.1,
 * kernels/caustics.cl) under water (002 §5.3's role, with the physical pattern in place of the
 * scrolling textures).
 *
 * The host (host/passes/caustic_stack.cpp) splats the ocean surface onto `layers` horizontal planes at
 * depths d_k = (k + 1) d_max / layers, k = 0..layers-1, and divides each map by its mean, so a layer
 * holds only the focusing pattern (mean 1): the mean transmitted, attenuated beam is already in the
 * underwater model (e_sun0, e^{-c y/μ_w}; 002 eq. 4.7). Layer k is m × m texels over the periodic
 * patch of side `extent`; texel (i, j) is centred at ((i + ½) L/m, (j + ½) L/m) as caustics.cl writes
 * it, and the map wraps around (the ocean tiles).
 *
 * Between layers the pattern is linear in depth; between the surface and the first layer it blends
 * from 1 (no focusing at d = 0: the rays have not converged yet) to layer 0; below the deepest layer
 * it is that layer. Layers are stored one after another: maps[k m² + j m + i].
 */

/* Bilinear blend of texels (i0, j0)..(i1, j1) with weights ax, az towards i1, j1. */
SEASIM_FN real caustic_map_blend(SEASIM_GLOBAL const float* map, int m, int i0, int i1, int j0, int j1, real ax, real az) {
  const real c00 = (real)map[j0 * m + i0], c10 = (real)map[j0 * m + i1];
  const real c01 = (real)map[j1 * m + i0], c11 = (real)map[j1 * m + i1];
  return (R(1.0) - az) * ((R(1.0) - ax) * c00 + ax * c10) + az * ((R(1.0) - ax) * c01 + ax * c11);
}

/* Bilinear read of one layer at world (x, z), periodic. */
SEASIM_FN real caustic_map_bilinear(SEASIM_GLOBAL const float* layer, int m, real extent, real x, real z) {
  const real u = x / extent * (real)m - R(0.5);
  const real v = z / extent * (real)m - R(0.5);
  const real fu = floor(u), fv = floor(v);
  const real ax = u - fu, az = v - fv;
  /* fu mod m, for negative coordinates too; clamped before the int conversion because rounding far
   * from the origin (or a non-finite input) can leave the remainder outside [0, m). */
  const int i0 = (int)fmin(fmax(fu - floor(fu / (real)m) * (real)m, R(0.0)), (real)(m - 1));
  const int j0 = (int)fmin(fmax(fv - floor(fv / (real)m) * (real)m, R(0.0)), (real)(m - 1));
  const int i1 = i0 + 1 == m ? 0 : i0 + 1;
  const int j1 = j0 + 1 == m ? 0 : j0 + 1;
  return caustic_map_blend(layer, m, i0, i1, j0, j1, ax, az);
}

/* Bilinear read of an M × M map over the square [origin, origin + extent]² at world (x, z): periodic
 * (the ocean patch over a flat bottom) or clamped to its edge texels (a height-field floor's map,
 * host/passes/caustic_stack.h seaBottomCaustics). */
SEASIM_FN real caustic_map_read(SEASIM_GLOBAL const float* map, int m, real extent, real origin, int periodic, real x,
                                real z) {
  if (m < 1 || !(extent > R(0.0))) return R(1.0);
  if (periodic) return caustic_map_bilinear(map, m, extent, x - origin, z - origin);
  const real u = fmin(fmax((x - origin) / extent * (real)m - R(0.5), R(0.0)), (real)(m - 1));
  const real v = fmin(fmax((z - origin) / extent * (real)m - R(0.5), R(0.0)), (real)(m - 1));
  const int i0 = (int)fmin(floor(u), (real)(m - 1)), j0 = (int)fmin(floor(v), (real)(m - 1));
  const int i1 = i0 + 1 < m ? i0 + 1 : i0, j1 = j0 + 1 < m ? j0 + 1 : j0;
  return caustic_map_blend(map, m, i0, i1, j0, j1, u - (real)i0, v - (real)j0);
}

/* The focusing factor (mean 1 over the patch) at world point (x, -depth, z). */
SEASIM_FN real caustic_map_sample(SEASIM_GLOBAL const float* maps, int m, int layers, real extent, real depth_max,
                                  real x, real depth, real z) {
  if (layers < 1 || m < 1 || !(extent > R(0.0)) || !(depth_max > R(0.0)) || !(depth > R(0.0))) return R(1.0);
  const real s = depth / depth_max * (real)layers; /* layer k sits at s = k + 1 */
  if (s >= (real)layers) return caustic_map_bilinear(maps + (size_t)(layers - 1) * m * m, m, extent, x, z);
  const int k = (int)floor(s); /* s in [k, k + 1): between layer k - 1 (or the surface) and layer k */
  const real t = s - (real)k;
  const real upper = k == 0 ? R(1.0) : caustic_map_bilinear(maps + (size_t)(k - 1) * m * m, m, extent, x, z);
  const real lower = caustic_map_bilinear(maps + (size_t)k * m * m, m, extent, x, z);
  return upper + t * (lower - upper);
}
