#include "underwater/discrete_ordinates.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "math/kernel_math.h"
#include "math/linear_solve.h"

namespace seasim {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Gauss-Legendre nodes and weights on (0, 1): Newton's method on P_n from the usual first guess.
void gaussLegendreUnit(int n, std::vector<double>& x, std::vector<double>& w) {
  x.assign(n, 0.0);
  w.assign(n, 0.0);
  for (int i = 0; i < n; ++i) {
    double z = std::cos(kPi * (i + 0.75) / (n + 0.5)), dp = 1;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1, p1 = z;
      for (int l = 2; l <= n; ++l) {
        const double p2 = ((2 * l - 1) * z * p1 - (l - 1) * p0) / l;
        p0 = p1;
        p1 = p2;
      }
      const double pn = n == 1 ? z : p1, pm = n == 1 ? 1.0 : p0;
      dp = n * (z * pn - pm) / (z * z - 1);
      const double dz = pn / dp;
      z -= dz;
      if (std::abs(dz) < 1e-15) break;
    }
    x[i] = 0.5 * (1 - z);  // ascending on (0, 1)
    w[i] = 1.0 / ((1 - z * z) * dp * dp);  // (2 / ((1 - z²) P_n'²)) / 2
  }
}

// The quadrature's cosines on (0, 1) for a phase of `moments` Legendre terms under a surface of index ior:
// Gauss-Legendre on [0, μ_c] and on [μ_c, 1] apart, μ_c = √(1 - 1/n²) the edge of Snell's window, beyond
// which the surface reflects totally. The surface's reflectance rises to 1 there with an infinite slope,
// which one Gauss rule over (0, 1) integrates poorly: the solution then moved with the node count, by
// several % in the regions' ratios (docs/journal/underwater_regions_4_*.md), and with the split it does
// not (8 streams give the 32's). Jin & Stamnes (1994) give the coupled atmosphere-ocean discrete ordinates
// separate streams in the region of total reflection for the same reason. Half the nodes on each side
// (the window's half nearer the vertical holds the field's asymptotic peak: in proportion to the lengths,
// 5 of 16 there, K∞ of isotropic water at ω = 0.5 moved by 1e-4). The split rule integrates polynomials to degree
// 2 min(n_tir, n_win) - 1 on each hemisphere: where that is short of the phase's moments (the full
// delta-M order) or ior <= 1, one rule, exact to 2 streams - 1.
void surfaceQuadrature(int n, double ior, int moments, std::vector<double>& x, std::vector<double>& w) {
  const double mu_c = ior > 1 ? std::sqrt(1 - 1 / (ior * ior)) : 0.0;
  const int n_tir = n / 2;
  if (mu_c <= 0 || 2 * n_tir < moments) {
    gaussLegendreUnit(n, x, w);
    return;
  }
  std::vector<double> x_tir, w_tir, x_win, w_win;
  gaussLegendreUnit(n_tir, x_tir, w_tir);
  gaussLegendreUnit(n - n_tir, x_win, w_win);
  x.assign(n, 0.0);
  w.assign(n, 0.0);
  for (int i = 0; i < n_tir; ++i) {
    x[i] = mu_c * x_tir[i];
    w[i] = mu_c * w_tir[i];
  }
  for (int i = 0; i < n - n_tir; ++i) {
    x[n_tir + i] = mu_c + (1 - mu_c) * x_win[i];
    w[n_tir + i] = (1 - mu_c) * w_win[i];
  }
}

// The azimuth mode's Legendre functions at x, l = 0..count-1, scaled for the addition theorem:
// mode 0: P_l(x); mode 1: P_l^1(x) / √(l (l + 1)) (0 at l = 0); mode 2: P_l^2(x) / √((l - 1) l (l + 1) (l + 2))
// (0 at l < 2), so that the mode's phase is Σ_l (2l + 1) χ_l q_l(μ) q_l(μ') / (4π) in each.
std::vector<double> azimuthLegendre(int mode, int count, double x) {
  // P_m^m = (2m - 1)!! (1 - x²)^{m/2} (the Condon-Shortley sign cancels in the products), P_{m+1}^m =
  // (2m + 1) x P_m^m, (l - m) P_l^m = (2l - 1) x P_{l-1}^m - (l + m - 1) P_{l-2}^m; scaled by
  // √((l - m)! / (l + m)!).
  std::vector<double> raw(count, 0.0), p(count, 0.0);
  const double s = std::sqrt(std::max(1 - x * x, 0.0));
  double pmm = 1;
  for (int k = 1; k <= mode; ++k) pmm *= (2 * k - 1) * s;
  if (mode < count) raw[mode] = pmm;
  if (mode + 1 < count) raw[mode + 1] = (2 * mode + 1) * x * pmm;
  for (int l = mode + 2; l < count; ++l)
    raw[l] = ((2 * l - 1) * x * raw[l - 1] - (l + mode - 1) * raw[l - 2]) / (l - mode);
  for (int l = mode; l < count; ++l) {
    double factorials = 1;  // (l + m)! / (l - m)!
    for (int i = l - mode + 1; i <= l + mode; ++i) factorials *= i;
    p[l] = raw[l] / std::sqrt(factorials);
  }
  return p;
}

