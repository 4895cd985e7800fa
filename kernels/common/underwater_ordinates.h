/* underwater_ordinates.h — underwater.model = "discrete_ordinates": a closed form per band for the light that
 * 002's eq. 4.7 ("thesis", common/underwater.h) models by an isotropic b/(4π) E(y) with a measured K_d.
 * The scalar form, one band per call: the host's (kmath_f / kmath_d, unit-tested in float and double)
 * and the reference that kd_multiple.cl's band lanes (SEASIM_UNDERWATER_MODEL == 1,
 * common/underwater_ordinates_bands.h) are tested against; needs optics.h, underwater_params.h, underwater.h and
 * underwater_ordinates_params.h before it. Coefficients per band: host/underwater/underwater_ordinates_solver.*
 * (and underwater_ordinates_setup.* for the two-stream)
 *
 * What it changes against eq. 4.7, each measured in results/BENCHMARKS.md ("A better fast underwater
 * model"):
 *  - delta-M scaling (Wiscombe 1977; the maths of quality.lamps_delta_m): the phase function's forward
 *    peak f counts as unscattered, b' = b (1 - f), c' = a + b'. Light turned by a few degrees goes on:
 *    view rays, surfaces and the sun beam (e^{-m y}, m = c'/μ_w) are attenuated by c', not c. With the
 *    discrete ordinates (the default) f = g³, their delta-M order (kOrdinatesSourceMoments: the one
 *    number fitted to the path tracer); with the two-stream f = g², g' = g / (1 + g).
 *  - the diffuse field from the IOPs and g, not a measured K_d, built on the host per band and frame
 *    (underwater.diffuse): by default ("discrete_ordinates", host/underwater/
 *    underwater_ordinates_solver.*) a discrete-ordinates solution of the plane-parallel water (16
 *    streams per hemisphere, the HG phase delta-M scaled to its first three Legendre moments, the sun
 *    beam and the sky through the Fresnel surface, a Lambertian bottom of albedo ρ) whose plane
 *    irradiances E_d, E_u are fitted to three exponentials in depth: e^{-k y}, e^{-k (H - y)} and the
 *    beam's e^{-m y}. Or ("two_stream") a two-stream solution over the bottom (quadrature
 *    coefficients γ1 = √3 (2 - ω'(1 + g'))/2, γ2 = √3 ω'(1 - g')/2, the beam's split
 *    γ3 = (2 - 3 g' μ_w)/4, γ4 = 1 - γ3; k the mean slope over the camera's depth of its mode plus a
 *    fitted share of e^{-K∞ y}, depthMeanDiffuseK). Either way the bottom's upwelling light lights the
 *    water and the objects' undersides.
 *  - the in-scatter source J(y, ν, Δφ) that view rays gather, tabulated per band in the photon's
 *    direction (UwiBand.src, common/underwater_ordinates_params.h: ν its cosine with the downward
 *    vertical, Δφ its azimuth from the sun beam's, uwi_cos_azimuth), per exponential of depth. By default
 *    (underwater.source_streams; host/underwater/ordinates_high_order.h) fitted on the host
 *    to the light a 32-stream solution's radiance gathers along rays with this kernel's c' (the kernel
 *    reads it as any table), but within 10-20° of the beam's polar angle, where it stays, as without that fit,
 *    the discrete ordinates' own in-scatter: their three-term phase against their radiance in azimuth
 *    modes 0, 1 and 2 (all that phase scatters into) at 129 cosines (a ray reads the nearest), fitted per cosine to the same three
 *    exponentials: DISORT's intensities at user angles (the source-function integration of Stamnes et
 *    al. 1988), exact in that frame but for the fit. Measured (docs/journal/underwater_regions_3_*.md): the
 *    first-order phase 1 + 3 g' cos Θ it replaces goes negative backwards for g' > 1/3, and the water
 *    looking up at g >= 0.9 (the surface mirroring upwelling light) came out 0.89–0.95 of the path
 *    tracer; the solver's full order (f = g^32) leaves light scattered by a few degrees in its field,
 *    whose in-scatter two azimuth modes could not hold (level views 1.13–1.19 at g = 0.9).
 *    The two-stream keeps the first-order source b' [E_0 + 3 g_f ν (E_d - E_u)]/(4π) (E_0 from fitted
 *    mean cosines, diffuseMeanCosines; g_f = s g', diffuseFluxScale) in the same table (exact at the
 *    nodes; within half a node's step of ν, 1/128, between them).
 *    Plus the beam scattered once with the exact phase function (Nakajima & Tanaka 1988's TMS
 *    correction: delta-M's truncated phase would overstate the back-scatter), b p_HG(g, cos θ_s)
 *    e_beam0 e^{-m y}, attenuated as the delta-M beam; with p_HG capped below its forward peak
 *    (uwi_tms_phase), whose light the delta-M beam already carries and uwi_aureole draws at the camera.
 *  - an object's face lit by the diffuse field's irradiance on its own plane (uwi_tilt_irradiance: the
 *    solver's radiance in azimuth modes 0-2 over the half-space the face sees, tabulated per band in the
 *    normal's vertical, UwiBand.tilt), not by uniform hemispheres E_d (1 + n_y)/2 + E_u (1 - n_y)/2 (the
 *    two-stream's table still is); less the light of the sunlit bottom where the sand the face sees is in
 *    shadow (uwi_bottom_visibility, UwiBand.tilt_bottom). Measured (docs/journal/underwater_regions_3_*.md).
 *  - when the froxel pass adds the strict single scattering b p_HG(g) of the beam e^{-c y/μ_w} (002 eq.
 *    5.2), that term's unshadowed closed form is taken off here, so the sum is the model's total.
 * Along a view ray (depth y(z) = o_d - z d_y; the photon towards the camera has ν = d_y):
 *   L = e^{-c' S} L_s + ∫_0^S e^{-c' z} J(y(z)) dz,
 * every term of J an exponential in y, so each integral is kd_exp_integral (common/underwater.h): four
 * per band with froxels (three without), where eq. 4.7 takes two.
 */

