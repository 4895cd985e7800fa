/* effective_coefficients.cl — the image-formation model's effective coefficients per pixel and sensor
 * channel (outputs.layers beta_d, beta_b; common/output_layers.h derives them and their undefined cases):
 *   β_D = -ln(direct / clear) / range,   β_B = -ln(1 - backscatter / veiling) / range,
 * from kd_multiple.cl's layers and raycast.cl's range, each with a mask channel: 1 where all three
 * channels are defined, else 0 (an undefined channel is written 0).
 *
 * Inputs: width, height; geom (S, n) per pixel (S >= UW_INFINITE: open water); formation[pixel][12]
 * (clear, direct, backscatter, transmission; RGB each); veiling[pixel][3] with SEASIM_LAYER_BETA_B.
 * Output: out[pixel * SEASIM_LAYER_CHANNELS + ...]: beta_d R, G, B, mask then beta_b R, G, B, mask, each
 * only when asked. Built without -cl-fast-relaxed-math (the finiteness tests must stay).
 * Defines (host/plan, EffectiveCoefficientsFeatures): SEASIM_LAYER_BETA_D, SEASIM_LAYER_BETA_B (the
 * layer's first channel, or -1), SEASIM_LAYER_CHANNELS.
 */
#include "common/compat.h"
#include "common/optics.h"
#include "common/shafts.h"
#include "common/underwater_params.h"
#include "common/underwater.h"
#include "common/output_layers.h"

__kernel void effective_coefficients(int width, int height, __global const float4* geom,
                                     __global const float* formation,
#if SEASIM_LAYER_BETA_B >= 0
                                     __global const float* veiling,
#endif
                                     __global float* out) {
  const int x = get_global_id(0);
  const int y = get_global_id(1);
  if (x >= width || y >= height) return;
  const size_t pixel = (size_t)y * width + x;
  const float range = geom[pixel].x;
  __global const float* f = formation + pixel * 12;
  __global float* o = out + pixel * SEASIM_LAYER_CHANNELS;
#if SEASIM_LAYER_BETA_D >= 0
  {
    int all = 1;
    for (int c = 0; c < 3; ++c) {
      int defined;
      o[SEASIM_LAYER_BETA_D + c] = layer_beta_d(f[3 + c], f[c], range, &defined);
      all = all && defined;
    }
    o[SEASIM_LAYER_BETA_D + 3] = all ? 1.0f : 0.0f;
  }
#endif
#if SEASIM_LAYER_BETA_B >= 0
  {
    int all = 1;
    for (int c = 0; c < 3; ++c) {
      int defined;
      o[SEASIM_LAYER_BETA_B + c] = layer_beta_b(f[6 + c], veiling[pixel * 3 + c], range, &defined);
      all = all && defined;
    }
    o[SEASIM_LAYER_BETA_B + 3] = all ? 1.0f : 0.0f;
  }
#endif
}
