/* froxel.h — froxel single scattering of the refracted sun beam (002 §5.1, eq. 5.2, §5.2): grid math,
 * the sun shadow map's frame and visibility, the per-slice integration of eq. 5.2 and the per-pixel
 * read, shared by froxel.cl, kd_multiple.cl and the host (kmath_f / kmath_d, tested in float and
 * double). Needs optics.h, shafts.h (ray_sphere/ray_box/ray_plane), underwater_params.h,
 * underwater.h and froxel_params.h before it.
 *
 * The integral (002 eq. 5.1) along a view ray o + z d below a flat surface, for one band:
 *   L_SS = ∫_0^S e^{-σ_t z} L_i(x_z) dz,   L_i = σ_s p_HG(cos θ, g) E_beam(y) V(x) C(x),
 *   E_beam(y) = e_beam0 e^{-σ_t y/μ_w}   (the extinction from the surface, which 002 §5.2 says HDRP's
 *                                         froxels lack and the thesis compensates),
 *   cos θ = (-s_w)·(-d) = s_w·d          (the beam travels along -s_w, is scattered towards the
 *                                         camera along -d; hg_phase is normalised to 1 over 4π sr).
 * V: sun visibility (shadow map for spheres/boxes, exact test for planes), C: caustics.
 *
 * Grid. Columns (i, j), i < nx, j < ny, cover the screen uniformly: column (i, j) follows the view ray
 * through the screen point ((i + ½)/nx, (j + ½)/ny), the pinhole camera of sea_single.cl. Slices run
 * along that ray, by DISTANCE ALONG THE RAY (the G-buffer's S), not camera depth, so a column is
 * exactly a ray and a pixel's S indexes it directly. Exponential slicing: slice k covers
 * (z_k, z_{k+1}], z_{k+1} = z_near (z_far/z_near)^{(k+1)/nz}, z_0 = 0 (slice 0 starts at the camera).
 *
 * Integration (002 eq. 5.2, done exactly for the beam): V·C is held at its value at the slice's
 * midpoint; the rest of the integrand is integrated exactly. The light reaching the camera from distance
 * t has travelled P(t) = y(t)/μ_w down from the surface along the beam and t to the camera, so
 *   e^{-σ_t t} L_i(t) = σ_s p V C e_beam0 e^{-σ_t P(t)},   P(t) = t + y(t)/μ_w,   y(t) = y_cam - t d_y,
 * and P is linear in t with slope r = 1 - d_y/μ_w (the column's `rate`, r > 0 unless the view rises
 * more steeply than the refracted sun). Over [t0, t1]:
 *   ∫ = σ_s p V C e_beam0 (t1 - t0) e^{-σ_t min(P0, P1)} φ(-σ_t |P1 - P0|),   φ(x) = expm1(x)/x,
 * both factors <= 1 for any optical depth (froxel_beam_segment): a slice 1 m long in 9C water (σ_t d =
 * 11) and a view towards the surface (P falling with t) neither lose light nor overflow. Held at the
 * midpoint, E_beam's exponential alone errs by (σ_t r d)²/24 relative in a slice of length d. With the
 * clipping below, 24 slices now err less on seabed than the rectangle rule's 64 did (1.02 against 1.24 %
 * rel. L2 without caustics, results/BENCHMARKS.md).
 * A slice that reaches the surface (a view rising to y = 0 at t_s = y_cam/d_y) is integrated over its
 * part below it, [t0, min(t1, t_s)], and V·C is taken at the middle of that part (froxel_sample_t).
 *
 * Read (froxel_lookup): the volume holds the integral to the END of each slice; a pixel at distance S
 * in slice k reads L(z_k) + f (L(z_{k+1}) - L(z_k)), f the fraction of that slice's light gathered by
 * S, f = (1 - e^{-τx})/(1 - e^{-τ}) with x = (S - z_k)/d and τ = σ̄_t r d per channel (σ̄_t =
 * FroxelParams.sigma_t_rgb, r = 1 - d_y/μ_w the rate), exact for one band; written without 0/0 at
 * τ = 0 and without overflow for τ < 0 (froxel_partial). d is the slice's part below the surface; d_y
 * is the pixel's, bilinear between its columns' (the volume's 4th float holds each column's d_y).
 * Columns: bilinear between the four columns around the pixel (clamped at the border). S >= z_far
 * (deep water, UW_INFINITE) reads the value at z_far: light beyond z_far is lost, part of the froxel
 * method's error. A pixel whose ray ends at the surface reads each column whole, to its own surface
 * (froxel_reads_whole_columns).
 */


