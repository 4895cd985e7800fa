/* underwater_lamps_ms.h — a spotlight's light scattered more than once in the water ("orders" model of
 * the lamps under water): the glow around the beam, the beam's forward halo and the bottom lit by it.
 * Shared by kernels/underwater_lamps.cl (SEASIM_LAMPS_ORDERS), the host's table of blurred profiles
 * (host/underwater/lamps_ms_table.h), the unit tests (float and double) and the kernel test's double
 * CPU evaluation. Single scattering stays paper 001's planes with the water as it is
 * (common/underwater_lamps.h, not delta-M scaled); this header adds orders n >= 1 of the light field.
 *
 * Model: orders of scattering along the lamp's rays (the small-angle picture of the beam spread
 * function; Wells 1973, McLean & Voss 1991), each order's angles taken from the exact HG algebra. A
 * ray from the lamp that has scattered n times has travelled a path ℓ_n; the number of scatterings on
 * a path ℓ is Poisson with mean σ_s ℓ, and it survives absorption with e^{-σ_a ℓ}. HG phase functions
 * compose exactly in their Legendre moments (g₁^l g₂^l = (g₁ g₂)^l), so n scatterings spread its
 * direction as HG(g^n) about the lamp's ray (Narasimhan & Nayar 2003 use the same moments). Spread
 * uniformly along the path, the deflections move the point the light reaches by a third of their
 * mean-square angle, as seen from the lamp: HG(h_n), h_n = 1 - (1 - g^n)/3 (small angles: the
 * variance of Σ (1 - u_i) δ_i with u_i uniform is n <δ²>/3). So the order-n fluence at x, at distance
 * s from the lamp and angle ψ from its axis, per unit I, is
 *   φ_n(x) = W_n(s) P_n(ψ) / s²,    P_n = P ⊛ HG(h_n)   (the lamp's profile blurred on the sphere),
 *   W_n(s) = (ℓ_n/s) e^{-σ_a ℓ_n} Pois(n; σ_s ℓ_n)       (the last order kept takes all higher ones),
 * with ℓ_n = s q_n^{-κ}, q_n = (1/(n+1)) Σ_{k=0}^{n} g^k the mean radial progress of a path whose
 * n + 1 legs have mean cosines g^0 .. g^n (κ = 0: paths as straight as the lamp's ray, exact as
 * g -> 1; κ = 1: light that turned more lingers longer, ℓ_n/s the density of slower light).
 * Its radiance at x spreads as HG(g^n) about the lamp's ray, so scattering once more towards the eye
 * takes the phase function HG(g^{n+1}) at the scattering angle α from the lamp's ray — except order 1
 * outside the cone, whose light comes in from the beam: its phase is averaged over the light of the
 * cone's nearest edge line (uw_ms_order1_phase) — and a surface of
 * normal n_s receives E_n = φ_n F(g^n, cos θ_i), F(G, cos θ_i) = ∫ p_HG(ω · r̂; G) max(-ω · n_s, 0) dω the
 * irradiance of radiance spread as HG(G) about the lamp's ray r̂ (collimated light, G = 1: cos θ_i;
 * isotropic, G = 0: 1/4; uw_ms_irradiance_exact). Along a view ray o + t d up to S:
 *   L_ms = I ∫_0^S σ_s e^{-σ_t t} Σ_n φ_n(x_t) p_HG(cos α; g^{n+1}) dt,
 * quadrature in v, t = a + r sinh v (uw_ms_ray), which spreads the steps over the scales of the
 * distance to the lamp.
 * A surface's radiance (the lamp's direct light and E_n ρ/π) reaches the eye through the water with
 * its own orders: light scattered k times on the way whose direction (HG(g^k) about the view ray)
 * still heads on towards the surface sees the same surface radiance (a lit patch wider than the
 * blur), so T_view(S) = e^{-σ_a S} Σ_k Pois(k; σ_s S) F(g^k), F(G) the forward-hemisphere share of
 * HG(G) (F(1) = 1: the unscattered e^{-σ_t S} is the k = 0 term).
 *
 * The bottom's glow. The lit bottom sends the lamp's light back into the water, where it scatters
 * towards the eye (with the lamp 1 m over a bottom of albedo 0.5 the beam's water without it was
 * 0.80-0.86 of the path tracer, 0.92-0.97 over a black bottom). The patch the lamp's direct light lights
 * is taken as one Lambertian source at its irradiance-weighted centre c, of intensity J cos ψ about the
 * bottom's normal (J = ∫ ρ E_direct/π dA, ψ from the normal), softened by the patch's RMS radius R:
 * 1/(s² + R²) instead of 1/s² (exact on the axis of a uniformly lit disk). The orders' light on the
 * bottom spreads far wider than the patch; it is the bottom's halo below, taken where it lands. Its light scatters in orders along straight paths
 * (W_n with ℓ = s: the source is already diffuse, its cosine lobe left unblurred), order 0 included:
 *   φ_glow(x) = J cos ψ Σ_{n>=0} w_n(s) / (s² + R²),
 * scattered towards the eye by HG(g^{n+1}) without its forward peak (delta-M: that light, from the
 * bottom through small angles, is already in the bottom's T_view; with it the lit bottom came out up
 * to 17 % too bright at g = 0.9). J, c and R come from the host (host/underwater/lamps_bottom_glow.h).
 *
 * Stiff cases: σ_s -> 0 (every order's weight is 0, T_view = e^{-σ_a S}); g -> 1 (h_n, g^n -> 1,
 * P_n -> P: the table is built from HG's inverse CDF, no peak to resolve; hg_phase is stable);
 * s -> 0 (1/s² clamped at s_min, the quadrature's weight is finite); S -> ∞ (capped at 30 optical
 * depths); large σ ℓ
 * (weights underflow to 0, never overflow: the Poisson terms are built on e^{-σ_t ℓ}).
 *
 * Written against compat.h; needs optics.h, band_lanes.h, band_lanes_math.h, shafts.h, underwater_lamps.h,
 * path_tracer.h (HG's inverse CDF) and polynomial_trig.h before it.
 */

#define UW_MS_TABLE 181    /* blurred profile entries over ψ in [0°, 180°], 1° apart */
#define UW_MS_IRRADIANCE 129 /* irradiance factor entries over cos θ_i in [-1, 1], uniform */
/* One order's row of a lamp's table: its blurred profile, then its surfaces' irradiance factor
 * (host/underwater/lamps_ms_table.h). */
#define UW_MS_ROW (UW_MS_TABLE + UW_MS_IRRADIANCE)
#define UW_MS_MAX_ORDERS 12
#define UW_MS_MAX_STEPS 64

/* g^n (n >= 0) by repeated multiplication (no pow of a negative base). */
SEASIM_FN real uw_ms_gpow(real g, int n) {
  real p = R(1.0);
  for (int k = 0; k < n; ++k) p *= g;
  return p;
}

/* h_n = 1 - β (1 - g^n): the HG parameter of where order-n light lands, as the lamp sees it (β = 1/3
 * for small angles; β is the model's spread knob). */
SEASIM_FN real uw_ms_spread(real g, int n, real beta) { return R(1.0) - beta * (R(1.0) - uw_ms_gpow(g, n)); }

