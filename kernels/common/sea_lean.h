/* sea_lean.h — wave normals filtered from the near waves to the horizon, for the sea seen
 * from above through the FFT ocean (common/sea_waves.h). Needs compat.h, gauss_legendre.h and optics.h.
 *
 * Why: far away a pixel covers many texels of the ocean's normal map. Reading one bilinear normal
 * there (sea_waves.h) picks one facet at random: the sea aliases into noise, the sun's glitter is a
 * few random sparkles, and the Fresnel mix of sky and water colour is wrong on average. The fix is the
 * one of LEAN mapping (Olano & Baker 2010) and of Bruneton, Neyret & Holzschuch 2010 ("Real-time
 * Realistic Ocean Lighting using Seamless Transitions from Geometry to BRDF", §4): filter the slopes'
 * first and second moments, which average linearly, and turn the variance left below the pixel into
 * a distribution of facets (a Gaussian of slopes, the Beckmann model) that the pixel integrates.
 *
 * The moment maps. Per texel of the normal map, the slope s = (s_x, s_z) = (−n_x/n_y, −n_z/n_y) of the
 * surface y = h(x, z), as M = (s_x, s_z, s_x², s_z², s_x s_z) (SEA_LEAN_STRIDE reals): the "point" map,
 * texel i at x = i L/N. The unfiltered path reads the normal map bilinearly, so the surface a ray sees
 * is the bilinear interpolation of these slopes; its moments over each cell between four texels
 * (cell i spans x ∈ [i, i + 1] L/N) are exact closed forms of the four corners (sea_lean_cell_moments):
 * level 0. Averaging the point values instead would overstate the variance of the interpolated
 * surface (by up to 9/4 for uncorrelated texels) and widen the glitter. A mip chain halves the side
 * per level by 2 × 2 box averages (the patch is periodic and N a power of two, so no level needs a
 * border): level l cell i spans x ∈ [i, i + 1] 2^l L/N. Stored one after the other: the point map,
 * then levels 0, 1, … down to 1 × 1.
 *
 * The pixel. The model is sea_waves.h's: the view ray meets the mean surface y = 0 and the pixel is
 * the plain average over its footprint there of what each facet returns (no masking, no projected-area
 * weighting: the unfiltered path does not weight either, so the filtered path converges to it as the
 * pixel shrinks, and its supersampled average is the reference). The footprint is a pixel's cone on
 * the plane: `minor` metres across the view and `major` = minor / |d.y| along it. Up to
 * SEA_LEAN_MAX_TAPS taps spaced along the major axis, each a trilinear read at the level whose cell
 * matches the tap's size, are averaged (anisotropic filtering of the moments, which stays exact
 * because moments average linearly). A tap smaller than a cell (size r < 1 cell) blends the point
 * map's bilinear slope (variance 0: what one ray sees) with level 0's cell moments, by r.
 *
 * The facets. Mean slope m and covariance Σ = E[s sᵀ] − m mᵀ (+ SEA_LEAN_MIN_VARIANCE per axis):
 *  - the sky's reflection and the Fresnel mix: E[F(s) L_sky(r(s))] by quadrature over the Gaussian
 *    (nodes m + L u, L the Cholesky factor of Σ): 3 × 3 Gauss–Hermite, or, when facets turn away
 *    from the eye near the horizon, a rule split at that boundary (sea_lean_rule); exact for the
 *    uniform sky's Fresnel mean at Σ = 0 (all nodes coincide);
 *  - the sun (the glitter): the sun is a disk of solid angle Ω and radiance E/Ω, seen by the facets
 *    whose mirror direction falls in it, those with the half vector h = normalize(sun − d). The
 *    fraction of the footprint's facets doing so is p(s_h) dA_s, with dA_s = dω_h / cos³θ_h the
 *    slope-space area of the half vectors and dω_h = Ω / (4 (−d·h)) (the mirror's Jacobian), so
 *      L_glint = E F(−d·h) p(s_h) / (4 (−d·h) cos³θ_h),
 *    independent of Ω. The disk's own size is added to Σ as the slope variance of a uniform disk of
 *    half-vector radius ρ/2: ρ²/16 per axis (ρ the sun's angular radius), so a calm sea shows the
 *    sun's disk as a finite spot, not a spike. The pixel averages it over its solid angle where it
 *    changes across the pixel (3 x 3 directions, sea_lean_pixel_glint): under a low sun it changes fast.
 * With no waves (Σ → the floor, m = 0) the sky term is exactly F L_sky of the flat sea (test:
 * tests/unit/sea_lean_test.cpp).
 *
 * Stiff cases: facets steeper than 20:1 (folded crests) are capped there; a half vector at or below
 * the horizon gives no glint; Σ is floored so that det Σ > 0 and its Cholesky factor exist; the
 * variance, a difference of averages, is clamped at 0 against rounding.
 */