/* End of slice k (k = 0 .. nz-1): z_near (z_far/z_near)^{(k+1)/nz} = z_near e^{(k+1) log_far_near/nz},
 * log_far_near = log(z_far/z_near) (FroxelParams.log_far_near: one value for host and device);
 * exactly z_far for the last slice. */
SEASIM_FN real froxel_slice_end(int k, int nz, real z_near, real z_far, real log_far_near) {
  if (k >= nz - 1) return z_far;
  return z_near * exp((real)(k + 1) * (log_far_near / (real)nz));
}

/* Start of slice k: 0 for slice 0, else the end of slice k - 1. */
SEASIM_FN real froxel_slice_start(int k, int nz, real z_near, real z_far, real log_far_near) {
  return k <= 0 ? R(0.0) : froxel_slice_end(k - 1, nz, z_near, z_far, log_far_near);
}

/* The slice holding distance t, with its ends [*t0, *t1]: slice k holds (start_k, end_k]; t <= 0 (and NaN)
 * gives 0, t >= z_far gives nz-1. Each end is computed once (the froxel read took six exp and log calls
 * when it asked for the slice and then for its ends). */
SEASIM_FN int froxel_slice_and_ends(real t, int nz, real z_near, real z_far, real log_far_near, real* t0, real* t1) {
  int k = nz - 1;
  if (nz > 1 && t < z_far) {
    k = t > R(0.0) ? (int)ceil((real)nz * log(t / z_near) / log_far_near) - 1 : 0;
    k = k < 0 ? 0 : (k > nz - 1 ? nz - 1 : k);
  }
  real lo = froxel_slice_start(k, nz, z_near, z_far, log_far_near);
  real hi = froxel_slice_end(k, nz, z_near, z_far, log_far_near);
  /* log/exp rounding can put t one slice off near a boundary: settle it on the same boundaries. */
  if (k < nz - 1 && t > hi) {
    k += 1;
    lo = hi;
    hi = froxel_slice_end(k, nz, z_near, z_far, log_far_near);
  } else if (k > 0 && t <= lo) {
    k -= 1;
    hi = lo;
    lo = froxel_slice_start(k, nz, z_near, z_far, log_far_near);
  }
  *t0 = lo;
  *t1 = hi;
  return k;
}

/* The slice holding distance t (froxel_slice_and_ends without its ends). */
SEASIM_FN int froxel_slice_index(real t, int nz, real z_near, real z_far, real log_far_near) {
  real t0, t1;
  return froxel_slice_and_ends(t, nz, z_near, z_far, log_far_near, &t0, &t1);
}

/* The ray of froxel column (i, j). */
SEASIM_FN real3 froxel_column_dir(const SEASIM_CONSTANT UwParams* p, const SEASIM_CONSTANT FroxelParams* fp, int i,
                                  int j) {
  return uw_screen_dir(p, ((real)i + R(0.5)) / (real)fp->nx, ((real)j + R(0.5)) / (real)fp->ny);
}

/* Where a view ray from a camera at depth y_cam (> 0 below the surface) with vertical direction d_y leaves
 * the water (y = 0): y_cam/d_y for a rising ray, UW_INFINITE otherwise. */
SEASIM_FN real froxel_surface_distance(real y_cam, real d_y) {
  return d_y > R(0.0) ? fmax(y_cam, R(0.0)) / d_y : (real)UW_INFINITE;
}

/* The distance along the column where slice [t0, t1] samples V·C: the middle of its part below the
 * surface (t_surface: froxel_surface_distance), the slice's midpoint when it lies wholly below. */
SEASIM_FN real froxel_sample_t(real t0, real t1, real t_surface) {
  return R(0.5) * (t0 + fmax(t0, fmin(t1, t_surface)));
}