/* ℓ_n / s = q_n^{-κ}, q_n the mean of max(g, 0)^k over k = 0..n (in (0, 1]; 1 for n = 0 or g = 1). */
SEASIM_FN real uw_ms_stretch(real g, int n, real kappa) {
  const real gp = fmax(g, R(0.0));
  real sum = R(0.0), p = R(1.0);
  for (int k = 0; k <= n; ++k) {
    sum += p;
    p *= gp;
  }
  const real q = sum / (real)(n + 1);
  return kappa == R(0.0) ? R(1.0) : pow(q, -kappa);
}

/* P(N >= n) for N Poisson with mean x >= 0, n >= 1: summed upwards when x < n + 1 (no cancellation
 * where it is small), else 1 - the lower terms. */
SEASIM_FN real uw_ms_poisson_at_least(int n, real x) {
  if (!(x > R(0.0))) return R(0.0);
  if (x < (real)(n + 1)) {
    real term = exp(-x);
    for (int k = 1; k <= n; ++k) term *= x / (real)k;
    real sum = R(0.0);
    for (int k = n; k < n + 60 && term > R(1e-9) * sum; ++k) { /* terms fall at least as x/(n+1) < 1 */
      sum += term;
      term *= x / (real)(k + 1);
    }
    return fmin(sum, R(1.0));
  }
  real term = exp(-x), lower = R(0.0);
  for (int k = 0; k < n; ++k) {
    lower += term;
    term *= x / (real)(k + 1);
  }
  return fmax(R(1.0) - lower, R(0.0));
}

/* W_n(s) of order n (1 <= n <= last) for one band: (ℓ/s) e^{-σ_a ℓ} Pois(n; σ_s ℓ), ℓ = s * stretch;
 * n == last: Pois(>= n). Built on e^{-σ_t ℓ} times (σ_s ℓ)^n/n!, so nothing overflows. */
SEASIM_FN real uw_ms_weight(real sigma_a, real sigma_s, real s, real stretch, int n, int last) {
  const real l = s * stretch;
  const real x = sigma_s * l;
  if (!(x > R(0.0))) return R(0.0);
  if (n >= last) return stretch * exp(-sigma_a * l) * uw_ms_poisson_at_least(n, x);
  real p = exp(-(sigma_a + sigma_s) * l);
  for (int k = 1; k <= n; ++k) p *= x / (real)k;
  return stretch * p;
}

/* The orders' weights tabulated: the kernel's way past the exps and the last order's Poisson tail per
 * step, band and order (host/underwater/lamps_ms_weights.h builds the table in double from uw_ms_weight
 * and uw_ms_glow_weights). Each row holds UW_MS_WEIGHT_STEPS entries uniform in u = ln(1 + s/s0) over
 * [0, ln(1 + S_MAX/s0)], s0 = 1/σ_t of the most extinguishing band: a step is about a hundredth of
 * that band's optical depth near the lamp and about 1 % of s far from it, so linear interpolation stays
 * within ~1e-4 of every weight's peak (tests/unit/underwater_lamps_weights_test.cpp). Layout: [0] = 1/s0,
 * [1] = entries per unit of u; from UW_MS_WEIGHT_HEADER the lamp's section, order n (1..orders), step j,
 * band i at ((n - 1) UW_MS_WEIGHT_STEPS + j) P + i; after it (uw_ms_glow_weight_rows) the bottom glow's,
 * order n (0..orders) at (n UW_MS_WEIGHT_STEPS + j) P + i. The bands run fastest, P = uw_ms_band_stride
 * apart (padded with zeros), so that a kernel's band lanes read one step of one order as one vector load
 * (uw_ms_weights_at_b). Beyond S_MAX (twice the view ray's longest cap, uw_ms_ray_cap) the last entry
 * holds. */
#define UW_MS_WEIGHT_STEPS 1024
#define UW_MS_WEIGHT_HEADER 2
#define UW_MS_WEIGHT_S_MAX 2e4
/* The tables' bands padded to a multiple of the widest band lanes (band_lanes.h: at most 16). */
#define UW_MS_BAND_PAD 16

/* P: the distance between one entry's bands and the next entry's (nb bands, padded). */
SEASIM_FN int uw_ms_band_stride(int nb) { return (nb + UW_MS_BAND_PAD - 1) / UW_MS_BAND_PAD * UW_MS_BAND_PAD; }

/* Where s falls in the weight table: entry *j and weight *f of entry *j + 1 (once per point: every band
 * and order shares it). */
SEASIM_FN void uw_ms_weight_index(const SEASIM_GLOBAL float* table, real s, int* j, real* f) {
  const real u = clamp(log1p(fmax(s, R(0.0)) * (real)table[0]) * (real)table[1], R(0.0),
                       (real)(UW_MS_WEIGHT_STEPS - 1));
  *j = (int)u < UW_MS_WEIGHT_STEPS - 2 ? (int)u : UW_MS_WEIGHT_STEPS - 2;
  *f = u - (real)*j;
}

/* The glow's section of the table (bands nb, the lamp's orders). */
SEASIM_FN const SEASIM_GLOBAL float* uw_ms_glow_weight_rows(const SEASIM_GLOBAL float* table, int nb, int orders) {
  return table + UW_MS_WEIGHT_HEADER + orders * UW_MS_WEIGHT_STEPS * uw_ms_band_stride(nb);
}

/* `count` weights of band `band` (of nb) at (j, f) into w[0 .. count - 1], from a section of `count`
 * orders (the lamp's: table + UW_MS_WEIGHT_HEADER, count = orders; the glow's: count = orders + 1). */
SEASIM_FN void uw_ms_weights_at(const SEASIM_GLOBAL float* rows, int nb, int band, int count, int j, real f, real* w) {
  const int P = uw_ms_band_stride(nb);
  const SEASIM_GLOBAL float* e = rows + j * P + band;
  for (int n = 0; n < count; ++n, e += UW_MS_WEIGHT_STEPS * P) w[n] = (R(1.0) - f) * (real)e[0] + f * (real)e[P];
}

/* Σ_n W_n geo[n - 1], n = 1..orders, for bands b0 .. b0 + SEASIM_BAND_LANES - 1 in lanes (one band, b0, on
 * the host): the lamp's orders' weights at (j, f) (their section, table + UW_MS_WEIGHT_HEADER) against one
 * point's band-free factors geo (a surface's, uw_ms_surface_geometry, or a view-ray step's); a factor <= 0
 * carries no light and is skipped. uw_ms_surface_sum with uw_ms_weights_at, run in lanes. */
SEASIM_FN realb uw_ms_orders_sum_b(const SEASIM_GLOBAL float* rows, int nb, int b0, int orders, int j, real f,
                                   const real* geo) {
  const int P = uw_ms_band_stride(nb);
  const SEASIM_GLOBAL float* e = rows + j * P;
  realb sum = SPLATB(R(0.0));
  for (int n = 0; n < orders; ++n, e += UW_MS_WEIGHT_STEPS * P)
    if (geo[n] > R(0.0)) sum += ((R(1.0) - f) * LOADB(e, b0) + f * LOADB(e + P, b0)) * geo[n];
  return sum;
}

