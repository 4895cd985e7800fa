/* underwater_improved_params.h — the per-band block of underwater.model = "improved"
 * (common/underwater_improved.h), built on the host (host/underwater/underwater_improved_setup.*,
 * which static_asserts its layout) and read by kd_multiple.cl with SEASIM_UNDERWATER_MODEL == 1.
 * Plain C on both sides, no math.
 *
 * Depth y >= 0 below the flat surface, bottom at H (UwParams.bottom_depth; <= 0: none). The diffuse
 * plane irradiances (W m^-2 nm^-1), downwelling E_d and upwelling E_u, are sums of three exponentials:
 *   E_d(y) = d1 e^{-k y} + d2 e^{-k (H - y)} + dp e^{-m y},   E_u(y) = u1 e^{-k y} + u2 e^{-k (H - y)} + up e^{-m y}
 * (d2 = u2 = 0 without a bottom); so are the scalar irradiance E_0 (o*) and the horizontal flux F_h (h*).
 * The host builds them from a discrete-ordinates solution (underwater.improved_diffuse =
 * "discrete_ordinates") or from the two-stream (o from the streams' mean cosines, no F_h).
 *
 * The in-scatter source J(y, ν, Δφ) that view rays gather (common/underwater_improved.h) is tabulated in
 * the photon's downward cosine ν at UWI_SOURCE_NODES evenly spaced nodes from -1 to 1, per exponential
 * (a ray reads its nearest node: s9b measured the linear interpolation between two at twice the kernel's
 * cost per band, for the same accuracy as twice the nodes):
 *   J = Σ_q [T0_q(ν) + cos Δφ T1_q(ν) + cos 2Δφ T2_q(ν)] e_q(y),
 *   e_q: e^{-k y}, e^{-k (H - y)}, e^{-m y},
 * src[node * UWI_SOURCE_TERMS + q] = T0_q, [... + 3 + q] = T1_q, [... + 6 + q] = T2_q
 * (Δφ: the photon's azimuth from the sun beam's). Integrated along a ray with extinction c_dm. */

#ifndef SEASIM_UNDERWATER_IMPROVED_PARAMS_H
#define SEASIM_UNDERWATER_IMPROVED_PARAMS_H

#define UWI_SOURCE_NODES 129
#define UWI_SOURCE_TERMS 9

typedef struct {
  float c_dm;   /* delta-M extinction c' = a + b (1 - f), 1/m: view rays and the sun beam (f = g³ with the
                   discrete ordinates, their delta-M order; g² with the two-stream) */
  float b_dm;   /* delta-M scattering b' = b (1 - f), 1/m */
  float g_dm;   /* delta-M asymmetry g' = (g - f)/(1 - f) (g / (1 + g) at f = g²) */
  float k;      /* the diffuse field's attenuation, 1/m: fitted with the coefficients to the discrete
                   ordinates' field (underwater_improved_ordinates.h), or the two-stream's mean slope over
                   the camera's depth (depthMeanDiffuseK, underwater_improved_setup.h) */
  float m;      /* the delta-M sun beam's attenuation with depth, c' / μ_w, 1/m */
  float d1, u1; /* E_d, E_u coefficients of e^{-k y} */
  float d2, u2; /* of e^{-k (H - y)} (light the bottom sends up, and its back-scatter) */
  float dp, up; /* of e^{-m y} (the delta-M beam's diffuse offspring) */
  /* Host-side only (the kernels read src): */
  float g_flux; /* the two-stream's first-order source's flux asymmetry: g' times a scale fitted to the path
                   tracer (diffuseFluxScale in underwater_improved_setup.h; s7c, results/BENCHMARKS.md) */
  float o1, o2, op; /* the diffuse scalar irradiance E_0(y) = o1 e^{-k y} + o2 e^{-k (H - y)} + op e^{-m y}:
                       the first-order source's isotropic part */
  float h1, h2, hp; /* the diffuse light's net horizontal flux towards the sun's azimuth, F_h(y), in the
                       same exponentials (the discrete ordinates'; 0 for the two-stream) */
  float src[UWI_SOURCE_NODES * UWI_SOURCE_TERMS]; /* the source's table, per m per sr (see above) */
} UwiBand;

#endif /* SEASIM_UNDERWATER_IMPROVED_PARAMS_H */
