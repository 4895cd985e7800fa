/* sea_view.h — sea_single.cl's per-pixel terms, found once before its band loop (common/sea_band_terms.h
 * runs the loop): the camera ray, the sky's shape, where the view meets the surface (flat, the wave
 * normals, or the normals filtered over the pixel's footprint), the sun's entry through the flat mean
 * surface, and where the view meets the bottom. The kernel's compile-time choices arrive as the fields
 * of SeaFeatures (constants there, so the compiler drops the branches not taken); the physics is in
 * the headers these call (sea_surface.h, sea_waves.h, sea_lean.h, sea_bottom.h, sea_multiple.h), and
 * sea_single.cl's header comment says which paper equation each term is. The operations are those of
 * the kernel's former single body, in the same order, so the images are unchanged.
 * tests/unit/sea_view_test.cpp holds these in float and double; tests/kernels/sea_single_test.cpp the
 * kernel to the double CPU reference.
 * Needs compat.h, optics.h, sea_params.h, sea_surface.h, sea_waves.h, sea_lean.h, sky.h, sky_table.h,
 * sea_bottom_params.h, sea_bottom.h, caustic_map.h, sea_multiple.h, sea_bands.h. */

/* The kernel's compile-time choices (sea_single.cl's SEASIM_* defines, chosen by host/plan). */
typedef struct {
  int reflection;         /* SEASIM_HAS_REFLECTION: Fresnel reflection of sky and sun */
  int single_scattering;  /* SEASIM_HAS_SINGLE_SCATTERING: eq. 5 */
  int bottom;             /* SEASIM_HAS_BOTTOM: eq. 9 */
  int sun;                /* SEASIM_HAS_SUN */
  int waves;              /* SEASIM_HAS_WAVES: the FFT ocean's normal map */
  int wave_filter;        /* SEASIM_WAVE_FILTER: normals filtered over the footprint (sea_lean.h) */
  int sky_model;          /* SEASIM_SKY_MODEL (sky.h) */
  int lut;                /* SEASIM_SEA_LUT: eq. 5's factors from the look-up table */
  int bottom_caustics;    /* SEASIM_BOTTOM_CAUSTICS */
  int bottom_heightfield; /* SEASIM_BOTTOM_HEIGHTFIELD */
  int model;              /* SEASIM_SEA_MODEL: 0 paper 000's eq. 5 and 9, 1 "multiple" */
  int sky_table;          /* SEASIM_SEA_SKY_TABLE: the reflected sky read from an n x n table (sky_table.h) in
                             the sky buffer from SKY_TABLE_OFFSET; 0 evaluates the model */
} SeaFeatures;

/* What the band loop needs of one pixel's ray below the horizon. */
typedef struct {
  real R_view;           /* Fresnel reflectance of the view (filtered: the footprint's mean) */
  real cos_ji;           /* cosine of the refracted view with the vertical */
  real3 reflected;       /* the reflected view (towards the sky) */
  real3 view_in_water;   /* travel direction of the refracted view */
  real3 reflected_shape; /* sky_shape of the reflected view; filtered: Fresnel-weighted over facets */
  real glint;            /* filtered: the sun's glint factor (R in it); 0 otherwise */
  real t_out;            /* T_o = (1 - R) / n² (docs/radiometry.md) */
  real t_in, cos_io, cos_alpha, sun_horizontal; /* the sun's entry (sea_sun_entry) */
  real c_f, phase;       /* forward fraction and HG phase towards the eye */
  real z_d;              /* depth of the bottom along the view (< 0: no bottom) */
  real cos_gamma;        /* height field: the floor's cosine to the refracted sun */
  real focus;            /* the bottom's caustic factor (1 without caustics) */
  int reflects_sun;      /* the reflected view sees the sun's disk */
  int lut_jm, lut_j, lut_jp; /* SEASIM_SEA_LUT: the Catmull–Rom taps (sea_lut_taps) */
  real lut_t;
  real mu_sky, r_below, mu_ret; /* sea.model "multiple": skylight's and the returned light's mean cosines */
  real hemisphere[3];            /* and sea_column_hemisphere of cos_io, mu_sky, mu_ret (SeaParams's) */
  int ord_row0, ord_row1;        /* and where it reads its factor κ (common/sea_ordinates.h, sea_ord_corner) */
  real ord_td, ord_tz, ord_ta;
} SeaPixel;

