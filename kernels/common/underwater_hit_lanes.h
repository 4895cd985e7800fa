/* underwater_hit_lanes.h — the underwater G-buffer's ray casts for several pixels at once: uw_scene_hit and
 * uw_sun_visibility of underwater.h (with shafts.h's ray_sphere, ray_box, ray_plane) on realb lanes, one pixel
 * per lane. The loop over the objects is the same for every lane; what differs between lanes (which root of
 * a sphere, which face of a box, whether a hit is nearer) is a select, not a branch. PoCL's work-group
 * vectoriser does not vectorise raycast.cl's scalar loop (control flow it cannot turn into selects), so the
 * kernel casts SEASIM_BAND_LANES pixels per work-item in these lanes instead. The host compiles them with one
 * lane (realb = real) and the unit test holds them to the scalar functions, hit for hit.
 * Needs compat.h, shafts.h, underwater_params.h, underwater.h and band_lanes.h before it. */

/* A point or direction per lane. */
typedef struct {
  realb x, y, z;
} real3b;

SEASIM_FN real3b uw_r3b(realb x, realb y, realb z) {
  real3b v;
  v.x = x;
  v.y = y;
  v.z = z;
  return v;
}

SEASIM_FN real3b uw_splat3b(real3 a) { return uw_r3b(SPLATB(a.x), SPLATB(a.y), SPLATB(a.z)); }

