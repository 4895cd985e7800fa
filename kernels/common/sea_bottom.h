/* sea_bottom.h — the non-uniform sea floor of 000 §5.4: a height field of depths below the flat sea
 * surface, the exact first intersection of a ray with it, and the second-order terms that use it
 * (the depth tables' sampling-ray ends in eq. 7, each pixel's share of the sampling planes above its
 * floor). Shared by kernels/sea_single.cl (z_Q of the refracted view ray and the floor normal for
 * eq. 5 and 9), kernels/sea_second.cl (depth tables, radiance map, accumulation), the double
 * references and tests/unit/sea_bottom_test.cpp. Needs compat.h, optics.h, sea_surface.h,
 * sea_second.h and sea_bottom_params.h (SeaHeightField).
 *
 * Floor. depth[j * nx + i] (m, positive down; float storage on both sides, so the float kernels and
 * the double host see the same nodes) is the depth at node (i, j), world x = -extent/2 + i extent/(nx-1),
 * z = -extent/2 + j extent/(ny-1): image columns run along +x, rows along +z (the top row at
 * z = -extent/2, the far side for a camera looking along -z). Between nodes the depth is bilinear;
 * outside the square it is clamped to the edge (the border extends outwards), so a ray going down
 * always meets the floor, at the latest where it passes the deepest node.
 *
 * Intersection (sea_hf_intersect). A 2-D DDA walks the grid's cells along the ray (the clamped border
 * is walked as virtual cells with repeated nodes). Inside a cell the floor is a bilinear patch, so
 * f(t) = floor depth - ray depth is a quadratic in t. The first t where f drops to <= 0 lies in the
 * first monotone piece of f (split at its extremum) whose end has f <= 0; it is bracketed there and
 * bisected: no root formula (no cancellation as the quadratic degenerates), and a ray that grazes a
 * patch tangentially is caught at the extremum. Cells where the ray stays above the patch's shallowest
 * node are skipped without the quadratic. The walk starts where the ray reaches the shallowest node
 * (nothing above can be hit) and ends where it passes the deepest one, at t_max, or after max_cells.
 *
 * Stiff cases: a start on or under the floor is a hit at t = 0 (a floor touching the surface gives
 * z_Q = 0); vertical rays cross no cell walls; near-horizontal rays are bounded by t_max and the cell
 * cap; a floor exactly at the start depth or tangent to the ray counts as a hit (f <= 0).
 */

/* floor() as an int without the C library (int casts truncate towards 0), clamped far from overflow. */
SEASIM_FN int sea_hf_floor(real x) {
  x = clamp(x, R(-1.0e8), R(1.0e8));
  int i = (int)x;
  return R(i) > x ? i - 1 : i;
}

/* Depth of node (i, j), indices clamped to the grid (the border extends outwards). */
SEASIM_FN real sea_hf_node(SEASIM_CONSTANT const SeaHeightField* hf, SEASIM_GLOBAL const float* depth, int i, int j) {
  i = i < 0 ? 0 : (i >= hf->nx ? hf->nx - 1 : i);
  j = j < 0 ? 0 : (j >= hf->ny ? hf->ny - 1 : j);
  return (real)depth[j * hf->nx + i];
}

/* Bilinear floor depth (m) at world (x, z). */
SEASIM_FN real sea_hf_depth_at(SEASIM_CONSTANT const SeaHeightField* hf, SEASIM_GLOBAL const float* depth, real x,
                               real z) {
  real gx = (x + R(0.5) * hf->extent) * R(hf->nx - 1) / hf->extent;
  real gz = (z + R(0.5) * hf->extent) * R(hf->ny - 1) / hf->extent;
  int i = sea_hf_floor(gx), j = sea_hf_floor(gz);
  real u = gx - R(i), v = gz - R(j);
  real h00 = sea_hf_node(hf, depth, i, j), h10 = sea_hf_node(hf, depth, i + 1, j);
  real h01 = sea_hf_node(hf, depth, i, j + 1), h11 = sea_hf_node(hf, depth, i + 1, j + 1);
  return (h00 + u * (h10 - h00)) + v * ((h01 + u * (h11 - h01)) - (h00 + u * (h10 - h00)));
}

/* Unit floor normal (pointing up, into the water) at world (x, z): the floor is y = -h(x, z), so
 * n ~ (dh/dx, 1, dh/dz), with the derivatives of the bilinear patch under (x, z). */
