/* sea_single.cl — the sea seen from above: Fresnel reflection of sky and sun, single scattering of
 * sunlight in the water (000 eq. 5), and the sun reflected by the bottom (000 eq. 9; flat, or a height
 * field with z_Q and the local floor normal per pixel, 000 §5.4, SEASIM_BOTTOM_HEIGHTFIELD), evaluated per
 * wavelength band and accumulated straight into sensor RGB (002 eq. 4.8), never storing the spectrum
 * unless SEASIM_SPECTRAL_OUTPUT asks for it.
 *
 * Inputs: SeaParams (camera, sun, water ior/g, bottom depth, ocean and sky sizes), SeaBand[band_count]
 * (the scalar loop), the band table (the lanes: SeaBand's fields and the LUT, bands contiguous,
 * common/sea_band_table.h), the ocean's normal map (N x N float4, SEASIM_HAS_WAVES; one dummy texel
 * otherwise) and the environment image (float4 texels, SEASIM_SKY_MODEL 2; one dummy texel otherwise),
 * the bottom's caustic map (SEASIM_BOTTOM_CAUSTICS: the FFT ocean's flux-conservation caustics on the
 * bottom, mean 1, periodic over the patch on a flat bottom, over the floor's square on a height field;
 * one dummy float otherwise).
 * Output: rgb[3 * pixels] linear sensor RGB; spectral[band_count * pixels] when SEASIM_SPECTRAL_OUTPUT.
 * Radiometry (docs/radiometry.md): the water-leaving terms (eq. 5, 9) cross the surface as
 * radiance / n², T_o (1 - R) / n²; the sun's irradiance is given normal to its beam.
 * Defines (chosen by host/plan): SEASIM_HAS_REFLECTION, SEASIM_HAS_SINGLE_SCATTERING,
 * SEASIM_HAS_BOTTOM, SEASIM_HAS_SUN, SEASIM_SPECTRAL_OUTPUT, SEASIM_HAS_WAVES (FFT wave normals,
 * common/sea_waves.h), SEASIM_SKY_MODEL (0 uniform, 1 CIE clear sky, 2 environment image,
 * common/sky.h; 3 Preetham), SEASIM_BOTTOM_CAUSTICS, SEASIM_BOTTOM_HEIGHTFIELD (with SEASIM_HAS_BOTTOM: the floor is the height field
 * of the last two arguments, common/sea_bottom.h; forces SEASIM_SEA_LUT 0); SEASIM_SEA_LUT (the
 * pass, from quality.sea_lut_size): 1 reads eq. 5's factors from the look-up table the paper uses,
 * 0 evaluates eq. 5 exactly; SEASIM_SEA_MODEL (sea.model): 0 paper 000's eq. 5 and 9, 1 "multiple", all
 * orders in closed form (common/sea_multiple.h: QSSA with Lee et al.'s factors, skylight in the water,
 * the bottom lit and seen through forward-scattering water; needs SEASIM_SEA_LUT 0).
 * Band loop: sea.model "single" (SEASIM_SEA_MODEL 0, every other variant) runs
 * SEASIM_BAND_LANES bands per step in floatN (common/band_lanes.h, common/sea_bands.h), reading the band
 * table (common/sea_band_table.h: SeaBand's fields and the LUT, bands contiguous); the pixel's work
 * (view, Fresnel, sun, bottom hit, LUT taps, whether the reflected ray sees the sun's disk) is done once
 * before it. sea.model "multiple" stays on the scalar loop over SeaBand (sea_multiple.h's closed form
 * has no lanes version); the sky above the horizon takes the lanes for both. The lanes add the bands
 * into RGB in another order than one band at a time (per lane, then across lanes): float rounding only.
 * LUT: row SEA_ROW_LUT + j of the table holds, for every band, eq. 5 without beta and T_o (T_o is
 * already computed per pixel for the reflection) at angle j/(lut_size - 1) * pi/2, built by the host
 * in double; the angle is theta_jo on a flat sea (the paper's table) and the refracted view's theta_ji
 * with waves (a tilted normal decouples the two, and theta_ji then ranges over [0, pi/2], not
 * [0, 48.6 deg]). Read by Catmull–Rom interpolation with mirrored ends (the factors are even about 0 and pi/2).
 * Waves: the view ray meets the mean surface y = 0 and takes the local normal there for Fresnel,
 * reflection and refraction; sunlight still enters through the flat mean surface (000 §3; the
 * approximations are spelled out in common/sea_waves.h).
 * Stiff cases: view rays at or above the horizon see the sky (no surface hit); the sun at or below
 * the horizon contributes nothing below the surface; grazing refraction is clamped away from cos = 0;
 * back-facing and folded wave normals, reflections pointing below the horizon (common/sea_waves.h).
 */
