/* water_spread.h — the water's point-spread of the light delta-M counts as unscattered.
 *
 * underwater.model = "discrete_ordinates" scales the phase by delta-M (common/underwater_ordinates.h): the share f
 * of each scattering in the phase's forward peak is taken as not scattered, so a hit's light reaches the
 * camera along its own ray as T(S) = e^{-c' S}, c' = c - b f. Of that light, the part
 *   F = 1 - e^{-(c - c') S} = 1 - e^{-tau},  tau = b f S                                  (1)
 * was in fact scattered by small angles, n >= 1 times (n Poisson with mean tau), and reaches the camera
 * from beside the hit: in the path tracer a bright object's edge spreads over the dark water around it,
 * and the object loses that light (without the spread: objects 0.926-0.942 at g >= 0.9, the pixels around
 * them 1.05-1.08).
 * kd_multiple.cl keeps F of each hit's light apart, and kernels/water_spread.cl puts it back blurred.
 *
 * The spread of one scattering seen from the camera. A photon from the hit at distance S, turned by a
 * small angle theta at distance x from the camera, arrives off the hit's direction by theta (1 - x/S)
 * (the path's two ends are fixed: its slope at the camera is minus the sum of the turns times
 * (1 - x_i/S)). With x even along the ray, one turn moves the light by
 *   theta v,  v = 1 - x/S uniform on [0, 1],                                               (2)
 * theta from the peak (HG less its delta-M expansion). The host takes sigma_1, per image axis, as the 2-D
 * Gaussian with the median radius of theta v (host/underwater/water_spread_setup.h: 2.9 deg at g = 0.9,
 * 1.7 at 0.95); theta v is peaked at 0 and heavy-tailed, and the Gaussian of its rms, sigma_theta / sqrt(3),
 * spread the light's bulk too wide (measured). n turns add n sigma_1^2. Conditioned on n >= 1 the mean count is
 *   E[n | n >= 1] = tau / (1 - e^{-tau})                                                  (3)
 * (1 for small tau, tau for large), which sets the pixel's mean variance E sigma_1^2.
 *
 * The in-scatter. Light scattered into the ray at distance x, x in [0, S], travels x to the camera with
 * e^{-c' x}: its share scattered by small angles on the way is 1 - e^{-(c - c') x}. With the in-scatter's
 * source taken as even along the ray (its depth profile left out), the ray's in-scatter has the share
 *   F_in = 1 - A(c) / A(c'),  A(kappa) = int_0^S e^{-kappa x} dx = S phi1(kappa S),               (4)
 * and its mean count, given n >= 1,
 *   E_in = (c - c') int_0^S x e^{-c' x} dx / (A(c') - A(c)) = (c - c') S^2 phi2(c' S) / (A(c') - A(c)),  (5)
 * phi1(z) = (1 - e^{-z})/z, phi2(z) = (1 - e^{-z}(1 + z))/z^2 (stable forms below). Without it a
 * bright object against the water would spread its light out while the water behind it spread none in
 * (measured: objects in deep water without a bottom 0.94 of the path tracer with the hit's light alone).
 *
 * What the spread can reach. Light from a pixel whose light comes from distance D reaches a neighbour that
 * ends at S' < D (an object in front) only by turning at x < S', in front of the object: for one turn at
 * an even x, a share S'/D of it; the rest meets the object. The blur weighs each tap by min(1, S'/D)
 * (kernels/water_spread.cl): the light of the far sand and water does not spread over a near object, while
 * a near object's spreads over what lies behind it. D per pixel is the forward light's mean distance: S
 * for the hit, x_in for the in-scatter, weighed by the light.
 *
 * The layers. The spread is a mixture of Gaussians, one per n. The light F of each channel is split
 * between the two layers of the ladder n_k = 1, 2, 4, 8 around its E, linearly in n: the light and its
 * mean variance are kept, and every layer is one fixed Gaussian of sigma_1 sqrt(n_k) (separable; the
 * blur in water_spread.cl). E above 8 stays in the widest layer (its light is nearly all forward and
 * faint). The split follows the channel's E, not each band's (per band only for spectral.exr's bands).
 *
 * Needs compat.h, band_lanes.h (realb: one band on the host, SEASIM_BAND_LANES in a kernel) and
 * water_spread_params.h (UWS_LAYERS). */
/* No include guard: host/math/kernel_math.h includes it once per precision namespace. */

/* n_k of layer k. */
SEASIM_FN real uws_layer_count(int k) { return (real)(1 << k); }

/* The moments a pixel keeps of its forward light, per band and summed into sensor RGB by kd_multiple.cl:
 * its light F, F E (E the mean count given n >= 1: the layers' split) and F D (D the mean distance it
 * comes from: what the spread can reach). Sums of them stay moments of the sum, so the blur can average
 * pixels before it splits the light between the layers. */

/* expm1(-t) for t >= 0 from exp, which PoCL vectorises (common/band_lanes.h): the series below t = 1e-3,
 * where exp(-t) - 1 would lose digits. */
