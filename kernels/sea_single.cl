/* sea_single.cl — the sea seen from above: Fresnel reflection of sky and sun, single scattering of
 * sunlight in the water (000 eq. 5), and the sun reflected by a flat bottom (000 eq. 9), evaluated per
 * wavelength band and accumulated straight into sensor RGB (002 eq. 4.8), never storing the spectrum
 * unless SEASIM_SPECTRAL_OUTPUT asks for it.
 *
 * Inputs: SeaParams (camera, sun, water ior/g, bottom depth), SeaBand[band_count].
 * Output: rgb[3 * pixels] linear sensor RGB; spectral[band_count * pixels] when SEASIM_SPECTRAL_OUTPUT.
 * Defines (chosen by host/plan): SEASIM_HAS_REFLECTION, SEASIM_HAS_SINGLE_SCATTERING,
 * SEASIM_HAS_BOTTOM, SEASIM_HAS_SUN, SEASIM_SPECTRAL_OUTPUT; SEASIM_SEA_LUT (the pass, from
 * quality.sea_lut_size): 1 reads eq. 5's factors from the look-up table over theta_jo the paper uses,
 * 0 evaluates eq. 5 exactly.
 * LUT: lut[band * lut_size + j] holds eq. 5 without beta and T_o (T_o is already computed per pixel
 * for the reflection) at theta_jo = j/(lut_size - 1) * pi/2, built by the host in double; read by
 * Catmull–Rom interpolation with mirrored ends (the factors are even about theta_jo = 0 and pi/2).
 * Stiff cases: view rays at or above the horizon see the sky (no surface hit); the sun at or below
 * the horizon contributes nothing below the surface; grazing refraction is clamped away from cos = 0.
 */
#include "common/compat.h"
#include "common/optics.h"
#include "common/sea_params.h"
#include "common/sea_surface.h"

/* Radiance of the sky (and the sun's disk) seen along direction d, for one band. */
static inline float sky_radiance(const __constant SeaParams* p, const __global SeaBand* band, float3 d) {
  float L = band->sky_radiance;
#if SEASIM_HAS_SUN
  float3 sun = (float3)(p->sun_dir[0], p->sun_dir[1], p->sun_dir[2]);
  if (dot(d, sun) >= p->cos_sun_radius) L += band->sun_irradiance / p->sun_solid_angle;
#endif
  return L;
}

#if SEASIM_SEA_LUT
/* Catmull–Rom read of one band's LUT at fractional index x in [0, n-1]; indices mirrored at both ends. */
static inline float lut_read(const __global float* lut, int n, float x) {
  const int j = clamp((int)x, 0, n - 2);
  const float t = x - (float)j;
  const int jm = j > 0 ? j - 1 : 1;
  const int jp = j + 2 < n ? j + 2 : n - 2;
  const float p0 = lut[jm], p1 = lut[j], p2 = lut[j + 1], p3 = lut[jp];
  return p1 + 0.5f * t * (p2 - p0 + t * (2.0f * p0 - 5.0f * p1 + 4.0f * p2 - p3 + t * (3.0f * (p1 - p2) + p3 - p0)));
}
#endif

