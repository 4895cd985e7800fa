/* reference.cl — the brute-force reference of the underwater model (paper 002 §6.1 validates against a
 * spectral path tracer): a spectral Monte Carlo volumetric path tracer for full multiple scattering in
 * the scene of common/underwater.h, progressive, with a per-pixel variance estimate.
 *
 * Scene (the same as raycast.cl / kd_multiple.cl): homogeneous water below y = 0 (per band a, b,
 * c = a + b), Henyey–Greenstein phase function with g = UwParams.g (isotropic with SEASIM_PT_ISOTROPIC, the
 * water's tabulated phase with SEASIM_PT_PHASE_TABLE),
 * a flat air–water surface with Fresnel reflection/refraction, Lambertian analytic objects and an
 * optional flat Lambertian bottom (uw_scene_hit). Light: the refracted sun beam, a delta in direction
 * along -sun_dir_water with normal irradiance e_beam0 just below the surface (its Fresnel transmission
 * is inside e_beam0), so E_beam(y) = e_beam0 e^{-c y/μ_w}; and the scene's sky, which a path reaches by
 * refracting out through Snell's window: n² (1 - F) L_sky(a) below the surface, a the direction in air
 * the path leaves along (Snell). L_sky(a) is the fast models' own sky (common/sky_view.h: the uniform
 * level times the [sky] model's shape towards a, uniform, CIE clear, image or Preetham, and the band's
 * share of it), so a non-uniform sky is integrated by the paths themselves over Snell's window, the
 * downwelling light and the reflections, where the fast models use its precomputed integrals.
 * Flat surface: no caustics.
 *
 * Estimator, one path per sample: one wavelength band chosen uniformly (weight band_count; the sample's
 * RGB is band_count L(λ_i) (w_r, w_g, w_b)_i, whose mean is Σ_i L(λ_i) w(λ_i), the sensor RGB of
 * 002 eq. 4.8 as kd_multiple.cl writes it). Free flight sampled with c (weight b/c at a scattering
 * event, 1 on reaching a surface). Next-event estimation to the sun at every medium vertex
 * (b/c · p(θ) · E_beam(y) · V, 002 eq. 5.1's integrand) and every Lambertian vertex
 * (ρ/π · max(n·s_w, 0) · E_beam(y) · V), V an exact shadow ray along sun_dir_water through the objects
 * to the surface — the only way to see a delta light. At the surface from below: reflect with
 * probability F, else escape and add n² L_sky(a). Continue by sampling the phase function / the cosine
 * lobe (weight 1 / albedo); Russian roulette from the 3rd vertex on; at most max_bounces vertices
 * (medium, Lambertian or surface reflection).
 * max_bounces = 1 is the single-scattering mode: only the sun NEE at the first medium vertex, no surface,
 * sky or Lambertian terms, i.e. an unbiased estimate of
 *   L_SS = ∫_0^S e^{-c z} b p(θ) E_beam(y(z)) V(x_z) dz   (S the first hit distance; 002 §5),
 * what the froxel integrator computes.
 *
 * Camera above the surface (y > 0; the sea seen from above, for paper 000's model): a ray up sees the
 * sky; a ray down meets the flat surface, which adds R L_sky(mirrored ray) and (1 - R)/n² times the path
 * traced from there along the refracted ray (deterministic split; no sun glint, no caustics).
 *
 * Spotlights (UwLampParams.lamp_count > 0; common/underwater_lamps_params.h): point lamps with a cone
 * and a soft edge (shafts_cone_profile) and a spectral intensity I(λ) per band. A point lamp is a delta
 * light, so next-event estimation is the only way a path sees it: on every segment of the path through
 * the water (to the next surface, or to infinity) one distance per lamp sampled equiangularly about the
 * lamp within the part of the segment inside its cone, weighted e^{-c t} b p_HG · I P e^{-c s}/s² · V /
 * pdf(t), plus next-event estimation at the segment's free-flight vertex, the two combined by the
 * balance heuristic (path_tracer_lamps.h, Kulla & Fajardo 2012 §5; SEASIM_PT_LAMP_MIS = 0: the
 * equiangular sample on the whole segment alone), and at every Lambertian vertex
 * ρ/π · max(n·w, 0) · I P e^{-c s}/s² · V; V an exact shadow ray to the lamp through the
 * objects, 1/s² clamped at the lamp radius s_min as in the fast pass. The lamps' light then goes on
 * scattering (all orders), which the fast pass (underwater_lamps.cl, single scattering) leaves out.
 * max_bounces = 1 keeps only the first segment's lamp estimates: the lamps' single scattering.
 *
 * Random numbers: common/path_tracer.h, a hash of (seed, pixel, sample index, dimension): reproducible
 * for a seed whatever the batching. Dimensions: 0, 1 pixel jitter; 2 band; then per event in order.
 *
 * Inputs: UwParams, UwBand[band_count], UwObject[object_count], albedo[object * band_count + band], SkyParams
 * and the sky's buffer (image texels or Preetham's reals, common/sky_view.h).
 * In/out per pixel: mean (float4: RGB mean, A the number of samples in it) and m2 (float4: RGB sum of
 * squared deviations from the mean), merged per launch with the launch's own mean/M2 (Chan, Golub,
 * LeVeque 1979), stable in float where a plain Σx² - n mean² would cancel. sample_start numbers the
 * paths (the random numbers), A counts what the pair holds: zeroed by the host at each block of paths.
 * direct_mean and direct_m2 hold the same for the unscattered part of each sample: the light a path
 * gathers from the first surface its camera ray reaches without scattering in the water (0 for a path
 * that scatters first or meets nothing), so that the image splits into the paths that reached a surface
 * unscattered and those that scattered, as the fast model's direct layer against backscatter + forward
 * (docs/layers.md). Camera above the surface: 0.
 * Height-field floor (SEASIM_PT_HEIGHT_FIELD = 1; the sea's [bottom] type = "heightfield", 000 §5.4): the floor of
 * common/sea_bottom.h (bilinear patches, exact first intersection, sea_hf_intersect) in place of the flat bottom
 * (UwParams.bottom_depth 0), met by every path segment and blocking the shadow rays to the sun; its local
 * normal for the Lambertian terms. SeaHeightField and its depth nodes are arguments 18 and 19.
 * FFT waves seen from above (SEASIM_PT_WAVES = 1; the sea's surface.type = "fft"): the surface the fast sea
 * model sees (common/sea_waves.h), met where its camera ray is: the mean surface y = 0 with the ocean's
 * normal map there (wave_normals, wave_n texels a side over wave_patch metres, arguments 20–22), bilinear
 * and periodic, read at every path's own jittered point of the pixel, so the pixel averages the
 * unfiltered normals over its footprint (what the fast model's wave filter, common/sea_lean.h,
 * approximates); its Fresnel split, mirrored sky and refracted ray (sea_view_interaction). Below it the water
 * is 000 §3's: sunlight through the flat mean surface, paths that come back up leave through y = 0.
 * So what is shared with the fast model is the surface's geometry; what it checks is the water's light to
 * all orders along each refracted ray, and the footprint's average. The sun is a disk of cos radius
 * sun_cos_radius (argument 23) in the facets' mirror: radiance E/Ω where a path's reflected ray falls in
 * it, the glitter the fast model's filter spreads over its Gaussian slopes (common/sea_lean.h).
 * Defines: SEASIM_SKY_MODEL (common/sky.h: 0 uniform, the default, 1 CIE clear, 2 image, 3 Preetham),
 * SEASIM_HAS_OBJECTS (0/1), SEASIM_PT_ISOTROPIC (0/1: phase 1/(4π) instead of HG),
 * SEASIM_PT_PHASE_TABLE (0/1: the water's measured or parameterised phase from `phase_tables`, its values
 * for next-event estimation and its inverse CDF for sampling, common/phase.h; else HG of g),
 * SEASIM_PT_JITTER (0/1: 0 traces every sample through the pixel centre, for tests against quadrature),
 * SEASIM_PT_LAMP_MIS (0/1, see the spotlights above).
 * Stiff cases: c = 0 (free flight UW_INFINITE; a ray into deep water then ends), a = 0 (albedo 1: only
 * roulette and the cap end a path), the sun below the horizon (e_beam0 = 0: no NEE), E_beam underflow at
 * great depth (0, never NaN), total internal reflection (F = 1), |g| -> 1 (path_tracer.h).
 */
