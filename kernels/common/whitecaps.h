/* whitecaps.h — sea-surface foam (whitecaps) on the FFT ocean: where it is, how much of the sea it
 * covers, how bright it is, and how a pixel sees it. Needs compat.h and whitecaps_params.h.
 *
 * Where. Foam marks the surface where the choppy displacement compresses it most: the low tail of
 * the Jacobian J = Jxx Jzz − Jxz² of the horizontal displacement (004 §3.7, eq. 30; J < 0 where the
 * surface folds over itself, a breaking crest). A texel of the ocean's N × N tile is foam when
 * J < J_th (whitecaps_mask).
 *
 * How much. J_th is not a knob: it is the W-quantile of J over the tile, taken on the host each frame
 * (host/passes/whitecaps_threshold.h), so that foam covers the fraction W of the surface that
 * Monahan & O'Muircheartaigh (1980, J. Phys. Oceanogr. 10, 2094–2099, eq. 3) fitted to photographs
 * of the open ocean:
 *     W = 3.84e-6 U10^3.41        (U10: wind speed 10 m above the sea, m/s)         (whitecaps_coverage)
 * 0.99 % at 10 m/s, 0.093 % at 5 m/s, 3.9 % at 15 m/s; the fit spans about 4–20 m/s and is extrapolated
 * beyond (W reaches 1 at 38.8 m/s and is held there). The scene's surface.wind_speed is taken as U10.
 *
 * How bright. Fresh foam is a Lambertian layer of reflectance R_0(λ) = 0.55 a(λ) (whitecaps_reflectance):
 * 0.55 is the fresh foam Koepke (1984, Appl. Opt. 23, 1816–1824) builds on (Whitlock, Bartlett &
 * Gurganus 1982), a(λ) the decrease towards the near infrared that Frouin, Schwindling & Deschamps
 * (1996, J. Geophys. Res. 101, 14361–14371) measured, as the ocean-colour processing tabulates it: 1 up
 * to 555 nm, 0.889 at 670, 0.760 at 765, 0.645 at 865 nm, linear between, held outside. It is lit by
 * the downwelling irradiance E_d(λ) on the mean horizontal surface (sun and sky): L_f = R_0 E_d / π,
 * one spectrum per scene. Foam thins as it ages, and Koepke put its mean over a whitecap's life at an
 * efficiency factor f_eff = 0.4 of fresh foam's reflectance (his effective reflectance 0.4 × 0.55 =
 * 0.22). The FFT ocean keeps no foam history, so a texel's rank q ∈ [0, 1) in J among the foam texels
 * stands in for its age (q = 0 the most compressed, breaking now; q → 1 at the threshold), and the
 * foam's opacity over the sea falls with it:
 *     α(q) = (1 − q)^(3/2),   mean over the foam ∫0^1 α dq = 1 / (1 + 3/2) = 0.4 = f_eff  (whitecaps_opacity)
 * so the foam-covered area reflects Koepke's 0.22 on average. The profile's form is ours (Koepke gives
 * the mean, not the profile). q comes from a table of J at WHITECAPS_RANK_NODES evenly spaced ranks
 * among the foam texels, made on the host with the threshold (whitecaps_rank).
 *
 * How a pixel sees it. The view ray meets the mean surface y = 0, as the sea's shading does
 * (common/sea_waves.h), and the foam fraction f of its footprint is composited over the sea's radiance
 * (which already holds the surface's reflection and the water's light):
 *     L = L_sea + f (L_f − L_sea)                                                   (whitecaps_composite)
 * f averages the mask α (0 off the foam) over the footprint: its box-filtered mip chain (level 0 α at the
 * texels, level l its 2^l × 2^l means; N is a power of two and the tile periodic, so no level needs a
 * border), read trilinearly at taps spaced along the footprint's major axis (as common/sea_lean.h
 * reads the slope moments). Box means keep the mean: the far sea, one 1 × 1 cell, is covered by the
 * tile's mean α, 0.4 W, and a view straight down over whole tiles averages to it.
 *
 * Stiff cases: no wind (W = 0) gives J_th below every J: f = 0 and L = L_sea bit for bit; equal nodes
 * of the rank table (few foam texels, ties) give q at the node, not 0/0; rays at or above the horizon are not touched; the hit distance and the footprint
 * are capped at grazing views (the footprint then reads the top level); f is a convex combination of
 * mask values in [0, 1], so L lies between two finite radiances and cannot become NaN or Inf. */