#define SEA_LEAN_STRIDE 5
#define SEA_LEAN_MAX_TAPS 8
#define SEA_LEAN_MAX_SLOPE R(20.0)
#define SEA_LEAN_MIN_VARIANCE R(1e-8)
/* A pixel averages its footprint with a box; a bilinear read of a mip level, blended trilinearly,
 * is a tent about twice as wide. Reading the level of 0.6 × the footprint brings the two closest:
 * against the 32 × 32 supersampled reference (tests/kernels/sea_lean_kernel_test.cpp's scene, sun off)
 * the whole sea's RMS went from 1.83 levels (1.0) to 1.26 (0.7) and 1.04 (0.5), the horizon's from
 * 1.34 to 1.26 and 1.36. */
#define SEA_LEAN_FOOTPRINT_SCALE R(0.6)
SEASIM_FN real sea_lean_footprint_scale(void) { return SEA_LEAN_FOOTPRINT_SCALE; }

/* The slope of the facet with unit normal n (y up), capped at SEA_LEAN_MAX_SLOPE. */
SEASIM_FN void sea_lean_slope(real3 n, real* sx, real* sz) {
  const real ny = fmax(n.y, R(1.0) / SEA_LEAN_MAX_SLOPE);
  *sx = clamp(-n.x / ny, -SEA_LEAN_MAX_SLOPE, SEA_LEAN_MAX_SLOPE);
  *sz = clamp(-n.z / ny, -SEA_LEAN_MAX_SLOPE, SEA_LEAN_MAX_SLOPE);
}

/* The unit normal of slope (sx, sz). */
SEASIM_FN real3 sea_lean_normal(real sx, real sz) { return normalize(MAKE_REAL3(-sx, R(1.0), -sz)); }

/* Mip levels of the n × n cell moments down to 1 × 1, and where level l starts (in reals): after the
 * point map (n × n, at offset 0). sea_lean_level_offset(n, sea_lean_levels(n)) is the whole size. */
SEASIM_FN int sea_lean_levels(int n) {
  int levels = 1;
  while ((n >> (levels - 1)) > 1) ++levels;
  return levels;
}
SEASIM_FN int sea_lean_level_offset(int n, int level) {
  int offset = n * n * SEA_LEAN_STRIDE;
  for (int l = 0; l < level; ++l) offset += (n >> l) * (n >> l) * SEA_LEAN_STRIDE;
  return offset;
}

/* Moments of the bilinear interpolation of the slopes at a cell's corners (a at (0, 0), b at (1, 0),
 * c at (0, 1), e at (1, 1); x and z slopes) over the cell: with ∫(1−u)² = ∫u² = 1/3 and
 * ∫u(1−u) = 1/6 per axis, E[f g] = Σ corner products weighted 1/9 (same corner), 1/18 (edge
 * neighbours), 1/36 (diagonal), each unordered pair of distinct corners counted twice. */
