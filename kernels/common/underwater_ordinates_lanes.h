/* underwater_ordinates_lanes.h — the discrete-ordinates model's shares that objects leave a view ray
 * (underwater_ordinates.h: uwi_open_above, uwi_sand_seen, uwi_sand_shares, uwi_inscatter_quantile,
 * uwi_above_share) for several view rays at once, one ray per lane, on underwater_hit_lanes.h's casts.
 * Every lane follows the same rays of the fixed golden-angle patterns; where the scalar form branches on
 * what a ray met (the sand, an object, nothing) the lanes compute each case and select, and a case no lane
 * needs is skipped (ANYB). sand_share.cl evaluates SEASIM_BAND_LANES lattice pixels per work-item in these
 * lanes: PoCL's work-group vectoriser runs the scalar form one pixel per instruction (its loops over
 * objects and rays are control flow it cannot turn into selects). The host compiles them with one lane
 * (realb = real) and the unit test holds them to the scalar functions.
 * Needs compat.h, shafts.h, underwater_params.h, underwater.h, band_lanes.h, underwater_hit_lanes.h,
 * underwater_band_table.h, underwater_ordinates_params.h and underwater_ordinates.h before it. */

/* uwi_open_above per lane: the share of n up-rays from x (cosine-weighted about the upward vertical, the
 * golden-angle pattern) that no object stops. */
SEASIM_FN realb uwi_open_above_b(const SEASIM_GLOBAL UwObject* objects, int count, real bottom_depth, real3b x, int n) {
  real cos_phi = R(1.0), sin_phi = R(0.0); /* azimuth ray × the golden angle */
  realb open = SPLATB(R(0.0));
  for (int ray = 0; ray < n; ++ray) {
    const real3 up = uwi_cosine_ray(ray, n, cos_phi, sin_phi);
    uwi_golden_advance(&cos_phi, &sin_phi);
    real3b normal;
    realb mat;
    uw_scene_hit_b(objects, count, bottom_depth, x, uw_splat3b(up), SPLATB(R(0.0)), &normal, &mat);
    open += SELECTB(mat < R(0.0), SPLATB(R(1.0)), SPLATB(R(0.0)));
  }
  return open / (real)n;
}

/* uwi_sand_seen per lane: the sunlit sand's share of the UWI_SAND_RAYS down-rays from x, and in *open the
 * diffusely lit sand's (the scalar form explains both). The sun's shadow ray is cast once for the lanes that
 * met the sand (normal up) and those that met an object (its face's normal). */
SEASIM_FN realb uwi_sand_seen_b(const SEASIM_GLOBAL UwObject* objects, int count, real bottom_depth, real3b x,
                                real3 s_w, const SEASIM_GLOBAL float* object_albedo, int albedo_stride,
                                real sand_albedo, real k, realb* open) {
  const realb zero = SPLATB(R(0.0));
  realb lit = zero, seen_open = zero;
  real cos_phi = R(1.0), sin_phi = R(0.0); /* azimuth ray × the golden angle */
  for (int ray = 0; ray < UWI_SAND_RAYS; ++ray) {
    const real3 l = uwi_cosine_ray(ray, UWI_SAND_RAYS, cos_phi, sin_phi);
    const real3 dir = MAKE_REAL3(l.x, -l.y, l.z); /* about the downward vertical */
    uwi_golden_advance(&cos_phi, &sin_phi);
    const real3b dir_b = uw_splat3b(dir);
    real3b nb;
    realb mat;
    const realb t = uw_scene_hit_b(objects, count, bottom_depth, x, dir_b, zero, &nb, &mat);
    const maskb sand = mat == (real)UW_MAT_BOTTOM;
    const maskb object = (mat >= R(0.0)) & (SPLATB(sand_albedo) > R(0.0));
    if (!ANYB(sand | object)) continue;
    /* Where the ray met nothing its hit is far away: those lanes are dropped below, their point kept finite. */
    const real3b hit = uw_along3b(x, SELECTB(sand | object, t, zero), dir_b);
    /* An object's face against the sand: its albedo over the sand's (a select per object: the lanes meet
     * different objects), the face's reflection of the beam and of the diffuse light from above. */
    realb ratio = zero;
    for (int j = 0; j < count; ++j)
      ratio = SELECTB(mat == (real)j, SPLATB((real)object_albedo[j * albedo_stride] / fmax(sand_albedo, R(1e-30))),
                      ratio);
    const realb face = ratio * fmax(nb.x * s_w.x + nb.y * s_w.y + nb.z * s_w.z, zero) / fmax(s_w.y, R(1e-3));
    const maskb shaded = sand | (object & (face > R(0.0)));
    realb vis = zero;
    if (ANYB(shaded)) {
      const real3b n_sun = uw_select3b(sand, uw_splat3b(MAKE_REAL3(0, 1, 0)), nb);
      vis = uw_sun_visibility_b(objects, count, hit, n_sun, s_w);
    }
    lit += SELECTB(sand, vis, SELECTB(shaded, face * vis, zero));
    /* The diffusely lit sand's: the up-rays start just above the sand, as the sun's shadow rays. */
    realb open_sand = zero;
    if (ANYB(sand)) open_sand = uwi_open_above_b(objects, count, bottom_depth, uw_r3b(hit.x, hit.y + R(1e-3), hit.z),
                                                 UWI_SAND_RAYS);
    const realb y_j = clamp(-hit.y, zero, SPLATB(bottom_depth));
    const realb open_face = ratio * R(0.5) * (R(1.0) + nb.y) * exp(k * (bottom_depth - y_j));
    seen_open += SELECTB(sand, open_sand, SELECTB(object, open_face, zero));
  }
  *open = seen_open / (real)UWI_SAND_RAYS;
  return lit / (real)UWI_SAND_RAYS;
}

