/* limits.cl — the device's throughput bounds the spectral kernels are measured against (DESIGN.md
 * "Performance rules"): exp evaluations and fused multiply-adds per second.
 *
 * Both are shaped the way a bound must be. The operations are independent of each other: each exp's
 * argument is known up front (no chain through exp's latency), and FMA_CHAINS independent FMA chains
 * cover the FMA latency. They are explicitly vectorised (float16: one AVX-512 register, two AVX2
 * ones, and on a GPU 16 independent operations per thread), because PoCL does not vectorise a kernel
 * with a loop across its work items (docs/journal/benchmarks_notes.md says which kernels it does
 * vectorise). Every result reaches `out`, so nothing is dead code.
 */
#ifndef EXP_PER_ITEM
#define EXP_PER_ITEM 256 /* a multiple of 16 */
#endif
#ifndef FMA_PER_ITEM
#define FMA_PER_ITEM 4096 /* a multiple of 16 * FMA_CHAINS */
#endif
#define FMA_CHAINS 4

#define LANES16 \
  (float16)(0.0f, 1.0f, 2.0f, 3.0f, 4.0f, 5.0f, 6.0f, 7.0f, 8.0f, 9.0f, 10.0f, 11.0f, 12.0f, 13.0f, 14.0f, 15.0f)

__kernel void exp_throughput(__global float* out, const float seed) {
  const float16 x = (float16)(seed + (float)(get_global_id(0) & 1023) * 1e-6f) + LANES16 * 1e-4f;
  float16 acc = (float16)(0.0f);
  for (int k = 0; k < EXP_PER_ITEM / 16; ++k) acc += exp(-(x + (float16)((float)k * 1e-3f))); /* independent */
  out[get_global_id(0)] = acc.s0 + acc.s1 + acc.s2 + acc.s3 + acc.s4 + acc.s5 + acc.s6 + acc.s7 + acc.s8 + acc.s9 +
                          acc.sa + acc.sb + acc.sc + acc.sd + acc.se + acc.sf;
}

__kernel void fma_throughput(__global float* out, const float seed) {
  const float16 x = (float16)(seed + (float)(get_global_id(0) & 1023) * 1e-6f) + LANES16 * 1e-4f;
  float16 a0 = x, a1 = x + 1.0f, a2 = x + 2.0f, a3 = x + 3.0f;
  const float16 m = (float16)(0.999f), c = (float16)(1e-3f); /* a -> m a + c stays bounded (fixed point 1) */
  for (int k = 0; k < FMA_PER_ITEM / (16 * FMA_CHAINS); ++k) {
    a0 = fma(a0, m, c);
    a1 = fma(a1, m, c);
    a2 = fma(a2, m, c);
    a3 = fma(a3, m, c);
  }
  const float16 s = a0 + a1 + a2 + a3;
  out[get_global_id(0)] = s.s0 + s.s1 + s.s2 + s.s3 + s.s4 + s.s5 + s.s6 + s.s7 + s.s8 + s.s9 + s.sa + s.sb + s.sc +
                          s.sd + s.se + s.sf;
}