#include "common/compat.h"
#include "common/gauss_legendre.h"
#include "common/optics.h"
#include "common/phase.h"
#include "common/shafts.h"
#include "common/underwater_params.h"
#include "common/underwater.h"
#include "common/path_tracer.h"
#include "common/path_tracer_lamps.h"
#include "common/underwater_lamps_params.h"
#include "common/underwater_lamps.h"
#ifndef SEASIM_SKY_MODEL
#define SEASIM_SKY_MODEL 0
#endif
#include "common/polynomial_trig.h"
#include "common/sky.h"
#include "common/sky_params.h"
#include "common/sky_view.h"
#include "common/sea_surface.h"
#include "common/sea_bottom_params.h"
#include "common/sea_second.h"
#include "common/sea_bottom.h"
#include "common/sea_waves.h"

#ifndef SEASIM_PT_HEIGHT_FIELD
#define SEASIM_PT_HEIGHT_FIELD 0
#endif
#ifndef SEASIM_PT_WAVES
#define SEASIM_PT_WAVES 0
#endif

#ifndef SEASIM_HAS_OBJECTS
#define SEASIM_HAS_OBJECTS 1
#endif
#ifndef SEASIM_PT_ISOTROPIC
#define SEASIM_PT_ISOTROPIC 0
#endif
#ifndef SEASIM_PT_JITTER
#define SEASIM_PT_JITTER 1
#endif
#ifndef SEASIM_PT_LAMP_MIS
#define SEASIM_PT_LAMP_MIS 1
#endif