/* The source table's node nearest the downward cosine nu (clamped to [-1, 1]). */
SEASIM_FN int uwi_source_node(real nu) {
  const real t = clamp((nu + R(1.0)) * R(0.5) * (real)(UWI_SOURCE_NODES - 1) + R(0.5), R(0.0),
                       (real)(UWI_SOURCE_NODES - 1));
  const int node = (int)t;
  return node < UWI_SOURCE_NODES - 1 ? node : UWI_SOURCE_NODES - 1;
}

/* The downward cosine of the table's node: the nodes are evenly spaced from -1 to 1. */
SEASIM_FN real uwi_source_node_cosine(int node) {
  return R(-1.0) + R(2.0) * (real)node / (real)(UWI_SOURCE_NODES - 1);
}

/* The source of exponential q (0: e^{-k y}, 1: e^{-k (H - y)}, 2: e^{-m y}) towards the photon
 * direction of the table's node (uwi_source_node), cos_dphi its azimuth's cosine from the sun beam's
 * (uwi_cos_azimuth), per m per sr per unit of the exponential: the azimuth modes 0, 1, 2. */
SEASIM_FN real uwi_source_weight(const SEASIM_GLOBAL UwiBand* ib, int node, real cos_dphi, int q) {
  const SEASIM_GLOBAL float* t = ib->src + node * UWI_SOURCE_TERMS;
  return (real)t[q] + cos_dphi * (real)t[q + 3] + (R(2.0) * cos_dphi * cos_dphi - R(1.0)) * (real)t[q + 6];
}

/* cos Δφ of a photon direction (downward cosine ν, cosine cos_s with the sun beam's direction of downward
 * cosine mu_w), Δφ its azimuth from the beam's: (cos_s - ν mu_w) / √((1 - ν²)(1 - mu_w²)), clamped to
 * [-1, 1]; 0 for a photon or a sun within about 0.1° of the vertical, where the table's cos Δφ part
 * vanishes (its Legendre functions P_l^1 go as √(1 - ν²)) or the field has none. */
SEASIM_FN real uwi_cos_azimuth(real cos_s, real nu, real mu_w) {
  const real s_nu = R(1.0) - nu * nu, s_w = R(1.0) - mu_w * mu_w;
  return s_nu > R(3e-6) && s_w > R(3e-6) ? clamp((cos_s - nu * mu_w) / sqrt(s_nu * s_w), R(-1.0), R(1.0)) : R(0.0);
}

/* The tilted plane's table (UwiBand.tilt): the node below the normal's upward vertical n_y (clamped to
 * [-1, 1]), at most UWI_TILT_NODES - 2, and n_y's fraction of the way to the next, in [0, 1]. */
SEASIM_FN int uwi_tilt_node(real n_y, real* frac) {
  const real t = clamp((n_y + R(1.0)) * R(0.5) * (real)(UWI_TILT_NODES - 1), R(0.0), (real)(UWI_TILT_NODES - 1));
  const int node = (int)t < UWI_TILT_NODES - 2 ? (int)t : UWI_TILT_NODES - 2;
  *frac = t - (real)node;
  return node;
}

/* The upward vertical of the tilted plane table's node's normal: evenly spaced from -1 to 1. */
SEASIM_FN real uwi_tilt_node_cosine(int node) {
  return R(-1.0) + R(2.0) * (real)node / (real)(UWI_TILT_NODES - 1);
}

/* The diffuse irradiance on a plane of unit normal n at depth y (the table UwiBand.tilt: azimuth modes
 * 0-2 in the azimuth φ_n of -n from the sun beam's, whose cosine is uwi_cos_azimuth of -n's downward
 * cosine n.y and its cosine n·s_w with the beam), not clamped. Light from above and below a plane that is
 * not horizontal, weighed by the field's own angular distribution: the discrete ordinates' near the surface
 * is Snell's window's cone and the forward-scattered beam, which a vertical face sees far less of than the
 * half of E_d that uniform hemispheres give it. vis_b (uwi_bottom_visibility, the share of the sand the
 * face sees that is sunlit): 1 - vis_b of the light the sunlit bottom brings (UwiBand.tilt_bottom) is taken
 * off. */
SEASIM_FN real uwi_tilt_irradiance(const SEASIM_GLOBAL UwiBand* ib, real bottom_depth, real y, real3 n, real3 s_w,
                                   real vis_b) {
  real frac;
  const int node = uwi_tilt_node(n.y, &frac);
  const real cos_phi = uwi_cos_azimuth(dot(n, s_w), n.y, s_w.y);
  const real cos_2phi = R(2.0) * cos_phi * cos_phi - R(1.0);
  const SEASIM_GLOBAL float* t0 = ib->tilt + node * UWI_SOURCE_TERMS;
  const SEASIM_GLOBAL float* t1 = t0 + UWI_SOURCE_TERMS;
  const SEASIM_GLOBAL float* b0 = ib->tilt_bottom + node * 3;
  const real e[3] = {exp(-(real)ib->k * y),
                     /* Selected, not branched: without a bottom the term is 0 and its exponent kept <= 0. */
                     bottom_depth > R(0.0) ? exp(-(real)ib->k * fmax(bottom_depth - y, R(0.0))) : R(0.0),
                     exp(-(real)ib->m * y)};
  real sum = R(0.0);
  for (int q = 0; q < 3; ++q) {
    const real a = (real)t0[q] + cos_phi * (real)t0[q + 3] + cos_2phi * (real)t0[q + 6];
    const real b = (real)t1[q] + cos_phi * (real)t1[q + 3] + cos_2phi * (real)t1[q + 6];
    const real lit = (real)b0[q] + frac * ((real)b0[q + 3] - (real)b0[q]);
    sum += (a + frac * (b - a) - (R(1.0) - vis_b) * lit) * e[q];
  }
  return sum;
}

#define UWI_BOTTOM_RAYS 8

/* cos and sin of the golden angle π(3 − √5): the rays' azimuths k × that angle advance by this rotation,
 * without a sin and cos per ray (PoCL's reduction of their growing arguments cost a sixth of sand_share). */
#define UWI_GOLDEN_COS R(-0.7373688780783201)
#define UWI_GOLDEN_SIN R(0.6754902942615235)
SEASIM_FN void uwi_golden_advance(real* c, real* s) {
  const real c1 = *c * UWI_GOLDEN_COS - *s * UWI_GOLDEN_SIN;
  *s = *s * UWI_GOLDEN_COS + *c * UWI_GOLDEN_SIN;
  *c = c1;
}

