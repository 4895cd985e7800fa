/* check.cl — counts NaN/Inf values in an output buffer (DESIGN.md: kernels never emit NaN/Inf; the
 * run fails loudly if this count is not zero). */
__kernel void count_nonfinite(__global const float* values, const unsigned count, __global unsigned* nonfinite) {
  const size_t i = get_global_id(0);
  if (i < count && !isfinite(values[i])) atomic_inc(nonfinite);
}
