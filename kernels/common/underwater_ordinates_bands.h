/* underwater_ordinates_bands.h — underwater.model = "discrete_ordinates" (common/underwater_ordinates.h) for
 * SEASIM_BAND_LANES bands at once: the discrete-ordinates model's band loop in kd_multiple.cl
 * (SEASIM_UNDERWATER_MODEL == 1) on the band lanes of common/band_lanes.h, as the thesis model's
 * (common/underwater_bands.h). The same formulas as underwater_ordinates.h (its header comment derives
 * them; "uwi" there), rewritten on realb because OpenCL C has no templates, with every pixel-invariant
 * per-band value precomputed in the band table's discrete-ordinates rows (UWI_ROW_*, common/underwater_band_table.h,
 * filled by host/underwater/underwater_band_table.cpp):
 *  - the in-scatter source's table (UwiBand.src) in the band table's rows UWI_ROW_SRC + …: the pixel's
 *    nearest node in ν and its cos Δφ (uwi_source_node, uwi_cos_azimuth) once per pixel, then one row per
 *    term and band (uwi_lanes_weights);
 *  - the TMS beam term b p_HG(g, cos θ_s) e_beam0 = (b e_beam0) p_HG: b e_beam0 per band, the phase
 *    (g is the scene's) once per pixel;
 *  - the bottom's sunlit unshadowed radiance that the surface's reflected ray ends on (uwi_surface's
 *    l_bottom / e^{-c' s_r}), which depends on no pixel.
 *  - an object's face reads the tilted plane's table (UwiBand.tilt, tilt_bottom: rows UWI_ROW_TILT…,
 *    UWI_ROW_TILT_BOTTOM…) at its normal's two nearest nodes (uwi_lanes_tilt; node, azimuth and the bottom's
 *    visibility once per pixel); the bottom, facing straight up, reads E_d's coefficients (uwi_lanes_down),
 *    which are that table's top node.
 * The material, the phase functions and the reflected ray's direction are per pixel (kd_multiple.cl);
 * bottom_depth is the scene's (one uniform test per step). The lanes are branch-free otherwise.
 * One exp fewer per lit band than underwater_ordinates.h: T(S) = e^{-c' S} is folded into the three
 * exps of the irradiance at the hit, e^{-c' S} e^{-k y} = e^{-(k y + c' S)} (the clamps at 0 commute with
 * the positive factor), as underwater_bands.h does for the thesis.
 * The budget (<= 2x the thesis per band; four integrals where eq. 4.7 takes two): each integral
 * is kd_exp_integral_ends_b, which takes no exp of its own. Its start factors e^{-κ o_d} (UwiStart) are
 * per band and frame for the camera's rays (the table's UWI_ROW_EXP_* rows) and 1 or e^{-k H} for the
 * surface's reflected ray (o_d = 0); its far ends e^{-(κ y(S) + c' S)} (UwiEnds) are the exps of the
 * hit's irradiance times T(S), taken once per step and shared by the integrals and the Lambert hit.
 * So a lit hit takes four exps per band (three without froxels) where the thesis's lanes take six, and
 * the surface from below seven with froxels (its T(S) the camera's far end; the reflected ray's three, no
 * froxel term along it) against nine. The source's table adds nine rows' loads per ray and band (its
 * two nearest nodes interpolated took twice the kernel's time per band: docs/journal/underwater_regions_3_*.md).
 * tests/unit/underwater_ordinates_bands_test.cpp holds these lanes (one band per step on the host) to
 * uwi_band_radiance in float and double; tests/kernels/underwater_ordinates_kernel_test.cpp the kernel
 * to the double CPU evaluation of uwi_band_radiance.
 * Needs compat.h, band_lanes.h, band_lanes_math.h, optics.h (fresnel_reflectance), underwater.h
 * (UW_INFINITE), underwater_bands.h (kd_exp_integral_ends_b), underwater_band_table.h.
 * The lanes' structs (UwiLanes, UwiWeights, UwiStart, UwiEnds) come back through an out pointer, not as
 * return values: a struct return is a `noalias sret` pointer in SPIR, and when Clang 14 inlines such a
 * function it emits llvm.experimental.noalias.scope.decl, which Oclgrind 21.10 cannot run ("Undefined
 * external function", and kd_multiple was not created). A plain pointer carries no noalias scope; the
 * code after inlining is the same (tests/runtimes/oclgrind_scenes.sh renders the discrete-ordinates model). */

