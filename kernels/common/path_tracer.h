/* path_tracer.h — the sampling math of the underwater Monte Carlo path tracer (kernels/reference.cl),
 * shared with the host (kmath_f / kmath_d) so every sampler is unit-tested in float and double.
 * Needs compat.h, optics.h and underwater.h (UW_INFINITE) before it.
 *
 * Random numbers are counter based: a sample's u for dimension k is a hash of (seed, pixel, sample,
 * k) (PCG hash, Jarzynski & Olano 2020, "Hash Functions for GPU Rendering"), so an image is the same
 * for a seed whatever the batch size, launch order or device, and any path can be replayed alone.
 * u = (h >> 8) 2^-24 lies in [0, 1 - 2^-24]: exact in float, so 1 - u is exact and never 0.
 *
 * Samplers (each returns a direction or distance distributed exactly as its pdf):
 *   free flight       t = -ln(1 - u)/σ_t, pdf σ_t e^{-σ_t t}; σ_t = 0 gives UW_INFINITE
 *   Henyey–Greenstein the inverse CDF written as 1 - cos θ = (1-|g|)(1-u)(s + 1-|g|)/(1-|g|+2|g|u),
 *                     s = (1-g²)/(1-|g|+2|g|u): a product of non-negative factors, so no cancellation
 *                     near the forward spike (|g| -> 1, where the textbook (1+g²-s²)/(2g) loses every
 *                     digit of 1 - cos θ in float), no 0/0 at g = 0 (it reduces to cos θ = 2u - 1), and
 *                     g < 0 is the mirror image of |g|
 *   isotropic         cos θ = 1 - 2u, pdf 1/(4π)
 *   cosine hemisphere about a normal, pdf cos θ/π (Lambertian reflection: weight = albedo)
 *   Fresnel choice    reflect with probability F (weight 1 either way)
 *   equiangular       a distance on a ray segment with pdf ∝ 1/(r² + (t - a)²) about a point light
 *                     (Kulla & Fajardo 2012, "Importance sampling techniques for path tracing in
 *                     participating media"): uniform in the angle the light sees, which cancels the
 *                     1/s² of a point light in the medium (free-flight sampling leaves it, and its
 *                     variance grows as 1/h³ with the ray's distance h to the light)
 * Directions are built from 1 - cos θ (not cos θ) so sin θ = sqrt((1-cos)(1+cos)) keeps its digits
 * for small angles.
 */

