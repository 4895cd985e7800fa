/* underwater_lamps_params.h — the parameter blocks of kernels/underwater_lamps.cl (spotlights in the
 * water's spectral medium), shared with host/passes/underwater_lamps_pass.cpp, which static_asserts
 * their layout. No float3 inside (16 bytes in OpenCL C): vectors are float[4]. Plain C on both sides. */

#ifndef SEASIM_UNDERWATER_LAMPS_PARAMS_H
#define SEASIM_UNDERWATER_LAMPS_PARAMS_H

typedef struct {
  float position[4];     /* m, world; below the surface (position[1] < 0) */
  float direction[4];    /* unit beam axis */
  float cos_cone;        /* cos of the cone half angle */
  float cos_inner;       /* cos(cone - falloff): full intensity inside */
  float sin2_cone;       /* sin² of the same two, from the angles (a 0.1° cone's edge is 1.5e-6 off 1 in */
  float sin2_inner;      /* cosine, at float's rounding: the planes' lanes compare sines, lamp_profile_lanes) */
} UwLamp;

typedef struct {
  float s_min;           /* m, the lamp's radius: 1/s² is clamped there (001 eq. 6 stiff case) */
  float pad[3];
  int lamp_count;
  int planes;            /* n sampling planes per lamp (001 eq. 5) */
  int subplanes;         /* m sub-sample planes per interval (001 eq. 7–9) */
  int band_count;
} UwLampParams;

#endif /* SEASIM_UNDERWATER_LAMPS_PARAMS_H */