/* One step's per-band values: the thesis rows the model shares (σ_t, σ_t/μ_w, e_beam0) and the
 * discrete-ordinates rows. */
typedef struct {
  realb c, k_beam, e_beam; /* σ_t; σ_t / max(μ_w, 1e-4) (the froxel term's beam); e_beam0 */
  realb c_dm, k, m;        /* delta-M extinction c', the diffuse field's k, the delta-M beam's c'/μ_w */
  realb b_e_beam;          /* b e_beam0: the TMS term and the froxel term per unit phase */
  realb p_clip;            /* the TMS term's phase ceiling (uwi_tms_phase; a large float for none) */
  realb d1, d2, dp;        /* E_d's coefficients (UwiBand): the bottom's light */
} UwiLanes;

/* Bands i..i+SEASIM_BAND_LANES-1 of the table (row stride `stride`), the discrete-ordinates rows starting at row
 * uwi_row0 = UW_ROWS + object count. */
SEASIM_FN void uwi_lanes_load(const SEASIM_GLOBAL float* table, int stride, int uwi_row0, int i, UwiLanes* out) {
  UwiLanes v;
#define UWI_LOAD(row) LOADB(table + (size_t)(row) * (size_t)stride, i)
  v.c = UWI_LOAD(UW_ROW_C);
  v.k_beam = UWI_LOAD(UW_ROW_K_BEAM);
  v.e_beam = UWI_LOAD(UW_ROW_E_BEAM);
  v.k = UWI_LOAD(uwi_row0 + UWI_ROW_K);
  v.m = UWI_LOAD(uwi_row0 + UWI_ROW_M);
  v.c_dm = UWI_LOAD(uwi_row0 + UWI_ROW_C_DM);
  v.b_e_beam = UWI_LOAD(uwi_row0 + UWI_ROW_B_E_BEAM);
  v.p_clip = UWI_LOAD(uwi_row0 + UWI_ROW_P_CLIP);
  v.d1 = UWI_LOAD(uwi_row0 + UWI_ROW_D1);
  v.d2 = UWI_LOAD(uwi_row0 + UWI_ROW_D2);
  v.dp = UWI_LOAD(uwi_row0 + UWI_ROW_DP);
#undef UWI_LOAD
  *out = v;
}

/* The source's weights of the three exponentials (uwi_source_weight) towards one photon direction:
 * node from uwi_source_node (once per pixel), cos_dphi from uwi_cos_azimuth. */
typedef struct {
  realb w1, w2, wp; /* of e^{-k y}, e^{-k (H - y)}, e^{-m y} */
} UwiWeights;

SEASIM_FN void uwi_lanes_weights(const SEASIM_GLOBAL float* table, int stride, int uwi_row0, int i, int node,
                                 real cos_dphi, UwiWeights* out) {
  const int row = uwi_row0 + UWI_ROW_SRC + node * UWI_SOURCE_TERMS;
#define UWI_TERM(q) LOADB(table + (size_t)(row + (q)) * (size_t)stride, i)
  const real cos_2dphi = R(2.0) * cos_dphi * cos_dphi - R(1.0);
  UwiWeights w;
  w.w1 = UWI_TERM(0) + cos_dphi * UWI_TERM(3) + cos_2dphi * UWI_TERM(6);
  w.w2 = UWI_TERM(1) + cos_dphi * UWI_TERM(4) + cos_2dphi * UWI_TERM(7);
  w.wp = UWI_TERM(2) + cos_dphi * UWI_TERM(5) + cos_2dphi * UWI_TERM(8);
#undef UWI_TERM
  *out = w;
}

