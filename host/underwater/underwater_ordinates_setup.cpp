#include "underwater/underwater_ordinates_setup.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

#include "math/kernel_math.h"
#include "underwater/forward_peak.h"

namespace seasim {

static_assert(sizeof(UwiBand) == (18 + (UWI_SOURCE_NODES + UWI_TILT_NODES) * UWI_SOURCE_TERMS + UWI_TILT_NODES * 3 + 2 +
                                   UWI_AUREOLE_NODES + UWI_SOURCE_NODES * 6 + 2) * 4,
              "UwiBand layout changed: update underwater_ordinates_params.h users");
static_assert(offsetof(UwiBand, d1) == 20 && offsetof(UwiBand, up) == 40 && offsetof(UwiBand, g_flux) == 44 &&
              offsetof(UwiBand, o1) == 48 && offsetof(UwiBand, op) == 56 && offsetof(UwiBand, h1) == 60 &&
              offsetof(UwiBand, hp) == 68 && offsetof(UwiBand, src) == 72 &&
              offsetof(UwiBand, tilt) == 72 + UWI_SOURCE_NODES * UWI_SOURCE_TERMS * 4 &&
              offsetof(UwiBand, tilt_bottom) == offsetof(UwiBand, tilt) + UWI_TILT_NODES * UWI_SOURCE_TERMS * 4 &&
              offsetof(UwiBand, p_clip) == offsetof(UwiBand, tilt_bottom) + UWI_TILT_NODES * 3 * 4 &&
              offsetof(UwiBand, aureole) == offsetof(UwiBand, p_clip) + 2 * 4 &&
              offsetof(UwiBand, aureole_modes) == offsetof(UwiBand, aureole) + UWI_AUREOLE_NODES * 4 &&
              offsetof(UwiBand, src_sand) == offsetof(UwiBand, aureole_modes) + UWI_SOURCE_NODES * 3 * 4 &&
              offsetof(UwiBand, sand_beam) == offsetof(UwiBand, src_sand) + UWI_SOURCE_NODES * 3 * 4 &&
              offsetof(UwiBand, sand_diffuse) == offsetof(UwiBand, sand_beam) + 4);

double internalDiffuseReflectance(double ior) {
  // Midpoint rule in μ: F jumps to 1 at the critical angle, so a fine uniform grid (error ~1e-5).
  const int n = 4000;
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    const double mu = (i + 0.5) / n;
    sum += kmath_d::fresnel_reflectance(mu, ior, 1.0) * mu;
  }
  return 2.0 * sum / n;
}

DiffuseMeanCosines diffuseMeanCosines(double g) {
  // Fitted offline to the path tracer (tests/perf/underwater_regions_fit.sh scans them on the training
  // grid of tests/perf/underwater_regions.sh; results/BENCHMARKS.md reports them on a held-out grid):
  // the up stream's 0.52 at every g (the quadrature's 1/√3 = 0.577 left the water looking up too dark
  // at g <= 0.5: the upwelling light lies nearer the horizon than its ring); the down stream's 1/√3 up
  // to g = 0.5, rising linearly to 0.72 at g = 0.9 and held there (forward scattering keeps the diffuse
  // downwelling light nearer the sun's direction, so less of it per unit flux reaches a level view).
  const double mu_quadrature = 1.0 / std::sqrt(3.0);
  const double t = std::clamp((g - 0.5) / 0.4, 0.0, 1.0);
  const double down = mu_quadrature + t * (0.72 - mu_quadrature);
  return {down, 0.52, down, 0.52};
}

TwoStreamClosure twoStreamClosure() { return TwoStreamClosure::Quadrature; }