__kernel void sea_single(__constant SeaParams* p, __global const SeaBand* bands, __global const float* lut,
                         __global float* rgb
#if SEASIM_SPECTRAL_OUTPUT
                         , __global float* spectral
#endif
) {
  const int x = get_global_id(0);
  const int y = get_global_id(1);
  if (x >= p->width || y >= p->height) return;
  const int pixel = y * p->width + x;

  /* Pinhole camera: pixel centre -> world direction (worldFromCamera basis). */
  const float u = (2.0f * (x + 0.5f) / p->width - 1.0f) * p->tan_half_fov_y * p->aspect;
  const float v = (1.0f - 2.0f * (y + 0.5f) / p->height) * p->tan_half_fov_y;
  const float3 right = (float3)(p->cam_right[0], p->cam_right[1], p->cam_right[2]);
  const float3 up = (float3)(p->cam_up[0], p->cam_up[1], p->cam_up[2]);
  const float3 fwd = (float3)(p->cam_forward[0], p->cam_forward[1], p->cam_forward[2]);
  const float3 d = normalize(fwd + u * right + v * up);

  float r = 0.0f, g = 0.0f, b = 0.0f;
  if (d.y >= 0.0f) {
    /* Above the horizon: the sky itself. */
    for (int i = 0; i < p->band_count; ++i) {
      const float L = sky_radiance(p, &bands[i], d);
      r += L * bands[i].w_r; g += L * bands[i].w_g; b += L * bands[i].w_b;
#if SEASIM_SPECTRAL_OUTPUT
      spectral[(size_t)pixel * p->band_count + i] = L;
#endif
    }
  } else {
    const float3 n = (float3)(0.0f, 1.0f, 0.0f);
    const float cos_jo = -d.y;                               /* view incidence at P */
    const float R_view = fresnel_reflectance(cos_jo, 1.0f, p->ior);
    const float t_out = 1.0f - R_view;                        /* T_o of 000 eq. 5, 9 */
    float3 view_in_water;
    refract_dir(d, n, 1.0f / p->ior, &view_in_water);        /* air -> water never TIRs */
    const float cos_ji = fmax(-view_in_water.y, 1e-4f);

    const float3 sun = (float3)(p->sun_dir[0], p->sun_dir[1], p->sun_dir[2]);
    float t_in = 0.0f, cos_io = 1.0f, cos_alpha = 1.0f, sun_horizontal = 0.0f;
#if SEASIM_HAS_SUN
    if (sun.y > 0.0f) {
      t_in = 1.0f - fresnel_reflectance(sun.y, 1.0f, p->ior);
      sun_horizontal = sun.y;                                 /* E on the horizontal surface / E normal */
      float3 sun_in_water;                                    /* travel direction of sunlight */
      refract_dir(-sun, n, 1.0f / p->ior, &sun_in_water);
      cos_io = fmax(-sun_in_water.y, 1e-4f);
      cos_alpha = dot(sun_in_water, -view_in_water);          /* scattered towards the eye */
    }
#endif
    const float3 reflected = reflect_dir(d, n);
    const float c_f = hg_forward_fraction(p->g);
    const float phase = hg_phase(cos_alpha, p->g);
#if SEASIM_HAS_BOTTOM
    const float z_d = p->bottom_depth;
#else
    const float z_d = -1.0f;                                  /* no bottom: infinitely deep */
#endif
#if SEASIM_SEA_LUT
    const float lut_x = acos(clamp(cos_jo, 0.0f, 1.0f)) * (p->lut_size - 1) * (2.0f / M_PI_F);
#endif
    for (int i = 0; i < p->band_count; ++i) {
      const __global SeaBand* band = &bands[i];
      float L = 0.0f;
#if SEASIM_HAS_REFLECTION
      L += R_view * sky_radiance(p, band, reflected);
#endif
#if SEASIM_HAS_SINGLE_SCATTERING
#if SEASIM_SEA_LUT
      L += band->b * phase * t_out * lut_read(lut + (size_t)i * p->lut_size, p->lut_size, lut_x);
#else
      const float albedo = band->c > 0.0f ? band->b / band->c : 0.0f;
      L += sea_single_scattering(band->sun_irradiance * sun_horizontal, t_in, t_out, band->b * phase, band->c, albedo, c_f,
                                 cos_io, cos_ji, z_d);
#endif
#endif
#if SEASIM_HAS_BOTTOM
      L += sea_bottom_reflection(band->sun_irradiance * sun_horizontal, t_in, t_out, band->bottom_albedo, band->c, z_d,
                                 cos_io, cos_ji);
#endif
      r += L * band->w_r; g += L * band->w_g; b += L * band->w_b;
#if SEASIM_SPECTRAL_OUTPUT
      spectral[(size_t)pixel * p->band_count + i] = L;
#endif
    }
  }
  rgb[3 * pixel + 0] = r;
  rgb[3 * pixel + 1] = g;
  rgb[3 * pixel + 2] = b;
}