SEASIM_FN real3 sea_sun_dir(SEASIM_CONSTANT const SeaParams* p) {
  return MAKE_REAL3(p->sun_dir[0], p->sun_dir[1], p->sun_dir[2]);
}

/* Pinhole camera: sub-pixel ray sub of n x n (the pixel's centre for n = 1) -> world direction. */
SEASIM_FN real3 sea_camera_ray(SEASIM_CONSTANT const SeaParams* p, int x, int y, int sub, int n) {
  const real3 right = MAKE_REAL3(p->cam_right[0], p->cam_right[1], p->cam_right[2]);
  const real3 up = MAKE_REAL3(p->cam_up[0], p->cam_up[1], p->cam_up[2]);
  const real3 fwd = MAKE_REAL3(p->cam_forward[0], p->cam_forward[1], p->cam_forward[2]);
  const real ox = ((real)(sub % n) + R(0.5)) / (real)n;
  const real oy = ((real)(sub / n) + R(0.5)) / (real)n;
  const real u = (R(2.0) * (x + ox) / p->width - R(1.0)) * p->tan_half_fov_y * p->aspect;
  const real v = (R(1.0) - R(2.0) * (y + oy) / p->height) * p->tan_half_fov_y;
  return normalize(fwd + u * right + v * up);
}

/* The sky's direction-dependent factor towards d (sky.h), the same for every band: scale × shape, as
 * RGB for the image and as CIE daylight basis weights for Preetham (mixed per band by sky_w_*); 1 for
 * the uniform sky. */
SEASIM_FN real3 sea_sky_shape(int model, SEASIM_CONSTANT const SeaParams* p, const SEASIM_GLOBAL real* sky, real3 d) {
  if (model == SEASIM_SKY_ANALYTIC) {
    const real s = p->sky_scale * sky_cie_clear_shape(d, sea_sun_dir(p));
    return MAKE_REAL3(s, s, s);
  }
  if (model == SEASIM_SKY_IMAGE) return p->sky_scale * sky_latlong_rgb(sky, p->sky_width, p->sky_height, d);
  if (model == SEASIM_SKY_PREETHAM) return p->sky_scale * sky_preetham_daylight(sky, d, sea_sun_dir(p));
  return MAKE_REAL3(R(1.0), R(1.0), R(1.0));
}

/* The sky's shape towards a reflected direction d: read from the table when the plan made one (an
 * analytic sky under the wave filter's facets), else sea_sky_shape. The sky seen directly keeps the
 * exact model. */
SEASIM_FN real3 sea_reflected_sky_shape(SeaFeatures f, SEASIM_CONSTANT const SeaParams* p, const SEASIM_GLOBAL real* sky,
                                        real3 d) {
  if (f.sky_table > 0) {
    const real3 sun = f.sky_model == SEASIM_SKY_PREETHAM ? sky_preetham_sun(sea_sun_dir(p)) : sea_sun_dir(p);
    return sky_table_shape(f.sky_model, sky, sky + SKY_TABLE_OFFSET, f.sky_table, p->sky_scale, d.y, dot(d, sun));
  }
  return sea_sky_shape(f.sky_model, p, sky, d);
}

/* Whether direction d sees the sun's disk; a point sun (radius 0) has none. */
SEASIM_FN int sea_sees_sun(int has_sun, SEASIM_CONSTANT const SeaParams* p, real3 d) {
  return has_sun && p->sun_solid_angle > R(0.0) && dot(d, sea_sun_dir(p)) >= p->cos_sun_radius;
}

/* One band's sky radiance for a shape from sea_sky_shape (linear in the shape: a weighted sum of
 * shapes gives the same sum of radiances, which the wave filter uses). The daylight basis past its
 * range is held at 0 (sky_view_band's rule, sky_view.h). */