/* Ray k of n cosine-weighted about a unit axis, in that axis's frame: (r cos φ, √(1 − u), r sin φ) with u = (k +
 * 1/2)/n, r = √u and (cos φ, sin φ) the ray's azimuth (k × the golden angle: uwi_golden_advance); y along the
 * axis. */
SEASIM_FN real3 uwi_cosine_ray(int k, int n, real cos_phi, real sin_phi) {
  const real u = ((real)k + R(0.5)) / (real)n;
  const real r = sqrt(u);
  return MAKE_REAL3(r * cos_phi, sqrt(R(1.0) - u), r * sin_phi);
}

/* The share of the bottom that a face at p (unit normal n) sees that is sunlit, in [0, 1]: UWI_BOTTOM_RAYS
 * rays from p, cosine-weighted about n (a fixed golden-angle pattern in the face's tangent frame, as a
 * Lambertian face weighs what it sees), and of those going down, the share whose sand a shadow ray finds
 * lit (a ray that meets an object first sees no sand, and the object is darker: 0). 1 without a bottom or
 * when no ray goes down (a face looking up sees no bottom). The model's diffuse field is the plane-parallel
 * water's, whose bottom is sunlit everywhere; the objects shade the sand next to them, which their own lower
 * faces see. Measured (docs/journal/underwater_regions_3_*.md): the objects in clear water over sand
 * were 1.04–1.06 of the path tracer with that light, 0.99–1.00 over a black bottom. Eight rays give the
 * shadow's edge on a face nine steps where the true one is soft (one ray drew it hard). */
SEASIM_FN real uwi_bottom_visibility(const SEASIM_GLOBAL UwObject* objects, int count, real bottom_depth, real3 p,
                                     real3 n, real3 s_w) {
  if (!(bottom_depth > R(0.0))) return R(1.0);
  /* A tangent frame (t, b, n): t from the axis least aligned with n. */
  const real3 axis = fabs(n.x) < R(0.9) ? MAKE_REAL3(1, 0, 0) : MAKE_REAL3(0, 0, 1);
  const real3 t = normalize(cross(axis, n));
  const real3 b = cross(n, t);
  const real3 o = p + R(1e-3) * n;
  real lit = R(0.0), down = R(0.0);
  real cos_phi = R(1.0), sin_phi = R(0.0); /* azimuth k × the golden angle */
  for (int k = 0; k < UWI_BOTTOM_RAYS; ++k) {
    const real3 l = uwi_cosine_ray(k, UWI_BOTTOM_RAYS, cos_phi, sin_phi);
    const real3 d = l.x * t + l.z * b + l.y * n;
    uwi_golden_advance(&cos_phi, &sin_phi);
    if (!(d.y < R(0.0))) continue;
    down += R(1.0);
    real3 nb = MAKE_REAL3(0, 1, 0);
    int mat = UW_MAT_NONE;
    const real s = uw_scene_hit(objects, count, bottom_depth, o, d, R(0.0), &nb, &mat);
    if (mat == UW_MAT_BOTTOM) lit += uw_sun_visibility(objects, count, o + s * d, MAKE_REAL3(0, 1, 0), s_w);
  }
  return down > R(0.0) ? lit / down : R(1.0);
}

/* E_d(y) and E_u(y), the diffuse plane irradiances at depth y (common/underwater_ordinates_params.h),
 * not clamped (the host's solution is positive; callers clamp what they shade with). */
SEASIM_FN void uwi_irradiance(const SEASIM_GLOBAL UwiBand* ib, real bottom_depth, real y, real* ed, real* eu) {
  const real e1 = exp(-(real)ib->k * y);
  /* Selected, not branched: without a bottom d2 = u2 = 0 and the exponent is kept at <= 0. */
  const real e2 = bottom_depth > R(0.0) ? exp(-(real)ib->k * fmax(bottom_depth - y, R(0.0))) : R(0.0);
  const real ep = exp(-(real)ib->m * y);
  *ed = (real)ib->d1 * e1 + (real)ib->d2 * e2 + (real)ib->dp * ep;
  *eu = (real)ib->u1 * e1 + (real)ib->u2 * e2 + (real)ib->up * ep;
}

/* The phase the TMS term scatters the delta-M beam with: p_HG capped at ib->p_clip, whose part above
 * the cap holds delta-M's f (host/underwater/forward_peak.h). The delta-M beam e^{-m y} already carries
 * that peak's light (its surplus over the unscattered beam, F0 (e^{-c' y/μ_w} - e^{-c y/μ_w})); scattered
 * once more with the whole p_HG, the light looking towards the sun was counted twice: measured
 * (docs/journal/underwater_regions_4_*.md), the water looking at the refracted sun at g >= 0.9 came out 1.26-2.66
 * of the path tracer. uwi_aureole draws the peak's light instead. p_clip <= 0: no cap. */
SEASIM_FN real uwi_tms_phase(real phase, real p_clip) {
  return p_clip > R(0.0) ? fmin(phase, p_clip) : phase;
}

/* The aureole table's node below the scattering angle θ = acos(cos_s) (nodes at θ_j = π t_j², t_j = j /
 * (UWI_AUREOLE_NODES - 1): a twentieth of a degree apart at the sun, where the peak is sharpest, 5.6° at
 * the back) and θ's fraction of the way to the next, in [0, 1]. */
SEASIM_FN int uwi_aureole_node(real cos_s, real* frac) {
  const real theta = acos(clamp(cos_s, R(-1.0), R(1.0)));
  const real t = clamp(sqrt(theta / SEASIM_PI), R(0.0), R(1.0)) * (real)(UWI_AUREOLE_NODES - 1);
  const int node = (int)t < UWI_AUREOLE_NODES - 2 ? (int)t : UWI_AUREOLE_NODES - 2;
  *frac = clamp(t - (real)node, R(0.0), R(1.0));
  return node;
}

/* The scattering angle of the aureole table's node, radians. */
SEASIM_FN real uwi_aureole_node_angle(int node) {
  const real t = (real)node / (real)(UWI_AUREOLE_NODES - 1);
  return SEASIM_PI * t * t;
}