SEASIM_FN real sea_lean_bilinear_product(real fa, real fb, real fc, real fe, real ga, real gb, real gc, real ge) {
  const real same = fa * ga + fb * gb + fc * gc + fe * ge;
  const real edge = fa * gb + fb * ga + fa * gc + fc * ga + fb * ge + fe * gb + fc * ge + fe * gc;
  const real diagonal = fa * ge + fe * ga + fb * gc + fc * gb;
  return same / R(9.0) + edge / R(18.0) + diagonal / R(36.0);
}
SEASIM_FN void sea_lean_cell_moments(real ax, real az, real bx, real bz, real cx, real cz, real ex, real ez,
                                     real m[SEA_LEAN_STRIDE]) {
  m[0] = R(0.25) * ((ax + bx) + (cx + ex));
  m[1] = R(0.25) * ((az + bz) + (cz + ez));
  m[2] = sea_lean_bilinear_product(ax, bx, cx, ex, ax, bx, cx, ex);
  m[3] = sea_lean_bilinear_product(az, bz, cz, ez, az, bz, cz, ez);
  m[4] = sea_lean_bilinear_product(ax, bx, cx, ex, az, bz, cz, ez);
}

/* Bilinear moments of one map (side nl, a power of two, periodic) at texel coordinates (u, v) (texel i at u = i). */
SEASIM_FN void sea_lean_read_level(const SEASIM_GLOBAL real* level, int nl, real u, real v, real m[SEA_LEAN_STRIDE]) {
  const real fu = floor(u), fv = floor(v);
  const real tu = u - fu, tv = v - fv;
  /* nl is a power of two (the ocean's grid is one, scene_parser.cpp, and each level halves it), so the
   * periodic wrap is a mask, negative indices included: the integer division it was cost a fifth of
   * the filtered sea's frame on PoCL. */
  const int i0 = (int)fu & (nl - 1), j0 = (int)fv & (nl - 1);
  const int i1 = i0 + 1 < nl ? i0 + 1 : 0, j1 = j0 + 1 < nl ? j0 + 1 : 0;
  const SEASIM_GLOBAL real* a = level + SEA_LEAN_STRIDE * (j0 * nl + i0);
  const SEASIM_GLOBAL real* b = level + SEA_LEAN_STRIDE * (j0 * nl + i1);
  const SEASIM_GLOBAL real* c = level + SEA_LEAN_STRIDE * (j1 * nl + i0);
  const SEASIM_GLOBAL real* e = level + SEA_LEAN_STRIDE * (j1 * nl + i1);
  for (int k = 0; k < SEA_LEAN_STRIDE; ++k) {
    const real near_row = a[k] + tu * (b[k] - a[k]);
    const real far_row = c[k] + tu * (e[k] - c[k]);
    m[k] = near_row + tv * (far_row - near_row);
  }
}

/* The mip levels a square tap of side `size` metres reads (header): the two cell levels whose cells
 * bracket SEA_LEAN_FOOTPRINT_SCALE × size, trilinear between them by t, and below one cell the blend with
 * the point map by ratio. Found once for all the taps of a footprint (they are one size). */
typedef struct {
  const SEASIM_GLOBAL real* level0;
  const SEASIM_GLOBAL real* level1;
  int n0, n1;           /* the two levels' sides */
  real inv0, inv1;      /* 1 / (2^l cell): level l cell i is centred at x = (i + 1/2) 2^l cell */
  real t;               /* the weight of level1 */
  real ratio;           /* the tap in cells (× the footprint scale): below 1 the point map is blended in */
  real inv_cell;
} SeaLeanTapLevels;

SEASIM_FN SeaLeanTapLevels sea_lean_tap_levels(const SEASIM_GLOBAL real* mips, int n, real patch, real size) {
  SeaLeanTapLevels lv;
  const int levels = sea_lean_levels(n);
  const real cell = patch / (real)n;
  lv.ratio = size / cell * SEA_LEAN_FOOTPRINT_SCALE;
  const real lod = clamp(log2(fmax(lv.ratio, R(1.0))), R(0.0), (real)(levels - 1));
  const int l0 = (int)floor(lod);
  const int l1 = l0 + 1 < levels ? l0 + 1 : l0;
  lv.t = lod - (real)l0;
  lv.level0 = mips + sea_lean_level_offset(n, l0);
  lv.level1 = mips + sea_lean_level_offset(n, l1);
  lv.n0 = n >> l0;
  lv.n1 = n >> l1;
  lv.inv0 = R(1.0) / (cell * (real)(1 << l0));
  lv.inv1 = R(1.0) / (cell * (real)(1 << l1));
  lv.inv_cell = R(1.0) / cell;
  return lv;
}