SEASIM_FN real sea_sky_band(int model, SEASIM_GLOBAL const SeaBand* band, real3 shape) {
  if (model == SEASIM_SKY_IMAGE || model == SEASIM_SKY_PREETHAM)
    return band->sky_radiance *
           fmax(band->sky_w_r * shape.x + band->sky_w_g * shape.y + band->sky_w_b * shape.z, R(0.0));
  return band->sky_radiance * shape.x; /* uniform: shape 1; analytic: grey */
}

/* The view's meeting with a flat sea or the wave normal where it crosses the mean surface y = 0
 * (sea_waves.h): Fresnel, the reflected and the refracted view. */
SEASIM_FN void sea_view_unfiltered(SeaFeatures f, SEASIM_CONSTANT const SeaParams* p, const SEASIM_GLOBAL real* normals,
                                   const SEASIM_GLOBAL real* sky, real3 d, SeaPixel* px) {
  real3 n = MAKE_REAL3(R(0.0), R(1.0), R(0.0));
  if (f.waves) {
    const real t_hit = sea_mean_surface_distance(p->cam_pos[1], d);
    n = sea_facing_normal(d, sea_wave_normal(normals, p->ocean_n, p->ocean_patch, p->cam_pos[0] + t_hit * d.x,
                                             p->cam_pos[2] + t_hit * d.z));
  }
  px->cos_ji = sea_view_interaction(d, n, p->ior, &px->R_view, &px->reflected, &px->view_in_water);
  px->glint = R(0.0);
  px->reflected_shape = MAKE_REAL3(R(0.0), R(0.0), R(0.0));
  if (f.reflection) px->reflected_shape = sea_reflected_sky_shape(f, p, sky, px->reflected);
  px->reflects_sun = f.reflection && sea_sees_sun(f.sun, p, px->reflected);
}

/* The footprint's slope statistics (sea_lean.h): its mean normal refracts the view, the
 * Fresnel-weighted sky of its facets is reflected, and the facets facing the sun give the glint.
 * Facets turned away from the eye are bent to grazing by the unfiltered path: F = 1, and the ray goes
 * on to the horizon's sky (sea_lean_rule). */
SEASIM_FN void sea_view_filtered(SeaFeatures f, SEASIM_CONSTANT const SeaParams* p, const SEASIM_GLOBAL real* slope_mips,
                                 const SEASIM_GLOBAL real* sky, real3 d, SeaPixel* px) {
  const real3 fwd = MAKE_REAL3(p->cam_forward[0], p->cam_forward[1], p->cam_forward[2]);
  const real t_hit = sea_mean_surface_distance(p->cam_pos[1], d);
  const real minor = t_hit * p->pixel_angle * fmax(dot(d, fwd), R(0.1));
  const real major = minor / fmax(-d.y, R(1e-6));
  const real horizontal = sqrt(d.x * d.x + d.z * d.z);
  const real dir_x = horizontal > R(1e-6) ? d.x / horizontal : R(1.0);
  const real dir_z = horizontal > R(1e-6) ? d.z / horizontal : R(0.0);
  real stats[SEA_LEAN_STRIDE];
  sea_lean_footprint(slope_mips, p->ocean_n, p->ocean_patch, p->cam_pos[0] + t_hit * d.x, p->cam_pos[2] + t_hit * d.z,
                     dir_x, dir_z, minor, major, stats);
  real cxx, czz, cxz, l11, l21, l22;
  sea_lean_covariance(stats[2], stats[3], stats[4], p->sun_slope_variance, &cxx, &czz, &cxz, &l11, &l21, &l22);
  const real3 n = sea_facing_normal(d, sea_lean_normal(stats[0], stats[1]));
  SeaLeanRule rule;
  sea_lean_rule(d, stats[0], stats[1], l11, l21, l22, &rule);
  real R_mean = rule.back;
  real3 reflected_shape = MAKE_REAL3(R(0.0), R(0.0), R(0.0));
  if (rule.split) reflected_shape = rule.back * sea_reflected_sky_shape(f, p, sky, sea_sky_direction(d));
  const int nodes = sea_lean_rule_nodes(&rule);
  for (int k = 0; k < nodes; ++k) {
    real sx, sz;
    const real w = sea_lean_rule_node(&rule, k, &sx, &sz);
    const real3 nk = sea_facing_normal(d, sea_lean_normal(sx, sz));
    const real wf = w * fresnel_reflectance(-dot(d, nk), R(1.0), p->ior);
    R_mean += wf;
    reflected_shape = reflected_shape + wf * sea_reflected_sky_shape(f, p, sky, sea_sky_direction(reflect_dir(d, nk)));
  }
  const real3 sun = sea_sun_dir(p);
  px->glint = R(0.0);
  if (f.sun && sun.y > R(0.0) && p->sun_solid_angle > R(0.0))
    px->glint = sea_lean_pixel_glint(d, fwd, p->pixel_angle * MAKE_REAL3(p->cam_right[0], p->cam_right[1], p->cam_right[2]),
                                     -p->pixel_angle * MAKE_REAL3(p->cam_up[0], p->cam_up[1], p->cam_up[2]), sun, p->ior,
                                     stats[0], stats[1], cxx, czz, cxz);
  real R_center;
  px->cos_ji = sea_view_interaction(d, n, p->ior, &R_center, &px->reflected, &px->view_in_water);
  px->R_view = R_mean;
  px->reflected_shape = reflected_shape;
  px->reflects_sun = 0; /* the glint holds the sun */
}