/* The point of froxel (i, j, k) where V·C is sampled: the column ray at froxel_sample_t. */
SEASIM_FN real3 froxel_center(const SEASIM_CONSTANT UwParams* p, const SEASIM_CONSTANT FroxelParams* fp, int i, int j,
                              int k) {
  const real3 d = froxel_column_dir(p, fp, i, j);
  const real t = froxel_sample_t(froxel_slice_start(k, fp->nz, fp->z_near, fp->z_far, fp->log_far_near),
                                 froxel_slice_end(k, fp->nz, fp->z_near, fp->z_far, fp->log_far_near),
                                 froxel_surface_distance(-p->cam_pos[1], d.y));
  const real3 o = MAKE_REAL3(p->cam_pos[0], p->cam_pos[1], p->cam_pos[2]);
  return o + t * d;
}

/* ---- the caustic texture over a froxel ---- */

/* How much of a texture's deviation from its mean one point sample may keep when it stands for the mean
 * over a footprint l_along × l_across: for a texture whose autocorrelation along a line integrates to
 * λ (its integral scale), the regression of the footprint's mean on the centre value is about
 * min(1, λ/l) per axis (measured for the caustic texture: FroxelMath.CausticShrinkFollowsItsIntegralScale).
 * The froxel keeps 1 + ρ (C - 1): the best linear estimate of the mean the pixel integrates from its
 * one sample, which point sampling (ρ = 1) overstates by the texture's whole variance where a slice or
 * the spacing of the columns spans many caustic cells. In [0, 1]; 1 at λ >= l. */
SEASIM_FN real froxel_footprint_correlation(real lambda, real l_along, real l_across) {
  return lambda / fmax(l_along, lambda) * (lambda / fmax(l_across, lambda));
}

/* Whether a froxel with this ρ evaluates the texture: below 1/64 it would keep less than 1/64 of the
 * texture's deviation, and takes its mean, 1. */
SEASIM_FN int froxel_caustic_evaluated(real rho) { return rho >= R(0.015625); }

/* The caustic a froxel keeps from its sample c: 1 + ρ (c - 1) (froxel_footprint_correlation). */
SEASIM_FN real froxel_kept_caustic(real c, real rho) { return R(1.0) + rho * (c - R(1.0)); }

/* ρ of froxel_footprint_correlation for the slice part [t0, s1] of column direction d (s1 its end below
 * the surface): the caustic at a point is the texture at the surface point its refracted sun ray came
 * from, so a segment of the column maps to the surface at |d_h - (d_y/s_w,y) s_w,h| per metre (h: x and
 * z), and the columns lie t × (their angular spacing) apart across it. lambda: the texture's integral
 * scale in metres. */
SEASIM_FN real froxel_caustic_correlation(const SEASIM_CONSTANT UwParams* p, const SEASIM_CONSTANT FroxelParams* fp,
                                          real3 d, real3 s_w, real t0, real s1, real lambda) {
  const real k = d.y / fmax(s_w.y, R(1e-4));
  const real ux = d.x - k * s_w.x, uz = d.z - k * s_w.z;
  const real along = (s1 - t0) * sqrt(ux * ux + uz * uz);
  const real spacing = R(2.0) * p->tan_half_fov_y * fmax(p->aspect / (real)fp->nx, R(1.0) / (real)fp->ny);
  const real across = R(0.5) * (t0 + s1) * spacing;
  return froxel_footprint_correlation(lambda, along, across);
}

/* One band's single scattering over the part [t0, t0 + len] of a view ray with constant V·C (see the
 * top): scale e_beam0 len e^{-σ_t min(P0, P1)} φ(-σ_t |P1 - P0|), scale = σ_s p V C, P the light's path
 * from the surface to the camera through the segment's ends. The exponent of the first factor and the
 * argument of φ are <= 0, so each factor is in [0, 1]: no overflow, underflow to 0 at depth. */
SEASIM_FN real froxel_beam_segment(real scale, real e_beam0, real sigma_t, real p0, real p1, real len) {
  return scale * e_beam0 * len * exp(-sigma_t * fmin(p0, p1)) * expm1_over_x(-sigma_t * fabs(p1 - p0));
}