/* The same for bands b0 .. b0 + SEASIM_BAND_LANES - 1 in lanes (one band, b0, on the host). */
SEASIM_FN void uw_ms_weights_at_b(const SEASIM_GLOBAL float* rows, int nb, int b0, int count, int j, real f, realb* w) {
  const int P = uw_ms_band_stride(nb);
  const SEASIM_GLOBAL float* e = rows + j * P;
  for (int n = 0; n < count; ++n, e += UW_MS_WEIGHT_STEPS * P) w[n] = (R(1.0) - f) * LOADB(e, b0) + f * LOADB(e + P, b0);
}

/* The share of HG(G) in the hemisphere about its own axis: ∫_0^1 2π p_HG(μ) dμ
 * = (1 + G)/(2G) (1 - (1 - G)/sqrt(1 + G²)); 1/2 at G = 0, 1 at G = 1. */
SEASIM_FN real uw_ms_forward_share(real G) {
  /* 1 - (1 - G)/√(1 + G²) = G (1 + G/(√(1 + G²) + 1))/√(1 + G²): no cancellation, no 0/0 at G = 0. */
  const real q = sqrt(R(1.0) + G * G);
  return (R(1.0) + G) * (R(1.0) + G / (q + R(1.0))) / (R(2.0) * q);
}

/* T_view(S)'s terms for one band: terms[k], k = 0..last, the surface's radiance seen through S of water
 * by light scattered k times (the last takes all higher ones with F(g^last)); returns their sum, T_view.
 * e^{-σ_t S} alone when σ_s = 0 (every other term 0); g = 1 -> e^{-σ_a S}. */
SEASIM_FN real uw_ms_view_terms(real sigma_a, real sigma_s, real g, real S, int last, real* terms) {
  const real x = sigma_s * S;
  real term = exp(-(sigma_a + sigma_s) * S); /* k = 0: unscattered */
  terms[0] = term;
  real T = term;
  if (!(x > R(0.0))) {
    for (int k = 1; k <= last; ++k) terms[k] = R(0.0);
    return T;
  }
  real Gk = R(1.0);
  for (int k = 1; k < last; ++k) {
    term *= x / (real)k;
    Gk *= g;
    terms[k] = term * uw_ms_forward_share(Gk);
    T += terms[k];
  }
  Gk *= g;
  terms[last] = exp(-sigma_a * S) * uw_ms_poisson_at_least(last, x) * uw_ms_forward_share(Gk);
  return T + terms[last];
}

/* T_view(S) for one band: the surface's radiance seen through S of water, orders up to `last` (the
 * last takes all higher ones with F(g^last)). e^{-σ_t S} exactly when σ_s = 0 or g = 1 -> e^{-σ_a S}. */
SEASIM_FN real uw_ms_view_transmission(real sigma_a, real sigma_s, real g, real S, int last) {
  real terms[UW_MS_MAX_ORDERS + 1];
  return uw_ms_view_terms(sigma_a, sigma_s, g, S, last, terms);
}

/* uw_ms_poisson_at_least for lanes of x (one band per lane): both of its sums, each lane taking its own; the
 * upward series runs until every lane that sums it has stopped (each stops as the scalar one does). */
SEASIM_FN realb uw_ms_poisson_at_least_b(int n, realb x) {
  const realb zero = SPLATB(R(0.0));
  const realb e = exp(-x);
  const maskb upward = (x > R(0.0)) & (x < (real)(n + 1));
  realb sum = zero;
  if (ANYB(upward)) {
    realb term = e;
    for (int k = 1; k <= n; ++k) term *= x / (real)k;
    maskb active = upward & (term > R(1e-9) * sum);
    for (int k = n; k < n + 60 && ANYB(active); ++k) { /* terms fall at least as x/(n+1) < 1 */
      sum = SELECTB(active, sum + term, sum);
      term *= x / (real)(k + 1);
      active = active & (term > R(1e-9) * sum);
    }
  }
  realb term = e, lower = zero;
  for (int k = 0; k < n; ++k) {
    lower += term;
    term *= x / (real)(k + 1);
  }
  return SELECTB(x > R(0.0), SELECTB(upward, fmin(sum, SPLATB(R(1.0))), fmax(R(1.0) - lower, zero)), zero);
}

/* uw_ms_view_terms for lanes of bands (σ_a, σ_s per lane): terms[k], k = 0..last, per lane, and their sum
 * T_view(S), the same terms added in the same order. */
SEASIM_FN realb uw_ms_view_terms_b(realb sigma_a, realb sigma_s, real g, real S, int last, realb* terms) {
  const realb x = sigma_s * S;
  realb term = exp(-(sigma_a + sigma_s) * S); /* k = 0: unscattered */
  terms[0] = term;
  realb T = term;
  if (!ANYB(x > R(0.0))) { /* every other term 0 */
    for (int k = 1; k <= last; ++k) terms[k] = SPLATB(R(0.0));
    return T;
  }
  real Gk = R(1.0);
  for (int k = 1; k < last; ++k) {
    term *= x / (real)k;
    Gk *= g;
    terms[k] = term * uw_ms_forward_share(Gk);
    T += terms[k];
  }
  Gk *= g;
  terms[last] = exp(-sigma_a * S) * uw_ms_poisson_at_least_b(last, x) * uw_ms_forward_share(Gk);
  return T + terms[last];
}

/* Where cos ψ falls in the table (UW_MS_TABLE entries over ψ, 1° apart): entry *i and weight *f of
 * entry *i + 1. Once per point: every order's row shares it. */
SEASIM_FN void uw_ms_table_index(real cos_psi, int* i, real* f) {
  const real deg = lookup_acos(clamp(cos_psi, R(-1.0), R(1.0))) * (R(180.0) / SEASIM_PI);
  *i = (int)deg < UW_MS_TABLE - 2 ? (int)deg : UW_MS_TABLE - 2;
  *f = clamp(deg - (real)*i, R(0.0), R(1.0));
}

/* P_n from a table row at (i, f), linear in ψ. */
SEASIM_FN real uw_ms_table_lerp(const SEASIM_GLOBAL float* row, int i, real f) {
  return (R(1.0) - f) * (real)row[i] + f * (real)row[i + 1];
}

/* P_n at cos ψ from a table row. */
SEASIM_FN real uw_ms_table_at(const SEASIM_GLOBAL float* row, real cos_psi) {
  int i;
  real f;
  uw_ms_table_index(cos_psi, &i, &f);
  return uw_ms_table_lerp(row, i, f);
}

/* F(G, cos θ_i): the irradiance, per unit fluence, that radiance spread as HG(G) about a direction r̂
 * gives a surface whose normal is θ_i from -r̂ (the light's surfaces, header), exactly:
 *   F = ∫ p_HG(μ; G) A(μ) dω,  A(μ) = (1/2π) ∫ max(μ x + √(1 - μ²) √(1 - x²) cos φ, 0) dφ,  x = cos θ_i,
 * the azimuthal mean of the clamped cosine in closed form (A = μ x where the whole circle faces the
 * surface, 0 where none does, else (a φ₀ + b sin φ₀)/π with a = μ x, b = √(1 - μ²) √(1 - x²), cos φ₀ = -a/b),
 * and μ by n midpoints of HG's inverse CDF (path_tracer.h), so that a lobe as narrow as G -> 1 gives is
 * sampled where its mass is. G = 0: 1/4; G = 1: max(x, 0). Its Legendre series, Σ_l G^l c_l P_l(x) with the
 * clamped cosine's c_0 = 1/4, c_1 = 1/2, c_2 = 5/16, c_3 = 0, c_4 = -3/32, is what the unit test checks it
 * against; the earlier mixture G max(x, 0) + (1 - G)/4 keeps the first two terms and was 9 % high at
 * G = 0.5 on a surface facing the lamp. The host tabulates it per order (uw_ms_irradiance_factor reads the
 * table); G < 0 is taken as 0 (the lamps' waters scatter forward). */