#ifndef SEASIM_PT_PHASE_TABLE
#define SEASIM_PT_PHASE_TABLE 0
#endif

/* The water's phase between travel directions with cos θ between them: isotropic, the table, or HG of g. */
static inline float pt_phase(const __global float* phase_tables, float g, float cos_theta) {
#if SEASIM_PT_ISOTROPIC
  return 1.0f / (4.0f * M_PI_F);
#elif SEASIM_PT_PHASE_TABLE
  return phase_table_value(phase_tables, PHASE_PT_VALUES, 1.0f - cos_theta);
#else
  return hg_phase(cos_theta, g);
#endif
}

/* A new travel direction scattered from d by the same phase (u1, u2 two uniforms). */
static inline float3 pt_scatter(const __global float* phase_tables, float3 d, float g, float u1, float u2) {
#if SEASIM_PT_ISOTROPIC
  return pt_sample_isotropic(u1, u2);
#elif SEASIM_PT_PHASE_TABLE
  return pt_direction(d, phase_table_sample_omc(phase_tables + PHASE_PT_VALUES, PHASE_PT_SAMPLES, u1), u2);
#else
  return pt_sample_hg(d, g, u1, u2);
#endif
}

/* Offset of a ray origin off a surface it leaves: relative to the coordinates' size, so float rounding
 * at large distances cannot put the origin back behind the surface. */
static inline float surface_offset(float3 x) { return 1e-4f * fmax(1.0f, fmax(fabs(x.x), fmax(fabs(x.y), fabs(x.z)))); }

/* The band's sky radiance in air towards the unit direction a (a.y >= 0): its uniform level times the
 * [sky]'s shape and the band's share of it, as kd_multiple.cl's Snell's window and sea_single.cl's
 * reflected sky read it (common/sky_view.h). Exactly the level for the uniform sky. */
static inline float pt_sky(const __global UwBand* bn, __constant SkyParams* sky_params, const __global float* sky,
                           float3 a) {
#if SEASIM_SKY_MODEL == SEASIM_SKY_UNIFORM
  return bn->sky_radiance;
#else
  const float3 w = (float3)(bn->sky_w_r, bn->sky_w_g, bn->sky_w_b);
  return bn->sky_radiance * sky_view_band(SEASIM_SKY_MODEL, w, sky_view_shape(sky_params, sky, a));
#endif
}

/* The scene's geometry for a path: objects, the surface and the flat bottom (uw_scene_hit), and with
 * SEASIM_PT_HEIGHT_FIELD the height-field floor where it comes first (UW_MAT_BOTTOM, its normal). */
static inline float pt_scene_hit(const __global UwObject* objects, int count, float bottom_depth,
                                 __constant SeaHeightField* hf, const __global float* hf_depth, float3 o, float3 d,
                                 float3* n, int* mat) {
  float S = uw_scene_hit(objects, count, bottom_depth, o, d, 0.0f, n, mat);
#if SEASIM_PT_HEIGHT_FIELD
  float t_floor;
  float3 n_floor;
  if (sea_hf_intersect(hf, hf_depth, o, d, fmin(S, 1.0e6f), &t_floor, &n_floor) && t_floor < S) {
    S = t_floor;
    *n = n_floor;
    *mat = UW_MAT_BOTTOM;
  }
#endif
  return S;
}