/* uwi_multiple_sand's weights: the sand's part of the source at the node (UwiBand.src_sand) times the
 * irradiance whose light the shares v_sand and v_diffuse (uwi_sand_shares, once per pixel) leave out
 * (uwi_sand_lost) taken off w. */
SEASIM_FN void uwi_lanes_hide_sand(const SEASIM_GLOBAL float* table, int stride, int uwi_row0, int i, int node,
                                   real v_sand, real v_diffuse, UwiWeights* w) {
  const realb lost = (R(1.0) - v_sand) * LOADB(table + (size_t)(uwi_row0 + UWI_ROW_SAND_BEAM) * (size_t)stride, i) +
                     (R(1.0) - v_diffuse) * LOADB(table + (size_t)(uwi_row0 + UWI_ROW_SAND_DIFFUSE) * (size_t)stride, i);
  const SEASIM_GLOBAL float* row = table + (size_t)(uwi_row0 + UWI_ROW_SRC_SAND + 3 * node) * (size_t)stride;
  w->w1 -= lost * LOADB(row, i);
  w->w2 -= lost * LOADB(row + stride, i);
  w->wp -= lost * LOADB(row + 2 * (size_t)stride, i);
}

/* The diffuse irradiance's weights of the three exponentials on a tilted plane (uwi_tilt_irradiance):
 * node and frac from uwi_tilt_node of the normal's n_y, cos_phi = uwi_cos_azimuth(n·s_w, n_y, μ_w) and vis_b
 * (uwi_bottom_visibility) once per pixel; the table's two nodes interpolated. */
SEASIM_FN void uwi_lanes_tilt(const SEASIM_GLOBAL float* table, int stride, int uwi_row0, int i, int node,
                              real frac, real cos_phi, real vis_b, UwiWeights* out) {
  const int row_b = uwi_row0 + UWI_ROW_TILT_BOTTOM + node * 3;
  const int row = uwi_row0 + UWI_ROW_TILT + node * UWI_SOURCE_TERMS;
#define UWI_TILT(q) LOADB(table + (size_t)(row + (q)) * (size_t)stride, i)
  const real cos_2phi = R(2.0) * cos_phi * cos_phi - R(1.0);
  realb t[3];
  for (int q = 0; q < 3; ++q) {
    const realb a = UWI_TILT(q) + cos_phi * UWI_TILT(q + 3) + cos_2phi * UWI_TILT(q + 6);
    const realb b = UWI_TILT(q + UWI_SOURCE_TERMS) + cos_phi * UWI_TILT(q + UWI_SOURCE_TERMS + 3) +
                    cos_2phi * UWI_TILT(q + UWI_SOURCE_TERMS + 6);
    const realb lit_a = LOADB(table + (size_t)(row_b + q) * (size_t)stride, i);
    const realb lit = lit_a + frac * (LOADB(table + (size_t)(row_b + 3 + q) * (size_t)stride, i) - lit_a);
    t[q] = a + frac * (b - a) - (R(1.0) - vis_b) * lit;
  }
#undef UWI_TILT
  UwiWeights w;
  w.w1 = t[0];
  w.w2 = t[1];
  w.wp = t[2];
  *out = w;
}

/* The same for a plane facing straight up (the bottom): E_d's coefficients, which are the tilted table's
 * top node. */
SEASIM_FN void uwi_lanes_down(const UwiLanes* v, UwiWeights* out) {
  UwiWeights w;
  w.w1 = v->d1;
  w.w2 = v->d2;
  w.wp = v->dp;
  *out = w;
}

/* The start factors e^{-κ o_d} of the integrals along a ray that starts at depth o_d, per band. */
typedef struct {
  realb k, m, beam; /* e^{-k o_d}, e^{-m o_d}, e^{-(σ_t/μ_w) o_d} */
  realb k_bottom;   /* e^{-k max(H - o_d, 0)}: the bottom's term, integrated from the bottom */
} UwiStart;

