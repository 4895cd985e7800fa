/* sea_single.cl — the sea seen from above: Fresnel reflection of sky and sun, single scattering of
 * sunlight in the water (000 eq. 5), and the sun reflected by the bottom (000 eq. 9; flat, or a height
 * field with z_Q and the local floor normal per pixel, 000 §5.4, SEASIM_BOTTOM_HEIGHTFIELD), evaluated per
 * wavelength band and accumulated straight into sensor RGB (002 eq. 4.8), never storing the spectrum
 * unless SEASIM_SPECTRAL_OUTPUT asks for it.
 *
 * Inputs: SeaParams (camera, sun, water ior/g, bottom depth, ocean and sky sizes), the band table
 * (SeaBand's fields and the LUT, bands contiguous,
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
 * the bottom lit and seen through forward-scattering water; needs SEASIM_SEA_LUT 0); SEASIM_SEA_SKY_TABLE
 * (quality.sea_sky_table, an analytic sky): n > 0 reads the reflected sky from the n x n table the pass
 * appends to the sky buffer (common/sky_table.h), 0 evaluates the sky model at every reflected direction.
 * Band loop: SEASIM_BAND_LANES bands per step in floatN (common/band_lanes.h), reading the band table
 * (common/sea_band_table.h: SeaBand's fields and the LUT, bands contiguous): sea.model "paper"
 * (SEASIM_SEA_MODEL 0) through common/sea_bands.h, "multiple" (SEASIM_SEA_MODEL 1) through
 * common/sea_multiple_bands.h (sea_multiple.h's closed form on the lanes), the sky above the horizon the
 * same for both; the pixel's work (view, Fresnel, sun, bottom hit, LUT taps, whether the reflected ray
 * sees the sun's disk) is done once before it. The lanes add the bands into RGB in another order than one
 * band at a time (per lane, then across lanes): float rounding only.
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
#include "common/gauss_legendre.h"
#include "common/optics.h"
#include "common/sea_params.h"
#include "common/sea_surface.h"
#include "common/sea_waves.h"
#include "common/sea_lean.h"
#include "common/polynomial_trig.h"
#include "common/sky.h"
#include "common/sky_table.h"
#include "common/sea_bottom_params.h"
#include "common/sea_second.h"
#include "common/sea_bottom.h"
#include "common/caustic_map.h"
#include "common/sea_multiple.h"
#include "common/band_lanes.h"
#include "common/band_lanes_math.h"
#include "common/sky_view_lanes.h"
#include "common/sea_band_table.h"
#include "common/sea_bands.h"
#include "common/sea_multiple_bands.h"
#include "common/sea_ordinates.h"
#include "common/sea_view.h"
#include "common/sea_band_terms.h"

#ifndef SEASIM_HAS_REFLECTION
#define SEASIM_HAS_REFLECTION 0
#endif
#ifndef SEASIM_HAS_SINGLE_SCATTERING
#define SEASIM_HAS_SINGLE_SCATTERING 0
#endif
#ifndef SEASIM_HAS_BOTTOM
#define SEASIM_HAS_BOTTOM 0
#endif
#ifndef SEASIM_HAS_SUN
#define SEASIM_HAS_SUN 0
#endif
#ifndef SEASIM_SPECTRAL_OUTPUT
#define SEASIM_SPECTRAL_OUTPUT 0
#endif
#ifndef SEASIM_SEA_LUT
#define SEASIM_SEA_LUT 0
#endif
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
#ifndef SEASIM_SEA_SKY_TABLE
#define SEASIM_SEA_SKY_TABLE 0
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

#if SEASIM_SPECTRAL_OUTPUT && SEASIM_SUPERSAMPLE > 1
/* Adds the first count (>= 1) lanes of v to dst (band_lanes.h's store_lanes, summing the sub-pixel rays). */
static inline void add_lanes(realb v, __global float* dst, int count) {
  float lanes[SEASIM_BAND_LANES] __attribute__((aligned(4 * SEASIM_BAND_LANES)));
  *(realb*)lanes = v;
  for (int j = 0; j < count && j < SEASIM_BAND_LANES; ++j) dst[j] += lanes[j];
}
#endif

/* The per-pixel terms are common/sea_view.h's, the band steps common/sea_band_terms.h's; this entry
 * point picks the sub-pixel rays and sums the bands into RGB (and the spectrum when it is asked for). */