/* Fraction of a slice's light gathered over the first fraction x in [0, 1] of its length when its
 * integrand falls as e^{-τ x} (τ = σ_t r d, of either sign: a view towards the surface gathers more
 * light further on): (1 - e^{-τx})/(1 - e^{-τ}) = x φ(-τx)/φ(-τ) for τ >= 0 (x at τ = 0, -> 1 as
 * τ -> ∞) and, the same quotient divided through by e^{|τ|}, e^{-|τ|(1-x)} x φ(-|τ|x)/φ(-|τ|) for τ < 0
 * (-> 0 for x < 1 as τ -> -∞), so neither form overflows. */
SEASIM_FN real froxel_partial(real x, real tau) {
  const real a = fabs(tau);
  const real q = x * expm1_over_x(-a * x) / expm1_over_x(-a);
  return tau >= R(0.0) ? q : exp(-a * (R(1.0) - x)) * q;
}

/* froxel_partial of the three channels' τ at one x. A kernel evaluates them as the lanes of one real3
 * (one vector exp for three scalar calls: froxel_lookup's three partials were half its cost); the host
 * calls froxel_partial per channel, so the double evaluation checks the lanes. */
#if defined(__OPENCL_VERSION__) || defined(__OPENCL_C_VERSION__)
SEASIM_FN real3 froxel_expm1_over_x3(real3 x) {
  const real3 series = SEASIM_EXPM1_OVER_X_SERIES(x);
  const real3 switch_at = MAKE_REAL3(0.5, 0.5, 0.5), one = MAKE_REAL3(1.0, 1.0, 1.0);
  const real3 xs = select(x, one, isless(fabs(x), switch_at));
  return select((exp(xs) - R(1.0)) / xs, series, isless(fabs(x), switch_at));
}
SEASIM_FN real3 froxel_partial3(real x, real3 tau) {
  const real3 a = fabs(tau);
  const real3 q = x * froxel_expm1_over_x3(-a * x) / froxel_expm1_over_x3(-a);
  return select(exp(-a * (R(1.0) - x)) * q, q, isgreaterequal(tau, MAKE_REAL3(0.0, 0.0, 0.0)));
}
#else
SEASIM_FN real3 froxel_partial3(real x, real3 tau) {
  return MAKE_REAL3(froxel_partial(x, tau.x), froxel_partial(x, tau.y), froxel_partial(x, tau.z));
}
#endif

/* ---- the sun shadow map: orthographic along the beam (-s_w), over the bounded objects ---- */

/* First hit of a sphere or box (planes skipped: unbounded, tested exactly instead) along o + t dir,
 * t in (t_min, ∞); UW_INFINITE when none. */
SEASIM_FN real froxel_bounded_hit(const SEASIM_GLOBAL UwObject* objects, int count, real3 o, real3 dir, real t_min) {
  real best = UW_INFINITE;
  for (int k = 0; k < count; ++k) {
    const SEASIM_GLOBAL UwObject* ob = &objects[k];
    const real3 a = MAKE_REAL3(ob->a[0], ob->a[1], ob->a[2]);
    real t = R(-1.0);
    if (ob->type == UW_SPHERE) {
      t = ray_sphere(o, dir, a, (real)ob->a[3], t_min, best);
    } else if (ob->type == UW_BOX) {
      int axis = 0;
      t = ray_box(o, dir, a, MAKE_REAL3(ob->b[0], ob->b[1], ob->b[2]), t_min, best, &axis);
    }
    if (t > R(0.0)) best = t;
  }
  return best;
}

/* Texel (i, j) of the map: the distance along -s_w from its origin on the map plane to the first
 * sphere/box below the water surface (hits above y = 0 are skipped: the beam starts at the surface,
 * as the exact shadow ray of raycast.cl stops there). */