/* The camera's (o_d = -cam_pos[1]): the table's per-frame rows. */
SEASIM_FN void uwi_start_camera(const SEASIM_GLOBAL float* table, int stride, int uwi_row0, int i, UwiStart* out) {
  UwiStart a;
  a.k = LOADB(table + (size_t)(uwi_row0 + UWI_ROW_EXP_K_OD) * (size_t)stride, i);
  a.m = LOADB(table + (size_t)(uwi_row0 + UWI_ROW_EXP_M_OD) * (size_t)stride, i);
  a.beam = LOADB(table + (size_t)(uwi_row0 + UWI_ROW_EXP_BEAM_OD) * (size_t)stride, i);
  a.k_bottom = LOADB(table + (size_t)(uwi_row0 + UWI_ROW_EXP_K_HOD) * (size_t)stride, i);
  *out = a;
}

/* The far ends of a ray's integrals, at distance S and depth y = max(y(S), 0) (T(S) = e^{-c' S} folded
 * in as underwater_bands.h does for the thesis; the clamps at 0 commute with the positive factor). */
typedef struct {
  realb k, m;     /* e^{-(k y + c' S)}, e^{-(m y + c' S)} */
  realb k_bottom; /* e^{-(k max(H - y, 0) + c' S)} with a bottom, else 0 */
  realb beam;     /* e^{-((σ_t/μ_w) y + σ_t S)} with the froxel term (single_scattering), else 0 */
} UwiEnds;

/* uwi_irradiance's exps at the end of the ray, times T(S): a Lambertian hit's and the integrals' far
 * ends alike. S = UW_INFINITE with y = its depth there: all 0 (deep water). */
SEASIM_FN void uwi_ends(const UwiLanes* v, real bottom_depth, real S, real y, int single_scattering, UwiEnds* out) {
  UwiEnds e;
  const realb c_s = v->c_dm * S;
  e.k = exp(-(v->k * y + c_s));
  e.m = exp(-(v->m * y + c_s));
  e.k_bottom = bottom_depth > R(0.0) ? exp(-(v->k * fmax(bottom_depth - y, R(0.0)) + c_s)) : SPLATB(R(0.0));
  e.beam = single_scattering ? exp(-(v->k_beam * y + v->c * S)) : SPLATB(R(0.0));
  *out = e;
}

/* uwi_multiple: in-scattered radiance along the ray (d_y) to distance S (UW_INFINITE: deep water),
 * w the source's weights towards the ray's photon (uwi_lanes_weights), phase = p_HG(g, d·s_w) of the
 * pixel, a the ray's start factors, e its far ends (uwi_ends with the same single_scattering). Each term
 * of J(y) an exponential in y, so each integral is kd_exp_integral_ends_b (002 eq. 4.7's form); with
 * single_scattering the froxel pass's unshadowed strict single scattering b p_HG e_beam0 ∫ e^{-c z}
 * e^{-(c/μ_w) y(z)} dz (002 eq. 5.2) is taken off below the peak (min(p_HG, p_clip), as the TMS term; the
 * rest is uwi_lanes_forward_peak's), and *strict is b e_beam0 ∫ e^{-c z} e^{-(c/μ_w) y(z)} dz (0 without). */
SEASIM_FN realb uwi_lanes_multiple(const UwiLanes* v, const UwiWeights* w, const UwiStart* a, const UwiEnds* e,
                                   real phase, real bottom_depth, real S, real d_y, int single_scattering,
                                   realb* strict) {
  const realb tms = v->b_e_beam * fmin(SPLATB(phase), v->p_clip); /* uwi_tms_phase */
  realb sum = w->w1 * kd_exp_integral_ends_b(v->k, v->c_dm, a->k, e->k, d_y, S) +
              (w->wp + tms) * kd_exp_integral_ends_b(v->m, v->c_dm, a->m, e->m, d_y, S);
  if (bottom_depth > R(0.0)) {
    /* e^{-k (H - y(z))} = e^{-k (H - o_d)} e^{-k d_y z}: the same integral seen from the bottom. */
    sum += w->w2 * kd_exp_integral_ends_b(v->k, v->c_dm, a->k_bottom, e->k_bottom, -d_y, S);
  }
  *strict = SPLATB(R(0.0));
  if (single_scattering) {
    *strict = v->b_e_beam * kd_exp_integral_ends_b(v->k_beam, v->c, a->beam, e->beam, d_y, S);
    sum -= fmin(SPLATB(phase), v->p_clip) * *strict;
  }
  return fmax(sum, R(0.0));
}

