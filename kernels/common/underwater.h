/* underwater.h — the underwater model of paper 002 per wavelength band, shared by kd_multiple.cl,
 * raycast.cl, froxel.cl and the host (kmath_f / kmath_d, unit-tested in float and double).
 * Needs optics.h, shafts.h (ray_sphere/ray_box/ray_plane) and underwater_params.h before it.
 *
 * A view ray leaves the camera at o (depth o_d = -o.y >= 0) along the unit direction d; a point on it
 * at distance z has depth y(z) = o_d - z d_y. The thesis writes the same with ω = -d pointing to the
 * camera (002 eq. 4.5: y = o_y - z ω_y with its y measured downwards), so its K_d ω_y is our K_d d_y.
 *
 * Multiple scattering (002 eq. 4.4–4.7): with the ambient irradiance E(y) = E_D0 e^{-K_d y} (eq. 4.1)
 * scattered isotropically,
 *   L_MS = σ_s/(4π) E_D0 ∫_0^S e^{-σ_t z} e^{-K_d (o_d - z d_y)} dz
 *        = σ_s/(4π) E_D0 e^{-K_d o_d} (e^{(K_d d_y - σ_t) S} - 1) / (K_d d_y - σ_t)      (eq. 4.7)
 * evaluated by kd_exp_integral without its removable singularity at K_d d_y = σ_t and without
 * overflow/underflow pairs (camera at 1000 m looking up: e^{-K_d o_d} underflows while e^{x S} would
 * overflow; their product is <= 1).
 *
 * Not counting the sun twice. The froxel pass (002 §5) integrates the single scattering of the direct
 * sun beam, E_beam(y) = e_beam0 e^{-σ_t y / μ_w}, whose horizontal irradiance e_sun0 e^{-σ_t y/μ_w} is
 * part of E(y). When that pass runs, L_MS uses the diffuse remainder
 *   E_dif(y) = (e_sky0 + e_sun0) e^{-K_d y} - e_sun0 e^{-(σ_t/μ_w) y},
 * a sum of two exponentials in y, so eq. 4.7 applies to each term with its own attenuation
 * (K_d, then σ_t/μ_w). Without single scattering the whole E(y) is used, as in the thesis.
 *
 * Surfaces (eq. 2.7, 2.10): L = T(S) L_s + L_MS with T(S) = e^{-σ_t S}. A Lambertian point of albedo ρ
 * and normal n at depth y receives the diffuse E_dif(y) on a plane tilted from the horizontal
 * ((1 + n_y)/2 of it, a uniform upper hemisphere) plus the direct beam E_beam(y) max(n·s_w, 0) times
 * its visibility (sun shadow ray, caustic modulation): L_s = ρ/π (E_dif (1 + n_y)/2 + E_beam n·s_w V).
 * From below, the surface shows the sky through Snell's window, n² (1 - F) L_sky (radiance over n² is
 * conserved), plus F times the multiple scattering seen along the reflected ray (total internal
 * reflection outside the window). The sun is a delta light and its disk is not drawn.
 */

/* The view direction through the screen point (sx, sy) in [0,1]² (x to the right, y down), the pinhole
 * camera of sea_single.cl: pixel (x, y) of a W×H image is ((x + ½)/W, (y + ½)/H). */
SEASIM_FN real3 uw_screen_dir(const SEASIM_CONSTANT UwParams* p, real sx, real sy) {
  const real u = (R(2.0) * sx - R(1.0)) * p->tan_half_fov_y * p->aspect;
  const real v = (R(1.0) - R(2.0) * sy) * p->tan_half_fov_y;
  const real3 right = MAKE_REAL3(p->cam_right[0], p->cam_right[1], p->cam_right[2]);
  const real3 up = MAKE_REAL3(p->cam_up[0], p->cam_up[1], p->cam_up[2]);
  const real3 fwd = MAKE_REAL3(p->cam_forward[0], p->cam_forward[1], p->cam_forward[2]);
  return normalize(fwd + u * right + v * up);
}

/* Distances at or beyond this are "no hit" (the ray runs into deep water). */
#define UW_INFINITE R(1e30)