#include "common/compat.h"
#include "common/optics.h"
#include "common/sea_params.h"
#include "common/sea_surface.h"
#include "common/sea_waves.h"
#include "common/sea_lean.h"
#include "common/sky.h"
#include "common/sea_bottom_params.h"
#include "common/sea_second.h"
#include "common/sea_bottom.h"
#include "common/caustic_map.h"
#include "common/sea_multiple.h"
#include "common/band_lanes.h"
#include "common/band_lanes_math.h"
#include "common/sea_band_table.h"
#include "common/sea_bands.h"

#ifndef SEASIM_HAS_WAVES
#define SEASIM_HAS_WAVES 0
#endif
#ifndef SEASIM_SKY_MODEL
#define SEASIM_SKY_MODEL 0
#endif
#ifndef SEASIM_BOTTOM_CAUSTICS
#define SEASIM_BOTTOM_CAUSTICS 0 /* 1: the FFT ocean's caustics modulate the sun on the bottom (004 §5.2.1) */
#endif
#ifndef SEASIM_BOTTOM_HEIGHTFIELD
#define SEASIM_BOTTOM_HEIGHTFIELD 0 /* 1: the bottom is a height field (000 §5.4, common/sea_bottom.h) */
#endif
#ifndef SEASIM_WAVE_FILTER
#define SEASIM_WAVE_FILTER 0 /* 1: wave normals filtered over the pixel's footprint (common/sea_lean.h) */
#endif
#ifndef SEASIM_SEA_MODEL
#define SEASIM_SEA_MODEL 0 /* 0: paper 000's eq. 5 and 9; 1: sea.model = "multiple" (common/sea_multiple.h) */
#endif
#if SEASIM_SEA_MODEL == 1 && SEASIM_SEA_LUT
#error "sea.model = \"multiple\" evaluates eq. 5 exactly (SEASIM_SEA_LUT=0)"
#endif
#ifndef SEASIM_SUPERSAMPLE
#define SEASIM_SUPERSAMPLE 1 /* n: n x n rays per pixel, averaged (the wave filter's reference) */
#endif
#if SEASIM_WAVE_FILTER && (!SEASIM_HAS_WAVES || SEASIM_SUPERSAMPLE > 1)
#error "the wave filter needs waves, and the supersampled reference reads the unfiltered normals"
#endif
#if SEASIM_BOTTOM_HEIGHTFIELD && SEASIM_SEA_LUT
#error "a height-field bottom needs the exact eq. 5 (SEASIM_SEA_LUT=0): z_Q changes from pixel to pixel"
#endif

/* The sky's direction-dependent factor towards d (common/sky.h), the same for every band: scale ×
 * shape, as RGB for the image and as CIE daylight basis weights for Preetham (mixed per band by
 * sky_w_*); 1 for the uniform sky. */
static inline float3 sky_shape(const __constant SeaParams* p, const __global float* sky, float3 d) {
#if SEASIM_SKY_MODEL == SEASIM_SKY_ANALYTIC
  const float3 sun = (float3)(p->sun_dir[0], p->sun_dir[1], p->sun_dir[2]);
  const float s = p->sky_scale * sky_cie_clear_shape(d, sun);
  return (float3)(s, s, s);
#elif SEASIM_SKY_MODEL == SEASIM_SKY_IMAGE
  return p->sky_scale * sky_latlong_rgb(sky, p->sky_width, p->sky_height, d);
#elif SEASIM_SKY_MODEL == SEASIM_SKY_PREETHAM
  const float3 sun = (float3)(p->sun_dir[0], p->sun_dir[1], p->sun_dir[2]);
  return p->sky_scale * sky_preetham_daylight(sky, d, sun); /* spectral: CIE daylight basis weights */
#else
  return (float3)(1.0f, 1.0f, 1.0f);
#endif
}

