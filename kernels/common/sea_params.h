/* sea_params.h — the parameter blocks of kernels/sea_single.cl, shared with host/passes/sea_single_pass.cpp
 * (which static_asserts their layout). No float3 inside (16 bytes in OpenCL C): vectors are float[4]. */
#ifndef SEASIM_SEA_PARAMS_H
#define SEASIM_SEA_PARAMS_H
typedef struct {
  float cam_pos[4];      /* m, world */
  float cam_right[4];    /* worldFromCamera basis, unit */
  float cam_up[4];
  float cam_forward[4];
  float sun_dir[4];      /* unit, towards the sun */
  float tan_half_fov_y;
  float aspect;          /* width / height */
  float ior;             /* water relative to air */
  float g;               /* HG asymmetry of the water's volume scattering function */
  float bottom_depth;    /* m, flat bottom (SEASIM_HAS_BOTTOM) */
  float cos_sun_radius;  /* cosine of the sun's angular radius: the reflected sun disk */
  float sun_solid_angle; /* sr, converts sun irradiance to disk radiance */
  float pixel_angle;     /* 2 tan(fov_y / 2) / height: a pixel's angle, for the wave filter's footprint */
  int width;
  int height;
  int band_count;
  int lut_size;          /* entries of the single-scattering LUT (SEASIM_SEA_LUT): over theta_jo, or
                            over theta_ji with SEASIM_HAS_WAVES (the local normal decouples the two) */
  float ocean_patch;     /* m, L of the ocean's periodic normal map (SEASIM_HAS_WAVES) */
  int ocean_n;           /* N, texels per side of the normal map */
  int sky_width;         /* texels of the environment image (SEASIM_SKY_MODEL 2) */
  int sky_height;
  float sky_scale;       /* 1 / cosine-weighted mean of the sky's shape (common/sky.h) */
  int caustic_map_size;  /* M: the bottom's caustic map (SEASIM_BOTTOM_CAUSTICS; common/caustic_map.h) */
  float caustic_extent;  /* m, side of the square it covers */
  float caustic_origin;  /* m, its corner on x and z: 0 (periodic ocean patch) or -extent/2 (height field) */
  float sun_slope_variance; /* the sun disk's slope variance per axis, rho^2 / 16 (common/sea_lean.h) */
  float sky_fresnel_mean; /* r̄: the uniform sky's cosine-weighted Fresnel reflectance (sea.model "multiple") */
  float column_hemisphere[4]; /* sea.model "multiple": sea_column_hemisphere (common/sea_multiple.h) of the
                                 refracted sun's cosine, the sky's and the returned light's mean cosines, as
                                 sea_pixel has them (once per frame); [3] unused */
} SeaParams;

/* One wavelength band: radiometry and water IOPs at the band centre, and the sensor weights that
 * turn this band's radiance into linear RGB by the rectangle rule (002 eq. 4.8). */
typedef struct {
  float sun_irradiance;  /* W m^-2 nm^-1, normal to the sun */
  float sky_radiance;    /* W m^-2 sr^-1 nm^-1, uniform sky */
  float a;               /* absorption, 1/m */
  float b;               /* scattering, 1/m */
  float c;               /* attenuation a + b, 1/m */
  float bottom_albedo;   /* Lambertian bottom reflectance */
  float w_r;             /* sensor weights (include the band width) */
  float w_g;
  float w_b;
  float sky_w_r;         /* share of the environment image's R, G, B in this band (common/sky.h) */
  float sky_w_g;
  float sky_w_b;
} SeaBand;

#endif /* SEASIM_SEA_PARAMS_H */