#define WHITECAPS_MAX_TAPS 8
/* A pixel averages its footprint with a box; a trilinear read of level l is a tent about two level-l
 * cells wide, so the level of half the footprint makes the two about as wide. */
#define WHITECAPS_FOOTPRINT_SCALE 0.5
/* Nodes of the rank table: J at ranks q = 0, 1/16, ..., 1 among the foam texels. */
#define WHITECAPS_RANK_NODES 17

/* Monahan & O'Muircheartaigh (1980) eq. 3: the whitecap fraction at wind speed u10 (m/s), in [0, 1]. */
SEASIM_FN real whitecaps_coverage(real u10) {
  const real u = fmax(u10, R(0.0));
  return fmin(R(3.84e-6) * pow(u, R(3.41)), R(1.0));
}

/* Fresh foam's reflectance 0.55 times Frouin et al.'s spectral factor (header) at lambda_nm. */
SEASIM_FN real whitecaps_reflectance(real lambda_nm) {
  const real l = lambda_nm;
  real a;
  if (l <= R(555.0))
    a = R(1.0);
  else if (l <= R(670.0))
    a = R(1.0) + (l - R(555.0)) / R(115.0) * (R(0.889) - R(1.0));
  else if (l <= R(765.0))
    a = R(0.889) + (l - R(670.0)) / R(95.0) * (R(0.760) - R(0.889));
  else if (l <= R(865.0))
    a = R(0.760) + (l - R(765.0)) / R(100.0) * (R(0.645) - R(0.760));
  else
    a = R(0.645);
  return R(0.55) * a;
}

/* The foam's opacity at age rank q (header): 1 when it breaks, 0 at the threshold, mean 0.4. */
SEASIM_FN real whitecaps_opacity(real q) {
  const real s = R(1.0) - clamp(q, R(0.0), R(1.0));
  return s * sqrt(s);
}

/* The rank q ∈ [0, 1] of J among the foam texels: piecewise linear through the table's nodes
 * rank_j[i] (non-decreasing) at q = i / (WHITECAPS_RANK_NODES − 1). */
SEASIM_FN real whitecaps_rank(real jacobian, const SEASIM_GLOBAL float* rank_j) {
  if (jacobian <= (real)rank_j[0]) return R(0.0);
  for (int i = 0; i + 1 < WHITECAPS_RANK_NODES; ++i) {
    const real lo = (real)rank_j[i], hi = (real)rank_j[i + 1];
    if (jacobian < hi) {
      const real t = hi > lo ? (jacobian - lo) / (hi - lo) : R(0.0);
      return ((real)i + t) / (real)(WHITECAPS_RANK_NODES - 1);
    }
  }
  return R(1.0);
}

/* The mask: the foam's opacity where the texel is foam (J below the threshold), else 0. */
SEASIM_FN real whitecaps_mask(real jacobian, real threshold, const SEASIM_GLOBAL float* rank_j) {
  return jacobian < threshold ? whitecaps_opacity(whitecaps_rank(jacobian, rank_j)) : R(0.0);
}

/* Levels of the mask's mip chain for an n × n tile, down to 1 × 1, and where level l starts. */
SEASIM_FN int whitecaps_levels(int n) {
  int levels = 1;
  while ((n >> (levels - 1)) > 1) ++levels;
  return levels;
}
SEASIM_FN int whitecaps_level_offset(int n, int level) {
  int offset = 0;
  for (int l = 0; l < level; ++l) offset += (n >> l) * (n >> l);
  return offset;
}

