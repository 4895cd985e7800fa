/* sea_waves.h — the sea seen from above through FFT waves: the ocean
 * module's normals give the sea scenes their surface normals and Fresnel when the scene has waves.
 * Needs compat.h and optics.h.
 *
 * The model, and what it leaves out:
 *  - The view ray meets the MEAN surface y = 0; the waves' height and choppy displacement are ignored
 *    for the hit point (a height-field ray march would move the hit by about h / tan(view elevation):
 *    metres at grazing views, which shifts the pattern but not its statistics). The normal there is
 *    read from the ocean's normal map (kernels/ocean.cl, 004 §3: normals of the displaced surface,
 *    texel (i, j) at x = iL/N, z = jL/N), bilinearly, wrapping around the periodic L × L patch.
 *    No filtering: far away (many texels per pixel) the normals alias into noise.
 *  - The local normal sets the Fresnel reflectance (004 eq. 43–44), the mirror direction of the
 *    reflected sky (004 eq. 37) and the refracted view direction (004 eq. 41–42), whose angle to the
 *    downward vertical, cos θ_ji = −refracted.y, is the in-water path of 000 eq. 5 and 9.
 *  - Sunlight still enters through the mean flat surface (000 §3: "for calculating the radiance of
 *    light scattered within the water and light reflected at the bottom of the sea, the water surface
 *    is assumed to be flat"), so T_i, θ_io and the beam are those of the flat sea.
 *
 * With the flat normal (0, 1, 0) sea_view_interaction performs exactly the operations of the flat
 * sea (cos θ_jo = −d.y, the same reflect/refract calls), so wind 0 reproduces the flat image.
 * Stiff cases: a normal facing away from the eye (a back face, hidden behind a crest in reality) is
 * bent to grazing (R = 1: the eye sees the sky); a folded facet's downward normal (ocean.cl keeps it)
 * is turned up; an interpolated normal of ~zero length (opposite texels) becomes (0, 1, 0); a
 * reflected ray pointing below the horizon sees the horizon sky; a refracted ray that does not go
 * down has cos θ_ji clamped to 1e-4 (the path then runs along the surface: finite terms); the hit
 * distance is capped (view rays within 1e-6 of the horizon), so coordinates stay finite.
 */

/* Periodic coordinate x (m) on a patch of side `patch` with n texels, texel i at x = i patch/n:
 * the two texels around x (i1 = i0 + 1 wrapped) and the weight t ∈ [0, 1) of i1. */
SEASIM_FN void sea_wrap_coord(real x, real patch, int n, int* i0, int* i1, real* t) {
  real u = x / patch;
  u = u - floor(u); /* [0, 1]; 1 only by rounding of a tiny negative u */
  const real f = u * (real)n;
  int i = (int)floor(f);
  real w = f - (real)i;
  if (i >= n) { /* u rounded to 1: that is texel 0 */
    i = 0;
    w = R(0.0);
  }
  if (i < 0) i = 0;
  *i0 = i;
  *i1 = i + 1 < n ? i + 1 : 0;
  *t = clamp(w, R(0.0), R(1.0));
}

/* The ocean's normal map (4 reals per texel: nx, ny, nz, unused; row j = z index, x fastest) at
 * (x, z), bilinear with wrap-around, renormalised. Written as a + t (b − a) so equal texels give
 * exactly their value (a flat map gives exactly (0, 1, 0)). */
SEASIM_FN real3 sea_wave_normal(const SEASIM_GLOBAL real* normals, int n, real patch, real x, real z) {
  int i0, i1, j0, j1;
  real tx, tz;
  sea_wrap_coord(x, patch, n, &i0, &i1, &tx);
  sea_wrap_coord(z, patch, n, &j0, &j1, &tz);
  const SEASIM_GLOBAL real* a = normals + 4 * (j0 * n + i0);
  const SEASIM_GLOBAL real* b = normals + 4 * (j0 * n + i1);
  const SEASIM_GLOBAL real* c = normals + 4 * (j1 * n + i0);
  const SEASIM_GLOBAL real* e = normals + 4 * (j1 * n + i1);
  real v[3];
  for (int k = 0; k < 3; ++k) {
    const real near_row = a[k] + tx * (b[k] - a[k]);
    const real far_row = c[k] + tx * (e[k] - c[k]);
    v[k] = near_row + tz * (far_row - near_row);
  }
  const real3 m = MAKE_REAL3(v[0], v[1], v[2]);
  const real len = length(m);
  return len > R(1e-6) ? m / len : MAKE_REAL3(R(0.0), R(1.0), R(0.0));
}

/* Where the view ray from eye (height eye_y > 0) along unit d (d.y < 0) meets the mean surface
 * y = 0; the distance is capped at eye_y · 1e6 (rays within 1e-6 of the horizon). */
SEASIM_FN real sea_mean_surface_distance(real eye_y, real3 d) { return eye_y / fmax(-d.y, R(1e-6)); }

/* The normal the eye sees: turned up if it points down (a folded facet), and bent to grazing if it
 * faces away from the eye along d (the back of a wave; the crest in front hides it): the component
 * along d is removed, leaving cos θ_jo = 0 and so R = 1. The flat normal passes unchanged. */
SEASIM_FN real3 sea_facing_normal(real3 d, real3 n) {
  real3 m = n.y < R(0.0) ? -n : n;
  const real c = dot(d, m);
  if (c >= R(0.0)) {
    const real3 bent = m - c * d;
    const real len = length(bent);
    m = len > R(1e-6) ? bent / len : MAKE_REAL3(R(0.0), R(1.0), R(0.0));
  }
  return m;
}

/* The sky a reflected ray sees: itself when it points up, else the horizon below it (its horizontal
 * part; straight down, +x). A ray reflected downwards would meet the sea again; the horizon sky
 * stands in for that second bounce. */
SEASIM_FN real3 sea_sky_direction(real3 r) {
  if (r.y >= R(0.0)) return r;
  const real len = sqrt(r.x * r.x + r.z * r.z);
  return len > R(1e-12) ? MAKE_REAL3(r.x / len, R(0.0), r.z / len) : MAKE_REAL3(R(1.0), R(0.0), R(0.0));
}

/* The view ray d (unit, going down) meets the surface with unit normal n (facing the eye, as from
 * sea_facing_normal): writes the Fresnel reflectance R of the view (004 eq. 43–44; T_o = 1 − R in
 * 000 eq. 5, 9), the sky direction of its reflection (004 eq. 37, clamped to the horizon) and the
 * refracted direction in the water (004 eq. 41–42; air to water never reflects totally). Returns
 * cos θ_ji = −refracted.y, clamped to >= 1e-4 (000 eq. 5's sec θ_ji stays finite). n faces the eye, so
 * cos θ_jo = −d·n is taken as at least 0: a normal bent to grazing keeps −d·n = ±1e-17 (double) to 2e-5
 * (float) of rounding, and refract_dir, which turns a normal that faces away, sent a fifth of such views
 * up into the air (cos θ_ji then clamped to 1e-4, and the water's forward phase at them: bright specks on
 * rough seas near the horizon). */
SEASIM_FN real sea_view_interaction(real3 d, real3 n, real ior, real* fresnel, real3* sky_dir, real3* view_in_water) {
  const real cos_jo = clamp(-dot(d, n), R(0.0), R(1.0));
  *fresnel = fresnel_reflectance(cos_jo, R(1.0), ior);
  refract_facing_dir(d, n, cos_jo, R(1.0) / ior, view_in_water);
  *sky_dir = sea_sky_direction(reflect_dir(d, n));
  return fmax(-(*view_in_water).y, R(1e-4));
}