SEASIM_FN realb uw_dot3b(real3b a, real3b b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

/* a + t d per lane. */
SEASIM_FN real3b uw_along3b(real3b a, realb t, real3b d) { return uw_r3b(a.x + t * d.x, a.y + t * d.y, a.z + t * d.z); }

SEASIM_FN real3b uw_normalize3b(real3b a) {
  const realb inv = R(1.0) / sqrt(uw_dot3b(a, a));
  return uw_r3b(a.x * inv, a.y * inv, a.z * inv);
}

/* Per lane m ? a : b. */
SEASIM_FN real3b uw_select3b(maskb m, real3b a, real3b b) {
  return uw_r3b(SELECTB(m, a.x, b.x), SELECTB(m, a.y, b.y), SELECTB(m, a.z, b.z));
}

/* uw_screen_dir per lane: the view directions through the screen points (sx, sy), sx per lane (a row's pixels). */
SEASIM_FN real3b uw_screen_dir_b(const SEASIM_CONSTANT UwParams* p, realb sx, real sy) {
  const realb u = (R(2.0) * sx - R(1.0)) * p->tan_half_fov_y * p->aspect;
  const real v = (R(1.0) - R(2.0) * sy) * p->tan_half_fov_y;
  const real3 right = MAKE_REAL3(p->cam_right[0], p->cam_right[1], p->cam_right[2]);
  const real3 up = MAKE_REAL3(p->cam_up[0], p->cam_up[1], p->cam_up[2]);
  const real3 fwd = MAKE_REAL3(p->cam_forward[0], p->cam_forward[1], p->cam_forward[2]);
  return uw_normalize3b(uw_r3b(fwd.x + u * right.x + v * up.x, fwd.y + u * right.y + v * up.y,
                               fwd.z + u * right.z + v * up.z));
}

/* ray_sphere per lane: the nearer root in (t_min, t_max), else the farther, else -1 (the same stable roots). */
SEASIM_FN realb uw_ray_sphere_b(real3b o, real3b d, real3 c, real r, realb t_min, realb t_max) {
  const real3b oc = uw_r3b(o.x - c.x, o.y - c.y, o.z - c.z);
  const realb b = uw_dot3b(oc, d);
  const realb cc = uw_dot3b(oc, oc) - r * r;
  const realb disc = b * b - cc;
  const realb sq = sqrt(fmax(disc, SPLATB(R(0.0))));
  const realb q = SELECTB(b >= R(0.0), -(b + sq), -(b - sq));
  const realb t1 = SELECTB(q != R(0.0), cc / q, SPLATB(R(0.0)));
  const realb lo = fmin(q, t1), hi = fmax(q, t1);
  realb t = SELECTB((hi > t_min) & (hi < t_max), hi, SPLATB(R(-1.0)));
  t = SELECTB((lo > t_min) & (lo < t_max), lo, t);
  return SELECTB(disc < R(0.0), SPLATB(R(-1.0)), t);
}

/* ray_plane per lane. */
SEASIM_FN realb uw_ray_plane_b(real3b o, real3b d, real3 p, real3 n, realb t_min, realb t_max) {
  const realb dn = d.x * n.x + d.y * n.y + d.z * n.z;
  const realb t = ((p.x - o.x) * n.x + (p.y - o.y) * n.y + (p.z - o.z) * n.z) / dn;
  return SELECTB((fabs(dn) >= R(1e-12)) & (t > t_min) & (t < t_max), t, SPLATB(R(-1.0)));
}

/* One axis of ray_box's slab test per lane: where the ray runs parallel to the slab (|d| < 1e-20) it adds
 * no bound inside and misses outside. */
SEASIM_FN void uw_ray_slab_b(realb o, realb d, real mn, real mx, real axis, realb* lo, realb* hi, realb* ax_lo,
                             realb* ax_hi, maskb* miss) {
  const maskb parallel = fabs(d) < R(1e-20);
  *miss = *miss | (parallel & ((o < mn) | (o > mx)));
  const realb inv = R(1.0) / SELECTB(parallel, SPLATB(R(1.0)), d);
  const realb ta = (mn - o) * inv, tb = (mx - o) * inv;
  const realb t_near = SELECTB(parallel, SPLATB(R(-1e30)), fmin(ta, tb));
  const realb t_far = SELECTB(parallel, SPLATB(R(1e30)), fmax(ta, tb));
  const maskb up = t_near > *lo, down = t_far < *hi;
  *lo = SELECTB(up, t_near, *lo);
  *ax_lo = SELECTB(up, SPLATB(axis), *ax_lo);
  *hi = SELECTB(down, t_far, *hi);
  *ax_hi = SELECTB(down, SPLATB(axis), *ax_hi);
}

/* ray_box per lane; *axis gets the face's axis (0, 1, 2 as a real) where it hits. */
SEASIM_FN realb uw_ray_box_b(real3b o, real3b d, real3 bmin, real3 bmax, realb t_min, realb t_max, realb* axis) {
  realb lo = SPLATB(R(-1e30)), hi = SPLATB(R(1e30)), ax_lo = SPLATB(R(0.0)), ax_hi = SPLATB(R(0.0));
  maskb miss = lo > hi; /* none yet */
  uw_ray_slab_b(o.x, d.x, bmin.x, bmax.x, R(0.0), &lo, &hi, &ax_lo, &ax_hi, &miss);
  uw_ray_slab_b(o.y, d.y, bmin.y, bmax.y, R(1.0), &lo, &hi, &ax_lo, &ax_hi, &miss);
  uw_ray_slab_b(o.z, d.z, bmin.z, bmax.z, R(2.0), &lo, &hi, &ax_lo, &ax_hi, &miss);
  miss = miss | (lo > hi);
  const maskb lo_in = (lo > t_min) & (lo < t_max), hi_in = (hi > t_min) & (hi < t_max);
  *axis = SELECTB(lo_in, ax_lo, ax_hi);
  const realb t = SELECTB(lo_in, lo, SELECTB(hi_in, hi, SPLATB(R(-1.0))));
  return SELECTB(miss, SPLATB(R(-1.0)), t);
}

/* box_normal per lane. */
SEASIM_FN real3b uw_box_normal_b(real3b p, real3 bmin, real3 bmax, realb axis) {
  const realb zero = SPLATB(R(0.0)), one = SPLATB(R(1.0)), minus = SPLATB(R(-1.0));
  const realb sx = SELECTB(p.x - R(0.5) * (bmin.x + bmax.x) >= R(0.0), one, minus);
  const realb sy = SELECTB(p.y - R(0.5) * (bmin.y + bmax.y) >= R(0.0), one, minus);
  const realb sz = SELECTB(p.z - R(0.5) * (bmin.z + bmax.z) >= R(0.0), one, minus);
  return uw_r3b(SELECTB(axis == R(0.0), sx, zero), SELECTB(axis == R(1.0), sy, zero), SELECTB(axis == R(2.0), sz, zero));
}

/* uw_scene_hit per lane: the first hit along o + t d, t in (t_min, ∞), among the objects, the flat bottom and
 * the surface; *normal the unit normal facing the ray's side, *material the object index or UW_MAT_* (as a
 * real; UW_MAT_NONE with UW_INFINITE where nothing is hit). */
SEASIM_FN realb uw_scene_hit_b(const SEASIM_GLOBAL UwObject* objects, int count, real bottom_depth, real3b o, real3b d,
                               realb t_min, real3b* normal, realb* material) {
  const realb zero = SPLATB(R(0.0)), one = SPLATB(R(1.0));
  realb best = SPLATB(UW_INFINITE), mat = SPLATB((real)UW_MAT_NONE);
  real3b nrm = uw_r3b(zero, one, zero);
  {
    const realb t = -o.y / d.y;
    const maskb hit = (d.y > R(0.0)) & (t > t_min) & (t < best);
    best = SELECTB(hit, t, best);
    mat = SELECTB(hit, SPLATB((real)UW_MAT_SURFACE), mat);
    nrm.y = SELECTB(hit, -one, nrm.y);
  }
  if (bottom_depth > R(0.0)) {
    const realb t = (-bottom_depth - o.y) / d.y;
    const maskb hit = (d.y < R(0.0)) & (t > t_min) & (t < best);
    best = SELECTB(hit, t, best);
    mat = SELECTB(hit, SPLATB((real)UW_MAT_BOTTOM), mat);
    nrm.y = SELECTB(hit, one, nrm.y);
  }
  for (int k = 0; k < count; ++k) {
    const SEASIM_GLOBAL UwObject* ob = &objects[k];
    const real3 a = MAKE_REAL3(ob->a[0], ob->a[1], ob->a[2]);
    const real3 b = MAKE_REAL3(ob->b[0], ob->b[1], ob->b[2]);
    realb t;
    real3b nk;
    if (ob->type == UW_SPHERE) {
      t = uw_ray_sphere_b(o, d, a, (real)ob->a[3], t_min, best);
      const real3b p = uw_along3b(o, t, d);
      nk = uw_normalize3b(uw_r3b(p.x - a.x, p.y - a.y, p.z - a.z));
    } else if (ob->type == UW_BOX) {
      realb axis;
      t = uw_ray_box_b(o, d, a, b, t_min, best, &axis);
      nk = uw_box_normal_b(uw_along3b(o, t, d), a, b, axis);
    } else {
      t = uw_ray_plane_b(o, d, a, b, t_min, best);
      const maskb facing = d.x * b.x + d.y * b.y + d.z * b.z < R(0.0);
      nk = uw_select3b(facing, uw_splat3b(b), uw_splat3b(-b));
    }
    const maskb hit = t > R(0.0);
    best = SELECTB(hit, t, best);
    mat = SELECTB(hit, SPLATB((real)k), mat);
    nrm = uw_select3b(hit, nk, nrm);
  }
  /* Inside a sphere or a box: shade the side we see. */
  const maskb inside = (uw_dot3b(nrm, d) > R(0.0)) & (mat >= R(0.0));
  *normal = uw_select3b(inside, uw_r3b(-nrm.x, -nrm.y, -nrm.z), nrm);
  *material = mat;
  return best;
}

/* uw_objects_block per lane: whether a candidate object (bit k of candidates for object k < 32, every object
 * from 32 on) lies on the ray o + t d (d unit, per lane) for t in (t_min, t_max) (per lane). */
SEASIM_FN maskb uw_objects_block_b(const SEASIM_GLOBAL UwObject* objects, int count, unsigned int candidates, real3b o,
                                   real3b d, realb t_min, realb t_max) {
  maskb blocked = SPLATB(R(1.0)) < R(0.0); /* none yet */
  for (int k = 0; k < count; ++k) {
    if (k < 32 && !((candidates >> k) & 1u)) continue;
    const SEASIM_GLOBAL UwObject* ob = &objects[k];
    const real3 a = MAKE_REAL3(ob->a[0], ob->a[1], ob->a[2]);
    const real3 b = MAKE_REAL3(ob->b[0], ob->b[1], ob->b[2]);
    realb t, axis;
    if (ob->type == UW_SPHERE) t = uw_ray_sphere_b(o, d, a, (real)ob->a[3], t_min, t_max);
    else if (ob->type == UW_BOX) t = uw_ray_box_b(o, d, a, b, t_min, t_max, &axis);
    else t = uw_ray_plane_b(o, d, a, b, t_min, t_max);
    blocked = blocked | (t > R(0.0));
  }
  return blocked;
}

/* uw_sun_visibility per lane: 0 where an object lies on the shadow ray from hit (offset 1e-3 along n) towards
 * the sun s_w before it leaves the water, else 1. */
SEASIM_FN realb uw_sun_visibility_b(const SEASIM_GLOBAL UwObject* objects, int count, real3b hit, real3b n, real3 s_w) {
  const real3b o = uw_r3b(hit.x + R(1e-3) * n.x, hit.y + R(1e-3) * n.y, hit.z + R(1e-3) * n.z);
  realb t_surface = SPLATB(UW_INFINITE);
  if (s_w.y > R(0.0)) {
    const realb t = -o.y / s_w.y;
    t_surface = SELECTB(t > R(0.0), t, t_surface);
  }
  const maskb blocked = uw_objects_block_b(objects, count, UW_ALL_OBJECTS, o, uw_splat3b(s_w), SPLATB(R(0.0)), t_surface);
  return SELECTB(blocked, SPLATB(R(0.0)), SPLATB(R(1.0)));
}
