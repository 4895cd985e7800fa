/* fourflow_params.h — the four-flow model's kernel arguments (paper 003), shared by kernels/fourflow.cl,
 * kernels/common/fourflow.h (the per-band evaluation) and the host (host/underwater/fourflow_setup.cpp
 * static_asserts the layout). Plain C on both sides, included before host/math/kernel_math.h's
 * namespaces (it holds no math). All floats: no float3 (16 bytes in OpenCL C), explicit padding.
 */
#ifndef SEASIM_FOURFLOW_PARAMS_H /* also included by host/math/kernel_math.h */
#define SEASIM_FOURFLOW_PARAMS_H

/* One wavelength band: the water, the surface, the light and the bottom materials, and the band's
 * weights into linear RGB (the sensor, Δλ included), so Σ_b rgb_b E_b is the pixel's linear colour. */
typedef struct {
  float eps;                    /* extinction ε = χ + σ, m⁻¹ (003 eq. 3) */
  float k, S, S1, S2;           /* 003 eq. 4 constants (ff_medium) */
  float T_dd, T_df, T_ff;       /* 003 eq. 7, air -> water */
  float Rw_dd, Rw_df, Rw_ff;    /* 003 eq. 7, "~": reflected back down under the surface */
  float e_sun, e_sky;           /* irradiance on a horizontal plane above the surface */
  float rho_a, rho_b;           /* bottom albedo of the two materials the bottom texture mixes */
  float rho_mean;               /* R̄: the texture's mean albedo, the "average bottom" of 003 eq. 12 */
  float rgb[3];                 /* band -> linear RGB weights */
  float pad0;
} FfBand;

/* The (l, h) tables of 003 eq. 22–23 and the blend. The paper indexes them by (r, h), r the distance
 * to the viewer; l(r, h), the view path length through the water, is what the physics depends on, so
 * the tables are indexed by l directly and the camera geometry (r -> l) stays outside them. */
typedef struct {
  int n_bands;
  int n_l, n_h;                 /* table resolution (>= 2 each) */
  float l_max, h_max;           /* m: table ranges, nodes at l_max (i/(n_l - 1))², h_max j/(n_h - 1) */
  float gamma;                  /* 003 eq. 23 transition exponent */
  float pad0, pad1;
  float rgb_a[4], rgb_b[4];     /* linear RGB reflectance of the two bottom materials (4th unused) */
} FfParams;

/* The view from above a flat water surface (kernels/fourflow.cl ff_render). */
typedef struct {
  float cam_pos[4], cam_right[4], cam_up[4], cam_forward[4]; /* world, m; 4th unused */
  float sky_rgb[4];          /* linear RGB of the uniform sky's radiance (reflected, and above the horizon) */
  float tan_half_fov_y, aspect;
  int width, height;
  float ior;                 /* water's refractive index */
  float bottom_depth;        /* m, flat bottom (without a height field) */
  float texture_scale;       /* m, feature size of the bottom texture (ff_bottom_texture) */
  float dark_fraction;       /* the texture's mean share of the dark material */
} FfView;

/* One table cell (ff_table_cell has the layout): eq. 22–23's T0, a, T1 and eq. 24's T_α, T0(h), T1(h). */
#define FF_TABLE_STRIDE 20

#endif