/* One band's sky radiance for a shape from sky_shape (linear in the shape: a weighted sum of shapes
 * gives the same sum of radiances, which the wave filter uses). */
static inline float sky_band(const __global SeaBand* band, float3 shape) {
#if SEASIM_SKY_MODEL == SEASIM_SKY_IMAGE || SEASIM_SKY_MODEL == SEASIM_SKY_PREETHAM
  /* sky_view_band's rule (common/sky_view.h): the daylight basis past its range is held at 0. */
  return band->sky_radiance *
         fmax(band->sky_w_r * shape.x + band->sky_w_g * shape.y + band->sky_w_b * shape.z, 0.0f);
#else
  return band->sky_radiance * shape.x; /* uniform: shape 1; analytic: grey */
#endif
}

/* Radiance of the sky (and the sun's disk) seen along direction d, for one band; shape = sky_shape(d). */
static inline float sky_radiance(const __constant SeaParams* p, const __global SeaBand* band, float3 shape, float3 d) {
  float L = sky_band(band, shape);
#if SEASIM_HAS_SUN
  float3 sun = (float3)(p->sun_dir[0], p->sun_dir[1], p->sun_dir[2]);
  /* A sun of radius 0 (a point) has no disk to see: skip it rather than divide by 0. */
  if (p->sun_solid_angle > 0.0f && dot(d, sun) >= p->cos_sun_radius) L += band->sun_irradiance / p->sun_solid_angle;
#endif
  return L;
}

#if SEASIM_SPECTRAL_OUTPUT && SEASIM_SUPERSAMPLE > 1
/* Adds the first count (>= 1) lanes of v to dst (band_lanes.h's store_lanes, summing the sub-pixel rays). */
static inline void add_lanes(realb v, __global float* dst, int count) {
  float lanes[SEASIM_BAND_LANES] __attribute__((aligned(4 * SEASIM_BAND_LANES)));
  *(realb*)lanes = v;
  for (int j = 0; j < count && j < SEASIM_BAND_LANES; ++j) dst[j] += lanes[j];
}
#endif