SEASIM_FN real froxel_shadow_texel(const SEASIM_CONSTANT FroxelParams* fp, const SEASIM_GLOBAL UwObject* objects,
                                   int count, real3 s_w, int i, int j) {
  const real h = fp->shadow_half_extent;
  const real a = (R(2.0) * ((real)i + R(0.5)) / (real)fp->shadow_size - R(1.0)) * h;
  const real b = (R(2.0) * ((real)j + R(0.5)) / (real)fp->shadow_size - R(1.0)) * h;
  const real3 o = MAKE_REAL3(fp->shadow_origin[0], fp->shadow_origin[1], fp->shadow_origin[2]) +
                  a * MAKE_REAL3(fp->shadow_right[0], fp->shadow_right[1], fp->shadow_right[2]) +
                  b * MAKE_REAL3(fp->shadow_up[0], fp->shadow_up[1], fp->shadow_up[2]);
  const real t_surface = o.y > R(0.0) ? o.y / s_w.y : R(0.0);
  return froxel_bounded_hit(objects, count, o, -s_w, t_surface);
}

/* Visibility of point q (below the surface) from the map: 2×2 percentage-closer filter (bilinear
 * weights of the four texels around q's projection); texels outside the map hold no object: lit. */
SEASIM_FN real froxel_shadow_visibility(const SEASIM_CONSTANT FroxelParams* fp, const SEASIM_GLOBAL float* map,
                                        real3 s_w, real3 q) {
  const int n = fp->shadow_size;
  if (n <= 0) return R(1.0);
  const real3 rel = q - MAKE_REAL3(fp->shadow_origin[0], fp->shadow_origin[1], fp->shadow_origin[2]);
  const real a = dot(rel, MAKE_REAL3(fp->shadow_right[0], fp->shadow_right[1], fp->shadow_right[2]));
  const real b = dot(rel, MAKE_REAL3(fp->shadow_up[0], fp->shadow_up[1], fp->shadow_up[2]));
  const real depth = -dot(rel, s_w);
  const real h = fp->shadow_half_extent;
  const real gx = (a / h + R(1.0)) * R(0.5) * (real)n - R(0.5);
  const real gy = (b / h + R(1.0)) * R(0.5) * (real)n - R(0.5);
  if (!(gx > R(-1.0) && gx < (real)n && gy > R(-1.0) && gy < (real)n)) return R(1.0);
  const int x0 = (int)floor(gx), y0 = (int)floor(gy);
  const real ax = gx - (real)x0, ay = gy - (real)y0;
  real vis = R(0.0);
  for (int dy = 0; dy <= 1; ++dy) {
    for (int dx = 0; dx <= 1; ++dx) {
      const int x = x0 + dx, y = y0 + dy;
      real lit = R(1.0);
      if (x >= 0 && x < n && y >= 0 && y < n) lit = depth <= (real)map[y * n + x] + fp->shadow_bias ? R(1.0) : R(0.0);
      vis += (dx ? ax : R(1.0) - ax) * (dy ? ay : R(1.0) - ay) * lit;
    }
  }
  return vis;
}

/* Planes block the beam exactly: 0 when a plane object lies between q and the surface along s_w. */
SEASIM_FN real froxel_plane_visibility(const SEASIM_GLOBAL UwObject* objects, int count, real3 s_w, real3 q) {
  const real t_surface = fmax(-q.y, R(0.0)) / s_w.y;
  for (int k = 0; k < count; ++k) {
    const SEASIM_GLOBAL UwObject* ob = &objects[k];
    if (ob->type != UW_PLANE) continue;
    const real t = ray_plane(q, s_w, MAKE_REAL3(ob->a[0], ob->a[1], ob->a[2]), MAKE_REAL3(ob->b[0], ob->b[1], ob->b[2]),
                             R(0.0), t_surface);
    if (t > R(0.0)) return R(0.0);
  }
  return R(1.0);
}

/* ---- integration and read ---- */

/* One column front to back (002 eq. 5.2, integrated as at the top). light: V·C per froxel (the
 * band-independent part of L_i, layout of the volume, 1 float each); bands: the wavelength bands
 * (spectral injection) or the three RGB pseudo-bands (w = unit vectors). Writes the volume's 4 floats
 * per froxel of the column: R, G, B to the slice's end and column_dy, the column's d_y as the host
 * tabulated it (froxel_column_extent reads the same table: both decide alike which rays reach the
 * surface, froxel_reads_whole_columns). */
