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
/* The modulation's integral scale along a line, ∫ R(s) ds over the normalised autocorrelation R, in
 * periods (tile sides): 0.032 m for the default 4 m tile (lines of 64 m, 400 directions, measured in
 * double; FroxelMath.CausticShrinkFollowsItsIntegralScale checks it). Its standard deviation is 0.485. */
#define CAUSTIC_INTEGRAL_SCALE R(0.0080)

/* The integral scale in metres of a texture whose tile is `period` metres (froxel.cl's footprint filter). */
SEASIM_FN real caustic_integral_scale(real period) { return CAUSTIC_INTEGRAL_SCALE * period; }

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

/* The texture's profile across a cell edge: h(e) = FLOOR + (1 − FLOOR) exp(−e²), e = (F2 − F1)/WIDTH >= 0.
 * h decreases with e, so the minimum of two textures is h of the larger e: one exp per point
 * (caustic_modulation) gives exactly fmin(h(e_a), h(e_b)). */
SEASIM_FN real caustic_profile(real e) {
  return CAUSTIC_FLOOR + (R(1.0) - CAUSTIC_FLOOR) * exp(-e * e);
}

/* The cell of an n-cell tile that (u, v) in [0,1)² falls in (clamped to the tile), and the position
 * (*fx, *fy) within it in cell units. */
SEASIM_FN void caustic_cell(real u, real v, int n, int* cx, int* cy, real* fx, real* fy) {
  const real x = u * (real)n, y = v * (real)n;
  int ix = (int)floor(x), iy = (int)floor(y);
  ix = ix < 0 ? 0 : (ix >= n ? n - 1 : ix);
  iy = iy < 0 ? 0 : (iy >= n ? n - 1 : iy);
  *cx = ix;
  *cy = iy;
  *fx = x - (real)ix;
  *fy = y - (real)iy;
}

/* A cell's feature point offset from the cell centre, JITTER (hash/65536 − ½) in x and y. */
SEASIM_FN void caustic_jitter(unsigned int h, real* jx, real* jy) {
  *jx = CAUSTIC_JITTER * ((real)(h & 0xffffU) * R(1.0 / 65536.0) - R(0.5));
  *jy = CAUSTIC_JITTER * ((real)(h >> 16) * R(1.0 / 65536.0) - R(0.5));
}

/* Keeps the two smallest squared distances seen, *f1 <= *f2, without branches (see caustic_edge). */
SEASIM_FN void caustic_keep_two_nearest(real d2, real* f1, real* f2) {
  const real hi = d2 > *f1 ? d2 : *f1;
  *f2 = *f2 < hi ? *f2 : hi;
  *f1 = d2 < *f1 ? d2 : *f1;
}

/* The edge distance e = (F2 − F1)/WIDTH of the seamless texture at (u, v) in [0,1)², n cells per tile
 * side, seed choosing the points (h = caustic_profile(e)). F1, F2 are kept as squared distances and
 * updated without branches: f2 = min(f2, max(f1, d2)), f1 = min(f1, d2) gives the same two smallest
 * values as "if (d2 < f1) {f2 = f1; f1 = d2;} else if (d2 < f2) f2 = d2;" (min/max are exact) without
 * the mispredicted jumps of that form. Written as selects, not fmin/fmax: without relaxed maths those
 * cost more on PoCL (their NaN rules; froxel_inject measured 160 → 115 ms wall with exact maths). */
SEASIM_FN real caustic_edge(real u, real v, int n, unsigned int seed) {
  int cx, cy;
  real fx, fy;
  caustic_cell(u, v, n, &cx, &cy, &fx, &fy);
  real f1 = R(1e9), f2 = R(1e9); /* squared distances */
  for (int j = -1; j <= 1; ++j) {
    int wy = cy + j;
    wy = wy < 0 ? wy + n : (wy >= n ? wy - n : wy);
    for (int i = -1; i <= 1; ++i) {
      int wx = cx + i;
      wx = wx < 0 ? wx + n : (wx >= n ? wx - n : wx);
      real jx, jy;
      caustic_jitter(caustic_hash((unsigned int)(wx + n * wy) + seed), &jx, &jy);
      const real dx = (real)i + R(0.5) + jx - fx, dy = (real)j + R(0.5) + jy - fy;
      caustic_keep_two_nearest(dx * dx + dy * dy, &f1, &f2);
    }
  }
  return (sqrt(f2) - sqrt(f1)) / CAUSTIC_WIDTH;
}

/* The seamless texture h at (u, v) in [0,1)², n cells per tile side, seed choosing the points. */
SEASIM_FN real caustic_texture(real u, real v, int n, unsigned int seed) {
  return caustic_profile(caustic_edge(u, v, n, seed));
}

/* ---- the same textures from a table of the feature points (froxel.cl: one look-up per cell instead of
 * a hash, an int-to-float conversion pair and the index wrap) ---- */

/* Reals in the table of one n-cell texture: 2 per cell of the tile padded by one wrapped cell on every
 * side, (n + 2)². */
#define CAUSTIC_TABLE_SIZE(n) (2 * ((n) + 2) * ((n) + 2))
/* Reals in caustic_fill_table's table of both textures (A, then B): 2 (34² + 29²) = 3994. */
#define CAUSTIC_TABLE_REALS (CAUSTIC_TABLE_SIZE(CAUSTIC_CELLS_A) + CAUSTIC_TABLE_SIZE(CAUSTIC_CELLS_B))