SEASIM_FN realb uws_expm1_neg_b(realb t) {
  return SELECTB(t < R(1e-3), -t * (R(1.0) - t * (R(0.5) - t * R(1.0 / 6.0))), exp(-t) - R(1.0));
}

/* The hit: (1) and (3), F = 1 - e^{-tau}, F E = tau, F D = F S, per unit of the hit's light. em =
 * expm1(-tau) given (the in-scatter shares it). */
SEASIM_FN realb uws_hit_share_b(realb em) { return -em; }

/* phi1(z) = (1 - e^{-z})/z, 1 at z -> 0; e_z = e^{-z} and r_z = 1/max(z, 1e-30) given. Its series to z^6
 * below z = 0.25 (truncation 2e-9), where the closed form's cancellation would cost float ~6e-8/z. */
SEASIM_FN realb uws_phi1_b(realb z, realb e_z, realb r_z) {
  const realb series =
      R(1.0) - z * (R(0.5) - z * (R(1.0 / 6.0) - z * (R(1.0 / 24.0) -
                                                      z * (R(1.0 / 120.0) - z * (R(1.0 / 720.0) - z * R(1.0 / 5040.0))))));
  return SELECTB(z < R(0.25), series, (R(1.0) - e_z) * r_z);
}

/* phi2(z) = (1 - e^{-z}(1 + z))/z^2, 1/2 at z -> 0: sum_n (-1)^n (n + 1) z^n / (n + 2)!, to z^7 below
 * z = 0.5 (truncation 3e-8 relative), where the closed form's cancellation would cost float ~1e-7/z^2. */
SEASIM_FN realb uws_phi2_b(realb z, realb e_z, realb r_z) {
  const realb series =
      R(0.5) - z * (R(1.0 / 3.0) -
                    z * (R(1.0 / 8.0) -
                         z * (R(1.0 / 30.0) -
                              z * (R(1.0 / 144.0) - z * (R(1.0 / 840.0) - z * (R(1.0 / 5760.0) - z * R(1.0 / 45360.0)))))));
  return SELECTB(z < R(0.5), series, (R(1.0) - e_z * (R(1.0) + z)) * (r_z * r_z));
}

/* 1/max(z, 1e-30): phi1 and phi2 of one z share it. */
SEASIM_FN realb uws_recip_b(realb z) { return R(1.0) / fmax(z, R(1e-30)); }

/* The in-scatter: (4) and (5), per unit of the ray's in-scatter, F_in returned, F_in E_in into *count and
 * F_in x_in into *depth, x_in the mean distance its forward part comes from,
 *   F_in E_in = (c - c') S phi2(c' S) / phi1(c' S),
 *   F_in x_in = int_0^S x (e^{-c' x} - e^{-c x}) dx / A(c') = S (phi2(c' S) - phi2(c S)) / phi1(c' S).
 * c_dm = c', delta = c - c' >= 0, S the ray's length (finite, >= 0), em = expm1(-delta S) (the hit's).
 * (The whole in-scatter's mean distance instead of its forward part's, one division fewer, brought the
 * objects 0.5-3 % up and cost as much.) */
SEASIM_FN realb uws_inscatter_share_b(realb c_dm, realb delta, real S, realb em, realb* count, realb* depth) {
  const realb z0 = fmax(c_dm, R(0.0)) * S;
  const realb z1 = z0 + fmax(delta, R(0.0)) * S;
  const realb e0 = exp(-z0);
  const realb e1 = e0 * (R(1.0) + em); /* e^{-c S} = e^{-c' S} e^{-(c - c') S} */
  const realb r0 = uws_recip_b(z0), r1 = uws_recip_b(z1);
  const realb inv_a0 = R(1.0) / uws_phi1_b(z0, e0, r0); /* S / A(c'); phi1 >= e^{-z} > 0, and 1/z beyond */
  const realb b0 = uws_phi2_b(z0, e0, r0);
  *count = fmax(delta, R(0.0)) * S * b0 * inv_a0;
  *depth = S * fmax(b0 - uws_phi2_b(z1, e1, r1), R(0.0)) * inv_a0;
  return fmax(R(1.0) - uws_phi1_b(z1, e1, r1) * inv_a0, R(0.0));
}

/* Layer k's share of light whose mean count is E: hat functions on the ladder, linear in n, so the
 * shares sum to 1 and sum_k share_k n_k = E for 1 <= E <= 8 (E below 1 counts as 1, above 8 as 8). */
SEASIM_FN real uws_layer_share(real mean_n, int k) {
  const real e = fmin(fmax(mean_n, R(1.0)), uws_layer_count(UWS_LAYERS - 1));
  const real n_k = uws_layer_count(k);
  const real rise = k == 0 ? R(1.0) : (e - R(0.5) * n_k) / (R(0.5) * n_k);
  const real fall = k == UWS_LAYERS - 1 ? R(1.0) : (R(2.0) * n_k - e) / n_k;
  return fmax(fmin(rise, fall), R(0.0));
}