SEASIM_FN real uw_ms_irradiance_exact(real G, real cos_i, int n) {
  const real x = clamp(cos_i, R(-1.0), R(1.0)), sx = sqrt(fmax(R(1.0) - x * x, R(0.0)));
  real sum = R(0.0);
  for (int k = 0; k < n; ++k) {
    const real mu = R(1.0) - pt_hg_one_minus_cos(fmax(G, R(0.0)), ((real)k + R(0.5)) / (real)n);
    const real a = mu * x, b = sqrt(fmax(R(1.0) - mu * mu, R(0.0))) * sx;
    if (a >= b) {
      sum += a;
    } else if (a > -b) {
      const real phi0 = acos(clamp(-a / b, R(-1.0), R(1.0)));
      sum += (a * phi0 + b * sin(phi0)) * (R(1.0) / SEASIM_PI);
    }
  }
  return sum / (real)n;
}

/* The irradiance factor of one order from its row of the lamp's table (UW_MS_ROW floats: the
 * UW_MS_IRRADIANCE entries after the profile, uniform in cos θ_i over [-1, 1]), linear between entries. */
SEASIM_FN real uw_ms_irradiance_factor(const SEASIM_GLOBAL float* row, real cos_i) {
  const SEASIM_GLOBAL float* f = row + UW_MS_TABLE;
  const real u = (clamp(cos_i, R(-1.0), R(1.0)) + R(1.0)) * R(0.5) * (real)(UW_MS_IRRADIANCE - 1);
  const int i = (int)u < UW_MS_IRRADIANCE - 2 ? (int)u : UW_MS_IRRADIANCE - 2;
  const real t = u - (real)i;
  return (R(1.0) - t) * (real)f[i] + t * (real)f[i + 1];
}

/* The quadrature of the view ray o + t d, t in [0, t_end], about the lamp: `steps` midpoints in v,
 * t = a + r sinh v (a, r the closest approach, r >= s_min). Order n's integrand grows as s^{n-2} from the
 * lamp (W_n ∝ (σ_s s)^n), at worst 1/s: dt/s is dv far from the lamp, so v spreads the steps evenly over
 * the scales of s from r to the ray's end, where the angle map (dt/s² = dθ/r) piles them up at r.
 * t_end is capped at t_cap (the caller's few tens of optical depths: nothing beyond). */
typedef struct {
  real a, r, v0, dv;
} UwMsRay;

SEASIM_FN void uw_ms_ray(real3 o, real3 d, real3 lamp, real s_min, real t_end, real t_cap, int steps, UwMsRay* q) {
  real h;
  shafts_closest_approach(o, d, lamp, &q->a, &h);
  q->r = fmax(h, s_min);
  const real t1 = fmin(t_end, t_cap);
  q->v0 = asinh(-q->a / q->r);
  q->dv = fmax(asinh((t1 - q->a) / q->r) - q->v0, R(0.0)) / (real)steps;
}

SEASIM_FN real uw_ms_ray_t(const UwMsRay* q, int j) { return q->a + q->r * sinh(q->v0 + ((real)j + R(0.5)) * q->dv); }

/* The step's dt at ray parameter t: dv dt/dv = dv sqrt(r² + (t - a)²). */
SEASIM_FN real uw_ms_ray_dt(const UwMsRay* q, real t) {
  const real x = t - q->a;
  return q->dv * sqrt(q->r * q->r + x * x);
}

/* dt / max(s, s_min)² at ray parameter t with distance s. */
SEASIM_FN real uw_ms_ray_weight(const UwMsRay* q, real t, real s, real s_min) {
  const real sc = fmax(s, s_min);
  return uw_ms_ray_dt(q, t) / (sc * sc);
}

/* dt / (s² + R²) at ray parameter t: the bottom glow's softened source (radius R). */
SEASIM_FN real uw_ms_glow_ray_weight(const UwMsRay* q, real t, real s, real radius) {
  return uw_ms_ray_dt(q, t) / (s * s + radius * radius);
}

/* The ray's cap: 30 optical depths of the least extinction (e^{-30} = 1e-13), 1e4 m in clear water. */
SEASIM_FN real uw_ms_ray_cap(real sigma_t_min) { return sigma_t_min > R(3e-3) ? R(30.0) / sigma_t_min : R(1e4); }

/* Order 1's phase towards the eye at a point x outside the cone. Light scattered once reaches x from the
 * beam, in the plane of the axis and x, not along the lamp's radial direction (a kernel copy that
 * integrated order 1 exactly over a hard cone reproduced the path tracer where HG(g²) about the radial
 * direction was 13-22 % low at g = 0.9: docs/journal/lamps_orders.md). Taken from the cone's edge line
 * nearest to x: e from the lamp at θc off the axis, in that plane. Light scattered at y = lamp + u e
 * reaches x along ω(δ) = cos δ e + sin δ n (n ⊥ e towards x), δ its deflection; with h = s sin(ψ − θc)
 * x's distance from the line, r = h / sin δ and du = h dδ / sin²δ, the line's light at x per dδ is
 * p_HG(cos δ; g) e^{-c(u + r)} / h, so the phase averaged over it is
 *   D₁ = ∫_{ψ−θc}^{π} p(cos δ) e^{-c(u + r − s)} p(ω(δ) · to_eye) dδ / ∫_{ψ−θc}^{π} p(cos δ) e^{-c(u + r − s)} dδ,
 * p = p_HG(·; g), by UW_MS_EDGE_NODES midpoints quadratic in δ from ψ − θc (the HG peak at the small
 * deflections). c: one extinction for every band (the kernel's least, so the bands share the nodes).
 * Inside the cone, and where x lies on the axis or on the edge line itself (no plane, h = 0), it is
 * HG(g²) about the radial direction, the orders' own rule (header). g = 0 gives 1/4π exactly. */