/* One texture's table: at 2 (X + (n + 2) Y) + {0, 1} for the padded cell (X, Y), X, Y in [0, n + 2),
 * which is the tile's cell ((X − 1) mod n, (Y − 1) mod n), that cell's jitter
 * JITTER (hash/65536 − ½) in x and y, the very product caustic_edge adds to the cell centre. */
SEASIM_FN void caustic_fill_texture_table(int n, unsigned int seed, SEASIM_GLOBAL real* table) {
  for (int Y = 0; Y < n + 2; ++Y) {
    const int wy = (Y - 1 + n) % n;
    for (int X = 0; X < n + 2; ++X) {
      const int wx = (X - 1 + n) % n;
      real jx, jy;
      caustic_jitter(caustic_hash((unsigned int)(wx + n * wy) + seed), &jx, &jy);
      table[2 * (X + (n + 2) * Y) + 0] = jx;
      table[2 * (X + (n + 2) * Y) + 1] = jy;
    }
  }
}

/* The table of both textures of caustic_modulation (CAUSTIC_TABLE_REALS reals): A's, then B's. It does
 * not depend on time, period or speed: filled once (host/passes/froxel_pass.cpp). */
SEASIM_FN void caustic_fill_table(SEASIM_GLOBAL real* table) {
  caustic_fill_texture_table(CAUSTIC_CELLS_A, 0U, table);
  caustic_fill_texture_table(CAUSTIC_CELLS_B, 0x68bc21ebU, table + CAUSTIC_TABLE_SIZE(CAUSTIC_CELLS_A));
}

/* caustic_edge with the feature points read from one texture's table: the same points (caustic_jitter)
 * and the same arithmetic, but for the jitter product, which the table holds rounded (caustic_edge's
 * compiler may fuse it into the addition: a difference of at most an ulp in a point's position). */
SEASIM_FN real caustic_edge_table(real u, real v, int n, const SEASIM_GLOBAL real* table) {
  int cx, cy;
  real fx, fy;
  caustic_cell(u, v, n, &cx, &cy, &fx, &fy);
  /* Padded cell (cx + i + 1, cy + j + 1) is cell (cx + i, cy + j) wrapped: row j starts at padded X = cx. */
  const SEASIM_GLOBAL real* corner = table + 2 * (cx + (n + 2) * cy);
  real f1 = R(1e9), f2 = R(1e9); /* squared distances */
  for (int j = -1; j <= 1; ++j) {
    const SEASIM_GLOBAL real* row = corner + 2 * (n + 2) * (j + 1);
    for (int i = -1; i <= 1; ++i) {
      const real dx = (real)i + R(0.5) + row[2 * (i + 1) + 0] - fx, dy = (real)j + R(0.5) + row[2 * (i + 1) + 1] - fy;
      caustic_keep_two_nearest(dx * dx + dy * dy, &f1, &f2);
    }
  }
  return (sqrt(f2) - sqrt(f1)) / CAUSTIC_WIDTH;
}

/* ---- the two scrolling instances ---- */

/* Where (x, z) (m) falls at time t (s) in the tiles of instance A (*ua, *va) and B (*ub, *vb), [0,1)². */
SEASIM_FN void caustic_tile_coords(real x, real z, real time, real period, real speed, real* ua, real* va, real* ub,
                                   real* vb) {
  const real inv = R(1.0) / period;
  const real s = speed * time * inv; /* tiles travelled at unit relative speed */
  const real u = x * inv, v = z * inv;
  *ua = caustic_fract(caustic_fract(u) - caustic_fract(R(0.8) * s));
  *va = caustic_fract(caustic_fract(v) - caustic_fract(R(0.6) * s));
  *ub = caustic_fract(caustic_fract(u) - caustic_fract(R(0.37) + R(-0.1764) * s));
  *vb = caustic_fract(caustic_fract(v) - caustic_fract(R(0.71) + R(0.6048) * s));
}

/* The sun's caustic modulation at the surface point (x, z) (m, world) at time t (s): 002 §5.3's
 * minimum of two scrolling instances, normalised to spatial mean 1 (see the top). period: m, the tile
 * side on the surface; speed: m/s. Callers project a point under water to the surface along the
 * refracted sun direction first. */
SEASIM_FN real caustic_modulation(real x, real z, real time, real period, real speed) {
  if (!(period > R(0.0))) return R(1.0);
  real ua, va, ub, vb;
  caustic_tile_coords(x, z, time, period, speed, &ua, &va, &ub, &vb);
  const real e = fmax(caustic_edge(ua, va, CAUSTIC_CELLS_A, 0U), caustic_edge(ub, vb, CAUSTIC_CELLS_B, 0x68bc21ebU));
  return caustic_profile(e) / CAUSTIC_MEAN; /* = fmin(h_a, h_b) / MEAN (caustic_profile) */
}

/* caustic_modulation with the feature points from caustic_fill_table's table (froxel.cl). */
SEASIM_FN real caustic_modulation_table(real x, real z, real time, real period, real speed,
                                        const SEASIM_GLOBAL real* table) {
  if (!(period > R(0.0))) return R(1.0);
  real ua, va, ub, vb;
  caustic_tile_coords(x, z, time, period, speed, &ua, &va, &ub, &vb);
  const real e = fmax(caustic_edge_table(ua, va, CAUSTIC_CELLS_A, table),
                      caustic_edge_table(ub, vb, CAUSTIC_CELLS_B, table + CAUSTIC_TABLE_SIZE(CAUSTIC_CELLS_A)));
  return caustic_profile(e) / CAUSTIC_MEAN;
}