/* The mean of a 2 × 2 block, in one fixed order (the kernel and its double evaluation agree). */
SEASIM_FN real whitecaps_box(real a, real b, real c, real e) { return R(0.25) * ((a + b) + (c + e)); }

/* Bilinear read of an nl × nl level at texel coordinates (u, v), wrapping around the tile. */
SEASIM_FN real whitecaps_read_level(const SEASIM_GLOBAL real* level, int nl, real u, real v) {
  const real fu = floor(u), fv = floor(v);
  const real tu = u - fu, tv = v - fv;
  const real size = (real)nl, inv_size = R(1.0) / size; /* nl a power of two: 1 / nl is exact */
  int i0 = (int)(fu - size * floor(fu * inv_size)), j0 = (int)(fv - size * floor(fv * inv_size));
  i0 = i0 >= nl ? i0 - nl : i0; /* rounding of fu / size just below an integer */
  j0 = j0 >= nl ? j0 - nl : j0;
  const int i1 = i0 + 1 < nl ? i0 + 1 : 0, j1 = j0 + 1 < nl ? j0 + 1 : 0;
  const real near_row = level[j0 * nl + i0] + tu * (level[j0 * nl + i1] - level[j0 * nl + i0]);
  const real far_row = level[j1 * nl + i0] + tu * (level[j1 * nl + i1] - level[j1 * nl + i0]);
  return near_row + tv * (far_row - near_row);
}

/* The two mip levels a square tap of side `size` m reads: those whose cells bracket
 * WHITECAPS_FOOTPRINT_SCALE × size (level 0, bilinear, when it is smaller), trilinear between them by t.
 * Level 0 texel i sits at x = i·cell; level l texel k is the mean of level-0 texels k 2^l … k 2^l + 2^l − 1,
 * centred at (k 2^l + (2^l − 1)/2)·cell, so x's level-l texel coordinate is x · inv_l − bias_l. Found once
 * for all the taps of a footprint (they are one size). */
typedef struct {
  const SEASIM_GLOBAL real* level0;
  const SEASIM_GLOBAL real* level1;
  int n0, n1;         /* the two levels' sides */
  real inv0, inv1;    /* 1 / (2^l cell) */
  real bias0, bias1;  /* (2^l − 1) / 2^(l+1) */
  real t;             /* the weight of level1 */
  int same;           /* level1 is level0 (the top of the chain) */
} WhitecapsTapLevels;

SEASIM_FN WhitecapsTapLevels whitecaps_tap_levels(const SEASIM_GLOBAL real* mips, int n, real patch, real size) {
  WhitecapsTapLevels lv;
  const int levels = whitecaps_levels(n);
  const real cell = patch / (real)n;
  const real ratio = size / cell * R(WHITECAPS_FOOTPRINT_SCALE);
  const real lod = clamp(log2(fmax(ratio, R(1.0))), R(0.0), (real)(levels - 1));
  const int l0 = (int)floor(lod);
  const int l1 = l0 + 1 < levels ? l0 + 1 : l0;
  const real s0 = (real)(1 << l0), s1 = (real)(1 << l1);
  lv.t = lod - (real)l0;
  lv.same = l1 == l0;
  lv.level0 = mips + whitecaps_level_offset(n, l0);
  lv.level1 = mips + whitecaps_level_offset(n, l1);
  lv.n0 = n >> l0;
  lv.n1 = n >> l1;
  lv.inv0 = R(1.0) / (cell * s0);
  lv.inv1 = R(1.0) / (cell * s1);
  lv.bias0 = (s0 - R(1.0)) / (R(2.0) * s0);
  lv.bias1 = (s1 - R(1.0)) / (R(2.0) * s1);
  return lv;
}

/* The foam fraction around (x, z) m on the levels lv. */
SEASIM_FN real whitecaps_read_tap(const WhitecapsTapLevels* lv, real x, real z) {
  const real f0 = whitecaps_read_level(lv->level0, lv->n0, x * lv->inv0 - lv->bias0, z * lv->inv0 - lv->bias0);
  if (lv->same) return f0;
  const real f1 = whitecaps_read_level(lv->level1, lv->n1, x * lv->inv1 - lv->bias1, z * lv->inv1 - lv->bias1);
  return f0 + lv->t * (f1 - f0);
}