/* Visibility of the sun from x (below the surface): 1 unless an object (or the height-field floor) blocks
 * the shadow ray along s_w before the surface (the flat bottom cannot: the ray goes up). */
static inline float sun_visibility(const __global UwObject* objects, int count, __constant SeaHeightField* hf,
                                   const __global float* hf_depth, float3 x, float3 s_w) {
#if SEASIM_HAS_OBJECTS
  float3 n;
  int mat;
  uw_scene_hit(objects, count, 0.0f, x, s_w, 0.0f, &n, &mat);
  if (mat >= 0) return 0.0f;
#endif
#if SEASIM_PT_HEIGHT_FIELD
  float t_floor;
  float3 n_floor;
  const float to_surface = s_w.y > 0.0f ? -x.y / s_w.y : 1.0e6f;
  if (sea_hf_intersect(hf, hf_depth, x, s_w, fmin(to_surface, 1.0e6f), &t_floor, &n_floor)) return 0.0f;
#endif
  return 1.0f;
}

/* Visibility of a lamp at distance s along the unit direction w from x: 1 unless an object blocks it. */
static inline float lamp_visibility(const __global UwObject* objects, int count, float3 x, float3 w, float s) {
#if SEASIM_HAS_OBJECTS
  float3 n;
  int mat;
  const float t = uw_scene_hit(objects, count, 0.0f, x, w, 0.0f, &n, &mat);
  return (mat >= 0 && t < s) ? 0.0f : 1.0f;
#else
  return 1.0f;
#endif
}

/* The lamps' direct light reflected by a Lambertian point x (normal n) per unit albedo:
 * Σ_lamps max(n·w, 0)/π · I P e^{-c s}/max(s, s_min)² · V, w the unit direction to the lamp. */
static inline float lamps_lambert(__constant UwLampParams* lp, const __global UwLamp* lamps,
                                  const __global float* lamp_spectra, const __global UwObject* objects, int count,
                                  int band, float c, float3 x, float3 normal) {
  float L = 0.0f;
  for (int l = 0; l < lp->lamp_count; ++l) {
    const __global UwLamp* lamp = &lamps[l];
    const float3 pos = (float3)(lamp->position[0], lamp->position[1], lamp->position[2]);
    const float3 axis = (float3)(lamp->direction[0], lamp->direction[1], lamp->direction[2]);
    const float3 to_lamp = pos - x;
    const float s = length(to_lamp);
    if (!(s > 0.0f)) continue;
    const float3 w = to_lamp / s;
    const float cos_n = dot(normal, w);
    if (cos_n <= 0.0f) continue;
    const float prof = uw_lamp_profile(x, pos, axis, lamp->cos_cone, lamp->cos_inner);
    if (prof <= 0.0f) continue;
    const float sc = fmax(s, lp->s_min);
    const float e = cos_n * M_1_PI_F * lamp_spectra[l * lp->band_count + band] * prof * exp(-c * s) / (sc * sc);
    if (e > 0.0f) L += e * lamp_visibility(objects, count, x, w, s);
  }
  return L;
}

/* f(x) of path_tracer_lamps.h for one lamp: the lamp's light scattered at x towards -d, per unit σ_s and
 * path throughput, p(cos α) I P e^{-c s} V / max(s, s_min)² (0 outside the cone or in shadow). */
static inline float lamp_inscatter_at(__constant UwLampParams* lp, const __global UwLamp* lamp,
                                      const __global float* spectrum, const __global UwObject* objects, int count,
                                      float c, float g, const __global float* phase_tables, float3 x, float3 d) {
  const float3 pos = (float3)(lamp->position[0], lamp->position[1], lamp->position[2]);
  const float3 axis = (float3)(lamp->direction[0], lamp->direction[1], lamp->direction[2]);
  const float prof = uw_lamp_profile(x, pos, axis, lamp->cos_cone, lamp->cos_inner);
  if (prof <= 0.0f) return 0.0f;
  const float3 to_lamp = pos - x;
  const float s = length(to_lamp);
  if (!(s > 0.0f)) return 0.0f;
  const float phase = pt_phase(phase_tables, g, dot(-to_lamp / s, -d)); /* lamp -> x, then along -d */
  const float sc = fmax(s, lp->s_min);
  const float e = exp(-c * s) * phase * *spectrum * prof / (sc * sc);
  return e > 0.0f ? e * lamp_visibility(objects, count, x, to_lamp / s, s) : 0.0f;
}