SEASIM_FN void froxel_integrate_column(const SEASIM_CONSTANT UwParams* p, const SEASIM_CONSTANT FroxelParams* fp,
                                       const SEASIM_GLOBAL UwBand* bands, int band_count,
                                       const SEASIM_GLOBAL float* light, SEASIM_GLOBAL float* volume, float column_dy,
                                       int i, int j) {
  const int nx = fp->nx, ny = fp->ny, nz = fp->nz;
  const real3 d = froxel_column_dir(p, fp, i, j);
  const real3 s_w = MAKE_REAL3(p->sun_dir_water[0], p->sun_dir_water[1], p->sun_dir_water[2]);
  const real mu_w = fp->mu_w;
  const real phase = hg_phase(dot(s_w, d), p->g);
  const real y_cam = fp->cam_depth;
  const real t_surface = froxel_surface_distance(y_cam, d.y);
  real acc_r = R(0.0), acc_g = R(0.0), acc_b = R(0.0);
  real t0 = R(0.0);
  for (int k = 0; k < nz; ++k) {
    const real t1 = froxel_slice_end(k, nz, fp->z_near, fp->z_far, fp->log_far_near);
    const real s1 = fmin(t1, t_surface); /* the slice's part below the surface is [t0, s1] */
    const int idx = (k * ny + j) * nx + i;
    const real vc = light[idx];
    if (vc > R(0.0) && s1 > t0) {
      const real scale = phase * vc;
      /* P at both ends; y clamped at 0 against rounding at the surface */
      const real p0 = t0 + fmax(y_cam - t0 * d.y, R(0.0)) / mu_w;
      const real p1 = s1 + fmax(y_cam - s1 * d.y, R(0.0)) / mu_w;
      for (int b = 0; b < band_count; ++b) {
        const SEASIM_GLOBAL UwBand* band = &bands[b];
        const real dl = froxel_beam_segment(scale * band->b, band->e_beam0, band->c, p0, p1, s1 - t0);
        acc_r += dl * band->w_r;
        acc_g += dl * band->w_g;
        acc_b += dl * band->w_b;
      }
    }
    volume[4 * idx + 0] = acc_r;
    volume[4 * idx + 1] = acc_g;
    volume[4 * idx + 2] = acc_b;
    volume[4 * idx + 3] = column_dy;
    t0 = t1;
  }
}

/* The continuous column coordinate of pixel x's centre in an image `width` pixels wide over n columns
 * (column i's centre sits at i), clamped at the border: froxel_lookup reads columns (int) g and the next
 * one (the last column at the border). */
SEASIM_FN real froxel_pixel_column(int x, int width, int n) {
  return clamp(((real)x + R(0.5)) / (real)width * (real)n - R(0.5), R(0.0), (real)(n - 1));
}

/* The slice froxel_lookup reads at distance S: it reads the volume at slice k and k − 1, which hold the
 * running integral over every froxel k' <= k; -1 when it reads nothing (S <= 0; a NaN S reads at z_far,
 * as fmin gives). */
SEASIM_FN int froxel_read_slice(const SEASIM_CONSTANT FroxelParams* fp, real S) {
  const real t = fmin(S, (real)fp->z_far);
  if (!(t > R(0.0))) return -1;
  return froxel_slice_index(t, fp->nz, fp->z_near, fp->z_far, fp->log_far_near);
}

/* froxel_read_slice with the slice's ends [*t0, *t1] (froxel_slice_and_ends). */
SEASIM_FN int froxel_read_slice_bounds(const SEASIM_CONSTANT FroxelParams* fp, real S, real* t0, real* t1) {
  const real t = fmin(S, (real)fp->z_far);
  if (!(t > R(0.0))) return -1;
  return froxel_slice_and_ends(t, fp->nz, fp->z_near, fp->z_far, fp->log_far_near, t0, t1);
}

/* The vertical direction of pixel (x, y)'s ray, bilinear between its four columns' d_y (the weights of
 * froxel_lookup): d00, d10, d01, d11 at (i0, j0), (i1, j0), (i0, j1), (i1, j1). */
SEASIM_FN real froxel_pixel_dy(real d00, real d10, real d01, real d11, real ax, real ay) {
  return (R(1.0) - ay) * ((R(1.0) - ax) * d00 + ax * d10) + ay * ((R(1.0) - ax) * d01 + ax * d11);
}

