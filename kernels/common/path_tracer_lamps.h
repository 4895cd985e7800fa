/* path_tracer_lamps.h — how the underwater path tracer (kernels/reference.cl) samples point lamps in
 * the water, shared with the host (kmath_f / kmath_d) so the pdfs and weights are unit-tested in float
 * and double. Needs compat.h, optics.h, shafts.h, underwater.h and path_tracer.h before it.
 *
 * A lamp (intensity I, profile P, a point at `lamp`) scattered once into a path segment o + t d,
 * t in [0, S), adds (per unit path throughput)
 *   L = ∫_0^S e^{-σ_t t} σ_s f(t) dt,  f(t) = p(cos α) I P e^{-σ_t s} V / max(s, s_min)²,   s = |x_t - lamp|.
 * Two strategies sample t (Kulla & Fajardo 2012, "Importance sampling techniques for path tracing in
 * participating media", §4 and §5):
 *   equiangular  pdf_e(t) = r / ((θ1 - θ0)(r² + (t - a)²)) on the part [t0, t1] of the segment inside the
 *                lamp's cone (path_tracer.h pt_sample_equiangular): it cancels the 1/s² near the lamp;
 *                P = 0 outside the cone, so sampling only its inside loses nothing and a ray that
 *                passes the lamp outside a narrow beam spends no sample where the integrand is 0;
 *   free flight  pdf_d(t) = σ_t e^{-σ_t t}, the path's own next vertex (weight σ_s/σ_t there): it
 *                follows e^{-σ_t t}, which equiangular ignores on long segments far from the lamp.
 * Each is weighted by the balance heuristic w_i = pdf_i / (pdf_e + pdf_d) (Veach 1997, eq. 9.13), so
 * the sum of the two weighted estimates is unbiased for any pdfs that cover f together: where one pdf is
 * 0 (equiangular outside the interval, e.g. at the cone's soft edge rounded in float; free flight with
 * σ_t = 0) the other takes weight 1.
 *
 * Stiff cases: h -> 0 (r = max(h, s_min) > 0), a cone of 0.1° (its interval is exact: the quadric of
 * shafts_cone_interval), S = UW_INFINITE (θ1 = π/2), σ_t = 0 (pdf_d = 0), both pdfs 0 (weight 0: no
 * estimate there), pdf overflow to +inf in float (weight by the ratio, never inf/inf).
 */

/* The equiangular pdf of t on [t0, t1] (t1 may be UW_INFINITE) about a light at closest approach a,
 * distance r > 0; the density pt_sample_equiangular samples. 0 outside [t0, t1] or on an empty interval. */
SEASIM_FN real pt_equiangular_pdf(real a, real r, real t0, real t1, real t) {
  if (!(t >= t0) || !(t <= t1)) return R(0.0);
  const real th0 = atan((t0 - a) / r);
  const real th1 = t1 >= UW_INFINITE ? R(0.5) * SEASIM_PI : atan((t1 - a) / r);
  if (!(th1 > th0)) return R(0.0);
  const real x = t - a;
  return r / ((th1 - th0) * (r * r + x * x));
}

/* The free-flight pdf of a scattering vertex at t: σ_t e^{-σ_t t} (0 for σ_t = 0). */
SEASIM_FN real pt_distance_pdf(real sigma_t, real t) {
  return sigma_t > R(0.0) ? sigma_t * exp(-sigma_t * t) : R(0.0);
}

/* The balance heuristic's weight of the strategy with pdf p_this against one with p_other: in [0, 1];
 * 0 when p_this = 0 (also when both are 0), 1 when p_other = 0, and 1/(1 + p_other/p_this) otherwise so
 * a pdf that overflowed to +inf in float gives weight 1, not inf/inf. */
SEASIM_FN real pt_mis_balance(real p_this, real p_other) {
  if (!(p_this > R(0.0))) return R(0.0);
  if (!(p_other > R(0.0))) return R(1.0);
  if (p_this >= p_other) return R(1.0) / (R(1.0) + p_other / p_this);
  const real q = p_this / p_other;
  return q / (q + R(1.0));
}

/* The part of a path segment o + t d, t in [0, S), on which a lamp is sampled equiangularly. */
typedef struct {
  real t0, t1; /* the sampled interval: [0, S) ∩ the lamp's cone (clip_to_cone = 0: all of [0, S)) */
  real a, r;   /* closest approach of the ray to the lamp: parameter, max(distance, s_min) */
} PtLampRange;

/* Fills *rg for a lamp at `lamp` with unit axis `axis` and cone cos_cone (half angle < 90°); returns 0
 * when the segment has no part in the cone (nothing to sample: the lamp adds nothing there). */
SEASIM_FN int pt_lamp_range(real3 o, real3 d, real S, real3 lamp, real3 axis, real cos_cone, real s_min, int clip_to_cone,
                            PtLampRange* rg) {
  real h;
  shafts_closest_approach(o, d, lamp, &rg->a, &h);
  rg->r = fmax(h, s_min);
  rg->t0 = R(0.0);
  rg->t1 = S;
  if (clip_to_cone) {
    real ta, tb;
    if (!shafts_cone_interval(o, d, lamp, axis, cos_cone, &ta, &tb)) return 0;
    rg->t0 = fmax(ta, R(0.0));
    rg->t1 = tb >= (real)SHAFTS_T_INF ? S : fmin(tb, S);
  }
  return rg->t1 > rg->t0;
}

/* The equiangular pdf of t within the lamp's range (0 outside it). */
SEASIM_FN real pt_lamp_range_pdf(const PtLampRange* rg, real t) {
  return pt_equiangular_pdf(rg->a, rg->r, rg->t0, rg->t1, t);
}