/* e^{-k o_d} ∫_0^S e^{(k d_y - c) z} dz for k, c >= 0, o_d >= 0, S >= 0 or S >= UW_INFINITE.
 * The integrand is e^{-k y(z) - c z}, never above 1 while y >= 0. With t = (k d_y - c) S and
 * φ(t) = (e^t - 1)/t (expm1_over_x), the integral is S e^{-k o_d} φ(t), and since e^t φ(-t) = φ(t),
 *   = S e^{max(t, 0) - k o_d} φ(-|t|):
 * one exp and one expm1, no branch a vectorising compiler would have to run both sides of, no
 * overflow (max(t, 0) - k o_d = -k y(S) - c S <= 0 when t > 0), φ(-|t|) in (0, 1]. S = ∞ needs t < 0,
 * where S φ(t) -> 1/(c - k d_y); S = 1e30 gives exactly that in float and double (|t| stays finite). */
SEASIM_FN real kd_exp_integral(real k, real c, real d_y, real o_d, real S) {
  const real x = k * d_y - c;
  /* S = ∞ with x >= 0 diverges; unreachable for a ray in water (x >= 0 needs d_y > 0, and such a ray
   * meets the surface): 0, selected without a branch, t zeroed so the discarded side stays finite. */
  const int diverges = S >= UW_INFINITE && x >= R(0.0);
  const real t = diverges ? R(0.0) : x * S;
  const real v = S * exp(fmax(t, R(0.0)) - k * o_d) * expm1_over_x(-fabs(t));
  return diverges ? R(0.0) : v;
}

/* 002 eq. 4.7 for one band: σ_s/(4π) [e_total0 I(K_d) - e_direct0 I(σ_t/μ_w)], I = kd_exp_integral.
 * e_total0 = e_sky0 + e_sun0; e_direct0 = e_sun0 when the froxel pass carries the direct beam, else 0.
 * Clamped at 0 (E_dif(y) can dip below 0 where K_d > σ_t/μ_w, which the data allow for clear water).
 * No branch: both integrals are always evaluated (finite for every input, so b = 0 or e_direct0 = 0
 * multiply them to exactly 0), which lets a compiler vectorise the band or pixel loop around it. */
SEASIM_FN real kd_multiple_scattering(real b, real c, real kd, real e_total0, real e_direct0, real mu_w, real d_y,
                                      real o_d, real S) {
  const real total = kd_exp_integral(kd, c, d_y, o_d, S);
  const real direct = kd_exp_integral(c / fmax(mu_w, R(1e-4)), c, d_y, o_d, S);
  const real v = e_total0 * total - (e_direct0 > R(0.0) ? e_direct0 * direct : R(0.0));
  return b > R(0.0) ? fmax(b * v / (R(4.0) * SEASIM_PI), R(0.0)) : R(0.0);
}

/* Diffuse downwelling irradiance E_dif(y) on a horizontal plane at depth y (see above). */
SEASIM_FN real uw_diffuse_irradiance(real e_sky0, real e_sun0, real e_direct0, real kd, real c, real mu_w, real y) {
  const real v = (e_sky0 + e_sun0) * exp(-kd * y) - e_direct0 * exp(-(c / fmax(mu_w, R(1e-4))) * y);
  return fmax(v, R(0.0));
}

/* The direct sun beam's irradiance normal to itself at depth y: e_beam0 e^{-σ_t y/μ_w}. */
SEASIM_FN real uw_beam_irradiance(real e_beam0, real c, real mu_w, real y) {
  return e_beam0 * exp(-(c / fmax(mu_w, R(1e-4))) * y);
}

/* Outgoing radiance of a Lambertian point (albedo ρ, unit normal n) at depth y (see above). vis is the
 * direct beam's visibility times any caustic modulation. e_direct0 as for kd_multiple_scattering: with
 * 0 the direct beam is left in the diffuse term and not added separately. */
SEASIM_FN real uw_lambert_radiance(real albedo, real3 n, real3 s_w, real vis, real e_sky0, real e_sun0,
                                   real e_beam0, real e_direct0, real kd, real c, real mu_w, real y) {
  const real diffuse = uw_diffuse_irradiance(e_sky0, e_sun0, e_direct0, kd, c, mu_w, y) * R(0.5) * (R(1.0) + n.y);
  /* Always evaluated, then selected (no branch; its exp is the diffuse term's second one). */
  const real beam = uw_beam_irradiance(e_beam0, c, mu_w, y) * fmax(dot(n, s_w), R(0.0)) * vis;
  const real direct = e_direct0 > R(0.0) ? beam : R(0.0);
  return albedo / SEASIM_PI * (diffuse + direct);
}