/* The equiangular range of one lamp on the segment o + t d, t in [0, S): clipped to the lamp's cone
 * when the estimate is combined with free flight (SEASIM_PT_LAMP_MIS), else all of [0, S). */
static inline int lamp_range(__constant UwLampParams* lp, const __global UwLamp* lamp, float3 o, float3 d, float S,
                             PtLampRange* rg) {
  const float3 pos = (float3)(lamp->position[0], lamp->position[1], lamp->position[2]);
  const float3 axis = (float3)(lamp->direction[0], lamp->direction[1], lamp->direction[2]);
  return pt_lamp_range(o, d, S, pos, axis, lamp->cos_cone, lp->s_min, SEASIM_PT_LAMP_MIS, rg);
}

/* The lamps' light scattered once towards -d along the segment o + t d, t in [0, S) (S may be
 * UW_INFINITE), per unit path throughput: one equiangular sample per lamp (dimension *dim onwards),
 * weighted by the balance heuristic against free flight (path_tracer_lamps.h). */
static inline float lamps_segment(__constant UwLampParams* lp, const __global UwLamp* lamps,
                                  const __global float* lamp_spectra, const __global UwObject* objects, int count,
                                  int band, float b, float c, float g, const __global float* phase_tables, float3 o,
                                  float3 d, float S, unsigned int key, unsigned int* dim) {
  float L = 0.0f;
  for (int l = 0; l < lp->lamp_count; ++l) {
    const float u = pt_uniform(key, (*dim)++);
    PtLampRange rg;
    if (!lamp_range(lp, &lamps[l], o, d, S, &rg)) continue;
    float pdf;
    const float t = pt_sample_equiangular(rg.a, rg.r, rg.t0, rg.t1, u, &pdf);
    if (!(pdf > 0.0f)) continue;
#if SEASIM_PT_LAMP_MIS
    const float w = pt_mis_balance(pdf, pt_distance_pdf(c, t));
#else
    const float w = 1.0f;
#endif
    const float f = lamp_inscatter_at(lp, &lamps[l], &lamp_spectra[l * lp->band_count + band], objects, count, c, g,
                                      phase_tables, o + t * d, d);
    if (f > 0.0f) L += w * exp(-c * t) * b * f / pdf;
  }
  return L;
}

/* The lamps' light at a free-flight scattering vertex o + t d of the segment [0, S) (the path's weight
 * already holds σ_s/σ_t there): f with the free-flight strategy's balance weight. Without
 * SEASIM_PT_LAMP_MIS the segment's equiangular sample alone estimates the lamps (weight 0 here). */
static inline float lamps_vertex(__constant UwLampParams* lp, const __global UwLamp* lamps,
                                 const __global float* lamp_spectra, const __global UwObject* objects, int count,
                                 int band, float c, float g, const __global float* phase_tables, float3 o, float3 d,
                                 float S, float t) {
  float L = 0.0f;
#if SEASIM_PT_LAMP_MIS
  for (int l = 0; l < lp->lamp_count; ++l) {
    PtLampRange rg;
    const float p_e = lamp_range(lp, &lamps[l], o, d, S, &rg) ? pt_lamp_range_pdf(&rg, t) : 0.0f;
    const float w = pt_mis_balance(pt_distance_pdf(c, t), p_e);
    if (w > 0.0f)
      L += w * lamp_inscatter_at(lp, &lamps[l], &lamp_spectra[l * lp->band_count + band], objects, count, c, g,
                                 phase_tables, o + t * d, d);
  }
#endif
  return L;
}

/* max_bounces = 1: single scattering of the sun beam only (no surface or sky terms). */
static inline int single_only_mode(int max_bounces) { return max_bounces == 1; }

