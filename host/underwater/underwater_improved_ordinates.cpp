#include "underwater/underwater_improved_ordinates.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <tbb/parallel_for.h>

#include "math/linear_solve.h"
#include "underwater/discrete_ordinates.h"
#include "underwater/underwater_improved_setup.h"

namespace seasim {
namespace {

constexpr int kDepthSamples = 96;

// One quantity's samples: the target (the kernel's diffuse part) and the reference its relative error
// is taken against.
struct Profile {
  std::vector<double> target, reference;
};

struct Fit {
  std::array<double, 3> c{};  // of e^{-k y}, e^{-k (H - y)}, e^{-m y}
  double error = 0;           // largest relative error
};

// Weighted least squares on the basis (2 functions without a bottom: the second is left 0) by its
// normal equations.
Fit fitProfile(const Profile& p, const std::vector<std::array<double, 3>>& basis, int n_basis) {
  std::vector<double> a(n_basis * n_basis, 0.0), rhs(n_basis, 0.0);
  const int idx[3] = {0, n_basis == 3 ? 1 : 2, 2};
  for (size_t s = 0; s < basis.size(); ++s) {
    const double w = 1.0 / p.reference[s];
    for (int i = 0; i < n_basis; ++i) {
      const double bi = basis[s][idx[i]] * w;
      rhs[i] += bi * p.target[s] * w;
      for (int j = 0; j < n_basis; ++j) a[i * n_basis + j] += bi * basis[s][idx[j]] * w;
    }
  }
  if (!solveLinear(a, rhs, n_basis)) return Fit{{}, 1e30};
  Fit f;
  for (int i = 0; i < n_basis; ++i) f.c[idx[i]] = rhs[i];
  for (size_t s = 0; s < basis.size(); ++s) {
    const double v = f.c[0] * basis[s][0] + f.c[1] * basis[s][1] + f.c[2] * basis[s][2];
    f.error = std::max(f.error, std::abs(v - p.target[s]) / p.reference[s]);
  }
  if (!std::isfinite(f.error)) f.error = 1e30;
  return f;
}

}  // namespace

UwiBand makeUwiBandFromOrdinates(const UwBand& band, double g, double mu_w, double bottom_depth, double ior,
                                 double view_depth, double flux_scale, int streams, OrdinatesFitError* fit) {
  const double a = band.a, b = band.b;
  // The kernel's delta-M (the two-stream's too): f = g², its beam e_beam0 e^{-m y}, m = c'/μ_w.
  const DeltaMMedium medium = improvedDeltaM(a, b, g);
  const double c_dm = medium.c_dm;
  const double mu0 = std::clamp(mu_w, 1e-3, 1.0);
  UwiBand o = uwiBandOfMedium(medium, flux_scale);
  if (fit) *fit = OrdinatesFitError{};
  const double e_sun0 = band.e_sun0, e_sky0 = band.e_sky0;
  if (!(c_dm > 0) || !(e_sun0 + e_sky0 > 0)) return o;  // no medium or no light: no diffuse field
  const double m = c_dm / mu0;
  const double H = bottom_depth > 0 ? bottom_depth : 0.0;
  o.m = static_cast<float>(m);

  DiscreteOrdinatesLayer layer;
  layer.a = a;
  layer.b = b;
  layer.g = std::clamp(g, -0.999, 0.999);
  layer.bottom_depth = H;
  layer.bottom_albedo = std::clamp(double(band.bottom_albedo), 0.0, 1.0);
  layer.ior = ior;
  layer.mu_sun = mu0;
  layer.e_sun0 = e_sun0;
  layer.e_sky0 = e_sky0;
  const DiscreteOrdinates field(layer, streams, 0);
  // The cos φ mode only where there is a beam off the zenith and a phase that is not isotropic.
  const bool azimuth = e_sun0 > 0 && mu0 < 1 - 1e-6 && g != 0;
  const DiscreteOrdinates field_h = azimuth ? DiscreteOrdinates(layer, streams, 1) : field;
  const double k_inf = field.asymptoticK();

  const double depth_end = H > 0 ? H : std::max(view_depth, 0.0) + 5.0 / c_dm;
  Profile down, up, scalar, horizontal;
  const double sin_w = std::sqrt(std::max(1 - mu0 * mu0, 0.0));
  double largest = 0;
  const std::vector<DiscreteOrdinatesIrradiance> field_y = field.profile(depth_end, kDepthSamples);
  const std::vector<DiscreteOrdinatesIrradiance> field_h_y =
      azimuth ? field_h.profile(depth_end, kDepthSamples) : std::vector<DiscreteOrdinatesIrradiance>{};
  for (int i = 0; i < kDepthSamples; ++i) {
    const double y = depth_end * i / (kDepthSamples - 1);
    const DiscreteOrdinatesIrradiance& e = field_y[i];
    const double beam = e_sun0 * std::exp(-m * y);  // the kernel's delta-M beam, horizontal irradiance
    const double total_down = e.down + e.beam_down, total_scalar = e.scalar + e.beam_scalar;
    down.target.push_back(total_down - beam);
    down.reference.push_back(total_down);
    up.target.push_back(e.up);
    up.reference.push_back(e.up);
    scalar.target.push_back(total_scalar - beam / mu0);
    scalar.reference.push_back(total_scalar);
    double h = 0;
    if (azimuth) {
      const DiscreteOrdinatesIrradiance& eh = field_h_y[i];
      h = eh.horizontal + eh.beam_horizontal - beam / mu0 * sin_w;
    }
    horizontal.target.push_back(h);
    horizontal.reference.push_back(total_scalar);
    largest = std::max({largest, std::abs(total_down), std::abs(e.up), std::abs(total_scalar)});
  }
  // References that vanish (no upwelling light over a black bottom, say) are weighed against the
  // largest value instead of dividing by 0.
  for (Profile* p : {&down, &up, &scalar, &horizontal})
    for (double& r : p->reference) r = std::max(std::abs(r), 1e-12 * largest);

  const int n_basis = H > 0 ? 3 : 2;
  // The samples are evenly spaced: each exponential is a geometric sequence (one exp per k).
  const double step = depth_end / (kDepthSamples - 1);
  auto basisAt = [&](double k) {
    std::vector<std::array<double, 3>> basis(kDepthSamples);
    const double rk = std::exp(-k * step), rm = std::exp(-m * step);
    double ek = 1, em = 1;
    for (int s = 0; s < kDepthSamples; ++s) {
      basis[s] = {ek, 0.0, em};
      ek *= rk;
      em *= rm;
    }
    // e^{-k (H - y_s)} = e^{-k y_{n-1-s}} since y_{n-1} = H.
    if (H > 0)
      for (int s = 0; s < kDepthSamples; ++s) basis[s][1] = basis[kDepthSamples - 1 - s][0];
    return basis;
  };
  // k from a scan over [0.8, 2.5] K∞, coarse (steps of 0.1 K∞) then fine (0.01 K∞) around the best: not
  // within 2 % of m, where the two exponentials fit each other's cancellation.
  double best_k = -1, best_error = 0;
  auto tryK = [&](double k) {
    if (!(k > 0) || std::abs(k - m) < 0.02 * m) return;
    const auto basis = basisAt(k);
    const double error =
        fitProfile(down, basis, n_basis).error + fitProfile(up, basis, n_basis).error + fitProfile(scalar, basis, n_basis).error;
    if (best_k < 0 || error < best_error) {
      best_k = k;
      best_error = error;
    }
  };
  for (int i = 0; i <= 17; ++i) tryK(k_inf * (0.8 + 0.1 * i));
  const double coarse = best_k;
  if (coarse > 0)
    for (int i = -9; i <= 9; ++i)
      if (i != 0) tryK(std::clamp(coarse + 0.01 * i * k_inf, 0.8 * k_inf, 2.5 * k_inf));
  if (best_k < 0) best_k = m * 1.05;  // K∞ = 0 (no absorption): a slow mode
  const auto basis = basisAt(best_k);
  const Fit fd = fitProfile(down, basis, n_basis), fu = fitProfile(up, basis, n_basis);
  const Fit fo = fitProfile(scalar, basis, n_basis), fh = fitProfile(horizontal, basis, n_basis);
  o.k = static_cast<float>(best_k);
  // Each quantity's coefficients of e^{-k y}, e^{-k (H - y)}, e^{-m y}.
  auto store = [](const Fit& f, float& first, float& second, float& beam) {
    first = static_cast<float>(f.c[0]);
    second = static_cast<float>(f.c[1]);
    beam = static_cast<float>(f.c[2]);
  };
  store(fd, o.d1, o.d2, o.dp);
  store(fu, o.u1, o.u2, o.up);
  store(fo, o.o1, o.o2, o.op);
  store(fh, o.h1, o.h2, o.hp);
  if (fit) *fit = OrdinatesFitError{fd.error, fu.error, fo.error, fh.error};
  return o;
}

double ordinatesFluxScale(double g) {
  // Fitted offline to the path tracer (`--model-set underwater.improved_flux_scale=s` on the training grid
  // of tests/perf/underwater_regions.sh, s = 0.8–2.0; results/BENCHMARKS.md, s9a, reports it and the
  // held-out grid): one number for every g (at g = 0, g' = 0 and it has no effect). The first-order
  // phase leaves out the forward peak's higher Legendre terms, which weigh the field's flux more.
  (void)g;
  return 1.2;
}

std::vector<UwiBand> makeUwiBandsFromOrdinates(const UwParams& params, const std::vector<UwBand>& bands,
                                               double flux_scale) {
  const double s = flux_scale >= 0 ? flux_scale : ordinatesFluxScale(params.g);
  const double view_depth = diffuseViewDepth(params);
  // Bands are independent (0.4–0.7 ms each at 16 streams on one core, results/BENCHMARKS.md s9a): in parallel.
  std::vector<UwiBand> out(bands.size());
  tbb::parallel_for(size_t(0), bands.size(), [&](size_t i) {
    out[i] = makeUwiBandFromOrdinates(bands[i], params.g, params.sun_dir_water[1], params.bottom_depth, params.ior,
                                      view_depth, s);
  });
  return out;
}

}  // namespace seasim
