/* compat.h — lets the headers in kernels/common/ compile as OpenCL C and as C++.
 *
 * Shared math is written once against this vocabulary:
 *   real, real3            scalar and 3-vector (float/float3 in kernels; float or double on the host)
 *   R(x)                   a literal in the real type: R(0.5)
 *   MAKE_REAL3(x, y, z)    a real3 value
 *   SEASIM_FN              'static inline' on both sides
 *   SEASIM_FN_INLINED      SEASIM_FN that a kernel compiler must inline (always_inline in kernels): for a
 *                          function with pointer out-parameters that several kernels of one program call.
 *                          Intel's CPU compiler, keeping sea_hf_intersect out of line, gave sea_second.cl's
 *                          depth tables the surface node's distances at every depth (PoCL and the inlined
 *                          form right; docs/journal/sea_second_order.md)
 *   SEASIM_GLOBAL          '__global' in kernels, nothing on the host (pointer arguments to buffers)
 *   SEASIM_CONSTANT        '__constant' in kernels, nothing on the host (parameter blocks)
 *   dot, cross, length, normalize, clamp, mix, +,-,* on real3 — OpenCL built-ins; C++ versions below
 *   exp, expm1, log, sqrt, pow, sin, cos, acos, atan2, fabs, fmin, fmax — plain C names
 *
 * Kernels: the host program loader inlines `#include "common/x.h"` once per file (pragma-once
 * semantics). Defining SEASIM_REAL_DOUBLE before this header makes `real` double (needs cl_khr_fp64).
 *
 * Host: do not include the model headers directly; include host/math/kernel_math.h, which includes
 * them twice, inside namespace seasim::kmath_f (real = float) and seasim::kmath_d (real = double),
 * so every formula a kernel runs is unit-tested on the CPU in both precisions. For that reason the
 * model headers carry no include guards and include nothing themselves (kernel_math.h orders them).
 */
#if defined(__OPENCL_VERSION__) || defined(__OPENCL_C_VERSION__)

#ifdef SEASIM_REAL_DOUBLE
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
typedef double real;
typedef double3 real3;
#define R(x) ((double)(x))
#define MAKE_REAL3(x, y, z) ((double3)((x), (y), (z)))
#else
typedef float real;
typedef float3 real3;
#define R(x) ((float)(x))
#define MAKE_REAL3(x, y, z) ((float3)((x), (y), (z)))
#endif
#define SEASIM_FN static inline
#define SEASIM_FN_INLINED static inline __attribute__((always_inline))
#define SEASIM_GLOBAL __global
#define SEASIM_CONSTANT __constant
#define SEASIM_PI R(3.14159265358979323846)

#else /* C++ host: this part is included once, outside the kmath namespaces */

#ifndef SEASIM_COMPAT_HOST_ONCE
#define SEASIM_COMPAT_HOST_ONCE
#include <cmath>
#define SEASIM_FN static inline
#define SEASIM_FN_INLINED static inline
#define SEASIM_GLOBAL
#define SEASIM_CONSTANT
#define R(x) (static_cast<real>(x))
#define MAKE_REAL3(x, y, z) (real3{static_cast<real>(x), static_cast<real>(y), static_cast<real>(z)})
#define SEASIM_PI R(3.14159265358979323846)
#endif

#endif