/* Moments at (x, z) metres for a tap on the levels lv (header): trilinear over the cell levels, blended
 * with the point map's slope below one cell. */
SEASIM_FN void sea_lean_read(const SEASIM_GLOBAL real* mips, int n, const SeaLeanTapLevels* lv, real x, real z,
                             real m[SEA_LEAN_STRIDE]) {
  real m0[SEA_LEAN_STRIDE], m1[SEA_LEAN_STRIDE];
  sea_lean_read_level(lv->level0, lv->n0, x * lv->inv0 - R(0.5), z * lv->inv0 - R(0.5), m0);
  sea_lean_read_level(lv->level1, lv->n1, x * lv->inv1 - R(0.5), z * lv->inv1 - R(0.5), m1);
  for (int k = 0; k < SEA_LEAN_STRIDE; ++k) m[k] = m0[k] + lv->t * (m1[k] - m0[k]);
  if (lv->ratio < R(1.0)) {
    real point[SEA_LEAN_STRIDE];
    sea_lean_read_level(mips, n, x * lv->inv_cell, z * lv->inv_cell, point); /* the point map: texel i at x = i cell */
    const real sx = point[0], sz = point[1];
    const real w = lv->ratio, wp = R(1.0) - lv->ratio;
    m[0] = wp * sx + w * m[0];
    m[1] = wp * sz + w * m[1];
    m[2] = wp * sx * sx + w * m[2];
    m[3] = wp * sz * sz + w * m[3];
    m[4] = wp * sx * sz + w * m[4];
  }
}

/* The footprint's slope statistics (header): mean (out[0], out[1]) and covariance (out[2] = Σxx,
 * out[3] = Σzz, out[4] = Σxz), without the floor. (x, z): where the view ray meets y = 0; (dir_x, dir_z):
 * the unit horizontal direction of the view (the major axis); minor, major: the footprint in metres. */
SEASIM_FN void sea_lean_footprint(const SEASIM_GLOBAL real* mips, int n, real patch, real x, real z, real dir_x,
                                  real dir_z, real minor, real major, real out[SEA_LEAN_STRIDE]) {
  const real ratio = major / fmax(minor, R(1e-30));
  const int taps = ratio >= (real)SEA_LEAN_MAX_TAPS ? SEA_LEAN_MAX_TAPS : (int)ceil(fmax(ratio, R(1.0)));
  const real tap_size = fmax(minor, major / (real)taps);
  const SeaLeanTapLevels lv = sea_lean_tap_levels(mips, n, patch, tap_size);
  real sum[SEA_LEAN_STRIDE] = {R(0.0), R(0.0), R(0.0), R(0.0), R(0.0)};
  for (int k = 0; k < taps; ++k) {
    const real offset = major * (((real)k + R(0.5)) / (real)taps - R(0.5));
    real m[SEA_LEAN_STRIDE];
    sea_lean_read(mips, n, &lv, x + offset * dir_x, z + offset * dir_z, m);
    for (int q = 0; q < SEA_LEAN_STRIDE; ++q) sum[q] += m[q];
  }
  const real mx = sum[0] / (real)taps, mz = sum[1] / (real)taps;
  out[0] = mx;
  out[1] = mz;
  out[2] = fmax(sum[2] / (real)taps - mx * mx, R(0.0));
  out[3] = fmax(sum[3] / (real)taps - mz * mz, R(0.0));
  out[4] = sum[4] / (real)taps - mx * mz;
}

/* Σ with the floor and the sun disk's variance (header), and its Cholesky factor (l11, l21, l22);
 * the off-diagonal term is clamped so that Σ stays positive definite. */