double isotropicAsymptoticKappa(double omega) {
  if (!(omega > 0)) return 1.0;
  if (omega >= 1) return 0.0;
  // f(κ) = omega atanh(κ) - κ is < 0 just above 0 (slope omega - 1) and -> +inf at 1, convex: one root.
  // Bisection in double; 200 halvings reach the double spacing near both ends.
  double lo = 0, hi = 1;
  for (int i = 0; i < 200 && hi - lo > 0; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid == lo || mid == hi) break;
    (omega * std::atanh(mid) - mid < 0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double asymptoticStreamCosine(double omega) {
  // Near omega = 1, κ = √(3 (1 - omega)) (1 + O(1 - omega)): the ratio -> 1/√3; within 1e-6 of it the
  // limit is taken (error O(1e-6)) rather than the 0/0 of two vanishing numbers.
  if (omega >= 1 - 1e-6) return 1.0 / std::sqrt(3.0);
  if (!(omega > 0)) return 1.0;
  return std::min(std::sqrt(1 - omega) / isotropicAsymptoticKappa(omega), 1.0);
}

double asymptoticDiffuseK(double a, double b_back) {
  const double c_s = a + 2 * b_back;
  if (!(c_s > 0) || !(a > 0)) return 0.0;
  return c_s * isotropicAsymptoticKappa(2 * b_back / c_s);
}

double depthMeanDiffuseK(double k_two_stream, double k_inf, double depth, double asymptotic_share) {
  const double w = asymptotic_share;
  if (!(depth > 0) || !(w > 0) || !(k_two_stream > k_inf)) return k_two_stream;
  if (w >= 1) return k_inf;
  // ln(w + (1 - w) e^{-q}) = log1p((1 - w) expm1(-q)): no cancellation as D -> 0 (the slope tends to
  // k), and ln w (finite) once e^{-q} underflows.
  const double q = (k_two_stream - k_inf) * depth / (1 - w);
  return k_inf - std::log1p((1 - w) * std::expm1(-q)) / depth;
}

// A table fitted per g of the training grid (tests/perf/underwater_regions.sh: g = 0, 0.5, 0.9, 0.95),
// linear in g between its points and held outside them.
static double interpolateOnTrainingG(const std::array<double, 4>& values, double g) {
  static constexpr std::array<double, 4> kG = {0.0, 0.5, 0.9, 0.95};
  if (!(g > kG[0])) return values[0];
  for (size_t i = 1; i < kG.size(); ++i)
    if (g <= kG[i]) return values[i - 1] + (g - kG[i - 1]) / (kG[i] - kG[i - 1]) * (values[i] - values[i - 1]);
  return values.back();
}

double diffuseAsymptoticShare(double g) {
  // Fitted offline to the path tracer (tests/perf/underwater_regions_fit_depth.sh scans w = 0.1–0.8 on
  // the training grid of tests/perf/underwater_regions.sh; docs/journal/underwater_regions_2_*.md reports them
  // and the held-out grid): per g of the grid the w with the most region cases within 5 % (ties: the
  // smaller w), linear in g between, held outside [0, 0.95]. Not monotone in g: at g = 0.5 w >= 0.3
  // over-brightens the coastal water's level views (0.4:1.2, 3.8 m); at g = 0.95 the views looking up
  // want 0.7 where the level views at g = 0.9 want 0.4.
  return interpolateOnTrainingG({0.3, 0.2, 0.4, 0.7}, g);
}

double diffuseFluxScale(double g) {
  // Fitted offline to the path tracer (`--model-set underwater.flux_scale=s` on the
  // training grid of tests/perf/underwater_regions.sh; results/BENCHMARKS.md reports it and the held-out
  // grid): per g of the grid the s with the most region cases within 5 %, linear in g between, held
  // outside [0, 0.95]. At g = 0 g' = 0 and s has no effect. At g = 0.95, 1.0–1.3 tie (25/27, the same
  // RMS): the value nearest g = 0.9's is kept, so the table does not drop where the grid has no g.
  // A larger s brightens the views looking up in turbid water at g = 0.9 (0.88–0.90 -> 0.96–0.98) and
  // darkens the long level rays looking down (clear water 1.14 -> 1.03); above 1.6 the level views over
  // shallow bottoms looking up leave the 5 % band.
  return interpolateOnTrainingG({1.0, 1.3, 1.6, 1.3}, g);
}

double diffuseViewDepth(const UwParams& params) {
  const double depth = std::max(-static_cast<double>(params.cam_pos[1]), 0.0);
  return params.bottom_depth > 0 ? std::min(depth, static_cast<double>(params.bottom_depth)) : depth;
}

DeltaMMedium ordinatesDeltaM(double a, double b, double g, int power) {
  const double gp = std::max(g, 0.0);
  const double f = std::pow(gp, power);
  DeltaMMedium m;
  m.b_dm = b * (1 - f);
  m.c_dm = a + m.b_dm;
  m.g_dm = g < 0 ? g : power == 2 ? g / (1 + g) : (g - f) / (1 - f);
  return m;
}

UwiBand uwiBandOfMedium(const DeltaMMedium& medium, double flux_scale) {
  UwiBand o{};
  o.c_dm = static_cast<float>(medium.c_dm);
  o.b_dm = static_cast<float>(medium.b_dm);
  o.g_dm = static_cast<float>(medium.g_dm);
  o.g_flux = static_cast<float>(flux_scale * medium.g_dm);
  return o;
}

UwiBand makeUwiBand(const UwBand& band, double g, double mu_w, double bottom_depth, double ior) {
  return makeUwiBand(band, g, mu_w, bottom_depth, ior, diffuseMeanCosines(g));
}

UwiBand makeUwiBand(const UwBand& band, double g, double mu_w, double bottom_depth, double ior,
                    DiffuseMeanCosines mean, TwoStreamClosure closure, DiffuseDepth view, const ForwardPeak* peak) {
  const double a = band.a, b = band.b;
  const DeltaMMedium medium = ordinatesDeltaM(a, b, g);
  const double b_dm = medium.b_dm, c_dm = medium.c_dm, g_dm = medium.g_dm;
  const double mu0 = std::clamp(mu_w, 1e-3, 1.0);
  UwiBand o = uwiBandOfMedium(medium, view.flux_scale);
  if (!(c_dm > 0)) return o;  // no medium: no diffuse source, nothing to attenuate

  // Two-stream (plane irradiances, depth y down; Meador & Weaver 1980's form in metres):
  //   dE_u/dy = α1 E_u - α2 E_d - s_up e_beam0 e^{-m y},   dE_d/dy = α2 E_u - α1 E_d + s_down e_beam0 e^{-m y}
  // with the quadrature closure (streams at ν = ±1/√3) on the delta-M medium:
  //   α1 = c' √3 (2 - ω'(1 + g'))/2 = √3 (a + b (1 - g)/2),  α2 = c' √3 ω'(1 - g')/2 = √3 b (1 - g)/2,
  // and the delta-M beam's b' split by Eddington's γ3 = (2 - 3 g' μ_w)/4 upwards, the rest downwards.
  // (Tried and measured worse overall: b B(g), the HG phase's own hemispheric back-scatter, in place
  // of b (1 - g)/2; results/BENCHMARKS.md.)
  // In general form with the streams at ±μ1 (TwoStreamClosure): b_b = b' (1 - g')/2 the back-scatter
  // per stream, α1 = (a + b_b)/μ1, α2 = b_b/μ1; the quadrature's μ1 = 1/√3 gives the α1, α2 above.
  const double b_back = b_dm * (1 - g_dm) / 2;
  const double mu1 = closure == TwoStreamClosure::Asymptotic
                         ? asymptoticStreamCosine(2 * b_back / (a + 2 * b_back))  // the similarity albedo
                         : 1.0 / std::sqrt(3.0);
  // Over the depths the frame sees, the field's mean slope (depthMeanDiffuseK) rather than its slope at
  // the surface: k moves towards K∞ by the factor s, with α1, α2 (the streams' cosine μ1/s), so the
  // two-stream stays a solution of its own equations and r = α2/(α1 + k) is unchanged.
  const double k_surface = std::sqrt(std::max(a * (a + 2 * b_back), 0.0)) / mu1;
  const double k_view = depthMeanDiffuseK(k_surface, asymptoticDiffuseK(a, b_back), view.depth, view.asymptotic_share);
  const double s_view = k_surface > 0 ? k_view / k_surface : 1.0;
  const double alpha1 = s_view * (a + b_back) / mu1;
  const double alpha2 = s_view * b_back / mu1;
  const double gamma3 = std::clamp((2 - 3 * g_dm * mu0) / 4, 0.0, 1.0);
  const double s_up = gamma3 * b_dm, s_down = b_dm - s_up;
  // k² = α1² - α2² = a (a + 2 b_b)/μ1² (= 3 c'² (1 - ω')(1 - ω' g') at μ1 = 1/√3), written without the
  // cancellation of the difference. Kept >= 1e-3 c': at a = 0 (no absorption) k = 0 and the pair
  // e^{-k y}, e^{-k (H - y)} would be one function, leaving the bottom's boundary system singular.
  double k = std::max(k_view, 1e-3 * c_dm);
  const double m = c_dm / mu0;
  // At k = m the particular solution resonates (it becomes y e^{-m y}) and P and A1 grow as 1/(k - m)
  // with opposite signs, so float loses digits in their sum. Within 0.1 % of it k is moved 0.1 % away.
  // Measured in the unit test (a = 1, b = 0.2, y = 3 m): E_d is continuous within 2.5 % across it, the
  // float rounding of k and m amplified by the cancellation; a resonant form (y e^{-m y}) would remove it.
  if (std::abs(k - m) < 1e-3 * m) k = k >= m ? (1 + 1e-3) * m : (1 - 1e-3) * m;
  const double r = alpha2 / (alpha1 + k);  // a semi-infinite layer's diffuse reflectance, in [0, 1)
  const double eb = band.e_beam0, es = band.e_sun0, esky = band.e_sky0;
  // Particular solution P e^{-m y}.
  const double det_p = k * k - m * m;
  const double pu = eb * (s_up * (alpha1 - m) + alpha2 * s_down) / det_p;
  const double pd = eb * (s_down * (alpha1 + m) + alpha2 * s_up) / det_p;
  // Boundaries: E_d(0) = e_sky0 + r_s E_u(0); E_u(H) = ρ (E_d(H) + e_sun0 e^{-m H}).
  // E_d = A1 e^{-k y} + r A2 e^{-k (H - y)} + pd e^{-m y}, E_u = r A1 e^{-k y} + A2 e^{-k (H - y)} + pu e^{-m y}.
  const double rs = internalDiffuseReflectance(ior);
  double A1 = 0, A2 = 0;
  if (bottom_depth > 0) {
    const double rho = band.bottom_albedo;
    const double e1 = std::exp(-k * bottom_depth), em = std::exp(-m * bottom_depth);
    const double m11 = 1 - rs * r, m12 = e1 * (r - rs), rhs1 = esky - pd + rs * pu;
    const double m21 = e1 * (r - rho), m22 = 1 - rho * r, rhs2 = (rho * es - pu + rho * pd) * em;
    const double det = m11 * m22 - m12 * m21;  // > 0: every reflectance is in [0, 1] and e1 <= 1
    A1 = (rhs1 * m22 - m12 * rhs2) / det;
    A2 = (m11 * rhs2 - m21 * rhs1) / det;
  } else {
    A1 = (esky - pd + rs * pu) / (1 - rs * r);
  }
  o.k = static_cast<float>(k);
  o.m = static_cast<float>(m);
  o.d1 = static_cast<float>(A1);
  o.u1 = static_cast<float>(r * A1);
  o.d2 = static_cast<float>(r * A2);
  o.u2 = static_cast<float>(A2);
  o.dp = static_cast<float>(pd);
  o.up = static_cast<float>(pu);
  // The scalar irradiance from the streams' mean cosines (E_d/μ̄_d + E_u/μ̄_u); the two streams carry
  // no horizontal flux.
  o.o1 = static_cast<float>(A1 / mean.down + r * A1 / mean.up);
  o.o2 = static_cast<float>(r * A2 / mean.down + A2 / mean.up);
  o.op = static_cast<float>(pd / mean.beam_down + pu / mean.beam_up);
  setFirstOrderSource(o);
  setHemisphereTilt(o);
  // The forward peak delta-M counts as unscattered, f = g² (forward_peak.h).
  setForwardPeak(o, band, peak ? *peak : forwardPeak(g, std::pow(std::max(g, 0.0), 2)), mu_w, view.depth);
  return o;
}

void setFirstOrderSource(UwiBand& o) {
  const double s = double(o.b_dm) / (4 * 3.14159265358979323846), s_flux = 3 * s * double(o.g_flux);
  const double coef[3][4] = {{o.o1, o.d1, o.u1, o.h1}, {o.o2, o.d2, o.u2, o.h2}, {o.op, o.dp, o.up, o.hp}};
  for (int node = 0; node < UWI_SOURCE_NODES; ++node) {
    const double nu = kmath_d::uwi_source_node_cosine(node);
    float* row = o.src + node * UWI_SOURCE_TERMS;
    for (int q = 0; q < 3; ++q) {
      row[q] = static_cast<float>(s * coef[q][0] + s_flux * nu * (coef[q][1] - coef[q][2]));
      row[q + 3] = static_cast<float>(s_flux * std::sqrt(std::max(1 - nu * nu, 0.0)) * coef[q][3]);
      row[q + 6] = 0.0f;
    }
  }
}

void setHemisphereTilt(UwiBand& o) {
  const double down[3] = {o.d1, o.d2, o.dp}, up[3] = {o.u1, o.u2, o.up};
  for (int node = 0; node < UWI_TILT_NODES; ++node) {
    const double n_y = kmath_d::uwi_tilt_node_cosine(node);
    float* row = o.tilt + node * UWI_SOURCE_TERMS;
    for (int q = 0; q < 3; ++q) {
      row[q] = static_cast<float>(0.5 * (1 + n_y) * down[q] + 0.5 * (1 - n_y) * up[q]);
      row[q + 3] = row[q + 6] = 0.0f;
    }
  }
}

std::vector<UwiBand> makeUwiBands(const UwParams& params, const std::vector<UwBand>& bands, DiffuseMeanCosines mean,
                                  TwoStreamClosure closure, double asymptotic_share, double flux_scale) {
  const DiffuseDepth view{diffuseViewDepth(params),
                          asymptotic_share >= 0 ? asymptotic_share : diffuseAsymptoticShare(params.g),
                          flux_scale >= 0 ? flux_scale : diffuseFluxScale(params.g)};
  const ForwardPeak peak = forwardPeak(params.g, std::pow(std::max(double(params.g), 0.0), 2));
  std::vector<UwiBand> out;
  out.reserve(bands.size());
  for (const UwBand& band : bands)
    out.push_back(makeUwiBand(band, params.g, params.sun_dir_water[1], params.bottom_depth, params.ior, mean, closure,
                              view, &peak));
  return out;
}

}  // namespace seasim