__kernel void sea_single(__constant SeaParams* p, __global const float* table,
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
#if !SEASIM_BOTTOM_HEIGHTFIELD
  __constant SeaHeightField* hf = 0;
  __global const float* hf_depth = 0;
#endif
  const SeaFeatures f = {SEASIM_HAS_REFLECTION, SEASIM_HAS_SINGLE_SCATTERING, SEASIM_HAS_BOTTOM, SEASIM_HAS_SUN,
                         SEASIM_HAS_WAVES, SEASIM_WAVE_FILTER, SEASIM_SKY_MODEL, SEASIM_SEA_LUT,
                         SEASIM_BOTTOM_CAUSTICS, SEASIM_BOTTOM_HEIGHTFIELD, SEASIM_SEA_MODEL, SEASIM_SEA_SKY_TABLE};
  const int band_count = p->band_count;
  const int stride = SEA_BAND_STRIDE(band_count);
  realb r_lanes = SPLATB(0.0f), g_lanes = SPLATB(0.0f), b_lanes = SPLATB(0.0f); /* the lanes' sums */
#if SEASIM_SUPERSAMPLE > 1
  /* The reference of the wave filter: n x n rays on a regular grid over the pixel, averaged. */
  const float sub_weight = 1.0f / (float)(SEASIM_SUPERSAMPLE * SEASIM_SUPERSAMPLE);
#if SEASIM_SPECTRAL_OUTPUT
  for (int i = 0; i < p->band_count; ++i) spectral[(size_t)pixel * p->band_count + i] = 0.0f;
#endif
#define SPECTRAL_LANES(i, L) add_lanes((L) * sub_weight, spectral + (size_t)pixel * band_count + (i), band_count - (i))
#else
  const float sub_weight = 1.0f;
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
    r_lanes += Lw_ * SEA_TABLE_LANES(table, stride, SEA_ROW_W_R, i);                                       \
    g_lanes += Lw_ * SEA_TABLE_LANES(table, stride, SEA_ROW_W_G, i);                                       \
    b_lanes += Lw_ * SEA_TABLE_LANES(table, stride, SEA_ROW_W_B, i);                                       \
    SPECTRAL_LANES_IF_ASKED(i, L);                                                                         \
  } while (0)
  for (int sub = 0; sub < SEASIM_SUPERSAMPLE * SEASIM_SUPERSAMPLE; ++sub) {
    const float3 d = sea_camera_ray(p, x, y, sub, SEASIM_SUPERSAMPLE);
    if (d.y >= 0.0f) { /* above the horizon: the sky itself */
      const float3 shape = sea_sky_shape(SEASIM_SKY_MODEL, p, sky, d);
      const int sees_sun = sea_sees_sun(SEASIM_HAS_SUN, p, d);
      for (int i = 0; i < band_count; i += SEASIM_BAND_LANES) {
        const realb L = sea_sky_lanes_b(SEASIM_SKY_MODEL, table, stride, i, shape, sees_sun, p->sun_solid_angle);
        ADD_LANES(i, L);
      }
      continue;
    }
    SeaPixel px;
    sea_pixel(f, p, normals, slope_mips, sky, bottom_caustics, hf, hf_depth, d, &px);
#if SEASIM_SEA_MODEL == 0 /* the band lanes (common/sea_bands.h), SEASIM_BAND_LANES bands per step */
    for (int i = 0; i < band_count; i += SEASIM_BAND_LANES) {
      const realb L = sea_band_lanes_b(f, table, stride, i, &px, p->sun_solid_angle);
      ADD_LANES(i, L);
    }
#else /* SEASIM_SEA_MODEL 1: the closed form on the band lanes (common/sea_multiple_bands.h) */
    for (int i = 0; i < band_count; i += SEASIM_BAND_LANES) {
      const realb L = sea_multiple_lanes_b(f, p, table, stride, i, &px);
      ADD_LANES(i, L);
    }
#endif
  } /* sub-pixel rays */
#undef SPECTRAL_LANES
#undef SPECTRAL_LANES_IF_ASKED
#undef ADD_LANES
  rgb[3 * pixel + 0] = SUMB(r_lanes);
  rgb[3 * pixel + 1] = SUMB(g_lanes);
  rgb[3 * pixel + 2] = SUMB(b_lanes);
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
