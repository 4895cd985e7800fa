/* whitecaps_params.h — the parameter block of kernels/whitecaps.cl, shared with
 * host/passes/whitecaps_pass.cpp (which static_asserts its layout). No float3 inside (16 bytes in
 * OpenCL C): vectors are float[4]. */
#ifndef SEASIM_WHITECAPS_PARAMS_H
#define SEASIM_WHITECAPS_PARAMS_H
typedef struct {
  float cam_pos[4];      /* m, world (y up, the mean sea surface at y = 0) */
  float cam_right[4];    /* worldFromCamera basis, unit */
  float cam_up[4];
  float cam_forward[4];
  float foam_rgb[4];     /* the foam's radiance R_f E_d / π in linear sensor RGB (common/whitecaps.h); [3] unused */
  float tan_half_fov_y;
  float aspect;          /* width / height */
  float pixel_angle;     /* 2 tan(fov_y / 2) / height: a pixel's angle, rad, for the footprint */
  float ocean_patch;     /* L, m: side of the ocean's periodic tile */
  int ocean_n;           /* N: texels per side of the Jacobian map (a power of two) */
  int width;             /* image, pixels */
  int height;
  int band_count;        /* bands of the spectral image and of foam_bands (SEASIM_SPECTRAL_OUTPUT) */
} WhitecapsParams;
#endif /* SEASIM_WHITECAPS_PARAMS_H */