/* The share of the aureole at the camera (depth y_c) that a view ray looking up and ending at depth y1 <=
 * y_c (an object; 0 at the surface) sees: the light whose first scattering by the peak was below y1,
 * (e^{-q y1} - e^{-q y_c}) / (1 - e^{-q y_c}), q = (c - c') / μ_w the peak's scatterings per metre of depth
 * (the rest met the object on its way); (y_c - y1) / y_c as q y_c -> 0. 1 at y1 = 0, 0 at y1 = y_c. */
SEASIM_FN real uwi_aureole_share(real q, real y_c, real y1) {
  if (!(y_c > R(0.0))) return R(0.0);
  const real y = clamp(y1, R(0.0), y_c);
  const real den = -expm1(-q * y_c);
  return den > R(1e-6) ? exp(-q * y) * -expm1(-q * (y_c - y)) / den : (y_c - y) / y_c;
}

/* The forward peak's light at the camera towards a view ray d (d_y > 0: looking up; cos_s = d·s_w, phase =
 * p_HG(g, cos_s)) that ends at depth y1 (the surface: 0): the light of the delta-M beam that delta-M counts
 * as unscattered but the peak turned (host/underwater/forward_peak.h). At the camera's depth y_c that
 * light is F0 e^{-c' y_c/μ_w} Σ_{k>=1} Poisson(k; n) P_k(θ), n = (c - c') y_c/μ_w its mean count of
 * scatterings by the peak (each turns the light by the peak's own distribution, independently): P_1 the peak
 * (p_HG - p_clip)+ / f itself, P_k for k >= 2 the peak convolved k times on the sphere (its Legendre moments
 * to the k-th power; host/underwater/forward_peak.h sums the series). The host tabulates the light scattered
 * twice or more per band for the camera's depth (UwiBand.aureole; the once-scattered part is aureole_single
 * times the pixel's (p_HG - p_clip)+); uwi_aureole_share takes off
 * what an object in front of the sun hides. 0 looking down. uwi_aureole_at_camera is that light whole;
 * uwi_aureole less the azimuth modes 0-2 of it that the source's table already holds at the ray's node
 * (UwiBand.aureole_modes): away from the beam's polar angle the table is fitted to a high-order field, which
 * has the peak's light, in those modes only. Measured (docs/journal/underwater_regions_5_*.md): with the aureole left
 * out there, the peak's light lost its azimuthal shape (the table has three modes): 0.73-1.18 of the path
 * tracer around the sun at g >= 0.9; taken off the fit's targets instead, the kernel was 2.4-3.5 % off that
 * field 30-70° from the beam in turbid water at g = 0.95 (three exponentials in depth cannot follow its
 * depth). */
SEASIM_FN real uwi_aureole_at_camera(const SEASIM_GLOBAL UwiBand* ib, real phase, real cos_s, real d_y) {
  if (!(d_y > R(0.0)) || !(ib->p_clip > R(0.0))) return R(0.0);
  real frac;
  const int node = uwi_aureole_node(cos_s, &frac);
  const real a0 = (real)ib->aureole[node], a1 = (real)ib->aureole[node + 1];
  return (real)ib->aureole_single * fmax(phase - (real)ib->p_clip, R(0.0)) + a0 + frac * (a1 - a0);
}

SEASIM_FN real uwi_aureole(const SEASIM_GLOBAL UwiBand* ib, const SEASIM_GLOBAL UwBand* band, real phase, real cos_s,
                           real d_y, real y_c, real y1, real mu_w) {
  if (!(d_y > R(0.0)) || !(ib->p_clip > R(0.0))) return R(0.0);
  const SEASIM_GLOBAL float* held = ib->aureole_modes + 3 * uwi_source_node(d_y);
  const real cos_dphi = uwi_cos_azimuth(cos_s, d_y, mu_w);
  const real light = uwi_aureole_at_camera(ib, phase, cos_s, d_y) -
                     ((real)held[0] + cos_dphi * (real)held[1] + (R(2.0) * cos_dphi * cos_dphi - R(1.0)) * (real)held[2]);
  const real q = fmax((real)band->c - (real)ib->c_dm, R(0.0)) / fmax(mu_w, R(1e-4));
  return light * uwi_aureole_share(q, y_c, y1);
}

#define UWI_SAND_POINTS 2
#define UWI_SAND_RAYS 4

/* The share of n up-rays from x, cosine-weighted about the upward vertical (the golden-angle pattern of
 * uwi_bottom_visibility), that no object stops: the light from above a point of the water or of the sand
 * gets where the objects do not hold it off. */
SEASIM_FN real uwi_open_above(const SEASIM_GLOBAL UwObject* objects, int count, real bottom_depth, real3 x, int n) {
  real cos_phi = R(1.0), sin_phi = R(0.0); /* azimuth ray × the golden angle */
  int open = 0;
  for (int ray = 0; ray < n; ++ray) {
    const real3 up = uwi_cosine_ray(ray, n, cos_phi, sin_phi);
    uwi_golden_advance(&cos_phi, &sin_phi);
    real3 normal = MAKE_REAL3(0, 1, 0);
    int mat = UW_MAT_NONE;
    uw_scene_hit(objects, count, bottom_depth, x, up, R(0.0), &normal, &mat);
    if (mat < 0) open += 1;
  }
  return (real)open / (real)n;
}

/* The sand's light a water point x gets from below, as shares of what the plane-parallel model's open,
 * sunlit sand everywhere would send: UWI_SAND_RAYS rays cosine-weighted about the downward vertical (the
 * golden-angle pattern of uwi_bottom_visibility). Returned, the sunlit sand's share: a ray that meets the
 * bottom counts 1 where a shadow ray from there finds the sun; one that meets an object counts that face's
 * reflection of the beam against the sand's, albedo_j max(n·s_w, 0) / (sand_albedo μ_w) where it is sunlit
 * (object_albedo[j * albedo_stride]: one band's). In *open, the diffusely lit sand's share: a ray that meets
 * the bottom counts the share of the water above that point no object hides (UWI_SAND_RAYS up-rays
 * cosine-weighted about the vertical: the sand reflects the diffuse light it gets from there, most of it
 * from above); one that meets an object counts that face's reflection of the diffuse light against the
 * sand's, albedo_j (1 + n_y) / (2 sand_albedo) e^{k (H - y_j)} (a plane of normal n under uniform light from
 * above gets (1 + n_y)/2 of E_d, and E_d at the face's depth y_j is e^{k (H - y_j)} of the sand's). Both 1
 * without objects. */
