/* caustic_texture.h — the scrolling caustic textures of 002 §5.3: "two instances of a seamless caustic
 * texture are offset and move in different directions and at different speeds; the final value, which
 * modulates the intensity of the sun at a given point, is the minimum of both textures" ([Ame22]).
 * Used by raycast.cl (surfaces) and froxel.cl (the volume); the host runs the same code in float and
 * double (host/math/kernel_math.h). Needs only compat.h.
 *
 * The texture. Bright lines along the edges of a Voronoi diagram, as real caustic nets look: a
 * tile [0,1)² holds N×N cells, one feature point per cell (jittered within the central 80 % of its
 * cell by an integer hash of the wrapped cell index, so the tile is seamless: periodic on [0,1)²);
 * e = F2 − F1 (distance to the second-nearest minus the nearest feature point, in cell units) is 0 on
 * the cell edges, and the texture is h = FLOOR + (1 − FLOOR) exp(−(e/WIDTH)²) in [FLOOR, 1]. F1 and
 * F2 come from the 3×3 cells around the point (with 80 % jitter a point two cells away can only win
 * in rare corner configurations; none among 2·10^6 samples of both tiles checked against a 7×7 search).
 *
 * The two instances. The first with N = 32 cells per tile, the second with N = 27 (the same texture
 * at another tiling, as [Ame22] samples it twice at different scales), moving at speed·(0.8, 0.6) and
 * 0.63·speed·(−0.28, 0.96) (m/s, in x and z). Two different lattices matter for energy: the mean of
 * min(h1, h2) depends on how the two patterns overlap, and two copies of one lattice drift in and out
 * of alignment (±7 % with one 8×8 lattice, +35 % where the offsets coincide); with 32/27 cells its
 * tile mean stays within ±0.6 % over all offsets, so a constant normalisation works at all times.
 *
 * Normalisation. caustic_modulation = min(h1, h2) / MEAN, MEAN the tile mean of min(h1, h2), measured
 * in double over 64 times (1024² midpoint samples each): 0.32258 (spread over times −0.4 % … +0.5 %).
 * So the modulation has spatial mean 1 — caustics move the sun's light around without adding energy —
 * and ranges over [FLOOR/MEAN, 1/MEAN] = [0.775, 3.10] (measured min 0.7756, max 3.1000).
 * Stiff cases: period <= 0 returns 1 (no texture); large coordinates and times are reduced modulo the
 * tile before the cell arithmetic (float keeps ~1e-4 of a tile for |x|/period, speed·t/period < 1e3);
 * the result is always finite and >= FLOOR/MEAN > 0 for finite inputs.
 */

#define CAUSTIC_CELLS_A 32
#define CAUSTIC_CELLS_B 27
#define CAUSTIC_JITTER R(0.8)
#define CAUSTIC_WIDTH R(0.15)  /* line half-width scale, cell units */
#define CAUSTIC_FLOOR R(0.25)  /* texture value inside the cells */
#define CAUSTIC_MEAN R(0.32258) /* tile mean of min(h1, h2) (see above) */

/* x - floor(x) in [0, 1). */
SEASIM_FN real caustic_fract(real x) {
  const real f = x - floor(x);
  return f < R(1.0) ? f : R(0.0); /* x = -tiny: x - floor(x) rounds to 1 */
}

/* Integer hash (Wellons' lowbias32): identical in OpenCL C and C++, float and double. */
SEASIM_FN unsigned int caustic_hash(unsigned int x) {
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return x;
}

/* The seamless texture h at (u, v) in [0,1)², n cells per tile side, seed choosing the points. */
SEASIM_FN real caustic_texture(real u, real v, int n, unsigned int seed) {
  const real x = u * (real)n, y = v * (real)n;
  int cx = (int)floor(x), cy = (int)floor(y);
  cx = cx < 0 ? 0 : (cx >= n ? n - 1 : cx);
  cy = cy < 0 ? 0 : (cy >= n ? n - 1 : cy);
  const real fx = x - (real)cx, fy = y - (real)cy;
  real f1 = R(1e9), f2 = R(1e9); /* squared distances */
  for (int j = -1; j <= 1; ++j) {
    int wy = cy + j;
    wy = wy < 0 ? wy + n : (wy >= n ? wy - n : wy);
    for (int i = -1; i <= 1; ++i) {
      int wx = cx + i;
      wx = wx < 0 ? wx + n : (wx >= n ? wx - n : wx);
      const unsigned int h = caustic_hash((unsigned int)(wx + n * wy) + seed);
      const real px = (real)i + R(0.5) + CAUSTIC_JITTER * ((real)(h & 0xffffU) * R(1.0 / 65536.0) - R(0.5));
      const real py = (real)j + R(0.5) + CAUSTIC_JITTER * ((real)(h >> 16) * R(1.0 / 65536.0) - R(0.5));
      const real dx = px - fx, dy = py - fy;
      const real d2 = dx * dx + dy * dy;
      if (d2 < f1) {
        f2 = f1;
        f1 = d2;
      } else if (d2 < f2) {
        f2 = d2;
      }
    }
  }
  const real e = (sqrt(f2) - sqrt(f1)) / CAUSTIC_WIDTH;
  return CAUSTIC_FLOOR + (R(1.0) - CAUSTIC_FLOOR) * exp(-e * e);
}

/* The sun's caustic modulation at the surface point (x, z) (m, world) at time t (s): 002 §5.3's
 * minimum of two scrolling instances, normalised to spatial mean 1 (see the top). period: m, the tile
 * side on the surface; speed: m/s. Callers project a point under water to the surface along the
 * refracted sun direction first. */
SEASIM_FN real caustic_modulation(real x, real z, real time, real period, real speed) {
  if (!(period > R(0.0))) return R(1.0);
  const real inv = R(1.0) / period;
  const real s = speed * time * inv; /* tiles travelled at unit relative speed */
  const real u = x * inv, v = z * inv;
  const real ua = caustic_fract(caustic_fract(u) - caustic_fract(R(0.8) * s));
  const real va = caustic_fract(caustic_fract(v) - caustic_fract(R(0.6) * s));
  const real ub = caustic_fract(caustic_fract(u) - caustic_fract(R(0.37) + R(-0.1764) * s));
  const real vb = caustic_fract(caustic_fract(v) - caustic_fract(R(0.71) + R(0.6048) * s));
  const real ha = caustic_texture(ua, va, CAUSTIC_CELLS_A, 0U);
  const real hb = caustic_texture(ub, vb, CAUSTIC_CELLS_B, 0x68bc21ebU);
  return fmin(ha, hb) / CAUSTIC_MEAN;
}