// The boundary and particular systems: singular only for a degenerate medium the checks above exclude.
void solveOrThrow(std::vector<double>& a, std::vector<double>& rhs, int n, int columns = 1) {
  if (!solveLinear(a, rhs, n, columns)) throw std::runtime_error("discrete ordinates: singular system");
}

// Eigen-decomposition of a symmetric n x n matrix (row-major, destroyed) by cyclic Jacobi rotations:
// eigenvalues in `values`, eigenvectors in the columns of `vectors`.
void symmetricEigen(std::vector<double>& a, int n, std::vector<double>& values, std::vector<double>& vectors) {
  vectors.assign(static_cast<size_t>(n) * n, 0.0);
  for (int i = 0; i < n; ++i) vectors[i * n + i] = 1;
  for (int sweep = 0; sweep < 100; ++sweep) {
    double off = 0, diag = 0;
    for (int i = 0; i < n; ++i) {
      diag += a[i * n + i] * a[i * n + i];
      for (int j = i + 1; j < n; ++j) off += a[i * n + j] * a[i * n + j];
    }
    if (off <= 1e-30 * diag) break;
    for (int p = 0; p < n; ++p)
      for (int q = p + 1; q < n; ++q) {
        const double apq = a[p * n + q];
        if (std::abs(apq) < 1e-300) continue;
        const double theta = (a[q * n + q] - a[p * n + p]) / (2 * apq);
        const double t = (theta >= 0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1));
        const double c = 1 / std::sqrt(t * t + 1), s = t * c;
        for (int k = 0; k < n; ++k) {  // columns p, q
          const double akp = a[k * n + p], akq = a[k * n + q];
          a[k * n + p] = c * akp - s * akq;
          a[k * n + q] = s * akp + c * akq;
        }
        for (int k = 0; k < n; ++k) {  // rows p, q
          const double apk = a[p * n + k], aqk = a[q * n + k];
          a[p * n + k] = c * apk - s * aqk;
          a[q * n + k] = s * apk + c * aqk;
        }
        for (int k = 0; k < n; ++k) {
          const double vkp = vectors[k * n + p], vkq = vectors[k * n + q];
          vectors[k * n + p] = c * vkp - s * vkq;
          vectors[k * n + q] = s * vkp + c * vkq;
        }
      }
  }
  values.resize(n);
  for (int i = 0; i < n; ++i) values[i] = a[i * n + i];
}

void requireRange(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("discrete ordinates: " + what);
}

}  // namespace

double tiltedIrradianceKernel(int mode, double nu, double n_y) {
  const double a = nu * n_y, b = std::sqrt(std::max((1 - nu * nu) * (1 - n_y * n_y), 0.0));
  if (a <= -b) return 0.0;  // the plane faces away from every such direction
  // The arc |ψ| < ψ0 where a + b cos ψ > 0: all of it when a >= b. sin 2ψ0 and sin 3ψ0 from sin ψ0 and
  // cos ψ0 (= -a/b), without more trigonometry.
  const double c1 = a >= b ? -1.0 : std::clamp(-a / b, -1.0, 1.0);
  const double psi0 = a >= b ? kPi : std::acos(c1);
  const double s1 = a >= b ? 0.0 : std::sqrt(std::max(1 - c1 * c1, 0.0));
  const double s2 = 2 * s1 * c1, s3 = s1 * (3 - 4 * s1 * s1);
  switch (mode) {
    case 0: return 2 * (a * psi0 + b * s1);
    case 1: return 2 * a * s1 + b * (psi0 + 0.5 * s2);      // ∫ (a cos ψ + b cos² ψ)
    case 2: return a * s2 + b * (s1 + s3 / 3);               // ∫ (a cos 2ψ + b cos ψ cos 2ψ)
    default: return 0.0;
  }
}

double hgAzimuthMode(double g, int mode, double nu, double mu) {
  requireRange(std::abs(g) < 1 && mode >= 0 && mode <= 2, "hgAzimuthMode: |g| < 1, mode 0, 1 or 2");
  // Terms until g^l < 1e-10 (at g = 0.95, 449), at most 4000.
  const int count = g == 0 ? 1 : std::clamp(static_cast<int>(std::ceil(std::log(1e-10) / std::log(std::abs(g)))) + 1,
                                            mode + 1, 4000);
  const std::vector<double> pn = azimuthLegendre(mode, count, std::clamp(nu, -1.0, 1.0));
  const std::vector<double> pm = azimuthLegendre(mode, count, std::clamp(mu, -1.0, 1.0));
  double sum = 0, gl = 1;
  for (int l = 0; l < count; ++l, gl *= g) sum += (2 * l + 1) * gl * pn[l] * pm[l];
  return (mode == 0 ? 1.0 : 2.0) * sum / (4 * kPi);
}