SEASIM_FN void sea_lean_covariance(real vxx, real vzz, real vxz, real sun_variance, real* cxx, real* czz, real* cxz,
                                   real* l11, real* l21, real* l22) {
  *cxx = vxx + sun_variance + SEA_LEAN_MIN_VARIANCE;
  *czz = vzz + sun_variance + SEA_LEAN_MIN_VARIANCE;
  const real bound = R(0.999) * sqrt(*cxx * *czz);
  *cxz = clamp(vxz, -bound, bound);
  *l11 = sqrt(*cxx);
  *l21 = *cxz / *l11;
  *l22 = sqrt(fmax(*czz - *l21 * *l21, R(0.0)));
}

/* The facets' quadrature (header, "The facets"). A facet of slope s faces away from the eye when
 * a·s ≤ d.y, a = (d.x, d.z): a half-plane of the Gaussian. There the unfiltered path bends the normal
 * to grazing (sea_facing_normal: F = 1, the ray goes on to the horizon's sky), so the integrand is the
 * constant "horizon" value there and has a kink at the boundary, which a Gauss–Hermite rule over the
 * whole plane integrates poorly (errors of 2–10 % for rough seas seen within 20° of the horizon;
 * tests/unit/sea_lean_test.cpp). With s = m + L u (u standard normal) the boundary is the line
 * t = q·u/|q| = β, q = Lᵀa, β = (d.y − a·m)/|q|, and
 *   E[g] = Φ(β) g_back + ∫_{t > β} φ(t) ∫ φ(v) g dv dt.
 * When β < SEA_LEAN_SPLIT_BETA (back-facing facets below 2e-4) the 3 × 3 Gauss–Hermite rule over the
 * plane is used as it is; otherwise 8 Gauss–Legendre nodes in t over [β, max(5, β + 1)] with weight
 * φ(t), normalised by their own sum, times 3 Gauss–Hermite nodes in v along the boundary. */
#define SEA_LEAN_SPLIT_BETA R(-3.5)

typedef struct {
  real mx, mz, l11, l21, l22; /* mean slope and the Cholesky factor of Σ */
  real e1u, e1v;              /* unit vector in u along q (the split rule's t axis) */
  real lo, hi;                /* the facing facets' t interval (split rule) */
  real back;                  /* Φ(β): the back-facing facets' share (0 for the plain rule) */
  real t[8], tw[8];           /* the split rule's t nodes and their weights, φ(t) and the normalisation in */
  int split;                  /* 0: 3 × 3 Gauss–Hermite; 1: 8 × 3 split rule */
} SeaLeanRule;

SEASIM_FN real sea_lean_gh3_node(int j, real* weight) {
  *weight = j == 1 ? R(2.0) / R(3.0) : R(1.0) / R(6.0);
  return (real)(j - 1) * R(1.7320508075688772);
}

/* Fills *r through a pointer: returned by value, the rule (with its arrays) made clang emit
 * llvm.experimental.noalias.scope.decl, which Oclgrind cannot run. */
SEASIM_FN void sea_lean_rule(real3 d, real mx, real mz, real l11, real l21, real l22, SeaLeanRule* r) {
  r->mx = mx, r->mz = mz, r->l11 = l11, r->l21 = l21, r->l22 = l22;
  r->e1u = R(1.0), r->e1v = R(0.0), r->lo = R(0.0), r->hi = R(0.0), r->back = R(0.0);
  for (int i = 0; i < 8; ++i) r->t[i] = r->tw[i] = R(0.0);
  r->split = 0;
  const real qu = d.x * l11 + d.z * l21, qv = d.z * l22;
  const real qn = sqrt(qu * qu + qv * qv);
  if (qn <= R(1e-20)) return; /* a vertical view: no facet faces away */
  const real beta = (d.y - (d.x * mx + d.z * mz)) / qn;
  if (beta < SEA_LEAN_SPLIT_BETA) return;
  r->split = 1;
  r->e1u = qu / qn, r->e1v = qv / qn;
  r->lo = beta;
  r->hi = fmax(R(5.0), beta + R(1.0));
  r->back = R(0.5) * erfc(-beta * R(0.70710678118654752));
  real mass = R(0.0);
  for (int i = 0; i < 8; ++i) {
    real w;
    r->t[i] = r->lo + (r->hi - r->lo) * R(0.5) * (gauss_legendre8_node(i, &w) + R(1.0));
    r->tw[i] = w * exp(R(-0.5) * r->t[i] * r->t[i]);
    mass += r->tw[i];
  }
  const real scale = mass > R(1e-30) ? (R(1.0) - r->back) / mass : R(0.0);
  for (int i = 0; i < 8; ++i) r->tw[i] *= scale;
}