__kernel void sea_single(__constant SeaParams* p, __global const SeaBand* bands, __global const float* table,
                         __global const float* normals, __global const float* slope_mips, __global const float* sky,
                         __global const float* bottom_caustics, __global float* rgb
#if SEASIM_SPECTRAL_OUTPUT
                         , __global float* spectral
#endif
#if SEASIM_BOTTOM_HEIGHTFIELD /* keep these two last: the pass sets them as the last two arguments */
                         , __constant SeaHeightField* hf, __global const float* hf_depth
#endif
) {
  const int x = get_global_id(0);
  const int y = get_global_id(1);
  if (x >= p->width || y >= p->height) return;
  const int pixel = y * p->width + x;

  const float3 right = (float3)(p->cam_right[0], p->cam_right[1], p->cam_right[2]);
  const float3 up = (float3)(p->cam_up[0], p->cam_up[1], p->cam_up[2]);
  const float3 fwd = (float3)(p->cam_forward[0], p->cam_forward[1], p->cam_forward[2]);
  const int band_count = p->band_count;
  const int stride = SEA_BAND_STRIDE(band_count);
#define ROW(r) (table + (size_t)(r) * stride)
  float r = 0.0f, g = 0.0f, b = 0.0f;                                     /* the scalar loop's sums */
  realb r_lanes = SPLATB(0.0f), g_lanes = SPLATB(0.0f), b_lanes = SPLATB(0.0f); /* the lanes' sums */
#if SEASIM_SUPERSAMPLE > 1
  /* The reference of the wave filter: n x n rays on a regular grid over the pixel, averaged. */
  const float sub_weight = 1.0f / (float)(SEASIM_SUPERSAMPLE * SEASIM_SUPERSAMPLE);
#if SEASIM_SPECTRAL_OUTPUT
  for (int i = 0; i < p->band_count; ++i) spectral[(size_t)pixel * p->band_count + i] = 0.0f;
#endif
#define SPECTRAL_STORE(i, L) spectral[(size_t)pixel * p->band_count + (i)] += (L) * sub_weight
#define SPECTRAL_LANES(i, L) add_lanes((L) * sub_weight, spectral + (size_t)pixel * band_count + (i), band_count - (i))
#else
  const float sub_weight = 1.0f;
#define SPECTRAL_STORE(i, L) spectral[(size_t)pixel * p->band_count + (i)] = (L)
#define SPECTRAL_LANES(i, L) store_lanes((L), spectral + (size_t)pixel * band_count + (i), band_count - (i))
#endif
#if SEASIM_SPECTRAL_OUTPUT
#define SPECTRAL_LANES_IF_ASKED(i, L) SPECTRAL_LANES(i, L)
#else
#define SPECTRAL_LANES_IF_ASKED(i, L)
#endif
/* One step's radiance L (bands i .. i + SEASIM_BAND_LANES - 1) into the pixel's sums (by the
 * sensor's weights per band; the padding bands' are 0), and into the spectral buffer when it is asked for. */
#define ADD_LANES(i, L)                                                                                   \
  do {                                                                                                     \
    const realb Lw_ = (L) * sub_weight;                                                                    \
    r_lanes += Lw_ * LOADB(ROW(SEA_ROW_W_R), i);                                                           \
    g_lanes += Lw_ * LOADB(ROW(SEA_ROW_W_G), i);                                                           \
    b_lanes += Lw_ * LOADB(ROW(SEA_ROW_W_B), i);                                                           \
    SPECTRAL_LANES_IF_ASKED(i, L);                                                                         \
  } while (0)
  for (int sub = 0; sub < SEASIM_SUPERSAMPLE * SEASIM_SUPERSAMPLE; ++sub) {
  /* Pinhole camera: a point of the pixel (its centre without supersampling) -> world direction. */
  const float ox = ((float)(sub % SEASIM_SUPERSAMPLE) + 0.5f) / (float)SEASIM_SUPERSAMPLE;
  const float oy = ((float)(sub / SEASIM_SUPERSAMPLE) + 0.5f) / (float)SEASIM_SUPERSAMPLE;
  const float u = (2.0f * (x + ox) / p->width - 1.0f) * p->tan_half_fov_y * p->aspect;
  const float v = (1.0f - 2.0f * (y + oy) / p->height) * p->tan_half_fov_y;
  const float3 d = normalize(fwd + u * right + v * up);

  if (d.y >= 0.0f) {
    /* Above the horizon: the sky itself. */
    const float3 shape = sky_shape(p, sky, d);
#if SEASIM_HAS_SUN
    /* sky_radiance's sun disk; a point sun (radius 0) has none. */
    const float3 sun = (float3)(p->sun_dir[0], p->sun_dir[1], p->sun_dir[2]);
    const int sees_sun = p->sun_solid_angle > 0.0f && dot(d, sun) >= p->cos_sun_radius;
#endif
    for (int i = 0; i < band_count; i += SEASIM_BAND_LANES) {
      const realb sky_l = sea_sky_band_b(SEASIM_SKY_MODEL, LOADB(ROW(SEA_ROW_SKY), i), LOADB(ROW(SEA_ROW_SKY_W_R), i),
                                         LOADB(ROW(SEA_ROW_SKY_W_G), i), LOADB(ROW(SEA_ROW_SKY_W_B), i), shape);
#if SEASIM_HAS_SUN
      const realb L = sees_sun ? sky_l + LOADB(ROW(SEA_ROW_SUN), i) / p->sun_solid_angle : sky_l;
#else
      const realb L = sky_l;
#endif
      ADD_LANES(i, L);
    }
  } else {
    const float3 sun = (float3)(p->sun_dir[0], p->sun_dir[1], p->sun_dir[2]);
#if SEASIM_WAVE_FILTER
    /* The footprint's slope statistics (common/sea_lean.h): its mean normal refracts the view, the
     * Fresnel-weighted sky of its facets is reflected, and the facets facing the sun give the glint. */
    const float t_hit = sea_mean_surface_distance(p->cam_pos[1], d);
    const float minor = t_hit * p->pixel_angle * fmax(dot(d, fwd), 0.1f);
    const float major = minor / fmax(-d.y, 1e-6f);
    const float horizontal = sqrt(d.x * d.x + d.z * d.z);
    const float dir_x = horizontal > 1e-6f ? d.x / horizontal : 1.0f, dir_z = horizontal > 1e-6f ? d.z / horizontal : 0.0f;
    float stats[SEA_LEAN_STRIDE];
    sea_lean_footprint(slope_mips, p->ocean_n, p->ocean_patch, p->cam_pos[0] + t_hit * d.x, p->cam_pos[2] + t_hit * d.z,
                       dir_x, dir_z, minor, major, stats);
    float cxx, czz, cxz, l11, l21, l22;
    sea_lean_covariance(stats[2], stats[3], stats[4], p->sun_slope_variance, &cxx, &czz, &cxz, &l11, &l21, &l22);
    const float3 n = sea_facing_normal(d, sea_lean_normal(stats[0], stats[1]));
    /* Facets turned away from the eye are bent to grazing by the unfiltered path: F = 1, and the ray
     * goes on to the horizon's sky (common/sea_lean.h, sea_lean_rule). */
    const SeaLeanRule rule = sea_lean_rule(d, stats[0], stats[1], l11, l21, l22);
    float R_mean = rule.back;
    float3 reflected_shape = rule.back * sky_shape(p, sky, sea_sky_direction(d));
    const int nodes = sea_lean_rule_nodes(&rule);
    for (int k = 0; k < nodes; ++k) {
      float sx, sz;
      const float w = sea_lean_rule_node(&rule, k, &sx, &sz);
      const float3 nk = sea_facing_normal(d, sea_lean_normal(sx, sz));
      const float wf = w * fresnel_reflectance(-dot(d, nk), 1.0f, p->ior);
      R_mean += wf;
      reflected_shape += wf * sky_shape(p, sky, sea_sky_direction(reflect_dir(d, nk)));
    }
    float glint = 0.0f;
#if SEASIM_HAS_SUN
    if (sun.y > 0.0f && p->sun_solid_angle > 0.0f) glint = sea_lean_glint(d, sun, p->ior, stats[0], stats[1], cxx, czz, cxz);
#endif
    float R_center;
    float3 reflected, view_in_water;
    const float cos_ji = sea_view_interaction(d, n, p->ior, &R_center, &reflected, &view_in_water);
    const float R_view = R_mean;
#else
#if SEASIM_HAS_WAVES
    /* The local normal where the view ray meets the mean surface (common/sea_waves.h). */
    const float t_hit = sea_mean_surface_distance(p->cam_pos[1], d);
    const float3 n = sea_facing_normal(d, sea_wave_normal(normals, p->ocean_n, p->ocean_patch,
                                                          p->cam_pos[0] + t_hit * d.x, p->cam_pos[2] + t_hit * d.z));
#else
    const float3 n = (float3)(0.0f, 1.0f, 0.0f);
#endif
    float R_view;
    float3 reflected, view_in_water;
    const float cos_ji = sea_view_interaction(d, n, p->ior, &R_view, &reflected, &view_in_water);
#endif
    /* T_o of 000 eq. 5, 9 with the n² law: radiance / n² is conserved across the surface, so the
     * water-leaving radiance L_w reaches the air as L_w (1 - R) / n² (docs/radiometry.md). Paper 000
     * writes T_o alone; kd_multiple.cl applies the same law the other way (sky seen from below). */
    const float t_out = (1.0f - R_view) / (p->ior * p->ior);
#if SEASIM_HAS_REFLECTION && !SEASIM_WAVE_FILTER
    const float3 reflected_shape = sky_shape(p, sky, reflected);
#endif

    /* Sunlight enters through the flat mean surface (000 §3), with or without waves. */
    const float3 flat_n = (float3)(0.0f, 1.0f, 0.0f);
    float t_in = 0.0f, cos_io = 1.0f, cos_alpha = 1.0f, sun_horizontal = 0.0f;
#if SEASIM_HAS_SUN
    if (sun.y > 0.0f) {
      t_in = 1.0f - fresnel_reflectance(sun.y, 1.0f, p->ior);
      sun_horizontal = sun.y;                                 /* E on the horizontal surface / E normal */
      float3 sun_in_water;                                    /* travel direction of sunlight */
      refract_dir(-sun, flat_n, 1.0f / p->ior, &sun_in_water);
      cos_io = fmax(-sun_in_water.y, 1e-4f);
      cos_alpha = dot(sun_in_water, -view_in_water);          /* scattered towards the eye */
    }
#endif
    const float c_f = hg_forward_fraction(p->g);
    const float phase = hg_phase(cos_alpha, p->g);
#if SEASIM_SEA_MODEL == 1
    const float mu_sky = sea_sky_mean_cosine(p->ior);             /* the skylight's mean cosine in the water */
    const float r_below = sea_surface_reflectance_below(p->sky_fresnel_mean, p->ior); /* the surface's light back down */
    const float mu_ret = sea_reflected_mean_cosine(r_below, p->ior);                   /* and its mean cosine */
#endif
#if SEASIM_HAS_BOTTOM && SEASIM_BOTTOM_HEIGHTFIELD
    /* 000 §5.4: z_Q, the depth where the refracted view ray from P meets the height field, replaces
     * z_d in eq. 5 and 9, and the floor's normal at Q gives eq. 9's cos(gamma). P is where the view
     * ray meets the mean surface y = 0. The floor does not shadow the sun (not modelled). */
    const float t_p = p->cam_pos[1] / -d.y;
    const float3 P = (float3)(p->cam_pos[0] + t_p * d.x, 0.0f, p->cam_pos[2] + t_p * d.z);
    float t_q;
    float3 n_q;
    sea_hf_intersect(hf, hf_depth, P, view_in_water, 1e30f, &t_q, &n_q);
    const float z_d = fmax(-view_in_water.y, 0.0f) * t_q;
    float cos_gamma = 0.0f;
#if SEASIM_HAS_SUN
    if (sun.y > 0.0f) {
      float3 sun_travel;
      refract_dir(-sun, flat_n, 1.0f / p->ior, &sun_travel);
      cos_gamma = fmax(dot(n_q, -sun_travel), 0.0f);
    }
#endif
#elif SEASIM_HAS_BOTTOM
    const float z_d = p->bottom_depth;
#if SEASIM_BOTTOM_CAUSTICS
    const float t_p = p->cam_pos[1] / -d.y;
    const float3 P = (float3)(p->cam_pos[0] + t_p * d.x, 0.0f, p->cam_pos[2] + t_p * d.z);
    const float t_q = z_d / fmax(-view_in_water.y, 1e-4f);
#endif
#else
    const float z_d = -1.0f;                                  /* no bottom: infinitely deep */
#endif
#if SEASIM_HAS_BOTTOM && SEASIM_BOTTOM_CAUSTICS
    /* The ocean's caustics where the view ray meets the bottom (Q = P + t_q view_in_water): the sun
     * term of eq. 9 is the mean beam times this focusing factor (mean 1; caustic_stack.h). */
    const float3 Q = P + t_q * view_in_water;
    const float focus = caustic_map_read(bottom_caustics, p->caustic_map_size, p->caustic_extent, p->caustic_origin,
                                         !SEASIM_BOTTOM_HEIGHTFIELD, Q.x, Q.z);
#else
    const float focus = 1.0f;
#endif
#if SEASIM_SEA_MODEL == 0
    /* The band lanes (common/sea_bands.h): what is the same for every band was found above or here,
     * once per pixel; each step then reads SEASIM_BAND_LANES bands of the table with vector loads. */
#if SEASIM_SEA_LUT
#if SEASIM_HAS_WAVES
    const float lut_angle = acos(clamp(cos_ji, 0.0f, 1.0f));          /* theta_ji */
#else
    const float lut_angle = acos(clamp(-d.y, 0.0f, 1.0f));            /* theta_jo (cos_jo = -d.y) */
#endif
    int lut_jm, lut_j, lut_jp;
    const float lut_t =
        sea_lut_taps(p->lut_size, lut_angle * (p->lut_size - 1) * (2.0f / M_PI_F), &lut_jm, &lut_j, &lut_jp);
#endif
#if SEASIM_HAS_REFLECTION && !SEASIM_WAVE_FILTER && SEASIM_HAS_SUN
    /* sky_radiance's sun disk along the reflected ray; a point sun (radius 0) has none. */
    const int reflects_sun = p->sun_solid_angle > 0.0f && dot(reflected, sun) >= p->cos_sun_radius;
#endif
    for (int i = 0; i < band_count; i += SEASIM_BAND_LANES) {
      const realb sun_e = LOADB(ROW(SEA_ROW_SUN), i);
      realb L = SPLATB(0.0f);
#if SEASIM_HAS_REFLECTION
      const realb sky_l = sea_sky_band_b(SEASIM_SKY_MODEL, LOADB(ROW(SEA_ROW_SKY), i), LOADB(ROW(SEA_ROW_SKY_W_R), i),
                                         LOADB(ROW(SEA_ROW_SKY_W_G), i), LOADB(ROW(SEA_ROW_SKY_W_B), i), reflected_shape);
#if SEASIM_WAVE_FILTER
      L += sky_l + glint * sun_e; /* R already in both */
#elif SEASIM_HAS_SUN
      L += R_view * (reflects_sun ? sky_l + sun_e / p->sun_solid_angle : sky_l);
#else
      L += R_view * sky_l;
#endif
#endif
#if SEASIM_HAS_SINGLE_SCATTERING
      const realb scattering = LOADB(ROW(SEA_ROW_B), i);
#if SEASIM_SEA_LUT
      L += scattering * phase * t_out *
           sea_lut_read_b(LOADB(ROW(SEA_ROW_LUT + lut_jm), i), LOADB(ROW(SEA_ROW_LUT + lut_j), i),
                          LOADB(ROW(SEA_ROW_LUT + lut_j + 1), i), LOADB(ROW(SEA_ROW_LUT + lut_jp), i), lut_t);
#else
      const realb c = LOADB(ROW(SEA_ROW_C), i);
      const realb albedo = SELECTB(c > 0.0f, scattering / c, SPLATB(0.0f));
      L += sea_single_scattering_b(sun_e * sun_horizontal, t_in, t_out, scattering * phase, c, albedo, c_f, cos_io,
                                   cos_ji, z_d);
#endif
#endif
#if SEASIM_HAS_BOTTOM
      const realb bottom = sea_bottom_reflection_b(sun_e * sun_horizontal, t_in, t_out,
                                                   LOADB(ROW(SEA_ROW_BOTTOM_ALBEDO), i), LOADB(ROW(SEA_ROW_C), i), z_d,
                                                   cos_io, cos_ji);
#if SEASIM_BOTTOM_HEIGHTFIELD
      L += focus * (bottom * (cos_gamma / cos_io)); /* sea_bottom_reflection_tilted */
#else
      L += focus * bottom;
#endif
#endif
      ADD_LANES(i, L);
    }
#else /* SEASIM_SEA_MODEL 1: one band per step over SeaBand */
    for (int i = 0; i < band_count; ++i) {
      const __global SeaBand* band = &bands[i];
      float L = 0.0f;
#if SEASIM_HAS_REFLECTION && SEASIM_WAVE_FILTER
      L += sky_band(band, reflected_shape) + glint * band->sun_irradiance; /* R already in both */
#elif SEASIM_HAS_REFLECTION
      L += R_view * sky_radiance(p, band, reflected_shape, reflected);
#endif
      /* sea.model = "multiple": all orders in closed form (common/sea_multiple.h), through the
       * surface with T_o = (1 - R)/n². The sky's irradiance below the surface: π L_sky (1 - r̄), L_sky
       * the band's cosine-weighted mean sky radiance (sky_shape is normalised to mean 1). */
      const float e_sky = M_PI_F * sky_band(band, (float3)(1.0f, 1.0f, 1.0f)) * (1.0f - p->sky_fresnel_mean);
#if SEASIM_HAS_SINGLE_SCATTERING
      L += t_out * sea_multiple_column(band->sun_irradiance * sun_horizontal, t_in, e_sky, band->a, band->b, c_f, z_d,
                                       cos_io, cos_ji, phase, mu_sky);
#endif
#if SEASIM_HAS_BOTTOM
      L += t_out * sea_multiple_bottom(band->sun_irradiance * sun_horizontal, t_in, e_sky, band->a, band->b, c_f,
                                       band->bottom_albedo, z_d, cos_io, cos_ji, mu_sky, focus);
#endif
#if SEASIM_HAS_SINGLE_SCATTERING || SEASIM_HAS_BOTTOM
      /* What the surface reflects back down of the upwelling light, returned by the water (z_d < 0: no
       * bottom, so its albedo is unused). */
      L += t_out * sea_multiple_surface_return(band->sun_irradiance * sun_horizontal, t_in, e_sky, band->a, band->b, c_f,
                                               band->bottom_albedo, z_d, cos_io, cos_ji, mu_sky, focus, r_below, mu_ret,
                                               SEASIM_HAS_SINGLE_SCATTERING);
#endif
      const float Lw = L * sub_weight;
      r += Lw * band->w_r; g += Lw * band->w_g; b += Lw * band->w_b;
#if SEASIM_SPECTRAL_OUTPUT
      SPECTRAL_STORE(i, L);
#endif
    }
#endif /* SEASIM_SEA_MODEL */
  }
  } /* sub-pixel rays */
#undef SPECTRAL_STORE
#undef SPECTRAL_LANES
#undef SPECTRAL_LANES_IF_ASKED
#undef ADD_LANES
#undef ROW
  r += SUMB(r_lanes);
  g += SUMB(g_lanes);
  b += SUMB(b_lanes);
  rgb[3 * pixel + 0] = r;
  rgb[3 * pixel + 1] = g;
  rgb[3 * pixel + 2] = b;
}