namespace {

void requireValidLayer(const DiscreteOrdinatesLayer& layer, int streams, int azimuth_mode) {
  requireRange(streams >= 2, "at least 2 streams per hemisphere");
  requireRange(azimuth_mode >= 0 && azimuth_mode <= 2, "the azimuth mode must be 0, 1 or 2");
  requireRange(layer.a >= 0 && layer.b >= 0 && std::isfinite(layer.a) && std::isfinite(layer.b),
               "a and b must be finite and >= 0");
  const bool hg = layer.moments.empty();
  requireRange(!hg || std::abs(layer.g) < 1, "|g| must be < 1");
  requireRange(hg || (std::abs(layer.moments[0] - 1) < 1e-9 &&
                      std::all_of(layer.moments.begin(), layer.moments.end(),
                                  [](double c) { return std::abs(c) <= 1 + 1e-12; })),
               "the phase's moments must start at 1 and lie in [-1, 1]");
  requireRange(layer.mu_sun > 0 && layer.mu_sun <= 1, "mu_sun must be in (0, 1]");
  requireRange(layer.bottom_albedo >= 0 && layer.bottom_albedo <= 1, "bottom albedo must be in [0, 1]");
  requireRange(layer.bottom_sunlit >= 0 && layer.bottom_sunlit <= 1, "the bottom's sunlit share must be in [0, 1]");
  requireRange(layer.e_sun0 >= 0 && layer.e_sky0 >= 0, "irradiances must be >= 0");
}

// The azimuth mode's phase between the quadrature's cosines: same hemisphere (pp) and opposite (pm),
// p^m(μ, μ') = Σ_l (2l + 1) χ_l q_l(μ) q_l(μ') / (4π) (azimuthLegendre; P_l^m(-μ) = (-1)^{l+m} P_l^m(μ)),
// and towards the sun's cosine. Mode 0 is the azimuth average; mode 1 the cos φ part (φ from the
// sun's azimuth), whose in-scatter has the same 2π ∫ dμ' form (Chandrasekhar 1960, §48).
struct ModePhase {
  std::vector<double> pp, pm;          // N x N
  std::vector<double> q_plus, q_minus; // N: the beam's scattering towards ±μ_i
};

ModePhase modePhase(int mode, const std::vector<double>& chi, const std::vector<double>& mu, double mu_sun,
                    double b_hat, double e_sun0) {
  const int n = static_cast<int>(mu.size()), moments = static_cast<int>(chi.size());
  std::vector<std::vector<double>> pl(n);
  for (int i = 0; i < n; ++i) pl[i] = azimuthLegendre(mode, moments, mu[i]);
  const std::vector<double> pl_sun = azimuthLegendre(mode, moments, mu_sun);
  ModePhase ph{std::vector<double>(n * n), std::vector<double>(n * n), std::vector<double>(n), std::vector<double>(n)};
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      double s_pp = 0, s_pm = 0;
      for (int l = 0; l < moments; ++l) {
        const double t = (2 * l + 1) * chi[l] * pl[i][l] * pl[j][l];
        s_pp += t;
        s_pm += ((l + mode) % 2 ? -t : t);
      }
      ph.pp[i * n + j] = s_pp / (4 * kPi);
      ph.pm[i * n + j] = s_pm / (4 * kPi);
    }
    double s_down = 0, s_up = 0;
    for (int l = 0; l < moments; ++l) {
      const double t = (2 * l + 1) * chi[l] * pl[i][l] * pl_sun[l];
      s_down += t;
      s_up += ((l + mode) % 2 ? -t : t);
    }
    // The beam's scattering towards ±μ_i: b̂ p^m F0 (twice that for m = 1: the cos φ term of the
    // addition theorem), F0 = e_sun0 / μ_sun its normal irradiance.
    const double fourier = mode == 0 ? 1.0 : 2.0;
    ph.q_plus[i] = fourier * b_hat * s_down / (4 * kPi) * e_sun0 / mu_sun;
    ph.q_minus[i] = fourier * b_hat * s_up / (4 * kPi) * e_sun0 / mu_sun;
  }
  return ph;
}