SEASIM_FN real3 sea_hf_normal_at(SEASIM_CONSTANT const SeaHeightField* hf, SEASIM_GLOBAL const float* depth, real x,
                                 real z) {
  real sx = R(hf->nx - 1) / hf->extent, sz = R(hf->ny - 1) / hf->extent;
  real gx = (x + R(0.5) * hf->extent) * sx, gz = (z + R(0.5) * hf->extent) * sz;
  int i = sea_hf_floor(gx), j = sea_hf_floor(gz);
  real u = clamp(gx - R(i), R(0.0), R(1.0)), v = clamp(gz - R(j), R(0.0), R(1.0));
  real h00 = sea_hf_node(hf, depth, i, j), h10 = sea_hf_node(hf, depth, i + 1, j);
  real h01 = sea_hf_node(hf, depth, i, j + 1), h11 = sea_hf_node(hf, depth, i + 1, j + 1);
  real dhdu = (h10 - h00) + v * ((h00 - h10 - h01 + h11));
  real dhdv = (h01 - h00) + u * ((h00 - h10 - h01 + h11));
  return normalize(MAKE_REAL3(dhdu * sx, R(1.0), dhdv * sz));
}

/* The root of f(tau) = f0 + tau (f1 + tau f2) in [0, ts] where f(0) = f0 > 0 >= f(ts) and f is monotone on
 * [0, ts] (a ray entering a bilinear patch from above: sea_hf_intersect), on or just under the floor
 * (f <= 0), or -1 when rounding leaves the closed form above it or outside [0, ts] (the caller bisects).
 * The quadratic's roots in the stable form q = -(f1 + sign(f1) sqrt(f1^2 - 4 f0 f2))/2, q/f2 and f0/q
 * (f0/q is -f0/f1 as f2 -> 0, where q/f2 runs off), the smaller one in [0, ts]; if rounding leaves f just
 * above 0 there, one step of 2^-20 of the bracket onwards (2^-48 in double). In place of a 48-step
 * bisection of the bracket (the hit within 2^-48 ts): the same point to the working precision, for one
 * square root. */
SEASIM_FN real sea_hf_patch_root(real f0, real f1, real f2, real ts) {
  const real disc = fmax(f1 * f1 - R(4.0) * f0 * f2, R(0.0));
  const real q = R(-0.5) * (f1 + (f1 >= R(0.0) ? sqrt(disc) : -sqrt(disc)));
  const real r_a = q != R(0.0) ? f0 / q : R(-1.0);
  const real r_b = f2 != R(0.0) ? q / f2 : R(-1.0);
  const int a_in = r_a >= R(0.0) && r_a <= ts, b_in = r_b >= R(0.0) && r_b <= ts;
  if (!a_in && !b_in) return R(-1.0);
  real tau = a_in && b_in ? fmin(r_a, r_b) : a_in ? r_a : r_b;
  if (f0 + tau * (f1 + tau * f2) > R(0.0)) /* 2^-20 of the bracket onwards in float, 2^-48 in double */
    tau = fmin(tau + ts * (sizeof(real) == sizeof(float) ? R(9.5367431640625e-7) : R(3.552713678800501e-15)), ts);
  return f0 + tau * (f1 + tau * f2) <= R(0.0) ? tau : R(-1.0);
}

/* First point where the ray o + t dir (world metres, unit dir, o in the water: o.y <= 0) meets the floor
 * coming from above, for t in [0, t_max]. Returns 1 with *t_hit and the floor's unit normal *normal
 * there (pointing up), or 0 when the ray leaves [0, t_max] (or runs out of max_cells) first, with
 * *t_hit = t_max (or where the walk stopped) and *normal = +y. A start on or under the floor is a hit
 * at t = 0. */
