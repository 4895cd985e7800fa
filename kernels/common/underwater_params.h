/* underwater_params.h — the parameter blocks of the underwater passes (kernels/raycast.cl,
 * kd_multiple.cl, froxel.cl, reference.cl), shared with host/passes (which static_assert their
 * layout). No float3 inside (16 bytes in OpenCL C): vectors are float[4]. Plain C on both sides,
 * included before host/math/kernel_math.h's namespaces (it holds no math).
 *
 * Conventions (DESIGN.md): metres, y up, water surface y = 0, the camera below it (cam_pos[1] < 0);
 * "depth" is -y. Directions are unit vectors. The sun is a delta light: in air it comes from
 * sun_dir_air (towards the sun); below the flat surface its beam travels along -sun_dir_water,
 * sun_dir_water being the refracted direction towards the sun (sun_dir_water[1] = μ_w > 0).
 */

#ifndef SEASIM_UNDERWATER_PARAMS_H /* also included by host/math/kernel_math.h */
#define SEASIM_UNDERWATER_PARAMS_H

/* Pixels of a row that one work-item of raycast.cl casts in lanes: its launch is ceil(width / this) wide. */
#define UW_RAYCAST_PIXELS 16
/* Lattice pixels of a row that one work-item of sand_share.cl evaluates in lanes: its launch is ceil(map_w / this). */
#define UW_SAND_SHARE_PIXELS 16

/* Object types (UwObject.type). */
#define UW_SPHERE 0
#define UW_BOX 1
#define UW_PLANE 2

/* G-buffer material codes (besides object indices 0..object_count-1). */
#define UW_MAT_NONE (-1)     /* the ray leaves into deep water: S = ∞ */
#define UW_MAT_SURFACE (-2)  /* the ray reaches the water surface from below */
#define UW_MAT_BOTTOM (-3)   /* the flat bottom y = -bottom_depth */

/* Caustic modes (UwParams.caustic_mode; kd_multiple.cl and froxel.cl also get it as a define). */
#define UW_CAUSTICS_NONE 0
#define UW_CAUSTICS_TEXTURE 1  /* two scrolling textures, min of both (002 §5.3) */
#define UW_CAUSTICS_MAP 2      /* flux-conservation map from the ocean surface (004 §5.2, caustics.cl) */

typedef struct {
  float cam_pos[4];        /* m, world; cam_pos[1] < 0 */
  float cam_right[4];      /* worldFromCamera basis, unit */
  float cam_up[4];
  float cam_forward[4];
  float sun_dir_air[4];    /* unit, towards the sun, above the surface */
  float sun_dir_water[4];  /* unit, towards the sun after refraction; [1] = μ_w (cosine in water) */
  float tan_half_fov_y;
  float aspect;            /* width / height */
  float ior;               /* water relative to air */
  float g;                 /* HG asymmetry for single scattering (L_MS is isotropic, 002 eq. 4.4) */
  float bottom_depth;      /* m > 0; <= 0 when there is no bottom (deep water) */
  float time;              /* s, for scrolling caustics */
  float caustic_period;    /* m, tile size of the caustic texture on the horizontal plane */
  float caustic_speed;     /* m/s, scroll speed of the caustic textures */
  float caustic_extent;    /* m, side of the square the caustic map covers (UW_CAUSTICS_MAP) */
  float caustic_depth_max; /* m, depth of the deepest caustic map layer (UW_CAUSTICS_MAP; caustic_map.h) */
  float pad1, pad2;
  int width;
  int height;
  int band_count;
  int object_count;
  int caustic_mode;        /* UW_CAUSTICS_* */
  int caustic_map_size;    /* texels per side (UW_CAUSTICS_MAP) */
  int caustic_layers;      /* maps at depths (k + 1) caustic_depth_max / caustic_layers (UW_CAUSTICS_MAP) */
  int pad4;
} UwParams;

/* One wavelength band at its centre: water IOPs, the light just below the surface, sensor weights
 * (002 eq. 4.8, band width included). */
typedef struct {
  float a;                 /* absorption, 1/m */
  float b;                 /* scattering σ_s, 1/m */
  float c;                 /* extinction σ_t = a + b, 1/m */
  float kd;                /* diffuse downwelling attenuation K_d, 1/m (002 eq. 4.1) */
  float e_sky0;            /* W m^-2 nm^-1: sky irradiance on a horizontal plane just below the
                              surface, ∫ L_sky (1 - F) cos θ dω (host/sky: π L_sky (1 - r̄) when uniform) */
  float e_sun0;            /* W m^-2 nm^-1: sun irradiance on a horizontal plane just below the
                              surface, E_sun cosθ_a (1 - F(θ_a)) */
  float e_beam0;           /* W m^-2 nm^-1: the refracted sun beam's irradiance normal to itself just
                              below the surface, e_sun0 / μ_w */
  float sky_radiance;      /* W m^-2 sr^-1 nm^-1, the sky's uniform level in air (× its shape, sky_view.h) */
  float bottom_albedo;     /* Lambertian reflectance of the bottom */
  float w_r;               /* sensor weights (002 eq. 4.8) */
  float w_g;
  float w_b;
  float sky_w_r;           /* share of the sky shape's R, G, B in this band (common/sky_view.h) */
  float sky_w_g;
  float sky_w_b;
  float pad;
} UwBand;

/* An analytic object: sphere (a = centre xyz, radius), box (a = min, b = max), plane (a = point,
 * b = unit normal). Albedo per band lives in a separate float array [object * band_count + band]. */
typedef struct {
  int type;                /* UW_SPHERE, UW_BOX, UW_PLANE */
  int pad[3];
  float a[4];
  float b[4];
} UwObject;

#endif /* SEASIM_UNDERWATER_PARAMS_H */