// dL+/dy = A L+ + B L-, dL-/dy = -B L+ - A L-, A = M^-1 (-ĉ + 2π b̂ Pp W), B = M^-1 2π b̂ Pm W. The
// modes e^{σ y} have σ² the eigenvalues of (A - B)(A + B) = W^-1 T^½ (Y1 Y2) T^-½ W, T = W M^-1,
// Y1,2 = T^½ (ĉ W^-1 - 2π b̂ (Pp ∓ Pm)) T^½ symmetric positive definite (a > 0): with Y2 = C Cᵀ the
// symmetric Cᵀ Y1 C has the same eigenvalues (sigma2), and its eigenvector z gives Y1 Y2's as Y1 C z.
struct ModeEigen {
  std::vector<double> sigma2, z, y1c;  // N, N x N (columns), N x N (Y1 C)
};

ModeEigen modeEigen(const std::vector<double>& mu, const std::vector<double>& w, double c_hat, double b_hat,
                    const ModePhase& ph) {
  const int n = static_cast<int>(mu.size());
  std::vector<double> y1(n * n), y2(n * n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double tij = std::sqrt(w[i] / mu[i] * w[j] / mu[j]);
      const double diag = i == j ? c_hat / w[i] : 0.0;
      y1[i * n + j] = tij * (diag - 2 * kPi * b_hat * (ph.pp[i * n + j] - ph.pm[i * n + j]));
      y2[i * n + j] = tij * (diag - 2 * kPi * b_hat * (ph.pp[i * n + j] + ph.pm[i * n + j]));
    }
  std::vector<double> chol(n * n, 0.0);  // lower C, Y2 = C Cᵀ
  for (int i = 0; i < n; ++i)
    for (int j = 0; j <= i; ++j) {
      double s = y2[i * n + j];
      for (int k = 0; k < j; ++k) s -= chol[i * n + k] * chol[j * n + k];
      if (i == j) {
        if (!(s > 0)) throw std::runtime_error("discrete ordinates: the medium's matrix is not positive definite");
        chol[i * n + i] = std::sqrt(s);
      } else {
        chol[i * n + j] = s / chol[j * n + j];
      }
    }
  ModeEigen e;
  e.y1c.assign(n * n, 0.0);
  std::vector<double> sym(n * n, 0.0);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      double s = 0;
      for (int k = j; k < n; ++k) s += y1[i * n + k] * chol[k * n + j];
      e.y1c[i * n + j] = s;
    }
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      double s = 0;
      for (int k = i; k < n; ++k) s += chol[k * n + i] * e.y1c[k * n + j];
      sym[i * n + j] = s;
    }
  for (int i = 0; i < n; ++i)  // symmetric up to rounding: make it exactly so for Jacobi
    for (int j = i + 1; j < n; ++j) sym[i * n + j] = sym[j * n + i] = 0.5 * (sym[i * n + j] + sym[j * n + i]);
  symmetricEigen(sym, n, e.sigma2, e.z);
  return e;
}

// The beam's particular solution Z e^{-m y}: [A + m, B; -B, -A + m] Z = [-M^-1 Q+; M^-1 Q-], solved into
// z_plus, z_minus (zero without a beam). At a mode's λ = m it resonates: m is moved by 1e-7 of itself (its
// solution changes by about as much); returns the m used.
double particularSolution(const std::vector<double>& mu, const std::vector<double>& w, double c_hat, double b_hat,
                          double m_beam, const std::vector<double>& lambda, const ModePhase& ph, bool has_beam,
                          std::vector<double>& z_plus, std::vector<double>& z_minus) {
  const int n = static_cast<int>(mu.size());
  double m = m_beam;
  for (double lam : lambda)
    if (std::abs(lam - m) < 1e-7 * m) m = lam + (m >= lam ? 1e-7 : -1e-7) * m_beam;
  const int n2 = 2 * n;
  std::vector<double> sys(n2 * n2, 0.0), rhs(n2, 0.0);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double a_ij = (2 * kPi * b_hat * ph.pp[i * n + j] * w[j] - (i == j ? c_hat : 0.0)) / mu[i];
      const double b_ij = 2 * kPi * b_hat * ph.pm[i * n + j] * w[j] / mu[i];
      sys[i * n2 + j] = a_ij + (i == j ? m : 0.0);
      sys[i * n2 + n + j] = b_ij;
      sys[(n + i) * n2 + j] = -b_ij;
      sys[(n + i) * n2 + n + j] = -a_ij + (i == j ? m : 0.0);
    }
    rhs[i] = -ph.q_plus[i] / mu[i];
    rhs[n + i] = ph.q_minus[i] / mu[i];
  }
  if (has_beam) solveOrThrow(sys, rhs, n2);
  z_plus.assign(rhs.begin(), rhs.begin() + n);
  z_minus.assign(rhs.begin() + n, rhs.end());
  return m;
}

}  // namespace

