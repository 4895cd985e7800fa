/* sky_params.h — the scene's [sky] as the kernels that look at it read it (common/sky_view.h):
 * host/sky/sky_light.cpp fills it; plain C, shared by OpenCL C and the host (static_asserts there). */
#ifndef SEASIM_SKY_PARAMS_H
#define SEASIM_SKY_PARAMS_H

typedef struct {
  float sun_dir[4]; /* unit, towards the sun in air (the CIE and Preetham skies' sun); w unused */
  float scale;      /* 1 / cosine-weighted mean of the shape (common/sky.h), 1 for the uniform sky */
  int model;        /* SEASIM_SKY_* of common/sky.h; a kernel built with SEASIM_SKY_MODEL uses that */
  int width;        /* texels of the environment image (model 2), else 1 */
  int height;
} SkyParams;

#endif /* SEASIM_SKY_PARAMS_H */
