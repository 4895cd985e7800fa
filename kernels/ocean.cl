/* ocean.cl — Tessendorf's FFT ocean (004 §3): initial amplitudes h̃0 (eq. 23–25), their time
 * evolution (eq. 26) into the spectra of the height, its exact slopes (eq. 20), the choppy
 * displacement (eq. 29) and the displacement's derivatives, and, after the inverse FFTs (VkFFT,
 * host/ocean/vkfft_plan.cpp), the maps: height, slope, displacement, normal, Jacobian and folding
 * (eq. 30–34).
 *
 * Grid: N x N texels over a periodic L x L patch, texel (i, j) at x = (i L/N, j L/N), i along +x
 * (fastest), j along +z; spectra in FFT order (ocean_wave_index). The inverse FFT is unnormalised
 * with kernel e^{+ik·x}, which is eq. 19 as written.
 *
 * Eight real fields go through four complex FFTs: each field's spectrum is Hermitian (h̃ is, and
 * the factors i k, -i k/|k|, k k/|k| keep it so), so two of them A, B ride in one transform as
 * Ã + iB̃ and come back as A + iB. Slots (each N² float2):
 *   0: h       + i ∂h/∂x       1: ∂h/∂z   + i Dx       2: Dz + i ∂Dx/∂x
 *   3: ∂Dz/∂z  + i ∂Dx/∂z       (D without λ; ∂Dx/∂z = ∂Dz/∂x)
 *
 * Outputs (per texel, world frame, y up, metres): height h; slope (∂h/∂x, ∂h/∂z); displacement
 * (λDx, h, λDz, 0) = displaced point minus (x, 0, z); normal (nx, ny, nz, 0) of the displaced
 * surface, unit; jacobian J (eq. 30); folding (J-, J+, e-x, e-z) (eq. 31–34).
 * Sign of D. Eq. 29 reads D = Σ -i k̂ h̃ e^{ik·x}; with eq. 19's e^{+ik·x} a single wave h = cos kx
 * then gets D = sin kx, and x + λD with λ > 0 spreads the crests and folds the troughs, the
 * opposite of what §3.7 and Figure 14 describe (sharp crests, broad troughs; the Gerstner form
 * x - k̂ A sin k·x of §3.1). We use D = Σ +i k̂ h̃ e^{ik·x}, so a positive choppiness λ sharpens
 * crests as the paper intends; eq. 30–34 are unchanged in terms of D.
 * Stiff cases: k = 0 and the Nyquist lines carry zero amplitude (no 0/0 in k/|k|); a degenerate
 * displaced tangent frame (zero-area facet) gives the normal (0, 1, 0); wind 0 gives a flat,
 * finite surface; folded facets (J < 0) keep their geometric, downward normal.
 */
#include "common/compat.h"
#include "common/ocean_params.h"
#include "common/ocean_spectrum.h"

__kernel void ocean_init(__constant OceanParams* p, __global float2* h0) {
  const int i = get_global_id(0), j = get_global_id(1);
  const int n = p->n;
  if (i >= n || j >= n) return;
  float re, im;
  ocean_h0(i, j, n, p->patch_size, p->wind_dir_x, p->wind_dir_z, p->wind_speed, p->gravity,
           p->phillips_a, p->directional_exponent, p->small_wave, p->seed, &re, &im);
  h0[j * n + i] = (float2)(re, im);
}

/* h̃(k, t) for texel (i, j): eq. 26 with the partner -k at ((N-i) mod N, (N-j) mod N). */
static inline float2 height_spectrum(__constant OceanParams* p, __global const float2* h0, int i, int j,
                                     float* kx, float* kz, float* k) {
  const int n = p->n;
  const float dk = 2.0f * SEASIM_PI / p->patch_size;
  *kx = dk * (float)ocean_wave_index(i, n);
  *kz = dk * (float)ocean_wave_index(j, n);
  *k = sqrt(*kx * *kx + *kz * *kz);
  const float2 a = h0[j * n + i];
  const float2 b = h0[((n - j) & (n - 1)) * n + ((n - i) & (n - 1))];
  const float omega = ocean_omega(*k, p->gravity, p->depth);
  const float phase = ocean_phase(omega, p->time, p->loop_period, p->loop_phase);
  float hr, hi;
  ocean_evolve(a.x, a.y, b.x, b.y, phase, &hr, &hi);
  return (float2)(hr, hi);
}