SEASIM_FN_INLINED int sea_hf_intersect(SEASIM_CONSTANT const SeaHeightField* hf, SEASIM_GLOBAL const float* depth,
                                       real3 o, real3 dir, real t_max, real* t_hit, real3* normal) {
  const real sx = R(hf->nx - 1) / hf->extent, sz = R(hf->ny - 1) / hf->extent;
  const real half_ext = R(0.5) * hf->extent;
  const real d0 = -o.y, dd = -dir.y; /* ray depth d0 + dd t */
  const real gx0 = (o.x + half_ext) * sx, gz0 = (o.z + half_ext) * sz;
  const real gxd = dir.x * sx, gzd = dir.z * sz; /* grid units per metre along the ray */
  *normal = MAKE_REAL3(R(0.0), R(1.0), R(0.0));
  *t_hit = t_max;
  real t = R(0.0), t_end = t_max;
  int bounded = 0; /* t_end is where the ray passes the deepest node: a hit by then is certain */
  if (dd > R(0.0)) {
    const real t_deep = fmax((R(hf->max_depth) - d0) / dd, R(0.0));
    if (t_deep <= t_end) {
      t_end = t_deep;
      bounded = 1;
    }
  }
  if (d0 < R(hf->min_depth)) { /* above every node: skip to the shallowest one, or never hit */
    if (dd <= R(0.0)) return 0;
    t = (R(hf->min_depth) - d0) / dd;
    if (t > t_end) return 0;
  }
  int ci = sea_hf_floor(gx0 + gxd * t), cj = sea_hf_floor(gz0 + gzd * t);
  const int si = gxd > R(0.0) ? 1 : -1, sj = gzd > R(0.0) ? 1 : -1;
  for (int n = 0; n < hf->max_cells; ++n) {
    /* Where the ray leaves this cell, from the cell index (no accumulated drift). */
    const real tx = gxd != R(0.0) ? (R(ci + (gxd > R(0.0) ? 1 : 0)) - gx0) / gxd : R(1.0e30);
    const real tz = gzd != R(0.0) ? (R(cj + (gzd > R(0.0) ? 1 : 0)) - gz0) / gzd : R(1.0e30);
    const real t_exit = fmax(fmin(fmin(tx, tz), t_end), t);
    const real h00 = sea_hf_node(hf, depth, ci, cj), h10 = sea_hf_node(hf, depth, ci + 1, cj);
    const real h01 = sea_hf_node(hf, depth, ci, cj + 1), h11 = sea_hf_node(hf, depth, ci + 1, cj + 1);
    const real h_min = fmin(fmin(h00, h10), fmin(h01, h11));
    if (fmax(d0 + dd * t, d0 + dd * t_exit) >= h_min) { /* else the ray passes above this patch */
      /* f(tau) = patch depth - ray depth at t + tau, tau in [0, L]: f0 + tau (f1 + tau f2). */
      const real u_e = gx0 + gxd * t - R(ci), v_e = gz0 + gzd * t - R(cj);
      const real B = h10 - h00, C = h01 - h00, D = h00 - h10 - h01 + h11;
      const real f0 = h00 + B * u_e + C * v_e + D * u_e * v_e - (d0 + dd * t);
      const real f1 = B * gxd + C * gzd + D * (u_e * gzd + v_e * gxd) - dd;
      const real f2 = D * gxd * gzd;
      const real L = t_exit - t;
      real tau = R(-1.0);
      if (f0 <= R(0.0)) {
        tau = R(0.0);
      } else {
        real ts = L; /* end of the first monotone piece */
        if (f2 > R(0.0)) {
          const real tm = -f1 / (R(2.0) * f2);
          if (tm > R(0.0) && tm < L) ts = tm;
        }
        if (f0 + ts * (f1 + ts * f2) <= R(0.0)) { /* bracketed: f(0) > 0 >= f(ts), monotone between */
          tau = sea_hf_patch_root(f0, f1, f2, ts);
          if (tau < R(0.0)) { /* rounding left the closed form's root above the floor: bisect */
            real lo = R(0.0), hi = ts;
            for (int it = 0; it < 48; ++it) {
              const real mid = R(0.5) * (lo + hi);
              if (f0 + mid * (f1 + mid * f2) > R(0.0)) lo = mid;
              else hi = mid;
            }
            tau = hi; /* on or just under the floor */
          }
        }
      }
      if (tau >= R(0.0)) {
        const real u = clamp(u_e + gxd * tau, R(0.0), R(1.0)), v = clamp(v_e + gzd * tau, R(0.0), R(1.0));
        *t_hit = t + tau;
        *normal = normalize(MAKE_REAL3((B + D * v) * sx, R(1.0), (C + D * u) * sz));
        return 1;
      }
    }
    if (t_exit >= t_end) {
      if (bounded) { /* passed the deepest node: the floor is here up to rounding */
        const real3 q = o + t_end * dir;
        *t_hit = t_end;
        *normal = sea_hf_normal_at(hf, depth, q.x, q.z);
        return 1;
      }
      return 0;
    }
    if (tx <= tz) ci += si;
    else cj += sj;
    t = t_exit;
  }
  *t_hit = t; /* cell cap: the ray is still in the water here */
  return 0;
}

/* Sunlight reflected by the height-field floor (000 eq. 9 with z_d -> z_Q, §5.4): as
 * sea_bottom_reflection, whose flat floor has cos(gamma) = cos(theta_io), with the Lambert cosine
 * cos_gamma = max(n_Q . (-sun travel direction), 0) of the local floor normal instead. Shadowing of
 * the sun by the floor itself is not modelled (nor is it in the paper). */