#define UW_MS_EDGE_NODES 12
SEASIM_FN real uw_ms_order1_phase(real3 x, real3 lamp, real3 axis, real cos_cone, real g, real c, real3 to_eye) {
  const real3 w = x - lamp;
  const real s = length(w);
  const real3 rad = s > R(0.0) ? w * (R(1.0) / s) : axis;
  const real cos_psi = dot(rad, axis);
  const real cos_alpha = dot(rad, to_eye);
  if (!(s > R(0.0)) || cos_psi >= cos_cone) return hg_phase(cos_alpha, g * g);
  real3 perp = rad - cos_psi * axis;
  const real pl = length(perp);
  if (!(pl > R(1e-6))) return hg_phase(cos_alpha, g * g);
  perp = perp * (R(1.0) / pl);
  const real sin_cone = sqrt(fmax(R(1.0) - cos_cone * cos_cone, R(0.0)));
  const real3 e = cos_cone * axis + sin_cone * perp;
  const real ce = clamp(dot(rad, e), R(-1.0), R(1.0));
  real3 n = rad - ce * e;
  const real nl = length(n); /* sin(ψ − θc), from the geometry: acos near 1 loses it under relaxed maths */
  const real d_min = lookup_atan2(nl, ce), h = s * nl, u0 = s * ce;
  if (!(nl > R(1e-6)) || !(h > R(0.0))) return hg_phase(cos_alpha, g * g);
  n = n * (R(1.0) / nl);
  /* The nodes in lanes (band_lanes.h; one at a time on the host), the ones past the last weighted 0. */
  const real e_eye = dot(e, to_eye), n_eye = dot(n, to_eye);
  realb num = SPLATB(R(0.0)), den = SPLATB(R(0.0));
  for (int k0 = 0; k0 < UW_MS_EDGE_NODES; k0 += SEASIM_BAND_LANES) {
    const realb k = lane_offsets() + (real)k0;
    const realb q = (k + R(0.5)) * (R(1.0) / (real)UW_MS_EDGE_NODES);
    const realb delta = d_min + (SEASIM_PI - d_min) * q * q;
    const realb jac = (SEASIM_PI - d_min) * R(2.0) / (real)UW_MS_EDGE_NODES * q;
    const realb cd = cos(delta), sd = fmax(sin(delta), R(1e-6)); /* delta in [0, π] on the nodes */
    const realb r = h / sd, u = fmax(u0 - h * cd / sd, R(0.0));
    const realb wgt = SELECTB(k < SPLATB((real)UW_MS_EDGE_NODES),
                              hg_phase_b(cd, g) * exp(-c * fmax(u + r - s, R(0.0))) * jac, SPLATB(R(0.0)));
    num += wgt * hg_phase_b(cd * e_eye + sd * n_eye, g);
    den += wgt;
  }
  const real num_sum = SUMB(num), den_sum = SUMB(den);
  return den_sum > R(0.0) ? num_sum / den_sum : hg_phase(cos_alpha, g * g);
}

/* L_ms per unit I(λ) for one band along a view ray (no shadows): `table` holds the lamp's P_1..P_orders
 * rows; orders <= UW_MS_MAX_ORDERS; t_cap the ray's cap (uw_ms_ray_cap of the least σ_t of the bands
 * that share the steps); order 1's phase from uw_ms_order1_phase with the cone cos_cone and the
 * extinction c_dir (the kernel's least σ_t too). The kernel runs the same steps, their geometry first and
 * then the bands in lanes. */
SEASIM_FN real uw_ms_inscatter(real3 o, real3 d, real3 lamp, real3 axis, real cos_cone, real s_min, real t_end, real t_cap,
                               real sigma_a, real sigma_s, real g, real kappa, real c_dir, const SEASIM_GLOBAL float* table,
                               int orders, int steps) {
  UwMsRay q;
  uw_ms_ray(o, d, lamp, s_min, t_end, t_cap, steps, &q);
  if (!(q.dv > R(0.0)) || !(sigma_s > R(0.0))) return R(0.0);
  real acc = R(0.0);
  for (int j = 0; j < steps; ++j) {
    const real t = uw_ms_ray_t(&q, j);
    real s, cos_alpha;
    uw_lamp_at(o, d, lamp, t, &s, &cos_alpha);
    const real cos_psi = s > R(0.0) ? dot(o + t * d - lamp, axis) / s : R(1.0);
    real sum = R(0.0), gn1 = g;
    for (int n = 1; n <= orders; ++n) {
      gn1 *= g; /* g^{n+1} */
      const real P = uw_ms_table_at(table + (n - 1) * UW_MS_ROW, cos_psi);
      if (P <= R(0.0)) continue;
      const real phase = n == 1 ? uw_ms_order1_phase(o + t * d, lamp, axis, cos_cone, g, c_dir, -d) : hg_phase(cos_alpha, gn1);
      sum += uw_ms_weight(sigma_a, sigma_s, s, uw_ms_stretch(g, n, kappa), n, orders) * P * phase;
    }
    acc += sigma_s * exp(-(sigma_a + sigma_s) * t) * sum * uw_ms_ray_weight(&q, t, s, s_min);
  }
  return acc;
}

/* The band-independent part of the irradiance orders n >= 1 give a surface point p of normal n_s, per
 * unit I(λ), divided by π: geo[n - 1] = P_n(ψ) (g^n max(cos θ_i, 0) + (1 - g^n)/4) / (π max(s, s_min)²)
 * (0 where the profile is). Returns s = |p - lamp|; at the lamp (s = 0) nothing is written. */
SEASIM_FN real uw_ms_surface_geometry(real3 p, real3 n_s, real3 lamp, real3 axis, real s_min,
                                      const SEASIM_GLOBAL float* table, int orders, real* geo) {
  const real3 w = p - lamp;
  const real s = length(w);
  if (!(s > R(0.0))) return R(0.0);
  const real cos_psi = dot(w, axis) / s;
  const real cos_i = -dot(w, n_s) / s; /* the lamp's ray arrives along +w; the surface faces -w when lit */
  const real sc = fmax(s, s_min), k = R(1.0) / (SEASIM_PI * sc * sc);
  int i;
  real f;
  uw_ms_table_index(cos_psi, &i, &f);
  for (int n = 1; n <= orders; ++n) {
    const SEASIM_GLOBAL float* row = table + (n - 1) * UW_MS_ROW;
    const real P = uw_ms_table_lerp(row, i, f);
    geo[n - 1] = P > R(0.0) ? P * uw_ms_irradiance_factor(row, cos_i) * k : R(0.0);
  }
  return s;
}

/* One band's orders summed over that geometry with its weights at s, wn[n - 1] = W_n(s). */
SEASIM_FN real uw_ms_surface_sum(const real* geo, const real* wn, int orders) {
  real sum = R(0.0);
  for (int n = 1; n <= orders; ++n) sum += wn[n - 1] * geo[n - 1];
  return sum;
}

/* The irradiance orders n >= 1 give a surface point p of normal n_s, per unit I(λ), divided by π (so
 * times the albedo it is the Lambertian radiance leaving p; T_view not applied), given the orders'
 * weights at s = |p - lamp|, wn[n - 1] = W_n(s) (exact: uw_ms_surface; the kernel: its table). */
SEASIM_FN real uw_ms_surface_weighted(real3 p, real3 n_s, real3 lamp, real3 axis, real s_min,
                                      const SEASIM_GLOBAL float* table, int orders, const real* wn) {
  real geo[UW_MS_MAX_ORDERS];
  if (!(uw_ms_surface_geometry(p, n_s, lamp, axis, s_min, table, orders, geo) > R(0.0))) return R(0.0);
  return uw_ms_surface_sum(geo, wn, orders);
}

/* The same with every weight from uw_ms_weight. */
SEASIM_FN real uw_ms_surface(real3 p, real3 n_s, real3 lamp, real3 axis, real s_min, real sigma_a, real sigma_s, real g,
                             real kappa, const SEASIM_GLOBAL float* table, int orders) {
  const real s = length(p - lamp);
  if (!(s > R(0.0)) || !(sigma_s > R(0.0))) return R(0.0);
  real wn[UW_MS_MAX_ORDERS];
  for (int n = 1; n <= orders; ++n) wn[n - 1] = uw_ms_weight(sigma_a, sigma_s, s, uw_ms_stretch(g, n, kappa), n, orders);
  return uw_ms_surface_weighted(p, n_s, lamp, axis, s_min, table, orders, wn);
}