/* Sunlight enters through the flat mean surface (000 §3), with or without waves: T_i, the refracted
 * sun's cosine, its cosine with the reversed view (the scattering angle), and E on the horizontal
 * surface per E normal to the beam. The sun at or below the horizon contributes nothing. */
SEASIM_FN void sea_sun_entry(int has_sun, SEASIM_CONSTANT const SeaParams* p, SeaPixel* px) {
  const real3 sun = sea_sun_dir(p);
  const real3 flat_n = MAKE_REAL3(R(0.0), R(1.0), R(0.0));
  px->t_in = R(0.0);
  px->cos_io = R(1.0);
  px->cos_alpha = R(1.0);
  px->sun_horizontal = R(0.0);
  if (has_sun && sun.y > R(0.0)) {
    px->t_in = R(1.0) - fresnel_reflectance(sun.y, R(1.0), p->ior);
    px->sun_horizontal = sun.y;
    real3 sun_in_water; /* travel direction of sunlight */
    refract_dir(-sun, flat_n, R(1.0) / p->ior, &sun_in_water);
    px->cos_io = fmax(-sun_in_water.y, R(1e-4));
    px->cos_alpha = dot(sun_in_water, -px->view_in_water); /* scattered towards the eye */
  }
}

/* Where the refracted view meets the bottom: z_d (eq. 5 and 9; -1 without a bottom: infinitely deep),
 * on a height field z_Q and the floor's cos(gamma) at Q (000 §5.4; P is where the view meets the mean
 * surface, and the floor does not shadow the sun), and the ocean's caustics at Q (mean 1). */
SEASIM_FN void sea_bottom_view(SeaFeatures f, SEASIM_CONSTANT const SeaParams* p, SEASIM_GLOBAL const float* caustics,
                               SEASIM_CONSTANT const SeaHeightField* hf, SEASIM_GLOBAL const float* hf_depth, real3 d,
                               SeaPixel* px) {
  const real3 view = px->view_in_water;
  const real t_p = p->cam_pos[1] / -d.y;
  const real3 P = MAKE_REAL3(p->cam_pos[0] + t_p * d.x, R(0.0), p->cam_pos[2] + t_p * d.z);
  real t_q = R(0.0);
  px->z_d = R(-1.0);
  px->cos_gamma = R(0.0);
  px->focus = R(1.0);
  if (!f.bottom) return;
  if (f.bottom_heightfield) {
    real3 n_q;
    sea_hf_intersect(hf, hf_depth, P, view, R(1e30), &t_q, &n_q);
    px->z_d = fmax(-view.y, R(0.0)) * t_q;
    const real3 sun = sea_sun_dir(p);
    if (f.sun && sun.y > R(0.0)) {
      real3 sun_travel;
      refract_dir(-sun, MAKE_REAL3(R(0.0), R(1.0), R(0.0)), R(1.0) / p->ior, &sun_travel);
      px->cos_gamma = fmax(dot(n_q, -sun_travel), R(0.0));
    }
  } else {
    px->z_d = p->bottom_depth;
    t_q = px->z_d / fmax(-view.y, R(1e-4));
  }
  if (f.bottom_caustics) {
    const real3 Q = P + t_q * view;
    px->focus = caustic_map_read(caustics, p->caustic_map_size, p->caustic_extent, p->caustic_origin,
                                 !f.bottom_heightfield, Q.x, Q.z);
  }
}