SEASIM_FN real sea_bottom_reflection_tilted(real sun_irradiance, real t_in, real t_out, real bottom_albedo, real c,
                                           real z_q, real cos_io, real cos_ji, real cos_gamma) {
  return sea_bottom_reflection(sun_irradiance, t_in, t_out, bottom_albedo, c, z_q, cos_io, cos_ji) *
         (cos_gamma / cos_io);
}

/* 000 eq. 7 for a sampling ray whose end comes from the depth table of §5.4: l_opt = c l, the optical
 * path from P_k along omega to where the ray leaves the water (the floor, or the surface when
 * nothing is in the way). For a flat floor l = tau_k / cos(theta) upwards and
 * (tau_d - tau_k) / |cos(theta)| downwards, and this is sea_radiance_map exactly. */
SEASIM_FN real sea_radiance_map_path(real e_beam, real albedo, real phase, real cos_io, real cos_theta, real tau_k,
                                     real l_opt) {
  real kappa = (cos_io - cos_theta) / cos_io; /* 1 - sec(theta_io) cos(theta) */
  return e_beam * albedo * phase * sea_path_integral(tau_k / cos_io, kappa, fmax(l_opt, R(0.0)));
}

/* Nodes of the depth tables (000 §5.4): the sampling points of table node t (0..n_z) lie on each
 * map ray at depth z_t, the cell walls of sea_plane_depth for the reference attenuation c_ref and
 * floor z_max: node 0 is the surface, node n_z the deepest floor, and the planes of a band with
 * c = c_ref lie half-way between nodes. A band's plane at depth z_k reads the table linearly in depth
 * between the nodes around it (the paper's interpolation between P_s and P'_s), exact when the
 * sampling ray's length is linear in depth, as for a flat floor. c_ref > 0. */
SEASIM_FN real sea_table_node_depth(int t, int n_z, real cos_io, real c_ref, real z_max) {
  if (t >= n_z) return z_max;
  real s = R(1.0) + R(1.0) / cos_io;
  real span = one_minus_exp_neg(s * c_ref * z_max);
  return -log1p(-(R(t) / R(n_z)) * span) / (s * c_ref);
}

/* The node interval [t, t + 1] holding depth z and the weight of node t + 1, for reading the tables. */
SEASIM_FN int sea_table_node_interval(real z, int n_z, real cos_io, real c_ref, real z_max, real* w_next) {
  real s = R(1.0) + R(1.0) / cos_io;
  real span = one_minus_exp_neg(s * c_ref * z_max);
  if (!(span > R(0.0))) { /* a floor at the surface everywhere: one node depth */
    *w_next = R(0.0);
    return 0;
  }
  real x = clamp(one_minus_exp_neg(s * c_ref * fmax(z, R(0.0))) / span * R(n_z), R(0.0), R(n_z));
  int t = (int)x;
  t = t > n_z - 1 ? n_z - 1 : t;
  real z0 = sea_table_node_depth(t, n_z, cos_io, c_ref, z_max);
  real z1 = sea_table_node_depth(t + 1, n_z, cos_io, c_ref, z_max);
  *w_next = z1 > z0 ? clamp((z - z0) / (z1 - z0), R(0.0), R(1.0)) : R(0.0);
  return t;
}

/* The share of sampling plane k's depth cell that lies above the optical depth tau_q where a pixel's
 * view ray meets the floor (its planes below the floor see no water). The cell is measured in
 * 1 - u, u = exp(-s tau) the transmittance the planes are uniform in (sea_plane_depth): it spans
 * [k, k + 1] span / n_z. 1 for every cell when tau_q >= tau_d (the flat floor), 0 below the floor,
 * and 0 when the cells are empty (tau_d = 0: c = 0, or the floor at the surface everywhere). */
SEASIM_FN real sea_plane_share_above(int k, int n_z, real cos_io, real tau_d, real tau_q) {
  real s = R(1.0) + R(1.0) / cos_io;
  real span = tau_d < R(0.0) ? R(1.0) : one_minus_exp_neg(s * tau_d);
  real top = R(k) / R(n_z) * span;
  real bottom = R(k + 1) / R(n_z) * span;
  real q = one_minus_exp_neg(s * fmax(tau_q, R(0.0)));
  if (!(bottom > top)) return R(0.0); /* tau_d = 0 (c = 0 or no water): the planes weigh nothing */
  return clamp((q - top) / (bottom - top), R(0.0), R(1.0));
}