/* First hit along o + t d (t in (t_min, ∞)) among the objects, the flat bottom y = -bottom_depth
 * (bottom_depth > 0) and the water surface y = 0 (approached from below). Writes the unit normal facing
 * the ray's side of the surface it hit, and the material: object index, UW_MAT_BOTTOM, UW_MAT_SURFACE or
 * UW_MAT_NONE (returns UW_INFINITE then). */
SEASIM_FN real uw_scene_hit(const SEASIM_GLOBAL UwObject* objects, int count, real bottom_depth, real3 o, real3 d,
                            real t_min, real3* normal, int* material) {
  real best = UW_INFINITE;
  int mat = UW_MAT_NONE;
  real3 nrm = MAKE_REAL3(0, 1, 0);
  if (d.y > R(0.0)) { /* the surface y = 0 from below */
    const real t = -o.y / d.y;
    if (t > t_min && t < best) {
      best = t;
      mat = UW_MAT_SURFACE;
      nrm = MAKE_REAL3(0, -1, 0);
    }
  }
  if (bottom_depth > R(0.0) && d.y < R(0.0)) {
    const real t = (-bottom_depth - o.y) / d.y;
    if (t > t_min && t < best) {
      best = t;
      mat = UW_MAT_BOTTOM;
      nrm = MAKE_REAL3(0, 1, 0);
    }
  }
  for (int k = 0; k < count; ++k) {
    const SEASIM_GLOBAL UwObject* ob = &objects[k];
    const real3 a = MAKE_REAL3(ob->a[0], ob->a[1], ob->a[2]);
    const real3 b = MAKE_REAL3(ob->b[0], ob->b[1], ob->b[2]);
    real t = R(-1.0);
    real3 nk = nrm;
    if (ob->type == UW_SPHERE) {
      t = ray_sphere(o, d, a, (real)ob->a[3], t_min, best);
      if (t > R(0.0)) nk = normalize(o + t * d - a);
    } else if (ob->type == UW_BOX) {
      int axis = 0;
      t = ray_box(o, d, a, b, t_min, best, &axis);
      if (t > R(0.0)) nk = box_normal(o + t * d, a, b, axis);
    } else {
      t = ray_plane(o, d, a, b, t_min, best);
      if (t > R(0.0)) nk = dot(b, d) < R(0.0) ? b : -b;
    }
    if (t > R(0.0)) {
      best = t;
      mat = k;
      nrm = nk;
    }
  }
  if (dot(nrm, d) > R(0.0) && mat >= 0) nrm = -nrm; /* inside a sphere/box: shade the side we see */
  *normal = nrm;
  *material = mat;
  return best;
}

/* Every object a candidate for uw_objects_block. */
#define UW_ALL_OBJECTS 0xffffffffu

/* Whether any object lies on the ray o + t d (d unit) for t in (t_min, t_max): a shadow ray's test, which
 * needs neither the nearest hit nor its normal, so it stops at the first object in the way. Only the
 * candidates are tested: bit k of `candidates` for object k < 32 (uw_objects_near_triangle), every
 * object from 32 on. The surface and the bottom are not tested (the caller's t_max stops before them). */
SEASIM_FN int uw_objects_block(const SEASIM_GLOBAL UwObject* objects, int count, unsigned int candidates, real3 o,
                               real3 d, real t_min, real t_max) {
  for (int k = 0; k < count; ++k) {
    if (k < 32 && !((candidates >> k) & 1u)) continue;
    const SEASIM_GLOBAL UwObject* ob = &objects[k];
    const real3 a = MAKE_REAL3(ob->a[0], ob->a[1], ob->a[2]);
    const real3 b = MAKE_REAL3(ob->b[0], ob->b[1], ob->b[2]);
    int axis;
    const real t = ob->type == UW_SPHERE ? ray_sphere(o, d, a, (real)ob->a[3], t_min, t_max)
                   : ob->type == UW_BOX  ? ray_box(o, d, a, b, t_min, t_max, &axis)
                                         : ray_plane(o, d, a, b, t_min, t_max);
    if (t > R(0.0)) return 1;
  }
  return 0;
}

