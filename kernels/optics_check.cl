/* optics_check.cl — test-only kernels: evaluate each function of common/optics.h over input
 * arrays so tests/kernels/optics_kernel_test.cpp can compare the device's float results with the
 * host's double evaluation (host/math/kernel_math.h, seasim::kmath_d). No model lives here.
 *
 * All arrays are float (the kernels' real type). 3-vectors travel as packed float triples
 * (vload3/vstore3), never float3 buffers, which are 16 bytes per element in OpenCL C.
 * One work-item per element; the global size equals the element count.
 */
#include "common/compat.h"
#include "common/optics.h"

/* out[i] = fresnel_reflectance(cos_i[i], n1[i], n2[i]) */
__kernel void check_fresnel(__global const float* cos_i, __global const float* n1,
                            __global const float* n2, __global float* out) {
  size_t i = get_global_id(0);
  out[i] = fresnel_reflectance(cos_i[i], n1[i], n2[i]);
}

/* refract_dir(dir[i], normal[i], eta[i]) -> out_dir[i], ok[i]; reflect_dir -> out_refl[i] */
__kernel void check_refract_reflect(__global const float* dir, __global const float* normal,
                                    __global const float* eta, __global float* out_dir,
                                    __global int* ok, __global float* out_refl) {
  size_t i = get_global_id(0);
  real3 d = vload3(i, dir);
  real3 n = vload3(i, normal);
  real3 t;
  ok[i] = refract_dir(d, n, eta[i], &t);
  vstore3(t, i, out_dir);
  vstore3(reflect_dir(d, n), i, out_refl);
}

/* out[i] = hg_phase(cos_theta[i], g[i]) */
__kernel void check_hg(__global const float* cos_theta, __global const float* g,
                       __global float* out) {
  size_t i = get_global_id(0);
  out[i] = hg_phase(cos_theta[i], g[i]);
}

/* out_angle[i] = shafts_phase(alpha[i]); out_cos[i] = shafts_phase_cos(cos_alpha[i]) */
__kernel void check_shafts(__global const float* alpha, __global const float* cos_alpha,
                           __global float* out_angle, __global float* out_cos) {
  size_t i = get_global_id(0);
  out_angle[i] = shafts_phase(alpha[i]);
  out_cos[i] = shafts_phase_cos(cos_alpha[i]);
}

/* out[i] = beer_lambert(sigma[i], distance[i]) */
__kernel void check_beer_lambert(__global const float* sigma, __global const float* distance,
                                 __global float* out) {
  size_t i = get_global_id(0);
  out[i] = beer_lambert(sigma[i], distance[i]);
}

/* out[i] = expm1_over_x(x[i]) */
__kernel void check_expm1_over_x(__global const float* x, __global float* out) {
  size_t i = get_global_id(0);
  out[i] = expm1_over_x(x[i]);
}
