/* limits.cl — the device's throughput bounds the spectral kernels are measured against (DESIGN.md
 * "Performance rules"): exp evaluations and fused multiply-adds per second.
 *
 * Both kernels are shaped the way a bound must be: the operations are independent of each other (no
 * chain through exp's latency: each exp's argument is known up front; FMA_CHAINS independent FMA
 * chains per work item cover the FMA latency), and the body is a straight uniform loop with no early
 * return, so PoCL can run the work items of a group in SIMD lanes and a GPU in a warp. The host times
 * them (commands.cpp, measureLimits) and divides the count by the time. Nothing is cached between
 * items: each item has its own arguments, and every result reaches `out`, so nothing is dead code.
 */
#ifndef EXP_PER_ITEM
#define EXP_PER_ITEM 256
#endif
#ifndef FMA_PER_ITEM
#define FMA_PER_ITEM 4096
#endif
#define FMA_CHAINS 8

__kernel void exp_throughput(__global float* out, const float seed) {
  const float x = seed + (float)(get_global_id(0) & 1023) * 1e-6f;
  float acc = 0.0f;
  for (int k = 0; k < EXP_PER_ITEM; ++k) acc += exp(-(x + (float)k * 1e-3f)); /* independent exps */
  out[get_global_id(0)] = acc;
}

__kernel void fma_throughput(__global float* out, const float seed) {
  const float x = seed + (float)(get_global_id(0) & 1023) * 1e-6f;
  float a0 = x, a1 = x + 1.0f, a2 = x + 2.0f, a3 = x + 3.0f, a4 = x + 4.0f, a5 = x + 5.0f, a6 = x + 6.0f,
        a7 = x + 7.0f;
  const float m = 0.999f, c = 1e-3f; /* a -> m a + c stays bounded (fixed point c / (1 - m) = 1) */
  for (int k = 0; k < FMA_PER_ITEM / FMA_CHAINS; ++k) {
    a0 = fma(a0, m, c);
    a1 = fma(a1, m, c);
    a2 = fma(a2, m, c);
    a3 = fma(a3, m, c);
    a4 = fma(a4, m, c);
    a5 = fma(a5, m, c);
    a6 = fma(a6, m, c);
    a7 = fma(a7, m, c);
  }
  out[get_global_id(0)] = a0 + a1 + a2 + a3 + a4 + a5 + a6 + a7;
}