/* The foam fraction around (x, z) m for a square tap of side `size` m. */
SEASIM_FN real whitecaps_read(const SEASIM_GLOBAL real* mips, int n, real patch, real x, real z, real size) {
  const WhitecapsTapLevels lv = whitecaps_tap_levels(mips, n, patch, size);
  return whitecaps_read_tap(&lv, x, z);
}

/* The foam fraction of a footprint centred at (x, z) m, `minor` m across and `major` m along the unit
 * horizontal direction (dir_x, dir_z): up to WHITECAPS_MAX_TAPS square taps along the major axis, all
 * of one size. */
SEASIM_FN real whitecaps_footprint(const SEASIM_GLOBAL real* mips, int n, real patch, real x, real z, real dir_x,
                                   real dir_z, real minor, real major) {
  const real ratio = major / fmax(minor, R(1e-30));
  const int taps = ratio >= (real)WHITECAPS_MAX_TAPS ? WHITECAPS_MAX_TAPS : (int)ceil(fmax(ratio, R(1.0)));
  const real tap_size = fmax(minor, major / (real)taps);
  const WhitecapsTapLevels lv = whitecaps_tap_levels(mips, n, patch, tap_size);
  real sum = R(0.0);
  for (int k = 0; k < taps; ++k) {
    const real offset = major * (((real)k + R(0.5)) / (real)taps - R(0.5));
    sum += whitecaps_read_tap(&lv, x + offset * dir_x, z + offset * dir_z);
  }
  return clamp(sum / (real)taps, R(0.0), R(1.0));
}

/* Where pixel (px, py)'s central ray meets the mean surface y = 0, and its footprint there (header);
 * 0 when the ray does not go down (the sky: no foam). The footprint follows sea_single.cl's: `minor`
 * the pixel's angle at the hit distance, `major` that stretched by 1 / |d.y|; the distance is capped
 * at cam_y · 1e6 (rays within 1e-6 of the horizon). */
SEASIM_FN int whitecaps_pixel_footprint(const SEASIM_CONSTANT WhitecapsParams* p, int px, int py, real* x, real* z,
                                        real* dir_x, real* dir_z, real* minor, real* major) {
  const real u = (R(2.0) * ((real)px + R(0.5)) / (real)p->width - R(1.0)) * (real)p->tan_half_fov_y * (real)p->aspect;
  const real v = (R(1.0) - R(2.0) * ((real)py + R(0.5)) / (real)p->height) * (real)p->tan_half_fov_y;
  real d[3];
  for (int k = 0; k < 3; ++k)
    d[k] = (real)p->cam_forward[k] + u * (real)p->cam_right[k] + v * (real)p->cam_up[k];
  const real inv = R(1.0) / sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  for (int k = 0; k < 3; ++k) d[k] *= inv;
  if (d[1] >= R(0.0)) return 0;
  const real t_hit = (real)p->cam_pos[1] / fmax(-d[1], R(1e-6));
  *x = (real)p->cam_pos[0] + t_hit * d[0];
  *z = (real)p->cam_pos[2] + t_hit * d[2];
  const real facing = d[0] * (real)p->cam_forward[0] + d[1] * (real)p->cam_forward[1] + d[2] * (real)p->cam_forward[2];
  *minor = t_hit * (real)p->pixel_angle * fmax(facing, R(0.1));
  *major = *minor / fmax(-d[1], R(1e-6));
  const real horizontal = sqrt(d[0] * d[0] + d[2] * d[2]);
  *dir_x = horizontal > R(1e-6) ? d[0] / horizontal : R(1.0);
  *dir_z = horizontal > R(1e-6) ? d[2] / horizontal : R(0.0);
  return 1;
}

/* The foam over the sea's radiance (header): exact at f = 0 and f = 1. */
SEASIM_FN real whitecaps_composite(real sea, real f, real foam) { return sea + f * (foam - sea); }