/* Everything of the pixel's ray d (below the horizon) that is the same for every band, into *out. An
 * output pointer, not a struct return: Clang 14 marks a returned struct noalias and, inlining it, emits
 * llvm.experimental.noalias.scope.decl, which Oclgrind 21.10 cannot run (underwater_ordinates_bands.h). */
SEASIM_FN void sea_pixel(SeaFeatures f, SEASIM_CONSTANT const SeaParams* p, const SEASIM_GLOBAL real* normals,
                         const SEASIM_GLOBAL real* slope_mips, const SEASIM_GLOBAL real* sky,
                         SEASIM_GLOBAL const float* caustics, SEASIM_CONSTANT const SeaHeightField* hf,
                         SEASIM_GLOBAL const float* hf_depth, real3 d, SeaPixel* out) {
  SeaPixel px;
  if (f.wave_filter) sea_view_filtered(f, p, slope_mips, sky, d, &px);
  else sea_view_unfiltered(f, p, normals, sky, d, &px);
  /* T_o of 000 eq. 5, 9 with the n² law: radiance / n² is conserved across the surface, so the
   * water-leaving radiance L_w reaches the air as L_w (1 - R) / n² (docs/radiometry.md). Paper 000
   * writes T_o alone; kd_multiple.cl applies the same law the other way (sky seen from below). */
  px.t_out = (R(1.0) - px.R_view) / (p->ior * p->ior);
  sea_sun_entry(f.sun, p, &px);
  px.c_f = hg_forward_fraction(p->g);
  px.phase = hg_phase(px.cos_alpha, p->g);
  px.mu_sky = px.r_below = px.mu_ret = R(0.0);
  px.hemisphere[0] = px.hemisphere[1] = px.hemisphere[2] = R(0.0);
  if (f.model == 1) {
    px.mu_sky = sea_sky_mean_cosine(p->ior);
    px.r_below = sea_surface_reflectance_below(p->sky_fresnel_mean, p->ior); /* the surface's light back down */
    px.mu_ret = sea_reflected_mean_cosine(px.r_below, p->ior);
    for (int q = 0; q < 3; ++q) px.hemisphere[q] = (real)p->column_hemisphere[q];
  }
  sea_bottom_view(f, p, caustics, hf, hf_depth, d, &px);
  px.ord_row0 = px.ord_row1 = 0;
  px.ord_td = px.ord_tz = px.ord_ta = R(0.0);
  if (f.model == 1) {
    /* The view as a whole vector, then its parts: reading px.view_in_water.x and .z in place made Clang
     * split the struct into integer pieces (an i128 load cut to i96) that Oclgrind 21.10 cannot run. */
    const real3 view = px.view_in_water;
    const real cos_phi = sea_ord_azimuth_cosine(view.x, view.z, (real)p->sun_dir[0], (real)p->sun_dir[2]);
    sea_ord_corner(px.z_d, f.bottom_heightfield, px.cos_ji, cos_phi, &px.ord_row0, &px.ord_row1, &px.ord_td,
                   &px.ord_tz, &px.ord_ta);
  }
  /* eq. 5's LUT over theta_ji with waves, theta_jo (cos_jo = -d.y) on a flat sea. */
  px.lut_jm = px.lut_j = px.lut_jp = 0;
  px.lut_t = R(0.0);
  if (f.lut) {
    const real lut_angle = acos(clamp(f.waves ? px.cos_ji : -d.y, R(0.0), R(1.0)));
    px.lut_t = sea_lut_taps(p->lut_size, lut_angle * (p->lut_size - 1) * (R(2.0) / SEASIM_PI), &px.lut_jm, &px.lut_j,
                            &px.lut_jp);
  }
  *out = px;
}