#if SEASIM_WAVE_FILTER
/* The point map (common/sea_lean.h) from the ocean's normal map (float4 per texel). A folded facet's
 * downward normal is turned up first, as sea_facing_normal does. */
__kernel void sea_slope_moments(__global const float* normals, int n, __global float* mips) {
  const int i = get_global_id(0), j = get_global_id(1);
  if (i >= n || j >= n) return;
  const size_t at = (size_t)j * n + i;
  float3 nn = (float3)(normals[4 * at], normals[4 * at + 1], normals[4 * at + 2]);
  if (nn.y < 0.0f) nn = -nn;
  float sx, sz;
  sea_lean_slope(nn, &sx, &sz);
  __global float* m = mips + SEA_LEAN_STRIDE * at;
  m[0] = sx;
  m[1] = sz;
  m[2] = sx * sx;
  m[3] = sz * sz;
  m[4] = sx * sz;
}

/* Level 0: the moments of the bilinear slope field over each cell between four texels (periodic). */
__kernel void sea_slope_cells(__global float* mips, int n) {
  const int i = get_global_id(0), j = get_global_id(1);
  if (i >= n || j >= n) return;
  const int i1 = i + 1 < n ? i + 1 : 0, j1 = j + 1 < n ? j + 1 : 0;
  const __global float* a = mips + SEA_LEAN_STRIDE * ((size_t)j * n + i);
  const __global float* b = mips + SEA_LEAN_STRIDE * ((size_t)j * n + i1);
  const __global float* c = mips + SEA_LEAN_STRIDE * ((size_t)j1 * n + i);
  const __global float* e = mips + SEA_LEAN_STRIDE * ((size_t)j1 * n + i1);
  float m[SEA_LEAN_STRIDE];
  sea_lean_cell_moments(a[0], a[1], b[0], b[1], c[0], c[1], e[0], e[1], m);
  __global float* t = mips + sea_lean_level_offset(n, 0) + SEA_LEAN_STRIDE * ((size_t)j * n + i);
  for (int k = 0; k < SEA_LEAN_STRIDE; ++k) t[k] = m[k];
}

/* One mip level from the one above: 2 x 2 box averages (src_n even; the patch is periodic). */
__kernel void sea_slope_downsample(__global float* mips, int src_offset, int src_n, int dst_offset) {
  const int i = get_global_id(0), j = get_global_id(1), dst_n = src_n / 2;
  if (i >= dst_n || j >= dst_n) return;
  const __global float* s = mips + src_offset;
  __global float* t = mips + dst_offset + SEA_LEAN_STRIDE * ((size_t)j * dst_n + i);
  for (int k = 0; k < SEA_LEAN_STRIDE; ++k) {
    const float a = s[SEA_LEAN_STRIDE * ((size_t)(2 * j) * src_n + 2 * i) + k];
    const float b = s[SEA_LEAN_STRIDE * ((size_t)(2 * j) * src_n + 2 * i + 1) + k];
    const float c = s[SEA_LEAN_STRIDE * ((size_t)(2 * j + 1) * src_n + 2 * i) + k];
    const float e = s[SEA_LEAN_STRIDE * ((size_t)(2 * j + 1) * src_n + 2 * i + 1) + k];
    t[k] = 0.25f * ((a + b) + (c + e));
  }
}
#endif
