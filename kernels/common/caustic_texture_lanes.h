/* caustic_texture_lanes.h — caustic_texture.h's scrolling caustic modulation (002 §5.3) for several surface
 * points at once, one per lane: the same cells, hashes, jitters and nearest two feature points, with the
 * cell indices held as exact integers in realb and the hash in uintb lanes. raycast.cl reads the caustics of
 * its UW_RAYCAST_PIXELS hits in these lanes: the scalar texture read (9 cells × 2 textures of integer hashing
 * per point) was most of the ray cast wherever caustics are on. The host compiles them with one lane and the
 * unit test holds them to caustic_modulation.
 * Needs compat.h, band_lanes.h and caustic_texture.h before it. */

/* caustic_fract per lane. */
SEASIM_FN realb caustic_fract_b(realb x) {
  const realb f = x - floor(x);
  return SELECTB(f < R(1.0), f, SPLATB(R(0.0)));
}

/* caustic_hash per lane. */
SEASIM_FN uintb caustic_hash_b(uintb x) {
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return x;
}

/* caustic_edge per lane: the cell (clamped to the tile) and the 3×3 cells around it, wrapped; the cell
 * indices are whole numbers below 2^24, exact in a float, and the hash's argument the same unsigned sum. */
SEASIM_FN realb caustic_edge_b(realb u, realb v, int n, unsigned int seed) {
  const real nr = (real)n;
  const realb x = u * nr, y = v * nr;
  const realb cx = clamp(floor(x), SPLATB(R(0.0)), SPLATB(nr - R(1.0)));
  const realb cy = clamp(floor(y), SPLATB(R(0.0)), SPLATB(nr - R(1.0)));
  const realb fx = x - cx, fy = y - cy;
  realb f1 = SPLATB(R(1e9)), f2 = SPLATB(R(1e9)); /* squared distances */
  for (int j = -1; j <= 1; ++j) {
    realb wy = cy + (real)j;
    wy = SELECTB(wy < R(0.0), wy + nr, SELECTB(wy >= nr, wy - nr, wy));
    for (int i = -1; i <= 1; ++i) {
      realb wx = cx + (real)i;
      wx = SELECTB(wx < R(0.0), wx + nr, SELECTB(wx >= nr, wx - nr, wx));
      const uintb h = caustic_hash_b(UINTB_OF(wx + nr * wy) + seed);
      const realb jx = CAUSTIC_JITTER * (REALB_OF_UINT(h & 0xffffU) * R(1.0 / 65536.0) - R(0.5));
      const realb jy = CAUSTIC_JITTER * (REALB_OF_UINT(h >> 16) * R(1.0 / 65536.0) - R(0.5));
      const realb dx = (real)i + R(0.5) + jx - fx, dy = (real)j + R(0.5) + jy - fy;
      const realb d2 = dx * dx + dy * dy;
      /* caustic_keep_two_nearest: f2 = min(f2, max(f1, d2)), f1 = min(f1, d2), as selects. */
      const realb hi = SELECTB(d2 > f1, d2, f1);
      f2 = SELECTB(f2 < hi, f2, hi);
      f1 = SELECTB(d2 < f1, d2, f1);
    }
  }
  return (sqrt(f2) - sqrt(f1)) / CAUSTIC_WIDTH;
}

/* caustic_modulation per lane: the surface points (x, z) per lane, one time, period and speed. */
SEASIM_FN realb caustic_modulation_b(realb x, realb z, real time, real period, real speed) {
  if (!(period > R(0.0))) return SPLATB(R(1.0));
  const real inv = R(1.0) / period;
  const real s = speed * time * inv; /* tiles travelled at unit relative speed */
  const realb u = caustic_fract_b(x * inv), v = caustic_fract_b(z * inv);
  const realb ua = caustic_fract_b(u - caustic_fract(R(0.8) * s));
  const realb va = caustic_fract_b(v - caustic_fract(R(0.6) * s));
  const realb ub = caustic_fract_b(u - caustic_fract(R(0.37) + R(-0.1764) * s));
  const realb vb = caustic_fract_b(v - caustic_fract(R(0.71) + R(0.6048) * s));
  const realb e = fmax(caustic_edge_b(ua, va, CAUSTIC_CELLS_A, 0U), caustic_edge_b(ub, vb, CAUSTIC_CELLS_B, 0x68bc21ebU));
  return (CAUSTIC_FLOOR + (R(1.0) - CAUSTIC_FLOOR) * exp(-e * e)) / CAUSTIC_MEAN; /* caustic_profile(e) / MEAN */
}