/* uwi_sand_shares per lane: view rays from o along d (per lane) to their hits S (per lane; a lane whose S is
 * not finite gets 1, as the scalar form). */
SEASIM_FN realb uwi_sand_shares_b(const SEASIM_GLOBAL UwObject* objects, int count, real bottom_depth, real3 o,
                                  real3b d, realb S, real c_dm, real k, real3 s_w,
                                  const SEASIM_GLOBAL float* object_albedo, int albedo_stride, real sand_albedo,
                                  realb* v_diffuse) {
  const realb zero = SPLATB(R(0.0)), one = SPLATB(R(1.0));
  *v_diffuse = one;
  if (!(bottom_depth > R(0.0)) || count <= 0) return one;
  const maskb finite = S < R(1e6);
  if (!ANYB(finite)) return one;
  const realb S_f = SELECTB(finite, S, zero);
  const real3b o_b = uw_splat3b(o);
  realb lit = zero, open = zero, den = zero;
  for (int q = 0; q < UWI_SAND_POINTS; ++q) {
    const realb z = S_f * ((real)q + R(0.5)) / (real)UWI_SAND_POINTS;
    const real3b x = uw_along3b(o_b, z, d);
    const realb y = clamp(-x.y, zero, SPLATB(bottom_depth));
    const realb w = exp(-c_dm * z - k * (bottom_depth - y));
    realb open_q;
    lit += w * uwi_sand_seen_b(objects, count, bottom_depth, x, s_w, object_albedo, albedo_stride, sand_albedo, k,
                               &open_q);
    open += w * open_q;
    den += w;
  }
  const maskb kept = finite & (den > R(0.0));
  const realb den_k = SELECTB(kept, den, one);
  *v_diffuse = SELECTB(kept, fmin(open / den_k, one), one);
  return SELECTB(kept, fmin(lit / den_k, one), one);
}

/* uwi_inscatter_quantile per lane (r and S per lane, u shared): the same three cases as selects. */
SEASIM_FN realb uwi_inscatter_quantile_b(realb r, realb S, real u) {
  const maskb linear = !(fabs(r) * fmin(S, SPLATB(R(1e6))) > R(1e-20));
  const realb from_start = -log1p(-u * -expm1(-r * S)) / r;
  const realb from_end = S + log1p(-(R(1.0) - u) * -expm1(r * S)) / -r;
  return SELECTB(linear, u * S, SELECTB(r > R(0.0), from_start, from_end));
}

/* uwi_above_share per lane: view rays from o along d (per lane) to S (per lane). */
SEASIM_FN realb uwi_above_share_b(const SEASIM_GLOBAL UwObject* objects, int count, real bottom_depth, real3 o,
                                  real3b d, realb S, real c_dm, real k) {
  if (count <= 0) return SPLATB(R(1.0));
  const realb r = c_dm - k * d.y;
  const real3b o_b = uw_splat3b(o);
  realb open = SPLATB(R(0.0));
  for (int q = 0; q < UWI_ABOVE_POINTS; ++q) {
    const realb z = uwi_inscatter_quantile_b(r, S, ((real)q + R(0.5)) / (real)UWI_ABOVE_POINTS);
    open += uwi_open_above_b(objects, count, bottom_depth, uw_along3b(o_b, z, d), UWI_ABOVE_RAYS);
  }
  return open / (real)UWI_ABOVE_POINTS;
}

/* uwi_view_sand_shares per lane: from the camera, with the band table's first band. */
SEASIM_FN realb uwi_view_sand_shares_b(SEASIM_CONSTANT const UwParams* p, const SEASIM_GLOBAL UwObject* objects,
                                       const SEASIM_GLOBAL float* band_table, int stride, real3b d, realb S,
                                       realb* v_diffuse) {
  const int row0 = UW_ROWS + p->object_count;
  const real3 cam = MAKE_REAL3(p->cam_pos[0], p->cam_pos[1], p->cam_pos[2]);
  const real3 s_w = MAKE_REAL3(p->sun_dir_water[0], p->sun_dir_water[1], p->sun_dir_water[2]);
  return uwi_sand_shares_b(objects, p->object_count, p->bottom_depth, cam, d, S,
                           band_table[(row0 + UWI_ROW_C_DM) * stride], band_table[(row0 + UWI_ROW_K) * stride], s_w,
                           band_table + UW_ROWS * stride, stride, band_table[UW_ROW_BOTTOM_ALBEDO * stride], v_diffuse);
}

/* uwi_view_above_share per lane: from the camera, with the band table's first band's c' and k. */
SEASIM_FN realb uwi_view_above_share_b(SEASIM_CONSTANT const UwParams* p, const SEASIM_GLOBAL UwObject* objects,
                                       const SEASIM_GLOBAL float* band_table, int stride, real3b d, realb S) {
  const int row0 = UW_ROWS + p->object_count;
  const real3 cam = MAKE_REAL3(p->cam_pos[0], p->cam_pos[1], p->cam_pos[2]);
  return uwi_above_share_b(objects, p->object_count, p->bottom_depth, cam, d, S,
                           band_table[(row0 + UWI_ROW_C_DM) * stride], band_table[(row0 + UWI_ROW_K) * stride]);
}