SEASIM_FN real uwi_sand_seen(const SEASIM_GLOBAL UwObject* objects, int count, real bottom_depth, real3 x, real3 s_w,
                             const SEASIM_GLOBAL float* object_albedo, int albedo_stride, real sand_albedo, real k,
                             real* open) {
  real lit = R(0.0), seen_open = R(0.0);
  real cos_phi = R(1.0), sin_phi = R(0.0); /* azimuth ray × the golden angle */
  for (int ray = 0; ray < UWI_SAND_RAYS; ++ray) {
    const real3 l = uwi_cosine_ray(ray, UWI_SAND_RAYS, cos_phi, sin_phi);
    const real3 dir = MAKE_REAL3(l.x, -l.y, l.z); /* about the downward vertical */
    uwi_golden_advance(&cos_phi, &sin_phi);
    real3 nb = MAKE_REAL3(0, 1, 0);
    int mat = UW_MAT_NONE;
    const real t = uw_scene_hit(objects, count, bottom_depth, x, dir, R(0.0), &nb, &mat);
    const real3 hit = x + t * dir;
    if (mat == UW_MAT_BOTTOM) {
      lit += uw_sun_visibility(objects, count, hit, MAKE_REAL3(0, 1, 0), s_w);
      /* The up-rays start just above the sand, as uw_sun_visibility's shadow rays. */
      seen_open += uwi_open_above(objects, count, bottom_depth, hit + MAKE_REAL3(0, R(1e-3), 0), UWI_SAND_RAYS);
    } else if (mat >= 0 && sand_albedo > R(0.0)) {
      const real ratio = (real)object_albedo[mat * albedo_stride] / sand_albedo;
      const real face = ratio * fmax(dot(nb, s_w), R(0.0)) / fmax(s_w.y, R(1e-3));
      if (face > R(0.0)) lit += face * uw_sun_visibility(objects, count, hit, nb, s_w);
      const real y_j = clamp(-hit.y, R(0.0), bottom_depth);
      seen_open += ratio * R(0.5) * (R(1.0) + nb.y) * exp(k * (bottom_depth - y_j));
    }
  }
  *open = seen_open / (real)UWI_SAND_RAYS;
  return lit / (real)UWI_SAND_RAYS;
}

/* The shares of the sunlit sand's light and (in *v_diffuse) of the diffusely lit sand's that a view ray from o
 * along d to distance S (finite) gathers where objects do not hide or shade the sand: uwi_sand_seen at
 * UWI_SAND_POINTS points evenly along the ray, weighted by how the bottom's term of the source e^{-k (H - y)}
 * reaches the camera, e^{-c' z - k (H - y(z))} (c', k and the albedos: one band's, the same for every band of
 * the pixel); not above 1. The model's plane-parallel water has sunlit, open sand everywhere below; measured
 * (docs/journal/underwater_regions_5_*.md) the objects in clear water came out 1.04-1.06 of the path tracer,
 * 1.10-1.11 when black, 1.03 with the sand black too; with the sunlit share the training and held-out grids
 * are all within 5 % (2 points x 4 rays: 4 x 8 lost a case and cost 81-88 ms where this costs 28-31 ms,
 * kd_multiple at 320x180 and 16 bands). The diffuse share takes the bright bottom's objects 0.5-0.8 % down
 * (docs/journal/beyond_the_grids.md). 1 without a bottom or objects. */
SEASIM_FN real uwi_sand_shares(const SEASIM_GLOBAL UwObject* objects, int count, real bottom_depth, real3 o, real3 d,
                               real S, real c_dm, real k, real3 s_w, const SEASIM_GLOBAL float* object_albedo,
                               int albedo_stride, real sand_albedo, real* v_diffuse) {
  *v_diffuse = R(1.0);
  if (!(bottom_depth > R(0.0)) || count <= 0 || !(S < R(1e6))) return R(1.0);
  real lit = R(0.0), open = R(0.0), den = R(0.0);
  for (int q = 0; q < UWI_SAND_POINTS; ++q) {
    const real z = S * ((real)q + R(0.5)) / (real)UWI_SAND_POINTS;
    const real3 x = o + z * d;
    const real y = clamp(-x.y, R(0.0), bottom_depth);
    const real w = exp(-c_dm * z - k * (bottom_depth - y));
    real open_q;
    lit += w * uwi_sand_seen(objects, count, bottom_depth, x, s_w, object_albedo, albedo_stride, sand_albedo, k,
                             &open_q);
    open += w * open_q;
    den += w;
  }
  if (!(den > R(0.0))) return R(1.0);
  *v_diffuse = fmin(open / den, R(1.0));
  return fmin(lit / den, R(1.0));
}

#define UWI_ABOVE_POINTS 2
#define UWI_ABOVE_RAYS 4

/* Distance along a view ray of quantile u of the in-scatter's weight e^{-r z} on [0, S] (r = c' - k d_y: the
 * reach e^{-c' z} times the diffuse source e^{-k y(z)}, y(z) = o_d - d_y z); S may be infinite only where r > 0
 * (a ray without a hit looks down or level). A ray looking up faster than its light fades (r < 0) weighs its
 * far end most: the quantile is then taken from S backwards, so no exponent is positive. */
SEASIM_FN real uwi_inscatter_quantile(real r, real S, real u) {
  if (!(fabs(r) * fmin(S, R(1e6)) > R(1e-20))) return u * S;
  if (r > R(0.0)) return -log1p(-u * -expm1(-r * S)) / r;
  return S + log1p(-(R(1.0) - u) * -expm1(r * S)) / -r;
}