DiscreteOrdinates::DiscreteOrdinates(const DiscreteOrdinatesLayer& layer, int streams, int azimuth_mode,
                                     int phase_moments) {
  requireValidLayer(layer, streams, azimuth_mode);
  mode_ = azimuth_mode;
  const bool hg = layer.moments.empty();
  const int n = n_ = streams;
  bottom_ = layer.bottom_depth > 0 ? layer.bottom_depth : 0;
  mu_sun_ = layer.mu_sun;
  e_sun0_ = layer.e_sun0;

  // Delta-M to the 2N moments the quadrature integrates exactly (Wiscombe 1977), or to fewer.
  requireRange(phase_moments >= 0 && phase_moments <= 2 * n, "the phase's moments must be in [0, 2 streams]");
  const int moments = 2 * n, kept = phase_moments > 0 ? phase_moments : moments;
  // An isotropic phase has one moment at any order.
  auto chi_of = [&](int l) {
    if (hg) return std::pow(layer.g, l);
    return l < static_cast<int>(layer.moments.size()) ? layer.moments[l] : 0.0;
  };
  surfaceQuadrature(n, layer.ior, hg && layer.g == 0 ? 1 : kept, mu_, w_);
  const double f = chi_of(kept);
  requireRange(f < 1, "the phase's moment at the delta-M order must be < 1");
  std::vector<double> chi(moments, 0.0);
  for (int l = 0; l < kept; ++l) chi[l] = (chi_of(l) - f) / (1 - f);
  const double b_hat = layer.b * (1 - f);
  // A little absorption keeps the conservative limit (a = 0: a mode that does not decay, a linear
  // solution) an exponential; 1e-6 of c changes the light by less than that over 1000 optical depths.
  const double a_hat = std::max({layer.a, 1e-6 * (layer.a + b_hat), 1e-9});
  const double c_hat = a_hat + b_hat;
  m_ = c_hat / mu_sun_;
  b_hat_ = b_hat;
  c_hat_ = c_hat;
  chi_ = chi;

  const ModePhase ph = modePhase(mode_, chi, mu_, mu_sun_, b_hat, e_sun0_);
  const ModeEigen eig = modeEigen(mu_, w_, c_hat, b_hat, ph);
  lambda_.assign(n, 0.0);
  x_plus_.assign(n * n, 0.0);
  x_minus_.assign(n * n, 0.0);
  k_min_ = 0;
  for (int j = 0; j < n; ++j) {
    const double lam = std::sqrt(std::max(eig.sigma2[j], 0.0));
    lambda_[j] = lam;
    // S = W^-1 T^½ Y1 C z; D = (A + B) S / σ with σ = -λ (the mode that decays downwards).
    std::vector<double> s(n);
    for (int i = 0; i < n; ++i) {
      double v = 0;
      for (int k = 0; k < n; ++k) v += eig.y1c[i * n + k] * eig.z[k * n + j];
      s[i] = std::sqrt(w_[i] / mu_[i]) / w_[i] * v;
    }
    for (int i = 0; i < n; ++i) {
      double apb = -c_hat * s[i];
      for (int k = 0; k < n; ++k) apb += 2 * kPi * b_hat * (ph.pp[i * n + k] + ph.pm[i * n + k]) * w_[k] * s[k];
      const double d = -(apb / mu_[i]) / lam;
      x_plus_[i * n + j] = 0.5 * (s[i] + d);
      x_minus_[i * n + j] = 0.5 * (s[i] - d);
    }
    k_min_ = j == 0 ? lam : std::min(k_min_, lam);
  }
  m_particular_ = particularSolution(mu_, w_, c_hat, b_hat, m_, lambda_, ph, e_sun0_ > 0, z_plus_, z_minus_);
  solveBoundaries(layer);
}

