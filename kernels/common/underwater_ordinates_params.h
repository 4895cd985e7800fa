/* underwater_ordinates_params.h — the per-band block of underwater.model = "discrete_ordinates"
 * (common/underwater_ordinates.h), built on the host (host/underwater/underwater_ordinates_setup.*,
 * which static_asserts its layout) and read by kd_multiple.cl with SEASIM_UNDERWATER_MODEL == 1.
 * Plain C on both sides, no math.
 *
 * Depth y >= 0 below the flat surface, bottom at H (UwParams.bottom_depth; <= 0: none). The diffuse
 * plane irradiances (W m^-2 nm^-1), downwelling E_d and upwelling E_u, are sums of three exponentials:
 *   E_d(y) = d1 e^{-k y} + d2 e^{-k (H - y)} + dp e^{-m y},   E_u(y) = u1 e^{-k y} + u2 e^{-k (H - y)} + up e^{-m y}
 * (d2 = u2 = 0 without a bottom); so are the scalar irradiance E_0 (o*) and the horizontal flux F_h (h*).
 * The host builds them from a discrete-ordinates solution (underwater.diffuse =
 * "discrete_ordinates") or from the two-stream (o from the streams' mean cosines, no F_h).
 *
 * The in-scatter source J(y, ν, Δφ) that view rays gather (common/underwater_ordinates.h) is tabulated in
 * the photon's downward cosine ν at UWI_SOURCE_NODES evenly spaced nodes from -1 to 1, per exponential
 * (a ray reads its nearest node: the region study measured the linear interpolation between two at twice the kernel's
 * cost per band, for the same accuracy as twice the nodes):
 *   J = Σ_q [T0_q(ν) + cos Δφ T1_q(ν) + cos 2Δφ T2_q(ν)] e_q(y),
 *   e_q: e^{-k y}, e^{-k (H - y)}, e^{-m y},
 * src[node * UWI_SOURCE_TERMS + q] = T0_q, [... + 3 + q] = T1_q, [... + 6 + q] = T2_q
 * (Δφ: the photon's azimuth from the sun beam's). Integrated along a ray with extinction c_dm.
 *
 * The diffuse irradiance on a tilted plane (the objects' faces) is tabulated the same way in the upward
 * vertical n_y of the plane's normal n, at UWI_TILT_NODES evenly spaced nodes from -1 to 1, read with
 * linear interpolation (common/underwater_ordinates.h uwi_tilt_irradiance):
 *   E(y, n) = Σ_q [A0_q(n_y) + cos φ_n A1_q(n_y) + cos 2φ_n A2_q(n_y)] e_q(y),
 * φ_n the azimuth of -n from the sun beam's; tilt[node * UWI_SOURCE_TERMS + q + 3 m] = Am_q. At n_y = 1 it
 * is E_d, at -1 E_u. The two-stream's is E_d (1 + n_y)/2 + E_u (1 - n_y)/2 (hemispheres of uniform
 * radiance), linear in n_y.
 * A face that sees shadowed sand (vis_b, uwi_bottom_visibility: the share of the sand it sees that is
 * sunlit; the objects shade the sand the model's plane-parallel field takes as sunlit) loses (1 - vis_b)
 * of tilt_bottom, the part of E(y, n) the beam reflected by the bottom brings (Lambertian, so azimuth mode
 * 0 only); 0 with the two-stream. */

#ifndef SEASIM_UNDERWATER_ORDINATES_PARAMS_H
#define SEASIM_UNDERWATER_ORDINATES_PARAMS_H

#define UWI_SOURCE_NODES 129
#define UWI_SOURCE_TERMS 9
#define UWI_TILT_NODES 33
#define UWI_AUREOLE_NODES 64

