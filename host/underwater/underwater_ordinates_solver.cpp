#include "underwater/underwater_ordinates_solver.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <tbb/parallel_for.h>

#include "math/kernel_math.h"
#include "math/linear_solve.h"
#include "underwater/discrete_ordinates.h"
#include "underwater/forward_peak.h"
#include "underwater/ordinates_high_order.h"
#include "underwater/sky_window_modes.h"
#include "underwater/underwater_ordinates_setup.h"

namespace seasim {
namespace {

constexpr int kDepthSamples = 96;

// One quantity's samples: the target (the kernel's diffuse part) and the reference its relative error
// is taken against.
struct Profile {
  std::vector<double> target, reference;
};

using Basis = std::vector<std::array<double, 3>>;  // e^{-k y}, e^{-k (H - y)}, e^{-m y} at each depth

struct Fit {
  std::array<double, 3> c{};  // of e^{-k y}, e^{-k (H - y)}, e^{-m y}
  double error = 0;           // largest weighted residual (relative error)
  bool solved = false;        // false: the normal equations were singular, c left 0
};

// Weighted least squares of `targets` targets (target(t, s): target t at depth sample s) on the basis
// functions `columns` (0, 1, 2 of the basis; the others left 0), the residual at sample s weighted by
// weight[s], by one set of normal equations for them all (one elimination, a right-hand side each).
template <class Target>
std::vector<Fit> fitWeighted(const Basis& basis, const std::vector<int>& columns, const std::vector<double>& weight,
                             int targets, Target target) {
  const int n = static_cast<int>(columns.size());
  std::vector<double> normal(n * n, 0.0);
  for (size_t s = 0; s < basis.size(); ++s) {
    const double w2 = weight[s] * weight[s];
    for (int r = 0; r < n; ++r)
      for (int c = 0; c < n; ++c) normal[r * n + c] += w2 * basis[s][columns[r]] * basis[s][columns[c]];
  }
  // Every target a right-hand side of the one system, solved by one elimination.
  std::vector<double> rhs(size_t(n) * targets, 0.0);
  for (int t = 0; t < targets; ++t)
    for (size_t s = 0; s < basis.size(); ++s) {
      const double w2t = weight[s] * weight[s] * target(t, int(s));
      for (int r = 0; r < n; ++r) rhs[size_t(r) * targets + t] += w2t * basis[s][columns[r]];
    }
  const bool solved = solveLinear(normal, rhs, n, targets);
  std::vector<Fit> fits(targets);
  for (int t = 0; t < targets; ++t) {
    Fit& f = fits[t];
    f.solved = solved;
    if (f.solved)
      for (int r = 0; r < n; ++r) f.c[columns[r]] = rhs[size_t(r) * targets + t];
    for (size_t s = 0; s < basis.size(); ++s) {
      const double v = f.c[0] * basis[s][0] + f.c[1] * basis[s][1] + f.c[2] * basis[s][2];
      f.error = std::max(f.error, std::abs(v - target(t, int(s))) * weight[s]);
    }
  }
  return fits;
}

// One profile in relative error (weights 1/reference); a singular system or a non-finite error counts as
// an error of 1e30.
Fit fitProfile(const Profile& p, const Basis& basis, const std::vector<int>& columns) {
  std::vector<double> weight(basis.size());
  for (size_t s = 0; s < basis.size(); ++s) weight[s] = 1.0 / p.reference[s];
  Fit f = fitWeighted(basis, columns, weight, 1, [&](int, int s) { return p.target[s]; })[0];
  if (!f.solved) return Fit{{}, 1e30, false};
  if (!std::isfinite(f.error)) f.error = 1e30;
  return f;
}

// The exponentials at the fit's evenly spaced depths (step apart from 0): e^{-k y}, e^{-k (H - y)} (0
// without a bottom; the samples then end at H), e^{-m y}, each a geometric sequence (one exp per rate).
Basis basisAt(double k, double m, double step, bool bottom) {
  Basis basis(kDepthSamples);
  const double rk = std::exp(-k * step), rm = std::exp(-m * step);
  double ek = 1, em = 1;
  for (int s = 0; s < kDepthSamples; ++s) {
    basis[s] = {ek, 0.0, em};
    ek *= rk;
    em *= rm;
  }
  // e^{-k (H - y_s)} = e^{-k y_{n-1-s}} since y_{n-1} = H.
  if (bottom)
    for (int s = 0; s < kDepthSamples; ++s) basis[s][1] = basis[kDepthSamples - 1 - s][0];
  return basis;
}

// k from a scan over [0.8, 2.5] K∞, coarse (steps of 0.1 K∞) then fine (0.01 K∞) around the best, by
// error(k): not within 2 % of m, where the two exponentials fit each other's cancellation. m 1.05 when
// nothing was tried (K∞ = 0: no absorption; a slow mode).
template <class Error>
double scanK(double k_inf, double m, Error error) {
  double best_k = -1, best_error = 0;
  auto tryK = [&](double k) {
    if (!(k > 0) || std::abs(k - m) < 0.02 * m) return;
    const double e = error(k);
    if (best_k < 0 || e < best_error) {
      best_k = k;
      best_error = e;
    }
  };
  for (int i = 0; i <= 17; ++i) tryK(k_inf * (0.8 + 0.1 * i));
  const double coarse = best_k;
  if (coarse > 0)
    for (int i = -9; i <= 9; ++i)
      if (i != 0) tryK(std::clamp(coarse + 0.01 * i * k_inf, 0.8 * k_inf, 2.5 * k_inf));
  return best_k > 0 ? best_k : m * 1.05;
}

// A table of the solver's azimuth modes 0, 1, 2 at `nodes` nodes (profiles[mode]: samples x nodes, mode 0
// at least; the last ones may be empty: 0, not fitted), fitted per node to e^{-k y}, e^{-k (H - y)}, e^{-m y} relative to
// the azimuth average's size: out[node * UWI_SOURCE_TERMS + q + 3 mode]. Returns the largest relative error
// over nodes and depths. Where k comes within 2 % of m (the k scan avoids it) the beam's exponential is
// left out, as the pair would fit each other's cancellation.
using ModeProfiles = std::array<std::vector<double>, 3>;
double fitModeTable(const ModeProfiles& profiles, int nodes, double depth_end, double k, double m, bool bottom,
                    float* out) {
  const std::vector<double>& j0 = profiles[0];
  double largest = 0;
  for (double v : j0) largest = std::max(largest, std::abs(v));
  const double step = depth_end / (kDepthSamples - 1);
  const auto basis = basisAt(k, m, step, bottom);
  std::vector<int> columns = bottom ? std::vector<int>{0, 1} : std::vector<int>{0};
  if (std::abs(k - m) >= 0.02 * m) columns.push_back(2);
  // Per node: one weighting (relative to the azimuth average), so one set of normal equations for the
  // three modes.
  std::vector<double> weight(kDepthSamples);
  double error = 0;
  // The modes to fit: up to the first empty one (those after it are 0).
  const int modes = profiles[1].empty() ? 1 : profiles[2].empty() ? 2 : 3;
  for (int j = 0; j < nodes; ++j) {
    for (int s = 0; s < kDepthSamples; ++s)
      weight[s] = 1.0 / std::max(std::abs(j0[size_t(s) * nodes + j]), 1e-9 * largest + 1e-300);
    const std::vector<Fit> fits = fitWeighted(basis, columns, weight, modes, [&](int mode, int s) {
      return profiles[mode][size_t(s) * nodes + j];
    });
    float* row = out + j * UWI_SOURCE_TERMS;
    for (int mode = 0; mode < 3; ++mode) {
      if (mode < modes) error = std::max(error, fits[mode].error);
      for (int q = 0; q < 3; ++q) row[q + 3 * mode] = mode < modes ? static_cast<float>(fits[mode].c[q]) : 0.0f;
    }
  }
  return error;
}

// The three azimuth modes' profiles, each field's `profile` (field_h, field_h2 null: empty, that mode 0).
template <class Profile>
ModeProfiles modeProfiles(const DiscreteOrdinates& field, const DiscreteOrdinates* field_h,
                          const DiscreteOrdinates* field_h2, Profile profile) {
  return {profile(field), field_h ? profile(*field_h) : std::vector<double>{},
          field_h2 ? profile(*field_h2) : std::vector<double>{}};
}

// The kernel's TMS per unit of e^{-m y} towards the table's cosines nus, as azimuth modes 0-2 (the coefficient
// of cos m Δφ, Δφ from the beam's azimuth; the midpoint rule on 256 azimuths over [0, π], the phase being even
// in Δφ): what the high-order fit leaves out. mu_w: the refracted sun's cosine as the kernel reads it.
void kernelTmsModes(const UwiBand& o, const UwBand& band, double g, double mu_w, const std::vector<double>& nus,
                    SourceTableBasis& basis) {
  for (int mode = 0; mode < 3; ++mode) basis.tms[mode].assign(nus.size(), 0.0);
  const double b_e_beam = double(band.b) * band.e_beam0;
  for (size_t j = 0; j < nus.size(); ++j) {
    const std::array<double, 3> m = azimuthModes(nus[j], mu_w, 256, [&](double cos_s) {
      return b_e_beam * kmath_d::uwi_tms_phase(kmath_d::hg_phase(cos_s, g), o.p_clip);
    });
    for (int mode = 0; mode < 3; ++mode) basis.tms[mode][j] = m[mode];
  }
}

// The discrete ordinates' in-scatter (azimuth modes 0, 1, 2; field_h, field_h2 null: only mode 0) at the
// source table's cosines, fitted per cosine: UwiBand.src. With source_streams > 0 the table is then fitted
// to the radiance of the solution at that order (ordinates_high_order.h), but near the beam's direction;
// the error returned is the order-3 fit's. Where the fit is taken, the aureole's modes 0-2 that its field
// holds are set for the kernel to take off (forward_peak.h setAureoleModesHeld).
double fitSourceTable(const DiscreteOrdinates& field, const DiscreteOrdinates* field_h,
                      const DiscreteOrdinates* field_h2, double depth_end, double k, double m, bool bottom,
                      UwiBand& o, const DiscreteOrdinatesLayer& layer, double c_kernel, double view_depth,
                      int source_streams, const UwBand& band, double g, double mu_w) {
  std::vector<double> nus(UWI_SOURCE_NODES);
  for (int j = 0; j < UWI_SOURCE_NODES; ++j) nus[j] = kmath_d::uwi_source_node_cosine(j);
  const ModeProfiles profiles = modeProfiles(field, field_h, field_h2, [&](const DiscreteOrdinates& f) {
    return f.inscatterProfile(nus, depth_end, kDepthSamples);
  });
  const double error = fitModeTable(profiles, UWI_SOURCE_NODES, depth_end, k, m, bottom, o.src);
  // The part of it the bottom brings per unit of the irradiance it reflects first (azimuth mode 0; over a
  // bottom), fitted the same way, and that irradiance of the beam and of the diffuse light: UwiBand.src_sand,
  // sand_beam and sand_diffuse, what the kernel takes off where objects hide or shade the sand
  // (uwi_sand_shares).
  if (bottom) {
    ModeProfiles lit;
    lit[0] = field.inscatterProfile(nus, depth_end, kDepthSamples, FieldPart::sand_unit);
    if (std::any_of(lit[0].begin(), lit[0].end(), [](double v) { return v != 0.0; })) {
      std::vector<float> table(UWI_SOURCE_NODES * UWI_SOURCE_TERMS);
      fitModeTable(lit, UWI_SOURCE_NODES, depth_end, k, m, bottom, table.data());
      for (int j = 0; j < UWI_SOURCE_NODES; ++j)
        for (int q = 0; q < 3; ++q) o.src_sand[j * 3 + q] = table[j * UWI_SOURCE_TERMS + q];
      o.sand_beam = static_cast<float>(field.sandBeam());
      o.sand_diffuse = static_cast<float>(field.sandDiffuse());
    }
  }
  if (source_streams > 0) {
    const int modes = field_h ? 3 : 1;
    const HighOrderField high = solveHighOrderField(layer, source_streams, modes, nus, depth_end);
    SourceTableBasis basis;
    basis.k = k;
    basis.m = m;
    basis.c_kernel = c_kernel;
    basis.bottom_depth = bottom ? depth_end : 0.0;
    basis.depth_end = depth_end;
    basis.view_depth = view_depth;
    basis.samples = kDepthSamples;
    if (o.p_clip > 0) kernelTmsModes(o, band, g, mu_w, nus, basis);
    std::vector<float> fit_weight(UWI_SOURCE_NODES, 0.0f);
    fitSourceTableToField(high, nus, basis, layer.mu_sun, layer.e_sun0 > 0, o.src, UWI_SOURCE_TERMS, fit_weight.data());
    setAureoleModesHeld(o, g, mu_w, fit_weight);
  }
  return error;
}

// The discrete ordinates' irradiance on tilted planes (azimuth modes 0, 1, 2) at the table's normals,
// fitted per normal: UwiBand.tilt. Its end nodes (a plane facing straight up, straight down) are E_d's and
// E_u's own fits (o.d*, o.u*), so the bottom, lit by E_d, reads the same from either. The part of the
// azimuth average that the bottom's reflection of the beam brings (FieldPart::sand_unit times sandBeam(); over
// a lit bottom), fitted the same way: UwiBand.tilt_bottom.
double fitTiltTable(const DiscreteOrdinates& field, const DiscreteOrdinates* field_h,
                    const DiscreteOrdinates* field_h2, double depth_end, double k, double m, bool bottom,
                    UwiBand& o) {
  std::vector<double> n_ys(UWI_TILT_NODES);
  for (int j = 0; j < UWI_TILT_NODES; ++j) n_ys[j] = kmath_d::uwi_tilt_node_cosine(j);
  ModeProfiles lit;
  if (bottom) {
    lit[0] = field.tiltedIrradianceProfile(n_ys, depth_end, kDepthSamples, FieldPart::sand_unit);
    for (double& e : lit[0]) e *= field.sandBeam();
  }
  // None where the bottom reflects no beam (black, no sun): tilt_bottom stays 0.
  if (std::any_of(lit[0].begin(), lit[0].end(), [](double v) { return v != 0.0; })) {
    std::vector<float> table(UWI_TILT_NODES * UWI_SOURCE_TERMS);
    fitModeTable(lit, UWI_TILT_NODES, depth_end, k, m, bottom, table.data());
    for (int j = 0; j < UWI_TILT_NODES; ++j)
      for (int q = 0; q < 3; ++q) o.tilt_bottom[j * 3 + q] = table[j * UWI_SOURCE_TERMS + q];
  }
  const ModeProfiles profiles = modeProfiles(field, field_h, field_h2, [&](const DiscreteOrdinates& f) {
    return f.tiltedIrradianceProfile(n_ys, depth_end, kDepthSamples);
  });
  const double error = fitModeTable(profiles, UWI_TILT_NODES, depth_end, k, m, bottom, o.tilt);
  float* up = o.tilt + (UWI_TILT_NODES - 1) * UWI_SOURCE_TERMS;
  float* down = o.tilt;
  const float d[3] = {o.d1, o.d2, o.dp}, u[3] = {o.u1, o.u2, o.up};
  for (int q = 0; q < 3; ++q) {
    up[q] = d[q];
    down[q] = u[q];
    up[q + 3] = up[q + 6] = down[q + 3] = down[q + 6] = 0.0f;  // no azimuth about the vertical
  }
  return error;
}

}  // namespace

UwiBand makeUwiBandFromOrdinates(const UwBand& band, double g, double mu_w, double bottom_depth, double ior,
                                 double view_depth, int streams, OrdinatesFitError* fit, int source_streams,
                                 const ForwardPeak* peak, const SkyWindowModes* sky) {
  const double a = band.a, b = band.b;
  // The kernel's delta-M is the solver's (kOrdinatesSourceMoments: f = g³ for g > 0), its beam
  // e_beam0 e^{-m y}, m = c'/μ_w: the view rays' source is the solver's in-scatter in that frame.
  const int moments = g > 0 ? kOrdinatesSourceMoments : 0;
  const DeltaMMedium medium = ordinatesDeltaM(a, b, g, kOrdinatesSourceMoments);
  const double c_dm = medium.c_dm;
  const double mu0 = std::clamp(mu_w, 1e-3, 1.0);
  UwiBand o = uwiBandOfMedium(medium, 1.0);  // g_flux = g': the first-order source's, unused here
  if (fit) *fit = OrdinatesFitError{};
  const double e_sun0 = band.e_sun0, e_sky0 = band.e_sky0;
  if (!(c_dm > 0) || !(e_sun0 + e_sky0 > 0)) return o;  // no medium or no light: no diffuse field
  const double m = c_dm / mu0;
  const double H = bottom_depth > 0 ? bottom_depth : 0.0;
  o.m = static_cast<float>(m);
  // The forward peak delta-M counts as unscattered (forward_peak.h): before the source's fit, which takes
  // the kernel's TMS term (capped at p_clip) off its targets.
  setForwardPeak(o, band, peak ? *peak : forwardPeak(g, std::pow(std::max(g, 0.0), kOrdinatesSourceMoments)), mu_w,
                 view_depth);

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
  if (sky) {
    const std::array<double, 3> w{band.sky_w_r, band.sky_w_g, band.sky_w_b};
    layer.sky_shape = [sky, w](double mu) { return sky->at(mu, w); };
  }
  // Delta-M to kOrdinatesSourceMoments moments (f = g³; measured against the full order in
  // docs/journal/underwater_regions_3_*.md). A
  // backward phase (g < 0) keeps every moment.
  const DiscreteOrdinates field(layer, streams, 0, moments);
  // The cos φ mode only where there is a beam off the zenith and a phase that is not isotropic.
  const bool azimuth = e_sun0 > 0 && mu0 < 1 - 1e-6 && g != 0;
  const DiscreteOrdinates field_h = azimuth ? DiscreteOrdinates(layer, streams, 1, moments) : field;
  const DiscreteOrdinates field_h2 = azimuth ? DiscreteOrdinates(layer, streams, 2, moments) : field;
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

  const std::vector<int> columns = H > 0 ? std::vector<int>{0, 1, 2} : std::vector<int>{0, 2};
  const double step = depth_end / (kDepthSamples - 1);
  const double best_k = scanK(k_inf, m, [&](double k) {
    const auto basis = basisAt(k, m, step, H > 0);
    return fitProfile(down, basis, columns).error + fitProfile(up, basis, columns).error +
           fitProfile(scalar, basis, columns).error;
  });
  const auto basis = basisAt(best_k, m, step, H > 0);
  const Fit fd = fitProfile(down, basis, columns), fu = fitProfile(up, basis, columns);
  const Fit fo = fitProfile(scalar, basis, columns), fh = fitProfile(horizontal, basis, columns);
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
  // The source view rays gather: the solver's own in-scatter at the table's cosines, in the same
  // exponentials (the kernel's delta-M is the solver's: c' = ĉ, the beam's m its own); by default then
  // refitted to the high-order solution's radiance (source_streams; ordinates_high_order.h).
  const double source_error = fitSourceTable(field, azimuth ? &field_h : nullptr, azimuth ? &field_h2 : nullptr,
                                             depth_end, best_k, m, H > 0, o, layer, c_dm, view_depth, source_streams,
                                             band, g, mu_w);
  const double tilt_error = fitTiltTable(field, azimuth ? &field_h : nullptr, azimuth ? &field_h2 : nullptr,
                                         depth_end, best_k, m, H > 0, o);
  if (fit) *fit = OrdinatesFitError{fd.error, fu.error, fo.error, fh.error, source_error, tilt_error};
  return o;
}

std::vector<UwiBand> makeUwiBandsFromOrdinates(const UwParams& params, const std::vector<UwBand>& bands,
                                               int source_streams, const SkyWindowModes* sky) {
  const double view_depth = diffuseViewDepth(params);
  const ForwardPeak peak = forwardPeak(params.g, std::pow(std::max(double(params.g), 0.0), kOrdinatesSourceMoments));
  // Bands are independent (1.5–1.8 ms each at 16 streams on one core,
  // docs/journal/underwater_regions_3_*.md): in parallel.
  std::vector<UwiBand> out(bands.size());
  tbb::parallel_for(size_t(0), bands.size(), [&](size_t i) {
    out[i] = makeUwiBandFromOrdinates(bands[i], params.g, params.sun_dir_water[1], params.bottom_depth, params.ior,
                                      view_depth, 16, nullptr, source_streams, &peak, sky);
  });
  return out;
}

}  // namespace seasim