SEASIM_FN int sea_lean_rule_nodes(const SeaLeanRule* r) { return r->split ? 24 : 9; }

/* Node k of the rule: its slope and weight (the weights and r->back sum to 1). */
SEASIM_FN real sea_lean_rule_node(const SeaLeanRule* r, int k, real* sx, real* sz) {
  real u1, u2, weight;
  if (!r->split) {
    real wa, wb;
    u1 = sea_lean_gh3_node(k / 3, &wa);
    u2 = sea_lean_gh3_node(k % 3, &wb);
    weight = wa * wb;
  } else {
    real wv;
    const real t = r->t[k / 3];
    const real v = sea_lean_gh3_node(k % 3, &wv);
    u1 = t * r->e1u - v * r->e1v;
    u2 = t * r->e1v + v * r->e1u;
    weight = r->tw[k / 3] * wv;
  }
  *sx = r->mx + r->l11 * u1;
  *sz = r->mz + r->l21 * u1 + r->l22 * u2;
  return weight;
}

/* The half vector's slope for view d and the sun, and the cosine c = −d·h; 0 when there is none (no half
 * vector, or one at or below the horizon: no glint). */
SEASIM_FN int sea_lean_half_slope(real3 d, real3 sun, real* sx, real* sz, real* c) {
  const real3 sum = sun - d;
  const real len = length(sum);
  if (len < R(1e-6)) return 0;
  const real3 h = sum / len;
  if (h.y <= R(1e-4)) return 0;
  *sx = -h.x / h.y;
  *sz = -h.z / h.y;
  *c = -dot(d, h);
  return 1;
}

/* The glitter (header): radiance reflected from a sun of irradiance 1 (normal to its beam) towards
 * the eye along d (unit, going down), by the footprint's facets of mean (mx, mz) and covariance
 * (cxx, czz, cxz) (already floored: sea_lean_covariance). */
SEASIM_FN real sea_lean_glint(real3 d, real3 sun, real ior, real mx, real mz, real cxx, real czz, real cxz) {
  real sx, sz, c;
  if (!sea_lean_half_slope(d, sun, &sx, &sz, &c)) return R(0.0);
  const real dx = sx - mx, dz = sz - mz;
  const real det = cxx * czz - cxz * cxz;
  const real q = (czz * dx * dx - R(2.0) * cxz * dx * dz + cxx * dz * dz) / det;
  const real pdf = exp(R(-0.5) * q) / (R(2.0) * SEASIM_PI * sqrt(det));
  const real hy = R(1.0) / sqrt(R(1.0) + sx * sx + sz * sz); /* cos θ_h */
  c = fmax(c, R(1e-4));
  return fresnel_reflectance(c, R(1.0), ior) * pdf / (R(4.0) * c * hy * hy * hy);
}

