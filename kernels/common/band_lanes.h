/* band_lanes.h — several wavelength bands in one value, so that a band loop is explicit SIMD.
 *
 * PoCL's work-group vectoriser does not vectorise kd_multiple (its loops and calls), but its builtin
 * library has vector exp (kernels/limits.cl reaches ~2e9 exp/s with float16). A band loop written on
 * `realb` runs SEASIM_BAND_LANES bands per step in a kernel (floatN, vector exp/fma/select) and one
 * band per step on the host (realb = real), so the same source is unit-tested in float and double on
 * the CPU (host/math/kernel_math.h) and compared with double on PoCL.
 *
 *   realb, maskb           N bands of real / their comparison mask (floatN, intN; real, int on the host)
 *   SEASIM_BAND_LANES      N (kernels: 4, 8 or 16, default 16; the host: 1)
 *   LOADB(p, i)            bands i..i+N-1 of a float row p (p padded to a multiple of N)
 *   SPLATB(x)              x in every lane
 *   SELECTB(m, a, b)       per lane: m ? a : b (m from a comparison of realb values, combined with &)
 *   ANYB(m)                whether any lane of m is set (a case no lane needs is skipped)
 *   uintb, UINTB_OF(x), REALB_OF_UINT(u)  unsigned integer lanes (hashes) and the conversions from and to realb
 *   SUMB(v)                the sum of the lanes
 *   load_lanes, store_lanes the first count lanes of a row that is not padded (the others read as 0)
 *   lane_offsets()         0, 1, …, N - 1 (a node loop run in lanes: node k0 + lane)
 * Comparisons of a realb with a scalar give a maskb on both sides; a scalar condition must be splat
 * first (SPLATB(s) >= x), since OpenCL's scalar true is 1, not the all-ones a vector mask uses.
 * Width, measured on PoCL 3.1 (AVX-512 CPU; seabed, 256 bands, kd_multiple ms, two rounds): 4 lanes
 * 454/454, 8 lanes 241/253, 16 lanes 142/148 (docs/journal/benchmarks_notes.md). A GPU, which runs
 * one work-item per lane already, would rather have 1 (not measured: no GPU lent).
 * Needs compat.h; kernels: float only. */
#if defined(__OPENCL_VERSION__) || defined(__OPENCL_C_VERSION__)

#ifndef SEASIM_BAND_LANES
#define SEASIM_BAND_LANES 16
#endif
#if SEASIM_BAND_LANES == 4
typedef float4 realb;
typedef int4 maskb;
typedef uint4 uintb;
#define UINTB_OF(x) convert_uint4(x)
#define REALB_OF_UINT(x) convert_float4(x)
#define LOADB(p, i) vload4(0, (p) + (i))
#define SUMB(v) (((v).s0 + (v).s1) + ((v).s2 + (v).s3))
#elif SEASIM_BAND_LANES == 8
typedef float8 realb;
typedef int8 maskb;
typedef uint8 uintb;
#define UINTB_OF(x) convert_uint8(x)
#define REALB_OF_UINT(x) convert_float8(x)
#define LOADB(p, i) vload8(0, (p) + (i))
#define SUMB(v) ((((v).s0 + (v).s1) + ((v).s2 + (v).s3)) + (((v).s4 + (v).s5) + ((v).s6 + (v).s7)))
#elif SEASIM_BAND_LANES == 16
typedef float16 realb;
typedef int16 maskb;
typedef uint16 uintb;
#define UINTB_OF(x) convert_uint16(x)
#define REALB_OF_UINT(x) convert_float16(x)
#define LOADB(p, i) vload16(0, (p) + (i))
#define SUMB(v)                                                                                          \
  (((((v).s0 + (v).s1) + ((v).s2 + (v).s3)) + (((v).s4 + (v).s5) + ((v).s6 + (v).s7))) +              \
   ((((v).s8 + (v).s9) + ((v).sa + (v).sb)) + (((v).sc + (v).sd) + ((v).se + (v).sf))))
#else
#error "SEASIM_BAND_LANES must be 4, 8 or 16"
#endif
#define SPLATB(x) ((realb)(x))
#define SELECTB(m, a, b) select((b), (a), (m))
#define ANYB(m) any(m)

/* Writes the first count (>= 1) lanes of v to dst (the last step of a band count that is not a
 * multiple of the lanes). */
SEASIM_FN void store_lanes(realb v, __global float* dst, int count) {
  float lanes[SEASIM_BAND_LANES] __attribute__((aligned(4 * SEASIM_BAND_LANES))); /* a realb's alignment */
  *(realb*)lanes = v;
  for (int j = 0; j < count && j < SEASIM_BAND_LANES; ++j) dst[j] = lanes[j];
}

/* 0, 1, ..., SEASIM_BAND_LANES - 1: lane j's index, so that a loop over nodes can run them in lanes too. */
SEASIM_FN realb lane_offsets(void) {
  float lanes[SEASIM_BAND_LANES] __attribute__((aligned(4 * SEASIM_BAND_LANES)));
  for (int j = 0; j < SEASIM_BAND_LANES; ++j) lanes[j] = (float)j;
  return *(realb*)lanes;
}

/* The first count lanes from src, the rest 0 (a row that is not padded to a multiple of the lanes). */
SEASIM_FN realb load_lanes(const __global float* src, int count) {
  float lanes[SEASIM_BAND_LANES] __attribute__((aligned(4 * SEASIM_BAND_LANES)));
  for (int j = 0; j < SEASIM_BAND_LANES; ++j) lanes[j] = j < count ? src[j] : 0.0f;
  return *(realb*)lanes;
}

#else /* C++ host: one band per step; included inside each kmath namespace after `typedef … real;` */

#ifndef SEASIM_BAND_LANES
#define SEASIM_BAND_LANES 1
#define LOADB(p, i) (static_cast<real>((p)[i]))
#define SPLATB(x) (static_cast<real>(x))
#define SELECTB(m, a, b) ((m) ? (a) : (b))
#define ANYB(m) ((m) != 0)
#define UINTB_OF(x) (static_cast<unsigned int>(x))
#define REALB_OF_UINT(x) (static_cast<realb>(x))
#define SUMB(v) (v)
#endif
typedef real realb;
typedef int maskb;
typedef unsigned int uintb;
SEASIM_FN void store_lanes(realb v, float* dst, int count) {
  if (count > 0) dst[0] = static_cast<float>(v);
}
SEASIM_FN realb load_lanes(const float* src, int count) { return count > 0 ? static_cast<realb>(src[0]) : realb(0); }
SEASIM_FN realb lane_offsets() { return realb(0); }

#endif