/* The share of the light from above that objects leave the in-scatter of a view ray from o along d to its hit
 * S (UW_INFINITE: none), in [0, 1]: at UWI_ABOVE_POINTS points at the quantiles of the in-scatter's weight
 * (uwi_inscatter_quantile, with the first band's c' and k), the share of UWI_ABOVE_RAYS up-rays that no object
 * stops (uwi_open_above: cosine-weighted about the vertical, as a plane's irradiance from above weighs its
 * directions). The model's diffuse field is the plane-parallel water's, lit from
 * above everywhere; under an object the water loses the light the object holds off, and with it the light
 * it scatters towards the camera. The whole of the table's source from above (its e^{-k y} and e^{-m y}
 * terms, whose weights cancel in part: both or neither) is scaled by it; the bottom's term is the sand
 * shares' (uwi_sand_shares). Measured against the path tracer with the objects and without them
 * (docs/journal/beyond_the_grids.md): from 8 m down in open water the objects 3-4 m above the level view's
 * rays take 4.0-4.6 % off the water below the horizon, this share 3.0-3.6 % converged (6 points x 16 rays);
 * from 3.8 m, where the rays pass just under the objects, the path tracer shows at most 1 % and the share
 * takes about 2 %. A local share sees an object's shade where its light is held off, not where multiple
 * scattering carries it. The 2 x 4 rays kept for cost are one fixed pattern: against the converged share
 * they move a region by up to 2-3 % (the deep case's 6.7 and 2.3 %), the same way in every frame. 1 without
 * objects. */
SEASIM_FN real uwi_above_share(const SEASIM_GLOBAL UwObject* objects, int count, real bottom_depth, real3 o, real3 d,
                               real S, real c_dm, real k) {
  if (count <= 0) return R(1.0);
  const real r = c_dm - k * d.y;
  real open = R(0.0);
  for (int q = 0; q < UWI_ABOVE_POINTS; ++q) {
    const real z = uwi_inscatter_quantile(r, S, ((real)q + R(0.5)) / (real)UWI_ABOVE_POINTS);
    open += uwi_open_above(objects, count, bottom_depth, o + z * d, UWI_ABOVE_RAYS);
  }
  return open / (real)UWI_ABOVE_POINTS;
}

/* uwi_sand_shares of a view ray from the camera along d to its hit S, with the band table's
 * (common/underwater_band_table.h) first band: c', k, the objects' albedo rows and the sand's albedo.
 * kd_multiple.cl per pixel, and sand_share.cl on a coarser lattice of pixels. */
SEASIM_FN real uwi_view_sand_shares(SEASIM_CONSTANT const UwParams* p, const SEASIM_GLOBAL UwObject* objects,
                                    const SEASIM_GLOBAL float* band_table, int stride, real3 d, real S,
                                    real* v_diffuse) {
  const int row0 = UW_ROWS + p->object_count;
  const real3 cam = MAKE_REAL3(p->cam_pos[0], p->cam_pos[1], p->cam_pos[2]);
  const real3 s_w = MAKE_REAL3(p->sun_dir_water[0], p->sun_dir_water[1], p->sun_dir_water[2]);
  return uwi_sand_shares(objects, p->object_count, p->bottom_depth, cam, d, S, band_table[(row0 + UWI_ROW_C_DM) * stride],
                         band_table[(row0 + UWI_ROW_K) * stride], s_w, band_table + UW_ROWS * stride, stride,
                         band_table[UW_ROW_BOTTOM_ALBEDO * stride], v_diffuse);
}

/* uwi_above_share of a view ray from the camera along d to its hit S, with the band table's first band's c' and
 * k. kd_multiple.cl per pixel, and sand_share.cl on a coarser lattice of pixels. */
SEASIM_FN real uwi_view_above_share(SEASIM_CONSTANT const UwParams* p, const SEASIM_GLOBAL UwObject* objects,
                                    const SEASIM_GLOBAL float* band_table, int stride, real3 d, real S) {
  const int row0 = UW_ROWS + p->object_count;
  const real3 cam = MAKE_REAL3(p->cam_pos[0], p->cam_pos[1], p->cam_pos[2]);
  return uwi_above_share(objects, p->object_count, p->bottom_depth, cam, d, S, band_table[(row0 + UWI_ROW_C_DM) * stride],
                         band_table[(row0 + UWI_ROW_K) * stride]);
}

/* The irradiance on the sand whose light the water does not get, W m^-2, where the shares v_sand of the sunlit
 * and v_diffuse of the diffusely lit sand's light are kept (uwi_sand_shares): times UwiBand.src_sand, the
 * part of the source that is taken off. */
SEASIM_FN real uwi_sand_lost(real v_sand, real v_diffuse, real sand_beam, real sand_diffuse) {
  return (R(1.0) - v_sand) * sand_beam + (R(1.0) - v_diffuse) * sand_diffuse;
}

/* The source's weights of its three terms (e^{-k y}, e^{-k (H - y)}, e^{-m y}: uwi_source_weight at the node and
 * azimuth) less what the objects take off: the sand's part (UwiBand.src_sand) times the irradiance the shares
 * v_sand and v_diffuse leave out (uwi_sand_lost), and the two terms from above scaled by v_above
 * (uwi_above_share). kd_multiple.cl's lanes do the same per band block (uwi_lanes_hide_sand). */
SEASIM_FN void uwi_shaded_weights(const SEASIM_GLOBAL UwiBand* ib, int node, real cos_dphi, real v_sand,
                                  real v_diffuse, real v_above, real* w) {
  const SEASIM_GLOBAL float* sand = ib->src_sand + 3 * node;
  const real lost = uwi_sand_lost(v_sand, v_diffuse, (real)ib->sand_beam, (real)ib->sand_diffuse);
  w[0] = (uwi_source_weight(ib, node, cos_dphi, 0) - lost * (real)sand[0]) * v_above;
  w[1] = uwi_source_weight(ib, node, cos_dphi, 1) - lost * (real)sand[1];
  w[2] = (uwi_source_weight(ib, node, cos_dphi, 2) - lost * (real)sand[2]) * v_above;
}

/* In-scattered radiance along a view ray from depth o_d along d (d_y its vertical component) to
 * distance S (UW_INFINITE: deep water); cos_s = d·s_w. g: the water's own asymmetry (for the froxel
 * term taken off when single_scattering). Never negative. The forward peak's aureole is not in it
 * (uwi_aureole: the water's point-spread, common/water_spread.h, spreads this light, not that).
 * uwi_multiple_sand: with v_sand and v_diffuse (uwi_sand_shares) of the sunlit and of the diffusely lit sand's
 * parts of the source kept (uwi_sand_lost), and v_above (uwi_above_share) of the source from above. */