/* The squared distance from p to the triangle (a, b, c): its closest point by the Voronoi regions of
 * the vertices, edges and face (Ericson, Real-Time Collision Detection, 2005, §5.1.5). A degenerate
 * triangle (a line: a view ray through the lamp) gives the distance to its segment from the vertex and
 * edge regions, or NaN (0/0) in the face's; the caller counts NaN as near. */
SEASIM_FN real uw_point_triangle_distance2(real3 p, real3 a, real3 b, real3 c) {
  const real3 ab = b - a, ac = c - a, ap = p - a;
  const real d1 = dot(ab, ap), d2 = dot(ac, ap);
  real3 q;
  if (d1 <= R(0.0) && d2 <= R(0.0)) {
    q = a;
  } else {
    const real3 bp = p - b;
    const real d3 = dot(ab, bp), d4 = dot(ac, bp);
    const real3 cp = p - c;
    const real d5 = dot(ab, cp), d6 = dot(ac, cp);
    const real vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
    if (d3 >= R(0.0) && d4 <= d3) q = b;
    else if (d6 >= R(0.0) && d5 <= d6) q = c;
    else if (vc <= R(0.0) && d1 >= R(0.0) && d3 <= R(0.0)) q = a + (d1 / (d1 - d3)) * ab;
    else if (vb <= R(0.0) && d2 >= R(0.0) && d6 <= R(0.0)) q = a + (d2 / (d2 - d6)) * ac;
    else if (va <= R(0.0) && d4 - d3 >= R(0.0) && d5 - d6 >= R(0.0))
      q = b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
    else {
      const real inv = R(1.0) / (va + vb + vc);
      q = a + (vb * inv) * ab + (vc * inv) * ac;
    }
  }
  const real3 e = p - q;
  return dot(e, e);
}

/* The candidates (uw_objects_block) among objects 0..31 for the shadow rays from the points of the segment
 * p1 p2 to p0 (a lamp): those whose bounding sphere comes within its radius of the triangle (p0, p1, p2),
 * which holds every such ray. Conservative: 1 cm of margin for rounding, planes always, and an object
 * whose distance comes out NaN (a degenerate triangle) kept. */
SEASIM_FN unsigned int uw_objects_near_triangle(const SEASIM_GLOBAL UwObject* objects, int count, real3 p0, real3 p1,
                                                real3 p2) {
  unsigned int candidates = 0u;
  for (int k = 0; k < count && k < 32; ++k) {
    const SEASIM_GLOBAL UwObject* ob = &objects[k];
    const real3 a = MAKE_REAL3(ob->a[0], ob->a[1], ob->a[2]);
    const real3 b = MAKE_REAL3(ob->b[0], ob->b[1], ob->b[2]);
    if (ob->type != UW_SPHERE && ob->type != UW_BOX) {
      candidates |= 1u << k;
      continue;
    }
    const real3 centre = ob->type == UW_SPHERE ? a : R(0.5) * (a + b);
    const real radius = (ob->type == UW_SPHERE ? (real)ob->a[3] : R(0.5) * length(b - a)) + R(0.01);
    if (!(uw_point_triangle_distance2(centre, p0, p1, p2) > radius * radius)) candidates |= 1u << k;
  }
  return candidates;
}

/* The direct sun's visibility at a hit point with unit normal n: a shadow ray towards the sun (s_w) up
 * to the surface, offset along the normal against self-hits; 0 if an object is in the way, else 1. */
SEASIM_FN real uw_sun_visibility(const SEASIM_GLOBAL UwObject* objects, int count, real3 hit, real3 n, real3 s_w) {
  const real3 o = hit + R(1e-3) * n;
  const real t_surface = s_w.y > R(0.0) && -o.y / s_w.y > R(0.0) ? -o.y / s_w.y : UW_INFINITE; /* it leaves there */
  return uw_objects_block(objects, count, UW_ALL_OBJECTS, o, s_w, R(0.0), t_surface) ? R(0.0) : R(1.0);
}

/* Radiance the surface sends down along -d to a point below it, d the upward view direction (d.y > 0):
 * n² (1 - F) L_sky through Snell's window plus F times l_reflected (the caller's radiance along the
 * reflected ray; F = 1 under total internal reflection). */