/* PCG hash of one 32-bit word (Jarzynski & Olano 2020): a full-avalanche permutation of 2^32. */
SEASIM_FN unsigned int pt_hash(unsigned int v) {
  const unsigned int state = v * 747796405u + 2891336453u;
  const unsigned int word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

/* The key of one path: seed, pixel index and sample index hashed in turn (nesting keeps the three
 * counters from aliasing: (pixel, sample) and (pixel + 1, sample - 1) give unrelated keys). */
SEASIM_FN unsigned int pt_path_key(unsigned int seed, unsigned int pixel, unsigned int sample) {
  return pt_hash(sample + pt_hash(pixel + pt_hash(seed)));
}

/* Uniform u in [0, 1 - 2^-24] for dimension `dim` of the path with key `key`. */
SEASIM_FN real pt_uniform(unsigned int key, unsigned int dim) {
  const unsigned int h = pt_hash(key ^ pt_hash(dim + 0x9e3779b9u));
  return (real)(h >> 8u) * R(5.9604644775390625e-8); /* 2^-24 */
}

/* Free-flight distance in a homogeneous medium of extinction sigma_t (1/m): pdf σ_t e^{-σ_t t}, so
 * P(t >= S) = e^{-σ_t S} is exactly the transmittance to a surface at S (weight 1 there, weight
 * σ_s/σ_t at a scattering event). */
SEASIM_FN real pt_sample_distance(real sigma_t, real u) {
  if (sigma_t <= R(0.0)) return UW_INFINITE;
  return -log(R(1.0) - u) / sigma_t;
}

/* 1 - cos θ of a Henyey–Greenstein sample with asymmetry g_abs = |g| in [0, 1] (see the top). In [0, 2]. */
SEASIM_FN real pt_hg_one_minus_cos(real g_abs, real u) {
  const real omg = R(1.0) - g_abs;
  const real den = omg + R(2.0) * g_abs * u;
  if (den <= R(0.0)) return R(0.0); /* g = 1 and u = 0: the delta spike itself */
  const real s = omg * (R(1.0) + g_abs) / den;
  return clamp(omg * (R(1.0) - u) * (s + omg) / den, R(0.0), R(2.0));
}

/* cos θ of a Henyey–Greenstein sample for any g in [-1, 1] (HG with -g is HG with g mirrored). */
SEASIM_FN real pt_sample_hg_cos(real g, real u) {
  const real omc = pt_hg_one_minus_cos(fabs(g), u);
  return g >= R(0.0) ? R(1.0) - omc : omc - R(1.0);
}

/* Orthonormal t1, t2 completing the unit n (Duff et al. 2017, "Building an orthonormal basis,
 * revisited": no normalisation, no branch on a near-parallel helper axis). */
SEASIM_FN void pt_basis(real3 n, real3* t1, real3* t2) {
  const real sign = n.z >= R(0.0) ? R(1.0) : R(-1.0);
  const real a = R(-1.0) / (sign + n.z);
  const real b = n.x * n.y * a;
  *t1 = MAKE_REAL3(R(1.0) + sign * n.x * n.x * a, sign * b, -sign * n.x);
  *t2 = MAKE_REAL3(b, sign + n.y * n.y * a, -n.y);
}

/* The unit direction at angle θ from the unit axis (given as 1 - cos θ in [0, 2]) and azimuth 2π u_phi. */
SEASIM_FN real3 pt_direction(real3 axis, real one_minus_cos, real u_phi) {
  real3 t1, t2;
  pt_basis(axis, &t1, &t2);
  const real omc = clamp(one_minus_cos, R(0.0), R(2.0));
  const real cos_t = R(1.0) - omc;
  const real sin_t = sqrt(fmax(omc * (R(2.0) - omc), R(0.0)));
  const real phi = R(2.0) * SEASIM_PI * u_phi;
  return normalize(cos_t * axis + (sin_t * cos(phi)) * t1 + (sin_t * sin(phi)) * t2);
}

/* A new travel direction after a Henyey–Greenstein scattering of the unit travel direction d
 * (cos θ = d·d_new, forward for g > 0). pdf = hg_phase(d·d_new, g); the path weight is unchanged. */
SEASIM_FN real3 pt_sample_hg(real3 d, real g, real u1, real u2) {
  const real omc = pt_hg_one_minus_cos(fabs(g), u1);
  return pt_direction(d, g >= R(0.0) ? omc : R(2.0) - omc, u2);
}

/* A uniformly distributed direction on the sphere, pdf 1/(4π). */
SEASIM_FN real3 pt_sample_isotropic(real u1, real u2) {
  const real z = R(1.0) - R(2.0) * u1;
  const real r = sqrt(fmax(R(0.0), (R(1.0) - z) * (R(1.0) + z)));
  const real phi = R(2.0) * SEASIM_PI * u2;
  return MAKE_REAL3(r * cos(phi), z, r * sin(phi));
}

/* A cosine-distributed direction about the unit normal n, pdf cos θ/π (Malley's method: a uniform
 * point on the unit disk lifted to the hemisphere; cos θ = sqrt(1 - u1) > 0). */
SEASIM_FN real3 pt_sample_cosine(real3 n, real u1, real u2) {
  real3 t1, t2;
  pt_basis(n, &t1, &t2);
  const real r = sqrt(u1);
  const real phi = R(2.0) * SEASIM_PI * u2;
  const real z = sqrt(fmax(R(0.0), R(1.0) - u1));
  return normalize(z * n + (r * cos(phi)) * t1 + (r * sin(phi)) * t2);
}

/* Fresnel choice at the water surface seen from below, d the upward travel direction (d.y > 0):
 * returns 1 (reflect, probability F) or 0 (refract into the air, probability 1 - F). F is the
 * water-to-air reflectance, 1 under total internal reflection (optics.h). Weight 1 either way: the
 * choice itself carries F and 1 - F, so a refracted path that escapes picks up n² L_sky (radiance
 * over n² is conserved across the interface). */
SEASIM_FN int pt_fresnel_reflects(real d_y, real ior, real u) {
  return u < fresnel_reflectance(d_y, ior, R(1.0)) ? 1 : 0;
}

/* Equiangular distance on [t0, t1] (t1 may be UW_INFINITE) of the ray o + t d about a light at closest
 * approach parameter a and distance r > 0 (r = max(h, the light's radius): any r > 0 gives a valid pdf):
 * θ uniform in [θ0, θ1], θ = atan((t - a)/r), t = a + r tan θ; writes pdf(t) = r / ((θ1 - θ0)(r² + (t - a)²)).
 * u < 1 keeps θ < π/2, so t is finite. Returns t in [t0, t1]; *pdf = 0 when the segment is empty. */
SEASIM_FN real pt_sample_equiangular(real a, real r, real t0, real t1, real u, real* pdf) {
  const real th0 = atan((t0 - a) / r);
  const real th1 = t1 >= UW_INFINITE ? R(0.5) * SEASIM_PI : atan((t1 - a) / r);
  if (!(th1 > th0)) {
    *pdf = R(0.0);
    return t0;
  }
  const real th = th0 + u * (th1 - th0);
  const real x = r * tan(th);
  *pdf = r / ((th1 - th0) * (r * r + x * x));
  return clamp(a + x, t0, t1); /* a + r tan(θ0) may round just outside [t0, t1] */
}