// Boundary conditions. Top: L+(0) = R L-(0) + the sky through the window, (1 - R) n² L_sky, scaled to
// e_sky0 (a shaped sky: (1 - R) S_m(μ) in mode m, scaled by mode 0's flux). Bottom: L-(H) = (ρ/π) (E_d(H)
// + s e_sun0 e^{-m H}), s the share of the beam it reflects. The uniform sky and the Lambertian bottom have
// no cos φ part: modes 1, 2 see neither (the surface reflects them as any radiance).
void DiscreteOrdinates::solveBoundaries(const DiscreteOrdinatesLayer& layer) {
  const int n = n_;
  const double m = m_particular_;
  std::vector<double> refl(n), sky(n);
  double sky_unit = 0;
  for (int i = 0; i < n; ++i) {
    refl[i] = kmath_d::fresnel_reflectance(mu_[i], layer.ior, 1.0);
    const std::array<double, 3> shape =
        layer.sky_shape ? layer.sky_shape(mu_[i]) : std::array<double, 3>{1.0, 0.0, 0.0};
    sky[i] = (1 - refl[i]) * shape[mode_];
    sky_unit += 2 * kPi * w_[i] * mu_[i] * (1 - refl[i]) * shape[0];
  }
  for (int i = 0; i < n; ++i) sky[i] = sky_unit > 0 ? sky[i] * layer.e_sky0 / sky_unit : 0.0;
  c_decay_.assign(n, 0.0);
  c_grow_.assign(n, 0.0);
  c_decay_sand_.assign(n, 0.0);
  c_grow_sand_.assign(n, 0.0);
  sand_beam_ = sand_diffuse_ = 0;
  if (!(bottom_ > 0)) {
    std::vector<double> sys(n * n, 0.0), rhs(n, 0.0);
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) sys[i * n + j] = x_plus_[i * n + j] - refl[i] * x_minus_[i * n + j];
      rhs[i] = sky[i] - (z_plus_[i] - refl[i] * z_minus_[i]);
    }
    solveOrThrow(sys, rhs, n);
    c_decay_ = rhs;
    return;
  }
  const int n2 = 2 * n;
  const double rho = mode_ == 0 ? layer.bottom_albedo : 0.0, em = std::exp(-m_ * bottom_), ep = std::exp(-m * bottom_);
  // Σ_k w_k μ_k of each mode's and the particular solution's down radiance (E_d / 2π at H, before the
  // modes' exponentials): the same for every row of the bottom's condition.
  std::vector<double> flux_dec(n, 0.0), flux_grow(n, 0.0);
  double flux_p = 0;
  for (int k = 0; k < n; ++k) {
    for (int j = 0; j < n; ++j) {
      flux_dec[j] += w_[k] * mu_[k] * x_plus_[k * n + j];
      flux_grow[j] += w_[k] * mu_[k] * x_minus_[k * n + j];
    }
    flux_p += w_[k] * mu_[k] * z_plus_[k];
  }
  // The system for bottom albedo rho (the bottom's rows reflect rho/π E_d).
  const auto system = [&](double albedo) {
    std::vector<double> sys(n2 * n2, 0.0);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const double e = std::exp(-lambda_[j] * bottom_);
        sys[i * n2 + j] = x_plus_[i * n + j] - refl[i] * x_minus_[i * n + j];
        sys[i * n2 + n + j] = e * (x_minus_[i * n + j] - refl[i] * x_plus_[i * n + j]);
        sys[(n + i) * n2 + j] = e * (x_minus_[i * n + j] - 2 * albedo * flux_dec[j]);
        sys[(n + i) * n2 + n + j] = x_plus_[i * n + j] - 2 * albedo * flux_grow[j];
      }
    return sys;
  };
  // E_d at the bottom over a black one, divided by 2π: the diffuse light the bottom reflects first.
  double flux_black = 0;
  if (rho > 0) {
    std::vector<double> sys = system(0.0), rhs(n2, 0.0);
    for (int i = 0; i < n; ++i) {
      rhs[i] = sky[i] - (z_plus_[i] - refl[i] * z_minus_[i]);
      rhs[n + i] = -ep * z_minus_[i];
    }
    solveOrThrow(sys, rhs, n2);
    flux_black = flux_p * ep;
    for (int j = 0; j < n; ++j)
      flux_black += rhs[j] * flux_dec[j] * std::exp(-lambda_[j] * bottom_) + rhs[n + j] * flux_grow[j];
  }
  // Two right-hand sides, one elimination: column 0 the whole field; column 1 the light a Lambertian bottom
  // sends per unit of the irradiance it reflects first, rho/π, with what that then sends back and forth
  // (FieldPart::sand_unit). The field is linear in what the bottom reflects: the whole field is the black
  // bottom's plus (bottom_sunlit sand_beam_ + sand_diffuse_) times column 1.
  std::vector<double> sys = system(rho), rhs(n2 * 2, 0.0);
  for (int i = 0; i < n; ++i) {
    rhs[2 * i] = sky[i] - (z_plus_[i] - refl[i] * z_minus_[i]);
    rhs[2 * (n + i)] = rho / kPi * layer.bottom_sunlit * e_sun0_ * em - ep * (z_minus_[i] - 2 * rho * flux_p);
    rhs[2 * (n + i) + 1] = rho / kPi;
  }
  solveOrThrow(sys, rhs, n2, 2);
  for (int j = 0; j < n; ++j) {
    c_decay_[j] = rhs[2 * j];
    c_grow_[j] = rhs[2 * (n + j)];
    c_decay_sand_[j] = rhs[2 * j + 1];
    c_grow_sand_[j] = rhs[2 * (n + j) + 1];
  }
  if (rho > 0) {
    sand_beam_ = e_sun0_ * em;
    sand_diffuse_ = 2 * kPi * flux_black;
  }
}