SEASIM_FN real uwi_multiple_sand(const SEASIM_GLOBAL UwiBand* ib, const SEASIM_GLOBAL UwBand* band, real g,
                                 real bottom_depth, real S, real d_y, real o_d, real cos_s, real mu_w,
                                 int single_scattering, int multiple, real v_sand, real v_diffuse, real v_above) {
  if (!multiple) return R(0.0);
  const real c_dm = ib->c_dm, k = ib->k;
  const int node = uwi_source_node(d_y);
  const real cos_dphi = uwi_cos_azimuth(cos_s, d_y, mu_w);
  real w[3];
  uwi_shaded_weights(ib, node, cos_dphi, v_sand, v_diffuse, v_above, w);
  const real w1 = w[0], w2 = w[1];
  /* The beam's diffuse offspring, and the beam scattered once with the exact phase function below its
   * peak (TMS; uwi_tms_phase). */
  const real phase = hg_phase(cos_s, g);
  const real wp = w[2] + (real)band->b * uwi_tms_phase(phase, (real)ib->p_clip) * (real)band->e_beam0;
  const real i1 = kd_exp_integral(k, c_dm, d_y, o_d, S);
  /* e^{-k (H - y(z))} = e^{-k (H - o_d)} e^{-k d_y z}: the same integral seen from the bottom. */
  const real i2 = bottom_depth > R(0.0) ? kd_exp_integral(k, c_dm, -d_y, fmax(bottom_depth - o_d, R(0.0)), S) : R(0.0);
  const real ip = kd_exp_integral(ib->m, c_dm, d_y, o_d, S);
  const real c = band->c;
  /* The strict single scattering's part below the peak: the part above it is in the aureole (uwi_forward_peak). */
  const real ss = single_scattering ? (real)band->b * uwi_tms_phase(phase, (real)ib->p_clip) * (real)band->e_beam0 *
                                          kd_exp_integral(c / fmax(mu_w, R(1e-4)), c, d_y, o_d, S)
                                    : R(0.0);
  return fmax(w1 * i1 + w2 * i2 + wp * ip - ss, R(0.0));
}

SEASIM_FN real uwi_multiple(const SEASIM_GLOBAL UwiBand* ib, const SEASIM_GLOBAL UwBand* band, real g,
                            real bottom_depth, real S, real d_y, real o_d, real cos_s, real mu_w,
                            int single_scattering, int multiple) {
  return uwi_multiple_sand(ib, band, g, bottom_depth, S, d_y, o_d, cos_s, mu_w, single_scattering, multiple, R(1.0),
                           R(1.0), R(1.0));
}

/* The forward peak's light along a view ray from depth o_d along d (d_y, cos_s = d·s_w) to distance S,
 * ending at depth y1 (the surface: 0): its aureole at the camera (uwi_aureole) less, with the froxel pass
 * (single_scattering), the peak's part of the strict single scattering that pass adds,
 * b (p_HG - p_clip)+ e_beam0 ∫_0^S e^{-c z} e^{-(c/μ_w) y(z)} dz: the aureole's once-scattered light holds
 * it (uwi_multiple takes off the part below the peak). Not clamped (it may be slightly negative where the
 * small-angle aureole is below the strict integral): uwi_band_radiance clamps its sum with uwi_multiple. */
SEASIM_FN real uwi_forward_peak(const SEASIM_GLOBAL UwiBand* ib, const SEASIM_GLOBAL UwBand* band, real g, real S,
                                real d_y, real o_d, real y1, real cos_s, real mu_w, int single_scattering) {
  if (!(ib->p_clip > R(0.0))) return R(0.0);
  const real phase = hg_phase(cos_s, g);
  const real aureole = uwi_aureole(ib, band, phase, cos_s, d_y, o_d, y1, mu_w);
  const real excess = fmax(phase - (real)ib->p_clip, R(0.0));
  if (!single_scattering || !(excess > R(0.0))) return aureole;
  const real c = band->c;
  return aureole - (real)band->b * excess * (real)band->e_beam0 *
                       kd_exp_integral(c / fmax(mu_w, R(1e-4)), c, d_y, o_d, S);
}

/* A Lambertian point (albedo, unit normal n) at depth y: the diffuse field on its tilted plane
 * (uwi_tilt_irradiance, vis_b the bottom it sees sunlit or not; E_d for the bottom, whose normal is straight
 * up) plus the delta-M beam times vis (shadow ray, caustic modulation). */
SEASIM_FN real uwi_lambert(const SEASIM_GLOBAL UwiBand* ib, const SEASIM_GLOBAL UwBand* band, real bottom_depth,
                           real y, real3 n, real3 s_w, real albedo, real vis, real vis_b) {
  const real e = uwi_tilt_irradiance(ib, bottom_depth, y, n, s_w, vis_b);
  const real beam = (real)band->e_beam0 * exp(-(real)ib->m * y) * fmax(dot(n, s_w), R(0.0)) * vis;
  return albedo / SEASIM_PI * (fmax(e, R(0.0)) + beam);
}

/* What the surface's reflected ray (d.x, -d.y, d.z) meets first when that is an object: the caller
 * traces it from the surface point with the scene's objects (uw_scene_hit without the bottom; kd_multiple.cl
 * once per surface pixel) and gives its distance s from the surface, the object's normal n, its albedo
 * in the band and the sun's visibility there (a shadow ray); s = UW_INFINITE (uwi_no_mirror_object) when
 * the ray meets no object, or meets the bottom first. */
typedef struct {
  real s;
  real3 n;
  real albedo;
  real vis;
} UwiMirrorHit;

SEASIM_FN UwiMirrorHit uwi_no_mirror_object(void) {
  UwiMirrorHit h;
  h.s = UW_INFINITE;
  h.n = MAKE_REAL3(0, 1, 0);
  h.albedo = R(0.0);
  h.vis = R(0.0);
  return h;
}

/* The object the surface's reflected ray meets first, for a view ray from o along d (d.y > 0) that
 * reaches the surface at distance S: traced from the surface point without the bottom (uwi_surface
 * compares it with the bottom), with a shadow ray towards the sun as raycast.cl's (no caustic
 * modulation). *mat: the object's index, or UW_MAT_NONE (then s = UW_INFINITE). The albedo is per band:
 * the caller fills it in. */
