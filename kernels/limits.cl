/* limits.cl — the device's exp throughput, the bound the spectral kernels are measured against
 * (DESIGN.md "Performance rules"). Each work item runs a dependent chain of EXP_PER_ITEM exps in 8
 * independent lanes so the measurement is throughput, not latency. */
#ifndef EXP_PER_ITEM
#define EXP_PER_ITEM 256
#endif
__kernel void exp_throughput(__global float* out, const float seed) {
  const size_t i = get_global_id(0);
  float8 x = (float8)(seed) + (float8)(0.0f, 1e-3f, 2e-3f, 3e-3f, 4e-3f, 5e-3f, 6e-3f, 7e-3f) + (float)(i & 15) * 1e-4f;
  for (int k = 0; k < EXP_PER_ITEM / 8; ++k) x = exp(-x) ;
  out[i] = x.s0 + x.s1 + x.s2 + x.s3 + x.s4 + x.s5 + x.s6 + x.s7;
}