double DiscreteOrdinates::exponentialsAt(double depth, std::vector<double>& e_dec, std::vector<double>& e_grow) const {
  const int n = n_;
  const double y = bottom_ > 0 ? std::clamp(depth, 0.0, bottom_) : std::max(depth, 0.0);
  e_dec.assign(n, 0.0);
  e_grow.assign(n, 0.0);
  for (int j = 0; j < n; ++j) {
    e_dec[j] = std::exp(-lambda_[j] * y);
    if (bottom_ > 0) e_grow[j] = std::exp(-lambda_[j] * (bottom_ - y));
  }
  return y;
}

DiscreteOrdinatesIrradiance DiscreteOrdinates::at(double depth) const {
  std::vector<double> e_dec, e_grow;
  const double y = exponentialsAt(depth, e_dec, e_grow);
  return irradianceFrom(y, e_dec.data(), e_grow.data());
}

double DiscreteOrdinates::sampleExponentials(double depth_end, int samples, std::vector<double>& dec,
                                             std::vector<double>& grow) const {
  const int n = n_;
  const double end = bottom_ > 0 ? std::clamp(depth_end, 0.0, bottom_) : std::max(depth_end, 0.0);
  const double step = end / (samples - 1);
  // e^{-λ y_s} for every sample and mode (decaying, so the products only underflow towards 0, as the
  // exps would); the bottom's e^{-λ (H - y_s)} is the same sequence read backwards when the samples end
  // at H, and its own sequence from e^{-λ H} otherwise.
  dec.assign(static_cast<size_t>(samples) * n, 0.0);
  grow.assign(static_cast<size_t>(samples) * n, 0.0);
  for (int j = 0; j < n; ++j) {
    const double r = std::exp(-lambda_[j] * step);
    double e = 1;
    for (int s = 0; s < samples; ++s, e *= r) dec[size_t(s) * n + j] = e;
  }
  if (bottom_ > 0)
    for (int s = 0; s < samples; ++s)
      for (int j = 0; j < n; ++j)
        grow[size_t(s) * n + j] = end == bottom_ ? dec[size_t(samples - 1 - s) * n + j]
                                                 : std::exp(-lambda_[j] * (bottom_ - s * step));
  return step;
}

void DiscreteOrdinates::radiances(double depth, std::vector<double>& down, std::vector<double>& up) const {
  std::vector<double> e_dec, e_grow;
  const double y = exponentialsAt(depth, e_dec, e_grow);
  down.assign(n_, 0.0);
  up.assign(n_, 0.0);
  radiancesFrom(y, e_dec.data(), e_grow.data(), down.data(), up.data());
}

std::vector<DiscreteOrdinatesIrradiance> DiscreteOrdinates::profile(double depth_end, int samples) const {
  const int n = n_;
  samples = std::max(samples, 2);
  std::vector<double> dec, grow;
  const double step = sampleExponentials(depth_end, samples, dec, grow);
  std::vector<DiscreteOrdinatesIrradiance> out(samples);
  for (int s = 0; s < samples; ++s) out[s] = irradianceFrom(s * step, &dec[size_t(s) * n], &grow[size_t(s) * n]);
  return out;
}

std::vector<double> DiscreteOrdinates::inscatterProfile(const std::vector<double>& nus, double depth_end,
                                                        int samples, FieldPart part) const {
  const int n = n_, moments = static_cast<int>(chi_.size()), nu_count = static_cast<int>(nus.size());
  samples = std::max(samples, 2);
  // 2π b̂ w_j p^m(ν, ±μ_j): the phase's addition-theorem sum between each user cosine and each node.
  std::vector<std::vector<double>> pl(n);
  for (int j = 0; j < n; ++j) pl[j] = azimuthLegendre(mode_, moments, mu_[j]);
  std::vector<double> to_down(size_t(nu_count) * n), to_up(size_t(nu_count) * n);
  for (int u = 0; u < nu_count; ++u) {
    const std::vector<double> pu = azimuthLegendre(mode_, moments, std::clamp(nus[u], -1.0, 1.0));
    for (int j = 0; j < n; ++j) {
      double s_down = 0, s_up = 0;
      for (int l = 0; l < moments; ++l) {
        const double t = (2 * l + 1) * chi_[l] * pu[l] * pl[j][l];
        s_down += t;
        s_up += (l + mode_) % 2 ? -t : t;
      }
      to_down[size_t(u) * n + j] = 2 * kPi * b_hat_ * w_[j] * s_down / (4 * kPi);
      to_up[size_t(u) * n + j] = 2 * kPi * b_hat_ * w_[j] * s_up / (4 * kPi);
    }
  }
  std::vector<double> dec, grow;
  const double step = sampleExponentials(depth_end, samples, dec, grow);
  std::vector<double> out(size_t(samples) * nu_count, 0.0), down(n), up(n);
  for (int s = 0; s < samples; ++s) {
    radiancesFrom(s * step, &dec[size_t(s) * n], &grow[size_t(s) * n], down.data(), up.data(), part);
    for (int u = 0; u < nu_count; ++u) {
      double j_in = 0;
      for (int j = 0; j < n; ++j) j_in += to_down[size_t(u) * n + j] * down[j] + to_up[size_t(u) * n + j] * up[j];
      out[size_t(s) * nu_count + u] = j_in;
    }
  }
  return out;
}