/* Whether a pixel whose ray has vertical direction d_y and ends at S reads its columns whole: its ray
 * reaches the surface (S within `tolerance` of the distance where it leaves the water) or z_far. Its
 * four columns leave the water at other distances (y_cam/d_y differs most near the horizon), and the
 * light gathers fastest just below the surface, so each column is read to its own end, not to the
 * pixel's S: read at S, a column rising less steeply would stop short of its brightest metres. */
SEASIM_FN int froxel_reads_whole_columns(const SEASIM_CONSTANT FroxelParams* fp, real d_y, real S, real tolerance) {
  return S >= (real)fp->z_far || S >= froxel_surface_distance(fp->cam_depth, d_y) * (R(1.0) - tolerance);
}

/* In-scattered sensor RGB from the camera to distance S along pixel (x, y) of a width × height image
 * (see the top: bilinear over columns, in-slice fraction by σ̄_t per channel, S clamped to z_far). */
SEASIM_FN real3 froxel_lookup(const SEASIM_CONSTANT FroxelParams* fp, const SEASIM_GLOBAL float* volume, int x, int y,
                              int width, int height, real S) {
  const int nx = fp->nx, ny = fp->ny;
  /* Continuous column coordinates of the pixel centre; column i's centre sits at i. */
  const real gx = froxel_pixel_column(x, width, nx);
  const real gy = froxel_pixel_column(y, height, ny);
  const int i0 = (int)gx, j0 = (int)gy;
  const int i1 = i0 + 1 < nx ? i0 + 1 : nx - 1, j1 = j0 + 1 < ny ? j0 + 1 : ny - 1;
  const real ax = gx - (real)i0, ay = gy - (real)j0;
  /* Every slice holds its column's d_y; slice 0's are read. A ray to the surface reads whole columns. */
  const real d_y = froxel_pixel_dy(volume[4 * (j0 * nx + i0) + 3], volume[4 * (j0 * nx + i1) + 3],
                                   volume[4 * (j1 * nx + i0) + 3], volume[4 * (j1 * nx + i1) + 3], ax, ay);
  if (S > R(0.0) && froxel_reads_whole_columns(fp, d_y, S, R(1e-3))) S = (real)fp->z_far;
  real t0, t1;
  const int k = froxel_read_slice_bounds(fp, S, &t0, &t1);
  if (k < 0) return MAKE_REAL3(0, 0, 0);
  const real t = fmin(S, (real)fp->z_far);
  /* The slice's part below the surface along the pixel's ray, how far into it S reaches, and the
   * fraction of its light gathered there per channel. */
  const real len = fmin(t1, froxel_surface_distance(fp->cam_depth, d_y)) - t0;
  const real xf = len > R(0.0) ? clamp((t - t0) / len, R(0.0), R(1.0)) : R(1.0);
  const real tau = (R(1.0) - d_y / fp->mu_w) * fmax(len, R(0.0));
  const real3 f = froxel_partial3(xf, MAKE_REAL3(fp->sigma_t_rgb[0], fp->sigma_t_rgb[1], fp->sigma_t_rgb[2]) * tau);
  const real f_r = f.x, f_g = f.y, f_b = f.z;
  real r = R(0.0), g = R(0.0), b = R(0.0);
  for (int c = 0; c < 4; ++c) {
    const int i = (c & 1) ? i1 : i0, j = (c & 2) ? j1 : j0;
    const real w = ((c & 1) ? ax : R(1.0) - ax) * ((c & 2) ? ay : R(1.0) - ay);
    const int end = 4 * ((k * ny + j) * nx + i);
    real r0 = R(0.0), g0 = R(0.0), b0 = R(0.0);
    if (k > 0) {
      const int start = 4 * (((k - 1) * ny + j) * nx + i);
      r0 = volume[start + 0];
      g0 = volume[start + 1];
      b0 = volume[start + 2];
    }
    r += w * (r0 + f_r * ((real)volume[end + 0] - r0));
    g += w * (g0 + f_g * ((real)volume[end + 1] - g0));
    b += w * (b0 + f_b * ((real)volume[end + 2] - b0));
  }
  return MAKE_REAL3(r, g, b);
}