/* The glow's phase function: HG(G) without its forward peak (delta-M: the share G² scatters straight
 * on, the rest as HG(G/(1 + G))). Light from the bottom scattered through small angles is already in
 * the surface's T_view, which sees the bottom through the water with its forward-scattered light. */
SEASIM_FN real uw_ms_glow_phase(real cos_alpha, real G) {
  return (R(1.0) - G * G) * hg_phase(cos_alpha, G / (R(1.0) + G));
}

/* The glow's quadrature steps along a view ray: half the lamp's, at least 12 (at most the lamp's). Its
 * source is spread over the lit patch and its phase has no forward peak, so its integrand is smoother
 * than the lamp's; 12 steps are within 1.6 % of 256 on a ray aimed at the patch's centre, 8 were 15 %
 * off there (tests/unit/underwater_lamps_glow_test.cpp). */
SEASIM_FN int uw_ms_glow_steps(int lamp_steps) {
  const int steps = lamp_steps / 2 > 12 ? lamp_steps / 2 : 12;
  return steps < lamp_steps ? steps : lamp_steps;
}

/* The glow's weights of orders 0..orders at distance s for one band, paths as long as s (no stretch:
 * the glow's source is already diffuse): w_0 = e^{-σ_t s} (unscattered), w_n = e^{-σ_t s} (σ_s s)^n / n!,
 * the last order all higher ones, e^{-σ_a s} P(N >= orders) (the Poisson tail summed where it is small:
 * 1 - the lower terms left rounding noise of ~1e-7 in float where the tail is 1e-30). The kernel reads
 * them from its table (UW_MS_WEIGHT_*). */
SEASIM_FN void uw_ms_glow_weights(real sigma_a, real sigma_s, real s, int orders, real* w) {
  const real x = sigma_s * s, keep = exp(-sigma_a * s);
  real term = keep * exp(-x);
  for (int n = 0; n < orders; ++n) {
    w[n] = term;
    term *= x / (real)(n + 1); /* now e^{-σ_t s} x^{n+1}/(n+1)! */
  }
  w[orders] = keep * uw_ms_poisson_at_least(orders, x);
}

/* The bottom's glow along a view ray o + t d, t in [0, t_end], per unit J for one band: the lit patch's
 * light (a Lambertian source at c of normal up, radius R > 0) scattered towards the eye, orders 0..orders
 * of its spread (uw_ms_glow_weights, phases uw_ms_glow_phase(g^{n+1})); *order0 (may be 0) receives
 * order 0's part alone (light scattered once in the water). */
SEASIM_FN real uw_ms_glow_inscatter(real3 o, real3 d, real3 c, real3 up, real radius, real t_end, real t_cap, real sigma_a,
                                    real sigma_s, real g, int orders, int steps, real* order0) {
  UwMsRay q;
  uw_ms_ray(o, d, c, radius, t_end, t_cap, steps, &q);
  real acc = R(0.0), acc0 = R(0.0);
  if (q.dv > R(0.0) && sigma_s > R(0.0)) {
    real wn[UW_MS_MAX_ORDERS + 1];
    for (int j = 0; j < steps; ++j) {
      const real t = uw_ms_ray_t(&q, j);
      real s, cos_alpha;
      uw_lamp_at(o, d, c, t, &s, &cos_alpha);
      const real cos_psi = s > R(0.0) ? dot(o + t * d - c, up) / s : R(0.0);
      if (!(cos_psi > R(0.0))) continue;
      uw_ms_glow_weights(sigma_a, sigma_s, s, orders, wn);
      const real first = wn[0] * uw_ms_glow_phase(cos_alpha, g);
      real sum = first, gn1 = g;
      for (int n = 1; n <= orders; ++n) {
        gn1 *= g; /* g^{n+1} */
        sum += wn[n] * uw_ms_glow_phase(cos_alpha, gn1);
      }
      const real w = sigma_s * exp(-(sigma_a + sigma_s) * t) * cos_psi * uw_ms_glow_ray_weight(&q, t, s, radius);
      acc += w * sum;
      acc0 += w * first;
    }
  }
  if (order0) *order0 = acc0;
  return acc;
}

/* The bottom's glow on a surface point p of normal n_s, per unit J, divided by π (times the surface's
 * albedo: its Lambertian radiance), given the glow's weights at s = |p - c|, wn[0..orders] (exact:
 * uw_ms_glow_surface; the kernel: its table) and the lamp's table (its orders' irradiance factors,
 * uw_ms_irradiance_factor); *order0 (may be 0) receives the unscattered part alone. */
SEASIM_FN real uw_ms_glow_surface_weighted(real3 p, real3 n_s, real3 c, real3 up, real radius,
                                           const SEASIM_GLOBAL float* table, int orders, const real* wn, real* order0) {
  const real3 w = p - c;
  const real s = length(w);
  real sum = R(0.0), first = R(0.0);
  /* Points on the bottom's own plane (cos ψ at rounding level) get nothing: the source lies in it. */
  if (s > R(0.0) && dot(w, up) > R(1e-4) * s) {
    const real cos_psi = dot(w, up) / s, cos_i = -dot(w, n_s) / s;
    const real k = cos_psi / (SEASIM_PI * (s * s + radius * radius));
    first = k * wn[0] * fmax(cos_i, R(0.0));
    sum = first;
    for (int n = 1; n <= orders; ++n) sum += k * wn[n] * uw_ms_irradiance_factor(table + (n - 1) * UW_MS_ROW, cos_i);
  }
  if (order0) *order0 = first;
  return sum;
}

/* The same with the weights from uw_ms_glow_weights. */
SEASIM_FN real uw_ms_glow_surface(real3 p, real3 n_s, real3 c, real3 up, real radius, real sigma_a, real sigma_s,
                                  const SEASIM_GLOBAL float* table, int orders, real* order0) {
  real wn[UW_MS_MAX_ORDERS + 1];
  uw_ms_glow_weights(sigma_a, sigma_s, length(p - c), orders, wn);
  return uw_ms_glow_surface_weighted(p, n_s, c, up, radius, table, orders, wn, order0);
}

/* E₂(x) = ∫_1^∞ e^{-x t}/t² dt = ∫_0^1 e^{-x/μ} dμ (A&S 5.1.4), x >= 0; E₂(0) = 1. From E₁ by
 * E₂ = e^{-x} − x E₁ (A&S 5.1.14): for x < 1, E₁ = −ln x + A&S 5.1.53's polynomial (|ε| < 2e-7); for
 * x >= 1, x e^x E₁ = A&S 5.1.56's rational (|ε| < 2e-8), so E₂ = e^{-x} (den − num)/den with den − num's
 * coefficients b_k − a_k taken exactly (no cancellation of 1 − x e^x E₁ at large x), written in 1/x so
 * that nothing overflows. */