std::vector<double> DiscreteOrdinates::tiltedIrradianceProfile(const std::vector<double>& n_ys, double depth_end,
                                                               int samples, FieldPart part) const {
  const int n = n_, count = static_cast<int>(n_ys.size());
  samples = std::max(samples, 2);
  // w_j K_m(±μ_j, n_y): the quadrature's weight of each stream on each plane (∫ dμ over a hemisphere is
  // Σ_j w_j; the azimuth integral is the kernel's).
  std::vector<double> from_down(size_t(count) * n), from_up(size_t(count) * n);
  for (int u = 0; u < count; ++u) {
    const double n_y = std::clamp(n_ys[u], -1.0, 1.0);
    for (int j = 0; j < n; ++j) {
      from_down[size_t(u) * n + j] = w_[j] * tiltedIrradianceKernel(mode_, mu_[j], n_y);
      from_up[size_t(u) * n + j] = w_[j] * tiltedIrradianceKernel(mode_, -mu_[j], n_y);
    }
  }
  std::vector<double> dec, grow;
  const double step = sampleExponentials(depth_end, samples, dec, grow);
  std::vector<double> out(size_t(samples) * count, 0.0), down(n), up(n);
  for (int s = 0; s < samples; ++s) {
    radiancesFrom(s * step, &dec[size_t(s) * n], &grow[size_t(s) * n], down.data(), up.data(), part);
    for (int u = 0; u < count; ++u) {
      double e = 0;
      for (int j = 0; j < n; ++j) e += from_down[size_t(u) * n + j] * down[j] + from_up[size_t(u) * n + j] * up[j];
      out[size_t(s) * count + u] = e;
    }
  }
  return out;
}

void DiscreteOrdinates::radiancesFrom(double y, const double* e_dec, const double* e_grow, double* down,
                                      double* up, FieldPart part) const {
  const int n = n_;
  // The bottom's reflection alone is a homogeneous solution: no particular part.
  const bool whole = part == FieldPart::whole;
  const double ep = whole ? std::exp(-m_particular_ * y) : 0.0;
  const std::vector<double>& c_dec = whole ? c_decay_ : c_decay_sand_;
  const std::vector<double>& c_gro = whole ? c_grow_ : c_grow_sand_;
  for (int i = 0; i < n; ++i) {
    double d = z_plus_[i] * ep, u = z_minus_[i] * ep;
    for (int j = 0; j < n; ++j) {
      d += c_dec[j] * x_plus_[i * n + j] * e_dec[j] + c_gro[j] * x_minus_[i * n + j] * e_grow[j];
      u += c_dec[j] * x_minus_[i * n + j] * e_dec[j] + c_gro[j] * x_plus_[i * n + j] * e_grow[j];
    }
    down[i] = d;
    up[i] = u;
  }
}

DiscreteOrdinatesIrradiance DiscreteOrdinates::irradianceFrom(double y, const double* e_dec, const double* e_grow) const {
  const int n = n_;
  std::vector<double> down(n), up(n);
  radiancesFrom(y, e_dec, e_grow, down.data(), up.data());
  DiscreteOrdinatesIrradiance out;
  for (int i = 0; i < n; ++i) {
    if (mode_ == 0) {
      out.down += 2 * kPi * w_[i] * mu_[i] * down[i];
      out.up += 2 * kPi * w_[i] * mu_[i] * up[i];
      out.scalar += 2 * kPi * w_[i] * (down[i] + up[i]);
      out.scalar_down += 2 * kPi * w_[i] * down[i];
      out.scalar_up += 2 * kPi * w_[i] * up[i];
    } else if (mode_ == 1) {  // ∫ L^1(μ) cos φ · √(1 - μ²) cos φ dφ dμ = π ∫ L^1 √(1 - μ²) dμ
      out.horizontal += kPi * w_[i] * std::sqrt(1 - mu_[i] * mu_[i]) * (down[i] + up[i]);
    }
  }
  out.beam_down = e_sun0_ * std::exp(-m_ * y);
  out.beam_scalar = out.beam_down / mu_sun_;
  out.beam_horizontal = out.beam_scalar * std::sqrt(std::max(1 - mu_sun_ * mu_sun_, 0.0));
  return out;
}

}  // namespace seasim