SEASIM_FN UwiMirrorHit uwi_mirror_hit(const SEASIM_GLOBAL UwObject* objects, int count, real3 o, real3 d, real S,
                                      real3 s_w, int* mat) {
  UwiMirrorHit h = uwi_no_mirror_object();
  real3 o_s = o + S * d;
  o_s.y = R(0.0);
  const real3 d_r = MAKE_REAL3(d.x, -d.y, d.z);
  real3 n = MAKE_REAL3(0, 1, 0);
  const real t = uw_scene_hit(objects, count, R(0.0), o_s, d_r, R(0.0), &n, mat);
  if (*mat < 0) {
    *mat = UW_MAT_NONE;
    return h;
  }
  h.s = t;
  h.n = n;
  h.vis = uw_sun_visibility(objects, count, o_s + t * d_r, n, s_w);
  return h;
}

/* The water surface seen from below along d (d.y > 0): the sky through Snell's window (sky_l, as
 * uw_band_surface_sky) plus F times what the reflected ray sees: its in-scatter down to what it meets,
 * and that: an object (mirror, UwiMirrorHit: lit as uwi_lambert), the bottom (its sunlit, unshadowed
 * radiance) or deep water. Without the objects in the mirror, measured
 * (docs/journal/underwater_regions_2_*.md), the pixels whose reflected ray meets a rock were 1.5–2.4x the path tracer
 * in clear water over a 2 m bottom, the rest within 2 %.
 * The reflected ray's in-scatter keeps the beam's single scattering (its TMS term, uwi_multiple with
 * single_scattering = 0) whether or not the froxel pass runs: that pass integrates along the camera's
 * ray only, so taking its term off here would drop the reflected ray's single scattering altogether.
 * Measured (docs/journal/underwater_regions_2_*.md): that was the water looking up under total internal reflection
 * too dark at g = 0 (clear water 0.86–0.93 of the path tracer). */
SEASIM_FN real uwi_surface(const SEASIM_GLOBAL UwiBand* ib, const SEASIM_GLOBAL UwBand* band, real g,
                           real bottom_depth, real sky_l, real3 d, real3 s_w, real ior, int multiple,
                           UwiMirrorHit mirror) {
  const real d_y = fmax(d.y, R(1e-6));
  const real s_bottom = bottom_depth > R(0.0) ? bottom_depth / d_y : UW_INFINITE;
  const int object = mirror.s < s_bottom;
  const real s_r = object ? mirror.s : s_bottom;
  const real cos_r = dot(d, s_w) - R(2.0) * d.y * s_w.y; /* the reflected ray (d.x, -d.y, d.z) */
  const real l_ms = uwi_multiple(ib, band, g, bottom_depth, s_r, -d_y, R(0.0), cos_r, s_w.y, 0, multiple);
  real l_hit = R(0.0);
  if (object) /* at depth s d_y on the reflected ray */
    l_hit = exp(-(real)ib->c_dm * mirror.s) *
            uwi_lambert(ib, band, bottom_depth, mirror.s * d_y, mirror.n, s_w, mirror.albedo, mirror.vis, R(1.0));
  else if (bottom_depth > R(0.0))
    l_hit = exp(-(real)ib->c_dm * fmin(s_r, R(1e4))) *
            uwi_lambert(ib, band, bottom_depth, bottom_depth, MAKE_REAL3(0, 1, 0), s_w, band->bottom_albedo, R(1.0),
                        R(1.0));
  return uw_window_radiance(d.y, ior, sky_l, l_ms + l_hit);
}

/* One band's radiance along the view ray (common/underwater.h uw_band_radiance's peer): mat, S, n from
 * uw_scene_hit; albedo of the hit; vis the direct beam's visibility; vis_b the share of the sand an
 * object's face sees that is sunlit (uwi_bottom_visibility; 1 for the bottom itself); sky_l the sky along the refracted
 * view and mirror the object the reflected ray meets (surface hits; uwi_no_mirror_object() otherwise). */
SEASIM_FN real uwi_band_radiance_sand(const SEASIM_GLOBAL UwiBand* ib, const SEASIM_GLOBAL UwBand* band, real g,
                                      int mat, real S, real3 n, real3 d, real o_d, real3 s_w, real albedo, real vis,
                                      real vis_b, real sky_l, real ior, real bottom_depth, int single_scattering,
                                      int multiple, UwiMirrorHit mirror, real v_sand, real v_diffuse,
                                      real v_above) {
  const real cos_s = dot(d, s_w);
  /* The aureole to where the ray ends (the surface: 0, as kd_multiple.cl takes it). */
  const real y1 = mat == UW_MAT_SURFACE ? R(0.0) : fmax(o_d - S * d.y, R(0.0));
  const real l_ms =
      multiple ? fmax(uwi_multiple_sand(ib, band, g, bottom_depth, S, d.y, o_d, cos_s, s_w.y, single_scattering,
                                        multiple, v_sand, v_diffuse, v_above) +
                          uwi_forward_peak(ib, band, g, S, d.y, o_d, y1, cos_s, s_w.y, single_scattering),
                      R(0.0))
               : R(0.0);
  if (mat == UW_MAT_NONE) return l_ms;
  const real l_s = mat == UW_MAT_SURFACE
                       ? uwi_surface(ib, band, g, bottom_depth, sky_l, d, s_w, ior, multiple, mirror)
                       : uwi_lambert(ib, band, bottom_depth, fmax(o_d - S * d.y, R(0.0)), n, s_w, albedo, vis, vis_b);
  return exp(-(real)ib->c_dm * S) * l_s + l_ms;
}

/* The same with every sand lit and seen and no object above the water (v_sand = v_diffuse = v_above = 1). */
SEASIM_FN real uwi_band_radiance(const SEASIM_GLOBAL UwiBand* ib, const SEASIM_GLOBAL UwBand* band, real g, int mat,
                                 real S, real3 n, real3 d, real o_d, real3 s_w, real albedo, real vis, real vis_b,
                                 real sky_l, real ior, real bottom_depth, int single_scattering, int multiple,
                                 UwiMirrorHit mirror) {
  return uwi_band_radiance_sand(ib, band, g, mat, S, n, d, o_d, s_w, albedo, vis, vis_b, sky_l, ior, bottom_depth,
                                single_scattering, multiple, mirror, R(1.0), R(1.0), R(1.0));
}