/* uwi_forward_peak for these bands: the aureole (uwi_aureole; d_y > 0, node and frac from uwi_aureole_node of
 * the pixel's cos_s, source_node uwi_source_node of d_y and cos_dphi the azimuth's cosine there
 * (uwi_cos_azimuth), y_c the camera's depth and y1 where the ray ends, each once per pixel) less strict
 * (uwi_lanes_multiple's: b e_beam0 times the strict single scattering's integral, 0 without froxels) times the
 * peak's excess (p_HG - p_clip)+. The aureole's share is 1 at the surface (y1 = 0), where the per-band exps
 * are skipped. Not clamped: the caller clamps its sum with uwi_lanes_multiple's. */
SEASIM_FN realb uwi_lanes_forward_peak(const SEASIM_GLOBAL float* table, int stride, int uwi_row0, int i,
                                       const UwiLanes* v, int node, real frac, int source_node, real cos_dphi,
                                       real phase, real d_y, real y_c, real y1, real mu_w, realb strict) {
  const realb excess = fmax(SPLATB(phase) - v->p_clip, SPLATB(R(0.0)));
  if (!(d_y > R(0.0)) || !(y_c > y1)) return -strict * excess;
  const SEASIM_GLOBAL float* row = table + (size_t)(uwi_row0 + UWI_ROW_AUREOLE + node) * (size_t)stride;
  const realb a0 = LOADB(row, i), a1 = LOADB(row + stride, i);
  const SEASIM_GLOBAL float* held = table + (size_t)(uwi_row0 + UWI_ROW_AUREOLE_M + 3 * source_node) * (size_t)stride;
  realb light = LOADB(table + (size_t)(uwi_row0 + UWI_ROW_AUREOLE_1) * (size_t)stride, i) * excess + a0 +
                frac * (a1 - a0) -
                (LOADB(held, i) + cos_dphi * LOADB(held + stride, i) +
                 (R(2.0) * cos_dphi * cos_dphi - R(1.0)) * LOADB(held + 2 * (size_t)stride, i));
  if (y1 > R(0.0)) {
    /* uwi_aureole_share, on the lanes. */
    const realb q = fmax(v->c - v->c_dm, SPLATB(R(0.0))) / fmax(mu_w, R(1e-4));
    const realb den = -expm1(-q * y_c);
    light *= SELECTB(den > SPLATB(R(1e-6)), exp(-q * y1) * -expm1(-q * (y_c - y1)) / den,
                     SPLATB((y_c - y1) / y_c));
  }
  return light - strict * excess;
}

/* uwi_lambert times T(S) = e^{-c' S}: a Lambertian hit (albedo, n_dot_s = n·s_w) at distance S and depth
 * y lit by the diffuse field on its plane (tilt: uwi_lanes_tilt, or uwi_lanes_down for the bottom) and the
 * delta-M beam times vis; e = uwi_ends(v, bottom_depth, S, y, …): its exps. */
SEASIM_FN realb uwi_lanes_lambert(const UwiLanes* v, const UwiEnds* e, const UwiWeights* tilt, realb albedo,
                                  real bottom_depth, real n_dot_s, real vis) {
  realb diffuse = tilt->w1 * e->k + tilt->wp * e->m;
  if (bottom_depth > R(0.0)) diffuse += tilt->w2 * e->k_bottom;
  const realb beam = v->e_beam * e->m * (fmax(n_dot_s, R(0.0)) * vis);
  return albedo / SEASIM_PI * (fmax(diffuse, R(0.0)) + beam);
}