/* One path's radiance in band `band` along the camera ray (o, d); key/dim as path_tracer.h. */
static inline float trace_path(__constant UwParams* p, const __global UwBand* bn, const __global UwObject* objects,
                               const __global float* albedo, __constant UwLampParams* lp, const __global UwLamp* lamps,
                               const __global float* lamp_spectra, const __global float* phase_tables,
                               __constant SkyParams* sky_params, const __global float* sky,
                               __constant SeaHeightField* hf, const __global float* hf_depth, int band,
                               int max_bounces, unsigned int key, float3 o, float3 d, float* direct) {
#if SEASIM_HAS_OBJECTS
  const int count = p->object_count;
#else
  const int count = 0;
#endif
  const float3 s_w = (float3)(p->sun_dir_water[0], p->sun_dir_water[1], p->sun_dir_water[2]);
  const float mu_w = s_w.y;
  const float c = bn->c, e_beam0 = bn->e_beam0;
  const float scatter_albedo = c > 0.0f ? bn->b / c : 0.0f;
  const int single_only = max_bounces == 1;
  unsigned int dim = 3; /* 0, 1: pixel jitter; 2: band */
  float beta = 1.0f;    /* path throughput divided by its pdf */
  float L = 0.0f;
  int vertices = 0;
  /* The unscattered part: what the path gathers after its first event when that event is a surface
   * (the water surface, an object, the bottom) reached without scattering; L_before the light gathered
   * before it (the camera ray's in-scatter of lamp light). -1: the path scattered first, or hit nothing. */
  float L_before = -1.0f;
  int segment = 0;
  for (;;) {
    float3 n;
    int mat;
    const float S = pt_scene_hit(objects, count, p->bottom_depth, hf, hf_depth, o, d, &n, &mat);
    if (lp->lamp_count > 0 && beta > 0.0f)
      L += beta * lamps_segment(lp, lamps, lamp_spectra, objects, count, band, bn->b, c, p->g, phase_tables, o, d, S, key, &dim);
    const float t = pt_sample_distance(c, pt_uniform(key, dim++));
    if (segment == 0 && t >= S && mat != UW_MAT_NONE) L_before = L;
    if (t < S) {
      /* A scattering event in the water: weight σ_s/σ_t (free flight pdf c e^{-ct}, transmittance e^{-ct}). */
      beta *= scatter_albedo;
      if (lp->lamp_count > 0 && beta > 0.0f)
        L += beta * lamps_vertex(lp, lamps, lamp_spectra, objects, count, band, c, p->g, phase_tables, o, d, S, t);
      o = o + t * d;
      ++vertices;
      if (e_beam0 > 0.0f && beta > 0.0f) {
        const float phase = pt_phase(phase_tables, p->g, dot(s_w, d)); /* sunlight along -s_w, then along -d */
        const float e_beam = uw_beam_irradiance(e_beam0, c, mu_w, fmax(-o.y, 0.0f));
        if (e_beam > 0.0f) L += beta * phase * e_beam * sun_visibility(objects, count, hf, hf_depth, o, s_w);
      }
      if (single_only || vertices >= max_bounces) break;
      d = pt_scatter(phase_tables, d, p->g, pt_uniform(key, dim), pt_uniform(key, dim + 1));
      dim += 2;
    } else if (mat == UW_MAT_NONE || single_only) {
      break; /* into deep water (nothing comes back along it) or, single scattering, past the first hit */
    } else if (mat == UW_MAT_SURFACE) {
      o = o + S * d;
      o.y = 0.0f;
      if (!pt_fresnel_reflects(d.y, p->ior, pt_uniform(key, dim++))) {
        /* n² L_sky(a), a the refracted direction in air; 1 - F is the choice's probability */
        L += beta * p->ior * p->ior * pt_sky(bn, sky_params, sky, sky_window_air_dir(d, p->ior));
        break;
      }
      if (++vertices >= max_bounces) break;
      d.y = -d.y; /* mirror reflection at the flat surface */
    } else {
      /* A Lambertian object or the bottom. */
      const float rho = mat >= 0 ? albedo[mat * p->band_count + band] : bn->bottom_albedo;
      o = o + S * d;
      ++vertices;
      const float3 x = o + surface_offset(o) * n;
      const float cos_sun = dot(n, s_w);
      if (e_beam0 > 0.0f && cos_sun > 0.0f && rho > 0.0f) {
        const float e_beam = uw_beam_irradiance(e_beam0, c, mu_w, fmax(-o.y, 0.0f));
        if (e_beam > 0.0f)
          L += beta * rho * M_1_PI_F * cos_sun * e_beam * sun_visibility(objects, count, hf, hf_depth, x, s_w);
      }
      if (lp->lamp_count > 0 && rho > 0.0f)
        L += beta * rho * lamps_lambert(lp, lamps, lamp_spectra, objects, count, band, c, x, n);
      if (vertices >= max_bounces) break;
      beta *= rho; /* ρ/π cos θ over the pdf cos θ/π */
      d = pt_sample_cosine(n, pt_uniform(key, dim), pt_uniform(key, dim + 1));
      dim += 2;
      o = x;
    }
    ++segment;
    if (!(beta > 0.0f)) break; /* absorbed (b = 0) or a black surface: nothing more can arrive */
    /* Russian roulette from the 3rd vertex on: a path below weight 1 survives with probability β and
     * then carries weight 1, so weights never grow (a fixed survival probability q < 1 would multiply
     * a conservative path's weight by 1/q per vertex: heavy tails). β = 1 (a = 0, white surfaces) is
     * never rouletted; escape through the window or max_bounces ends it. */
    if (vertices >= 3 && beta < 1.0f) {
      if (pt_uniform(key, dim++) >= beta) break;
      beta = 1.0f;
    }
  }
  *direct = L_before >= 0.0f ? L - L_before : 0.0f;
  return L;
}