SEASIM_FN real uw_window_radiance(real d_y, real ior, real sky_radiance, real l_reflected) {
  const real f = fresnel_reflectance(d_y, ior, R(1.0));
  return ior * ior * (R(1.0) - f) * sky_radiance + f * l_reflected;
}

/* One band's radiance along a view ray, split by what the ray hit, so that a caller can test the
 * material once per pixel and run a band loop with no material test in it (kd_multiple.cl, the
 * vectorised C++ baseline): L = L_MS for UW_MAT_NONE, T(S) L_s + L_MS otherwise (002 eq. 2.7 with 4.7).
 * single_scattering: 1 when the froxel pass adds the direct beam's single scattering (then L_MS and
 * L_s split off the direct sun as described at the top); multiple: 0 leaves L_MS out (scenes that
 * look at single scattering alone). */

/* L_MS along the view ray (o_d, d_y) to distance S (UW_INFINITE: deep water). */
SEASIM_FN real uw_band_multiple(const SEASIM_GLOBAL UwBand* band, real S, real d_y, real o_d, real mu_w,
                                int single_scattering, int multiple) {
  if (!multiple) return R(0.0);
  const real e_direct0 = single_scattering ? (real)band->e_sun0 : R(0.0);
  return kd_multiple_scattering(band->b, band->c, band->kd, band->e_sky0 + band->e_sun0, e_direct0, mu_w, d_y, o_d,
                                S);
}

/* L_s of the water surface seen from below (d_y > 0): the sky through Snell's window plus the
 * reflected ray, which starts at depth 0 going down (d_y -> -d_y) to the bottom or deep water.
 * sky_l: the sky's radiance in air along the refracted view (common/sky_view.h; band->sky_radiance
 * for the uniform sky, which uw_band_surface passes). */
SEASIM_FN real uw_band_surface_sky(const SEASIM_GLOBAL UwBand* band, real sky_l, real d_y, real mu_w, real ior,
                                   real bottom_depth, int single_scattering, int multiple) {
  const real s_r = bottom_depth > R(0.0) ? bottom_depth / fmax(d_y, R(1e-6)) : UW_INFINITE;
  const real l_r = uw_band_multiple(band, s_r, -d_y, R(0.0), mu_w, single_scattering, multiple);
  return uw_window_radiance(d_y, ior, sky_l, l_r);
}

SEASIM_FN real uw_band_surface(const SEASIM_GLOBAL UwBand* band, real d_y, real mu_w, real ior, real bottom_depth,
                               int single_scattering, int multiple) {
  return uw_band_surface_sky(band, band->sky_radiance, d_y, mu_w, ior, bottom_depth, single_scattering, multiple);
}

/* L_s of a Lambertian hit (an object or the bottom) at distance S, normal n, albedo, visibility vis. */
SEASIM_FN real uw_band_lambert(const SEASIM_GLOBAL UwBand* band, real S, real3 n, real d_y, real o_d, real3 s_w,
                               real albedo, real vis, int single_scattering) {
  const real y = fmax(o_d - S * d_y, R(0.0));
  const real e_direct0 = single_scattering ? (real)band->e_sun0 : R(0.0);
  return uw_lambert_radiance(albedo, n, s_w, vis, band->e_sky0, band->e_sun0, band->e_beam0, e_direct0, band->kd,
                             band->c, s_w.y, y);
}

/* The three together, for callers that test the material per band (references, tests). mat/S/n from
 * uw_scene_hit; albedo of the hit (object or bottom); vis as for uw_lambert_radiance. */
SEASIM_FN real uw_band_radiance(const SEASIM_GLOBAL UwBand* band, int mat, real S, real3 n, real3 d, real o_d,
                                real3 s_w, real albedo, real vis, real ior, real bottom_depth, int single_scattering,
                                int multiple) {
  const real l_ms = uw_band_multiple(band, S, d.y, o_d, s_w.y, single_scattering, multiple);
  if (mat == UW_MAT_NONE) return l_ms;
  const real l_s = mat == UW_MAT_SURFACE
                       ? uw_band_surface(band, d.y, s_w.y, ior, bottom_depth, single_scattering, multiple)
                       : uw_band_lambert(band, S, n, d.y, o_d, s_w, albedo, vis, single_scattering);
  return exp(-band->c * S) * l_s + l_ms;
}