SEASIM_FN real uw_ms_expint2(real x) {
  if (!(x > R(0.0))) return R(1.0);
  if (x < R(1.0)) {
    const real e1 = -log(x) + (R(-0.57721566) +
                               x * (R(0.99999193) + x * (R(-0.24991055) + x * (R(0.05519968) + x * (R(-0.00976004) + x * R(0.00107857))))));
    return exp(-x) - x * e1;
  }
  const real y = R(1.0) / x;
  const real num = R(0.9999936053) + y * (R(7.5739391756) + y * (R(12.4648921902) + y * R(3.6907231885)));
  const real den = R(1.0) + y * (R(9.5733223454) + y * (R(25.6329561486) + y * (R(21.0996530827) + y * R(3.9584969228))));
  return exp(-x) * y * num / den;
}

/* The bottom's halo seen from the water above it. The orders' light lands on the bottom well beyond the
 * lit patch; that sand sends it back up, and the water above it scatters it towards the eye. Lumped
 * into the glow's one source at the patch's centre, it came from metres away (1/s², e^{-σ_a s}):
 * rov_lights' far water above the sand was 6.5 times too dark (docs/journal/lamps_orders.md). So the
 * glow's source is the patch's direct light alone, and the halo's light is taken where it is: the water
 * at x, height z over the bottom, sees the bottom as a uniform Lambertian plane of its foot f's radiance
 * ρ Ê(f) (per unit I; Ê = uw_ms_surface's E/π, orders n >= 1), whose light reaches x as the glow's
 * does, in orders along straight paths (uw_ms_glow_weights) scattered towards the eye by the glow's
 * phase (uw_ms_glow_phase: HG(g^{n+1}) without its forward peak). Over the plane, with μ = z/s the
 * cosine of the light's path to the vertical and φ its azimuth (dA cos θ/s² = dμ dφ):
 *   F(z, μ_e) = σ_s ∫_0^1 dμ Σ_{n>=0} w_n(z/μ) ∫_0^{2π} p_glow(cos α; g^{n+1}) dφ,
 *   cos α = μ μ_e + √(1 − μ²) √(1 − μ_e²) cos φ   (μ_e: the vertical cosine of the light's way to the eye),
 *   L_halo = I ∫_0^S e^{-σ_t t} ρ Ê(f_t) F(z_t, μ_e) dt.
 * No knob: the plane shares the glow's model, nothing fitted. F is finite at z = 0 (w_0 = 1 there) and
 * falls as the orders' weights far above the bottom. With g = 0 every phase is 1/(4π) and the orders'
 * weights sum to e^{-σ_a s}, so F = σ_s E₂(σ_a z)/2 (A&S 5.1.4): the unit test's closed form. */
#define UW_MS_HALO_QUAD_MU 64  /* midpoints in μ over [0, 1] */
#define UW_MS_HALO_QUAD_PHI 32 /* midpoints in φ over [0, π] (the integrand is even in φ) */

/* ∫_0^{2π} p_glow(cos α; G) dφ at μ, μ_e. G ≤ 1 puts the glow's HG at G/(1 + G) ≤ 1/2: smooth in φ. */
SEASIM_FN real uw_ms_halo_azimuth(real mu, real mu_e, real G) {
  const real ss = sqrt(fmax(R(1.0) - mu * mu, R(0.0)) * fmax(R(1.0) - mu_e * mu_e, R(0.0)));
  const real dphi = SEASIM_PI / (real)UW_MS_HALO_QUAD_PHI;
  real sum = R(0.0);
  for (int k = 0; k < UW_MS_HALO_QUAD_PHI; ++k)
    sum += uw_ms_glow_phase(clamp(mu * mu_e + ss * cos(((real)k + R(0.5)) * dphi), R(-1.0), R(1.0)), G);
  return R(2.0) * dphi * sum;
}

/* Every μ midpoint's azimuthal phase integrals at μ_e, az[k (orders + 1) + n] for order n's G = g^{n+1}
 * (they do not depend on the band: done once per direction). */
SEASIM_FN void uw_ms_halo_azimuths(real mu_e, real g, int orders, real* az) {
  for (int k = 0; k < UW_MS_HALO_QUAD_MU; ++k) {
    const real mu = ((real)k + R(0.5)) / (real)UW_MS_HALO_QUAD_MU;
    real G = g;
    for (int n = 0; n <= orders; ++n, G *= g) az[k * (orders + 1) + n] = uw_ms_halo_azimuth(mu, mu_e, G);
  }
}

/* F(z, μ_e) of one band from uw_ms_halo_azimuths' az. */
SEASIM_FN real uw_ms_halo_plane_from(real z, real sigma_a, real sigma_s, int orders, const real* az) {
  if (!(sigma_s > R(0.0))) return R(0.0);
  real w[UW_MS_MAX_ORDERS + 1];
  const real dmu = R(1.0) / (real)UW_MS_HALO_QUAD_MU;
  real sum = R(0.0);
  for (int k = 0; k < UW_MS_HALO_QUAD_MU; ++k) {
    const real mu = ((real)k + R(0.5)) * dmu;
    uw_ms_glow_weights(sigma_a, sigma_s, fmax(z, R(0.0)) / mu, orders, w);
    for (int n = 0; n <= orders; ++n) sum += w[n] * az[k * (orders + 1) + n];
  }
  return sigma_s * dmu * sum;
}

/* L_halo per unit I(λ) for one band (the bottom at y = -depth, albedo ρ), from F evaluated exactly at
 * every step: the double reference of the kernel's lamp_halo_ray, which reads F from its table and takes
 * the same steps (t = a + r sinh v about the lamp, the glow's count, uw_ms_ray). */
SEASIM_FN real uw_ms_halo_inscatter(real3 o, real3 d, real depth, real albedo, real3 lamp, real3 axis, real s_min, real t_end,
                                    real t_cap, real sigma_a, real sigma_s, real g, real kappa,
                                    const SEASIM_GLOBAL float* table, int orders, int steps) {
  if (!(depth > R(0.0)) || !(sigma_s > R(0.0)) || !(albedo > R(0.0))) return R(0.0);
  UwMsRay q;
  uw_ms_ray(o, d, MAKE_REAL3(lamp.x, -depth, lamp.z), s_min, t_end, t_cap, steps, &q);
  if (!(q.dv > R(0.0))) return R(0.0);
  real az[UW_MS_HALO_QUAD_MU * (UW_MS_MAX_ORDERS + 1)];
  uw_ms_halo_azimuths(-d.y, g, orders, az);
  const real3 up = MAKE_REAL3(0.0, 1.0, 0.0);
  real acc = R(0.0);
  for (int j = 0; j < steps; ++j) {
    const real t = uw_ms_ray_t(&q, j);
    const real3 x = o + t * d;
    const real z = x.y + depth;
    if (!(z >= R(0.0))) continue;
    const real dt = uw_ms_ray_dt(&q, t);
    const real E = uw_ms_surface(MAKE_REAL3(x.x, -depth, x.z), up, lamp, axis, s_min, sigma_a, sigma_s, g, kappa, table, orders);
    acc += exp(-(sigma_a + sigma_s) * t) * dt * E * uw_ms_halo_plane_from(z, sigma_a, sigma_s, orders, az);
  }
  return albedo * acc;
}