__kernel void reference_path_trace(__constant UwParams* p, __global const UwBand* bands,
                                   __global const UwObject* objects, __global const float* albedo, uint seed,
                                   int sample_start, int samples, int max_bounces, __global float4* mean,
                                   __global float4* m2, __constant UwLampParams* lp, __global const UwLamp* lamps,
                                   __global const float* lamp_spectra, __global const float* phase_tables,
                                   __global float4* direct_mean, __global float4* direct_m2,
                                   __constant SkyParams* sky_params, __global const float* sky,
                                   __constant SeaHeightField* hf, __global const float* hf_depth,
                                   __global const float* wave_normals, int wave_n, float wave_patch,
                                   float sun_cos_radius) {
  const int x = get_global_id(0);
  const int y = get_global_id(1);
  if (x >= p->width || y >= p->height) return;
  const int pixel = y * p->width + x;

  const float3 right = (float3)(p->cam_right[0], p->cam_right[1], p->cam_right[2]);
  const float3 up = (float3)(p->cam_up[0], p->cam_up[1], p->cam_up[2]);
  const float3 forward = (float3)(p->cam_forward[0], p->cam_forward[1], p->cam_forward[2]);
  const float3 eye = (float3)(p->cam_pos[0], p->cam_pos[1], p->cam_pos[2]);

  /* This batch's mean and M2 by Welford's update, then merged into the running pair. */
  float3 b_mean = (float3)(0.0f), b_m2 = (float3)(0.0f);
  float3 bd_mean = (float3)(0.0f), bd_m2 = (float3)(0.0f); /* the unscattered part's (trace_path) */
  for (int j = 0; j < samples; ++j) {
    const unsigned int key = pt_path_key(seed, (unsigned int)pixel, (unsigned int)(sample_start + j));
#if SEASIM_PT_JITTER
    const float jx = pt_uniform(key, 0), jy = pt_uniform(key, 1);
#else
    const float jx = 0.5f, jy = 0.5f;
#endif
    /* Pinhole camera as in sea_single.cl, at a jittered point of the pixel. */
    const float u = (2.0f * (x + jx) / p->width - 1.0f) * p->tan_half_fov_y * p->aspect;
    const float v = (1.0f - 2.0f * (y + jy) / p->height) * p->tan_half_fov_y;
    const float3 d = normalize(forward + u * right + v * up);
    const int band = min((int)(pt_uniform(key, 2) * p->band_count), p->band_count - 1);
    const __global UwBand* bn = &bands[band];
    float L, L_direct = 0.0f;
    if (eye.y <= 0.0f) {
      L = trace_path(p, bn, objects, albedo, lp, lamps, lamp_spectra, phase_tables, sky_params, sky, hf, hf_depth,
                     band, max_bounces, key, eye, d, &L_direct);
    } else if (d.y >= 0.0f) {
      L = pt_sky(bn, sky_params, sky, d); /* camera above the surface looking up: the sky (no sun disk) */
    } else {
      /* Camera above the surface (the sea seen from above, paper 000's view): the flat surface reflects
       * the sky along the mirrored ray with R and lets (1 - R)/n² of the water's radiance out (radiance/n² is
       * conserved; docs/radiometry.md), both taken deterministically; the water side is the same
       * all-orders path from the surface point along the refracted ray. The sun's glint is not drawn. */
      const float3 o = (float3)(eye.x + eye.y / -d.y * d.x, 0.0f, eye.z + eye.y / -d.y * d.z);
#if SEASIM_PT_WAVES
      const float3 n = sea_facing_normal(d, sea_wave_normal(wave_normals, wave_n, wave_patch, o.x, o.z));
#else
      const float3 n = (float3)(0.0f, 1.0f, 0.0f);
#endif
      float R;
      float3 d_w, sky_dir;
      sea_view_interaction(d, n, p->ior, &R, &sky_dir, &d_w);
      /* A refracted ray along or above the surface (a wave tilted far towards the eye): just below it,
       * as the fast model's cos θ_ji >= 1e-4. */
      if (d_w.y > -1e-4f) d_w = normalize((float3)(d_w.x, -1e-4f, d_w.z));
      float unused;
      float sky_reflected = single_only_mode(max_bounces) ? 0.0f : pt_sky(bn, sky_params, sky, sky_dir);
#if SEASIM_PT_WAVES
      /* The sun's disk in the facet's mirror (the glitter): E/Ω within angular radius ρ of the sun, E the
       * sun's normal irradiance in air (e_sun0 = E cos θ_s (1 - R(θ_s)) just below the surface). */
      const float3 sun_air = (float3)(p->sun_dir_air[0], p->sun_dir_air[1], p->sun_dir_air[2]);
      const float t_sun = sun_air.y * (1.0f - fresnel_reflectance(sun_air.y, 1.0f, p->ior));
      /* A disk of no size (cos radius 1) has no solid angle to divide by: no glitter. */
      if (!single_only_mode(max_bounces) && t_sun > 0.0f && sun_cos_radius < 1.0f &&
          dot(reflect_dir(d, n), sun_air) >= sun_cos_radius)
        sky_reflected += bn->e_sun0 / t_sun / (2.0f * M_PI_F * (1.0f - sun_cos_radius));
#endif
      L = R * sky_reflected + (1.0f - R) / (p->ior * p->ior) *
                                 trace_path(p, bn, objects, albedo, lp, lamps, lamp_spectra, phase_tables, sky_params,
                                            sky, hf, hf_depth, band, max_bounces, key, o, d_w, &unused);
    }
    L *= p->band_count;
    L_direct *= p->band_count;
    const float3 s = L * (float3)(bn->w_r, bn->w_g, bn->w_b), s_d = L_direct * (float3)(bn->w_r, bn->w_g, bn->w_b);
    const float3 delta = s - b_mean, delta_d = s_d - bd_mean;
    b_mean += delta / (float)(j + 1);
    b_m2 += delta * (s - b_mean);
    bd_mean += delta_d / (float)(j + 1);
    bd_m2 += delta_d * (s_d - bd_mean);
  }
  /* mean.w counts the samples already merged: the host zeroes the pair to start a new block of paths
   * (its independent batches, host/reference/batch_error.h) while sample_start goes on numbering them. */
  const float4 a = mean[pixel];
  const float na = a.w, nb = (float)samples, n = na + nb;
  const float3 a_mean = a.xyz, a_m2 = m2[pixel].xyz;
  const float3 delta = b_mean - a_mean;
  const float3 new_mean = na > 0.0f ? a_mean + delta * (nb / n) : b_mean;
  const float3 new_m2 = na > 0.0f ? a_m2 + b_m2 + delta * delta * (na * nb / n) : b_m2;
  mean[pixel] = (float4)(new_mean, n);
  m2[pixel] = (float4)(new_m2, 0.0f);
  const float3 ad_mean = direct_mean[pixel].xyz, ad_m2 = direct_m2[pixel].xyz;
  const float3 delta_d = bd_mean - ad_mean;
  direct_mean[pixel] = (float4)(na > 0.0f ? ad_mean + delta_d * (nb / n) : bd_mean, n);
  direct_m2[pixel] = (float4)(na > 0.0f ? ad_m2 + bd_m2 + delta_d * delta_d * (na * nb / n) : bd_m2, 0.0f);
}