typedef struct {
  float c_dm;   /* delta-M extinction c' = a + b (1 - f), 1/m: view rays and the sun beam (f = g³ with the
                   discrete ordinates, their delta-M order; g² with the two-stream) */
  float b_dm;   /* delta-M scattering b' = b (1 - f), 1/m */
  float g_dm;   /* delta-M asymmetry g' = (g - f)/(1 - f) (g / (1 + g) at f = g²) */
  float k;      /* the diffuse field's attenuation, 1/m: fitted with the coefficients to the discrete
                   ordinates' field (underwater_ordinates_solver.h), or the two-stream's mean slope over
                   the camera's depth (depthMeanDiffuseK, underwater_ordinates_setup.h) */
  float m;      /* the delta-M sun beam's attenuation with depth, c' / μ_w, 1/m */
  float d1, u1; /* E_d, E_u coefficients of e^{-k y} */
  float d2, u2; /* of e^{-k (H - y)} (light the bottom sends up, and its back-scatter) */
  float dp, up; /* of e^{-m y} (the delta-M beam's diffuse offspring) */
  /* Host-side only (the kernels read src): */
  float g_flux; /* the two-stream's first-order source's flux asymmetry: g' times a scale fitted to the path
                   tracer (diffuseFluxScale in underwater_ordinates_setup.h) */
  float o1, o2, op; /* the diffuse scalar irradiance E_0(y) = o1 e^{-k y} + o2 e^{-k (H - y)} + op e^{-m y}:
                       the first-order source's isotropic part */
  float h1, h2, hp; /* the diffuse light's net horizontal flux towards the sun's azimuth, F_h(y), in the
                       same exponentials (the discrete ordinates'; 0 for the two-stream) */
  float src[UWI_SOURCE_NODES * UWI_SOURCE_TERMS]; /* the source's table, per m per sr (see above) */
  float tilt[UWI_TILT_NODES * UWI_SOURCE_TERMS];  /* the tilted plane's irradiance table (see above) */
  float tilt_bottom[UWI_TILT_NODES * 3];         /* [node * 3 + q]: the part of tilt's A0_q that the bottom's
                                                    reflection of the beam brings: what a face loses where
                                                    the bottom it sees is in shadow */
  /* The forward peak (host/underwater/forward_peak.h, common/underwater_ordinates.h uwi_aureole): */
  float p_clip;         /* the TMS term's phase ceiling, per sr: it scatters the delta-M beam with
                           min(p_HG, p_clip), the part of p_HG above it holding delta-M's f; 0: none */
  float aureole_single; /* the aureole at the camera scattered by the peak once, per unit of (p_HG - p_clip)+ */
  float aureole[UWI_AUREOLE_NODES]; /* the aureole at the camera scattered by the peak twice or more, W m^-2
                                       nm^-1 sr^-1, at the scattering angles θ_j = π (j / (UWI_AUREOLE_NODES -
                                       1))² (uwi_aureole_node) */
  float aureole_modes[UWI_SOURCE_NODES * 3]; /* [node * 3 + m]: the aureole's azimuth modes m = 0-2 at the
                                                source node's cosine that src already holds (the high-order
                                                fit's weight times them, ordinates_high_order.h: its field has
                                                the peak's light; 0 where src is the order-3 in-scatter) */
  float src_sand[UWI_SOURCE_NODES * 3]; /* [node * 3 + q]: the part of src's T0_q that the bottom brings per
                                           unit of the irradiance it reflects first (the order-3 field's; 0
                                           without a bottom): a Lambertian bottom's light has one shape
                                           whatever lights it */
  float sand_beam;    /* the irradiance of the whole beam on the sand, W m^-2: src_sand times it is what the
                         water loses where objects hide the sand or shade it from the sun (uwi_sand_shares) */
  float sand_diffuse; /* the diffuse irradiance on the sand (over a black one: what it reflects first), W m^-2:
                         src_sand times it is what the water loses where objects hide the sand or shade it
                         from the water above */
} UwiBand;

#endif /* SEASIM_UNDERWATER_ORDINATES_PARAMS_H */
