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
 * Integration (002 eq. 5.2, the rectangle rule, done stably): L_i is held at its value at the
 * slice's midpoint; the slice's transmittance-weighted length is integrated exactly,
 *   ∫_{z_k}^{z_k + d} e^{-σ_t z} dz = e^{-σ_t z_k} d φ(-σ_t d),   φ(x) = expm1(x)/x = expm1_over_x,
 * so a slice of any optical depth (1 m of 9C water, σ_t d = 11) neither loses its light (the plain
 * rule's d e^{-σ_t z} at one point) nor overshoots. The medium is homogeneous, so the transmittance to
 * the slice's start is e^{-σ_t z_k} directly (froxel_slice_integral; froxel_beam_slice fuses it with
 * E_beam's exponential); froxel_integrate_step is the same step in the running form
 * ΔL = T L_i d φ(-σ_t d), T *= e^{-σ_t d}.
 * Slices are the same distances along every column, so σ_s e_beam0 e^{-σ_t z_k} d φ(-σ_t d) depends on
 * (band, slice) only: froxel_fill_slice_factors tabulates it once per set-up, and the column loop
 * (froxel_integrate_column) is left with one exp per band and froxel, E_beam's e^{-σ_t y/μ_w}.
 *
 * Read (froxel_lookup): the volume holds the integral to the END of each slice; a pixel at distance S
 * in slice k reads L(z_k) + f (L(z_{k+1}) - L(z_k)), f the fraction of that slice's light gathered by
 * S when L_i is constant in it, f = x φ(-τ x)/φ(-τ) with x = (S - z_k)/d and τ = σ̄_t d per channel
 * (σ̄_t = FroxelParams.sigma_t_rgb), which is (1 - e^{-τx})/(1 - e^{-τ}) written without 0/0 at τ = 0.
 * Columns: bilinear between the four columns around the pixel (clamped at the border). S >= z_far
 * (deep water, UW_INFINITE) reads the value at z_far: light beyond z_far is lost, part of the froxel
 * method's error.
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

/* The slice holding distance t: slice k holds (start_k, end_k]; t <= 0 gives 0, t >= z_far gives nz-1. */
SEASIM_FN int froxel_slice_index(real t, int nz, real z_near, real z_far, real log_far_near) {
  if (nz <= 1 || t <= froxel_slice_end(0, nz, z_near, z_far, log_far_near)) return 0;
  if (t >= z_far) return nz - 1;
  int k = (int)ceil((real)nz * log(t / z_near) / log_far_near) - 1;
  k = k < 0 ? 0 : (k > nz - 1 ? nz - 1 : k);
  /* log/exp rounding can put t one slice off near a boundary: settle it on the same boundaries. */
  if (k < nz - 1 && t > froxel_slice_end(k, nz, z_near, z_far, log_far_near)) k += 1;
  else if (k > 0 && t <= froxel_slice_end(k - 1, nz, z_near, z_far, log_far_near)) k -= 1;
  return k;
}

/* The ray of froxel column (i, j). */
SEASIM_FN real3 froxel_column_dir(const SEASIM_CONSTANT UwParams* p, const SEASIM_CONSTANT FroxelParams* fp, int i,
                                  int j) {
  return uw_screen_dir(p, ((real)i + R(0.5)) / (real)fp->nx, ((real)j + R(0.5)) / (real)fp->ny);
}

/* The centre of froxel (i, j, k): the column ray at the slice's midpoint distance. */
SEASIM_FN real3 froxel_center(const SEASIM_CONSTANT UwParams* p, const SEASIM_CONSTANT FroxelParams* fp, int i, int j,
                              int k) {
  const real t = R(0.5) * (froxel_slice_start(k, fp->nz, fp->z_near, fp->z_far, fp->log_far_near) +
                           froxel_slice_end(k, fp->nz, fp->z_near, fp->z_far, fp->log_far_near));
  const real3 o = MAKE_REAL3(p->cam_pos[0], p->cam_pos[1], p->cam_pos[2]);
  return o + t * froxel_column_dir(p, fp, i, j);
}

/* 002 eq. 5.2 for one slice [t0, t0 + d] of a homogeneous medium with constant in-scatter l_i:
 * ∫ e^{-σ_t z} l_i dz = e^{-σ_t t0} l_i d φ(-σ_t d). Finite for every σ_t, t0, d >= 0 (each factor <= 1
 * except l_i d). */
SEASIM_FN real froxel_slice_integral(real l_i, real sigma_t, real t0, real d) {
  return exp(-sigma_t * t0) * l_i * d * expm1_over_x(-sigma_t * d);
}

/* The same step in running form: returns ΔL = T l_i d φ(-σ_t d) and updates *T *= e^{-σ_t d}. */
SEASIM_FN real froxel_integrate_step(real l_i, real sigma_t, real d, real* T) {
  const real tau = sigma_t * d;
  const real dl = *T * l_i * d * expm1_over_x(-tau);
  *T *= exp(-tau);
  return dl;
}

/* One band's share of 002 eq. 5.2 over a slice [t0, t0 + d] at the froxel-centre depth y:
 * σ_s p V C e_beam0 e^{-σ_t y/μ_w} · e^{-σ_t t0} d φ(-σ_t d) (froxel_slice_integral with
 * L_i = σ_s p V C E_beam(y)), the two decaying exponentials in one exp (both exponents <= 0: no
 * overflow, underflow to 0 at depth). scale = σ_s p V C. */
SEASIM_FN real froxel_beam_slice(real scale, real e_beam0, real sigma_t, real mu_w, real y, real t0, real d) {
  return scale * e_beam0 * exp(-sigma_t * (t0 + y / mu_w)) * d * expm1_over_x(-sigma_t * d);
}

/* The (band, slice) part of froxel_beam_slice: σ_s e_beam0 e^{-σ_t t0} d φ(-σ_t d) for the slice
 * [t0, t0 + d] (froxel_integrate_column multiplies by p V C and E_beam(y)). Both exponents are <= 0;
 * a factor underflows to 0 only where its product with E_beam (<= 1) would too. */
SEASIM_FN real froxel_slice_factor(real b, real e_beam0, real sigma_t, real t0, real d) {
  return b * e_beam0 * exp(-sigma_t * t0) * d * expm1_over_x(-sigma_t * d);
}

/* factors[k * band_count + b] = froxel_slice_factor of slice k < fp->nz and band b: the table
 * froxel_integrate_column reads (nz × band_count values, computed where the bands are set up). */
SEASIM_FN void froxel_fill_slice_factors(const SEASIM_CONSTANT FroxelParams* fp, const SEASIM_GLOBAL UwBand* bands,
                                         int band_count, SEASIM_GLOBAL real* factors) {
  real t0 = R(0.0);
  for (int k = 0; k < fp->nz; ++k) {
    const real t1 = froxel_slice_end(k, fp->nz, fp->z_near, fp->z_far, fp->log_far_near);
    for (int b = 0; b < band_count; ++b)
      factors[k * band_count + b] = froxel_slice_factor(bands[b].b, bands[b].e_beam0, bands[b].c, t0, t1 - t0);
    t0 = t1;
  }
}

/* Fraction of a slice's light (constant L_i, optical depth tau >= 0) gathered over the first fraction
 * x in [0, 1] of its length: (1 - e^{-τx})/(1 - e^{-τ}) = x φ(-τx)/φ(-τ); x at τ = 0, → 1 as τ → ∞. */
SEASIM_FN real froxel_partial(real x, real tau) {
  return x * expm1_over_x(-tau * x) / expm1_over_x(-tau);
}

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

/* One column front to back (002 eq. 5.2). light: V·C per froxel (the band-independent part of L_i,
 * layout of the volume, 1 float each); bands: the wavelength bands (spectral injection) or the three
 * RGB pseudo-bands (w = unit vectors); slice_factors: froxel_fill_slice_factors of the same bands.
 * Writes the volume's 4 floats per froxel of the column. */
SEASIM_FN void froxel_integrate_column(const SEASIM_CONSTANT UwParams* p, const SEASIM_CONSTANT FroxelParams* fp,
                                       const SEASIM_GLOBAL UwBand* bands, int band_count,
                                       const SEASIM_GLOBAL real* slice_factors, const SEASIM_GLOBAL float* light,
                                       SEASIM_GLOBAL float* volume, int i, int j) {
  const int nx = fp->nx, ny = fp->ny, nz = fp->nz;
  const real3 d = froxel_column_dir(p, fp, i, j);
  const real3 s_w = MAKE_REAL3(p->sun_dir_water[0], p->sun_dir_water[1], p->sun_dir_water[2]);
  const real mu_w = fmax(s_w.y, R(1e-4));
  const real phase = hg_phase(dot(s_w, d), p->g);
  const real o_d = -p->cam_pos[1];
  const real sigma_g = fp->sigma_t_rgb[1];
  real acc_r = R(0.0), acc_g = R(0.0), acc_b = R(0.0);
  real t0 = R(0.0);
  for (int k = 0; k < nz; ++k) {
    const real t1 = froxel_slice_end(k, nz, fp->z_near, fp->z_far, fp->log_far_near);
    const real y = o_d - R(0.5) * (t0 + t1) * d.y; /* depth of the froxel centre */
    const int idx = (k * ny + j) * nx + i;
    const real vc = light[idx];
    if (vc > R(0.0) && y >= R(0.0)) {
      const real scale = phase * vc;
      const real y_beam = y / mu_w; /* the beam's path from the surface to the froxel centre */
      const SEASIM_GLOBAL real* factor = slice_factors + k * band_count;
      for (int b = 0; b < band_count; ++b) {
        const SEASIM_GLOBAL UwBand* band = &bands[b];
        /* froxel_beam_slice(scale σ_s, e_beam0, σ_t, μ_w, y, t0, len) with its (band, slice) part tabulated */
        const real dl = scale * factor[b] * exp(-band->c * y_beam);
        acc_r += dl * band->w_r;
        acc_g += dl * band->w_g;
        acc_b += dl * band->w_b;
      }
    }
    volume[4 * idx + 0] = acc_r;
    volume[4 * idx + 1] = acc_g;
    volume[4 * idx + 2] = acc_b;
    volume[4 * idx + 3] = exp(-sigma_g * t1);
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

/* In-scattered sensor RGB from the camera to distance S along pixel (x, y) of a width × height image
 * (see the top: bilinear over columns, in-slice fraction by σ̄_t per channel, S clamped to z_far). */
SEASIM_FN real3 froxel_lookup(const SEASIM_CONSTANT FroxelParams* fp, const SEASIM_GLOBAL float* volume, int x, int y,
                              int width, int height, real S) {
  const int nx = fp->nx, ny = fp->ny, nz = fp->nz;
  const int k = froxel_read_slice(fp, S);
  if (k < 0) return MAKE_REAL3(0, 0, 0);
  const real t = fmin(S, (real)fp->z_far);
  const real t0 = froxel_slice_start(k, nz, fp->z_near, fp->z_far, fp->log_far_near);
  const real len = froxel_slice_end(k, nz, fp->z_near, fp->z_far, fp->log_far_near) - t0;
  const real xf = len > R(0.0) ? clamp((t - t0) / len, R(0.0), R(1.0)) : R(1.0);
  const real f_r = froxel_partial(xf, fp->sigma_t_rgb[0] * len);
  const real f_g = froxel_partial(xf, fp->sigma_t_rgb[1] * len);
  const real f_b = froxel_partial(xf, fp->sigma_t_rgb[2] * len);
  /* Continuous column coordinates of the pixel centre; column i's centre sits at i. */
  const real gx = froxel_pixel_column(x, width, nx);
  const real gy = froxel_pixel_column(y, height, ny);
  const int i0 = (int)gx, j0 = (int)gy;
  const int i1 = i0 + 1 < nx ? i0 + 1 : nx - 1, j1 = j0 + 1 < ny ? j0 + 1 : ny - 1;
  const real ax = gx - (real)i0, ay = gy - (real)j0;
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