/* The glitter over the pixel's solid angle. Under a low sun the glint changes fast across one pixel — on
 * ocean_sunset (sun 5° up, 64 x 36) the half vector's slope moves by up to one standard deviation across
 * it — and the centre's value was 8–32 % off the pixel's mean near the horizon (docs/journal/
 * waves_reference.md). The glint is exp(−q/2) times slow factors, q = |u|² the half vector's slope in σ
 * (Mahalanobis) from the facets' mean; half a pixel moves u by δ, so ln glint moves by about d δ + δ²/2,
 * d = |u| at the centre. Where the glint's argument moves across the pixel — δ above 0.2 (from the centre to
 * half a pixel along either image axis), d δ above 0.2 (in the tail a small δ is a large factor: where δ
 * alone decided, the centre was up to 11 % off the pixel's mean at 4–5 σ and 19 % at 5–6 σ, against 48 x 48
 * directions; tests/unit/sea_lean_test.cpp), or c by more than 2 % — and the pixel comes
 * within 6 σ of the facets' mean, the glint is averaged over 3 x 3 Gauss–Legendre directions (0 and
 * ±√(3/5)/2 of a pixel on each axis, weights 8/18 and 5/18: within 1 % of 64 x 64 of them, tests/unit/
 * sea_lean_test.cpp; 2 x 2 still missed by 4 % two degrees under the horizon); elsewhere the centre's
 * value is the mean within about 1 % and is used alone (nine glints for every pixel cost ocean_noon 25 %
 * of its frame). d: the pixel's centre (unit, going down); fwd: the camera's forward axis; du, dv: one pixel
 * along the image's x and y on the image plane at distance 1. A direction at or above the horizon adds
 * nothing (it sees the sky, not the sea). */
SEASIM_FN real sea_lean_pixel_glint(real3 d, real3 fwd, real3 du, real3 dv, real3 sun, real ior, real mx, real mz,
                                    real cxx, real czz, real cxz) {
  const real centre_glint = sea_lean_glint(d, sun, ior, mx, mz, cxx, czz, cxz);
  const real3 centre = d / fmax(dot(d, fwd), R(1e-6)); /* the pixel's centre on the image plane */
  real sx = R(0.0), sz = R(0.0), c = R(0.0); /* left as they are where there is no half vector */
  int centre_only = sea_lean_half_slope(d, sun, &sx, &sz, &c) && d.y < R(0.0);
  const real det = cxx * czz - cxz * cxz;
  real shift = R(0.0); /* the half vector's slope from the centre to half a pixel along du, plus along dv, in σ */
  int slow = 1;        /* ... each below 0.2 σ and below 0.2 / d, and c within 2 % */
  const real cx = sx - mx, cz = sz - mz;
  const real d2 = fmax((czz * cx * cx - R(2.0) * cxz * cx * cz + cxx * cz * cz) / det, R(0.0)); /* d² */
  for (int axis = 0; axis < 2 && centre_only; ++axis) {
    real ex = R(0.0), ez = R(0.0), ec = R(0.0);
    centre_only = sea_lean_half_slope(normalize(centre + R(0.5) * (axis == 0 ? du : dv)), sun, &ex, &ez, &ec);
    const real dx = ex - sx, dz = ez - sz;
    const real m2 = (czz * dx * dx - R(2.0) * cxz * dx * dz + cxx * dz * dz) / det;
    shift += sqrt(m2);
    slow = slow && m2 < R(0.04) && d2 * m2 < R(0.04) && fabs(ec - c) < R(0.02) * c;
  }
  /* The centre suffices where the glint is slow across the pixel, or where even the pixel's nearest corner
   * lies more than 6 σ from the facets' mean (the glint there is below e^-18 of its peak). */
  const real far = sqrt(d2) - shift;
  if (centre_only && (slow || far > R(6.0))) return centre_glint;
  const real node[3] = {R(-0.38729833462074170), R(0.0), R(0.38729833462074170)};
  const real weight[3] = {R(5.0) / R(18.0), R(8.0) / R(18.0), R(5.0) / R(18.0)};
  real sum = R(0.0);
  for (int k = 0; k < 9; ++k) {
    if (k == 4) {
      sum += weight[1] * weight[1] * (d.y < R(0.0) ? centre_glint : R(0.0));
      continue;
    }
    const real3 dk = normalize(centre + node[k % 3] * du + node[k / 3] * dv);
    if (dk.y < R(0.0)) sum += weight[k % 3] * weight[k / 3] * sea_lean_glint(dk, sun, ior, mx, mz, cxx, czz, cxz);
  }
  return sum;
}