/* i·z for complex z = (re, im). */
static inline float2 times_i(float2 z) { return (float2)(-z.y, z.x); }

__kernel void ocean_evolve_fields(__constant OceanParams* p, __global const float2* h0,
                                  __global float2* fields) {
  const int i = get_global_id(0), j = get_global_id(1);
  const int n = p->n;
  if (i >= n || j >= n) return;
  float kx, kz, k;
  const float2 h = height_spectrum(p, h0, i, j, &kx, &kz, &k);
  const float inv_k = k > 0.0f ? 1.0f / k : 0.0f;
  const float2 ih = times_i(h);
  const float2 slope_x = kx * ih;                 /* i kx h̃ (eq. 20) */
  const float2 slope_z = kz * ih;
  /* D̃ = +i k/|k| h̃: see the sign note in the header. */
  const float2 disp_x = (kx * inv_k) * ih;
  const float2 disp_z = (kz * inv_k) * ih;
  const float2 dxx = -(kx * kx * inv_k) * h;      /* i kx · (i kx/k) h̃ = -kx²/k h̃ */
  const float2 dzz = -(kz * kz * inv_k) * h;
  const float2 dxz = -(kx * kz * inv_k) * h;
  const size_t nn = (size_t)n * (size_t)n;
  const size_t at = (size_t)j * n + i;
  fields[at] = h + times_i(slope_x);
  fields[nn + at] = slope_z + times_i(disp_x);
  fields[2 * nn + at] = disp_z + times_i(dxx);
  fields[3 * nn + at] = dzz + times_i(dxz);
}

/* h̃(k, t) alone (tests: Hermitian symmetry, real height after one FFT; dispersion). */
__kernel void ocean_height_spectrum(__constant OceanParams* p, __global const float2* h0,
                                    __global float2* out) {
  const int i = get_global_id(0), j = get_global_id(1);
  const int n = p->n;
  if (i >= n || j >= n) return;
  float kx, kz, k;
  out[j * n + i] = height_spectrum(p, h0, i, j, &kx, &kz, &k);
}

__kernel void ocean_maps(__constant OceanParams* p, __global const float2* fields, __global float* height,
                         __global float2* slope, __global float4* displacement, __global float4* normal,
                         __global float* jacobian, __global float4* folding) {
  const int i = get_global_id(0), j = get_global_id(1);
  const int n = p->n;
  if (i >= n || j >= n) return;
  const size_t nn = (size_t)n * (size_t)n;
  const size_t at = (size_t)j * n + i;
  const float2 f0 = fields[at], f1 = fields[nn + at], f2 = fields[2 * nn + at], f3 = fields[3 * nn + at];
  const float lambda = p->choppiness;
  const float h = f0.x, hx = f0.y, hz = f1.x;
  const float dx = f1.y, dz = f2.x;
  const float jxx = 1.0f + lambda * f2.y;
  const float jzz = 1.0f + lambda * f3.x;
  const float jxz = lambda * f3.y;
  height[at] = h;
  slope[at] = (float2)(hx, hz);
  displacement[at] = (float4)(lambda * dx, h, lambda * dz, 0.0f);
  /* Tangents of the displaced surface P(x, z) = (x + λDx, h, z + λDz):
   * ∂P/∂x = (Jxx, hx, Jxz), ∂P/∂z = (Jxz, hz, Jzz); n = ∂P/∂z × ∂P/∂x points up where J > 0. */
  const float3 tx = (float3)(jxx, hx, jxz);
  const float3 tz = (float3)(jxz, hz, jzz);
  const float3 c = cross(tz, tx);
  const float len = length(c);
  const float3 nrm = len > 0.0f ? c / len : (float3)(0.0f, 1.0f, 0.0f);
  normal[at] = (float4)(nrm.x, nrm.y, nrm.z, 0.0f);
  jacobian[at] = jxx * jzz - jxz * jxz;
  float jm, jp, ex, ez;
  ocean_jacobian_eigen(jxx, jzz, jxz, &jm, &jp, &ex, &ez);
  folding[at] = (float4)(jm, jp, ex, ez);
}