/* The kernel's table of F: after the glow's weights in the orders' weight table (UW_MS_WEIGHT_*),
 * UW_MS_HALO_DIRS rows over μ_e in [-1, 1] (uniform), each UW_MS_HALO_Z heights uniform in
 * u = ln(1 + z/s0) over the weights' own range (s0 and the range from the table's header); row m, height
 * j, band i at (m UW_MS_HALO_Z + j) P + i, the bands fastest as in the weights. F is smooth in both: a
 * height step is ~2 % of z far up, ~s0/20 near the bottom. */
#define UW_MS_HALO_DIRS 33
#define UW_MS_HALO_Z 256

SEASIM_FN const SEASIM_GLOBAL float* uw_ms_halo_rows(const SEASIM_GLOBAL float* table, int nb, int orders) {
  return uw_ms_glow_weight_rows(table, nb, orders) + (orders + 1) * UW_MS_WEIGHT_STEPS * uw_ms_band_stride(nb);
}

/* The row of direction μ_e: index *m and weight *f of row *m + 1 (once per view ray). */
SEASIM_FN void uw_ms_halo_dir_index(real mu_e, int* m, real* f) {
  const real u = clamp((mu_e + R(1.0)) * R(0.5) * (real)(UW_MS_HALO_DIRS - 1), R(0.0), (real)(UW_MS_HALO_DIRS - 1));
  *m = (int)u < UW_MS_HALO_DIRS - 2 ? (int)u : UW_MS_HALO_DIRS - 2;
  *f = u - (real)*m;
}

/* The entry of height z: index *j and weight *f of entry *j + 1 (the weights' u, scaled to UW_MS_HALO_Z). */
SEASIM_FN void uw_ms_halo_z_index(const SEASIM_GLOBAL float* table, real z, int* j, real* f) {
  const real per_u = (real)table[1] * (real)(UW_MS_HALO_Z - 1) / (real)(UW_MS_WEIGHT_STEPS - 1);
  const real u = clamp(log1p(fmax(z, R(0.0)) * (real)table[0]) * per_u, R(0.0), (real)(UW_MS_HALO_Z - 1));
  *j = (int)u < UW_MS_HALO_Z - 2 ? (int)u : UW_MS_HALO_Z - 2;
  *f = u - (real)*j;
}

/* F of bands b0 .. b0 + SEASIM_BAND_LANES - 1 (of nb) from the table, bilinear, in lanes (one band, b0, on
 * the host). */
SEASIM_FN realb uw_ms_halo_at_b(const SEASIM_GLOBAL float* rows, int nb, int b0, int m, real fm, int j, real fz) {
  const int P = uw_ms_band_stride(nb);
  const SEASIM_GLOBAL float* r0 = rows + (m * UW_MS_HALO_Z + j) * P;
  const SEASIM_GLOBAL float* r1 = r0 + UW_MS_HALO_Z * P;
  const realb a = (R(1.0) - fz) * LOADB(r0, b0) + fz * LOADB(r0 + P, b0);
  const realb b = (R(1.0) - fz) * LOADB(r1, b0) + fz * LOADB(r1 + P, b0);
  return (R(1.0) - fm) * a + fm * b;
}

/* The lit bottom blurred on its way to the eye. T_view's k-th term sees the surface through light
 * scattered k times; by reciprocity with the lamp's own spread, where that light left the bottom, as the
 * eye sees it, spreads as HG(h_k) about the view ray, h_k = uw_ms_spread(g, k, β). So the k-th term
 * takes the bottom's direct lamp light averaged over that spread instead of its value at the ray's end:
 * beside a lit patch the halo, on it a little less. UW_MS_BLUR_U × UW_MS_BLUR_PHI directions (midpoints
 * of HG's inverse CDF and of the azimuth) are cast to the bottom plane; the average is of the light's
 * geometry (profile cos θ_i / (π s²), no shadows) with the mean lamp distance s̄ it was weighted at, so a
 * band's attenuation is one exp, e^{-σ_t s̄}. Directions that miss the bottom bring nothing. */
#define UW_MS_BLUR_U 4
#define UW_MS_BLUR_PHI 6
/* The spread's β for the eye: the small-angle value 1/3 (deflections spread uniformly along the path
 * move the apparent origin by a third of their mean-square angle), not the lamp's fitted 0.8. On the
 * lamps' fifteen cases the blur with 0.8 overshot beside the lit patch (outside the beam 1 m over the
 * bottom up to 1.35): mean |ratio - 1| 0.084 against 0.073 with 1/3 (docs/journal/lamps_orders.md). */
#define UW_MS_VIEW_BETA (1.0f / 3.0f)

typedef struct {
  real geometry; /* mean of profile cos θ_i / (π max(s, s_min)²) over the spread */
  real s_mean;   /* its weighted mean distance from the lamp */
} UwMsBlur;

SEASIM_FN UwMsBlur uw_ms_blurred_bottom(real3 o, real3 d, real depth, real3 lamp, real3 axis, real cos_cone, real cos_inner,
                                       real s_min, real h) {
  /* Not pt_basis: its frame turns the 24 directions' azimuths, and this coarse a set then misses a 10°
   * patch beside the ray that the frame below sees (tests/unit/underwater_lamps_glow_test.cpp). */
  const real3 helper = fabs(d.y) < R(0.9) ? MAKE_REAL3(0.0, 1.0, 0.0) : MAKE_REAL3(1.0, 0.0, 0.0);
  const real3 e1 = normalize(cross(helper, d));
  const real3 e2 = cross(d, e1);
  const real3 up = MAKE_REAL3(0.0, 1.0, 0.0);
  real sum = R(0.0), sum_s = R(0.0);
  /* The azimuths' midpoints by rotation: cos and sin once per call, not per direction. */
  const real step = (R(2.0) * SEASIM_PI) / (real)UW_MS_BLUR_PHI;
  const real c_step = cos(step), s_step = sin(step), c0 = cos(R(0.5) * step), s0 = sin(R(0.5) * step);
  for (int iu = 0; iu < UW_MS_BLUR_U; ++iu) {
    const real omc = pt_hg_one_minus_cos(fmax(h, R(0.0)), ((real)iu + R(0.5)) / (real)UW_MS_BLUR_U);
    const real cb = R(1.0) - omc, sb = sqrt(fmax(omc * (R(2.0) - omc), R(0.0)));
    real cp = c0, sp = s0;
    for (int ip = 0; ip < UW_MS_BLUR_PHI; ++ip) {
      const real3 w = cb * d + (sb * cp) * e1 + (sb * sp) * e2;
      const real next_c = cp * c_step - sp * s_step;
      sp = sp * c_step + cp * s_step;
      cp = next_c;
      if (!(w.y < R(0.0))) continue;
      const real t = (-depth - o.y) / w.y;
      if (!(t > R(0.0))) continue;
      const real3 p = o + t * w;
      const real geo = uw_lamp_surface(p, up, R(0.0), lamp, axis, cos_cone, cos_inner, s_min, R(0.0), R(1.0));
      if (!(geo > R(0.0))) continue;
      sum += geo;
      sum_s += geo * length(p - lamp);
    }
  }
  UwMsBlur b;
  b.geometry = sum / (real)(UW_MS_BLUR_U * UW_MS_BLUR_PHI);
  b.s_mean = sum > R(0.0) ? sum_s / sum : R(0.0);
  return b;
}