/* uwi_surface times T(S): the surface seen from below along d (d_y = d.y > 0) at distance S: the sky
 * through Snell's window (sky_l, the lanes' sky radiance in air along the refracted view) plus F times
 * the reflected ray's in-scatter (phase_r = p_HG(g, cos of the reflected ray with s_w), w_r the source's
 * weights towards its photon) down to the
 * bottom, and the bottom itself (bottom_l: UWI_ROW_BOTTOM_L, its sunlit radiance), or deep water.
 * t_s: T(S) = e^{-c' S}, which is the camera ray's far end e^{-(k y + c' S)} at the surface (y = 0:
 * uwi_ends' k). exp_k_h:
 * e^{-k H} (UWI_ROW_EXP_K_H), the reflected ray's start factor of the bottom's
 * term; the others are 1 at o_d = 0. The reflected ray keeps its single scattering (no froxel term
 * taken off: the froxel pass runs along the camera's ray only), as uwi_surface.
 * An object in the mirror (uwi_surface's UwiMirrorHit, traced once per pixel by the caller): its
 * distance s_m from the surface (UW_INFINITE: none), albedo_m in these bands, the diffuse light on its plane
 * tilt_m (uwi_lanes_tilt of its normal; unread without one),
 * n_m_dot_s = n·s_w and the sun's visibility vis_m; the reflected ray's integrals then end on it, and its
 * Lambert hit shares their far ends (no more exps than the bottom's case). */
SEASIM_FN realb uwi_lanes_surface(const UwiLanes* v, const UwiWeights* w_r, realb t_s, realb sky_l, realb bottom_l,
                                  realb exp_k_h, real phase_r, real bottom_depth, real d_y, real ior, int multiple, real s_m,
                                  realb albedo_m, const UwiWeights* tilt_m, real n_m_dot_s, real vis_m) {
  const real dy = fmax(d_y, R(1e-6));
  const real s_r = bottom_depth > R(0.0) ? bottom_depth / dy : UW_INFINITE;
  realb reflected = SPLATB(R(0.0));
  /* The bottom's attenuation along the reflected ray, e^{-c' min(s_r, 1e4)} as uwi_surface takes it. */
  realb t_bottom = SPLATB(R(0.0));
  UwiStart a;
  a.k = SPLATB(R(1.0));
  a.m = SPLATB(R(1.0));
  a.beam = SPLATB(R(1.0));
  a.k_bottom = exp_k_h;
  if (s_m < s_r) { /* per pixel: an object in the mirror, at depth s_m dy */
    UwiEnds e;
    uwi_ends(v, bottom_depth, s_m, s_m * dy, 0, &e);
    reflected = uwi_lanes_lambert(v, &e, tilt_m, albedo_m, bottom_depth, n_m_dot_s, vis_m);
    realb unused;
    if (multiple) reflected += uwi_lanes_multiple(v, w_r, &a, &e, phase_r, bottom_depth, s_m, -dy, 0, &unused);
  } else if (multiple) {
    /* It ends on the bottom (y = H) or in deep water (S, y = ∞: its ends 0). */
    UwiEnds e;
    uwi_ends(v, bottom_depth, s_r, bottom_depth > R(0.0) ? bottom_depth : UW_INFINITE, 0, &e);
    realb unused;
    reflected = uwi_lanes_multiple(v, w_r, &a, &e, phase_r, bottom_depth, s_r, -dy, 0, &unused);
    /* Its far end e^{-(k (H - y) + c' s_r)} at y = H: the same but past s_r = 1e4 (within H/1e4 of
     * the horizon), where both are e^{-c' 1e4} or less. */
    t_bottom = e.k_bottom;
  } else if (bottom_depth > R(0.0)) {
    t_bottom = exp(-v->c_dm * fmin(s_r, R(1e4)));
  }
  if (bottom_depth > R(0.0) && !(s_m < s_r)) reflected += t_bottom * bottom_l;
  const real f = fresnel_reflectance(d_y, ior, R(1.0));
  return t_s * (ior * ior * (R(1.0) - f) * sky_l + f * reflected);
}
