#include "radiometry/phase_function.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "math/kernel_math.h"
#include "spectral/csv_table.h"
#include "util/error.h"
#include "util/paths.h"

namespace seasim {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kPsiLow = 1e-7, kPsiSplit = 0.1;
constexpr int kLogNodes = 4000, kLinearNodes = 20000;
// Fournier–Forand's particle index relative to water: Mobley, Sundman & Boss (2002) fix n = 1.10 and
// take the Junge slope from b_b/b; at n = 1.10, b_b/b spans (0, 0.5] as ν runs over [-1, 0).
constexpr double kFfIndex = 1.10;

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

}  // namespace

PhaseFunction PhaseFunction::henyeyGreenstein(double g) {
  if (!(std::abs(g) < 1)) throw std::invalid_argument("henyey_greenstein: |g| must be < 1, got " + fmt(g));
  PhaseFunction p;
  p.kind_ = Kind::HenyeyGreenstein;
  p.name_ = "hg";
  p.g_ = g;
  p.buildQuadrature();
  return p;
}

PhaseFunction PhaseFunction::rayleighLike() {
  PhaseFunction p;
  p.kind_ = Kind::RayleighLike;
  p.name_ = "rayleigh_like";
  p.buildQuadrature();
  return p;
}

PhaseFunction PhaseFunction::fournierForand(double bb_ratio) {
  if (!(bb_ratio >= 0.001 && bb_ratio <= 0.5))
    throw std::invalid_argument("fournier_forand: b_b/b must be in [0.001, 0.5], got " + fmt(bb_ratio));
  PhaseFunction p;
  p.kind_ = Kind::FournierForand;
  p.name_ = "fournier_forand";
  p.ff_k_ = 4.0 / (3.0 * (kFfIndex - 1) * (kFfIndex - 1));
  // b_b/b falls monotonically from 0.5 at ν = -1 to 0 as ν -> 0: bisection to double precision.
  double lo = -1.0, hi = -1e-9;
  for (int it = 0; it < 200 && hi - lo > 1e-15; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (kmath_d::phase_fournier_forand_bb(mid, p.ff_k_) > bb_ratio) lo = mid;
    else hi = mid;
  }
  p.ff_nu_ = 0.5 * (lo + hi);
  p.buildQuadrature();
  return p;
}

PhaseFunction PhaseFunction::table(const std::vector<double>& angles_deg, const std::vector<double>& values,
                                   const std::string& source) {
  if (angles_deg.size() != values.size() || angles_deg.size() < 2)
    throw std::invalid_argument(source + ": a phase table needs at least two rows of angle and value");
  PhaseFunction p;
  p.kind_ = Kind::Table;
  p.name_ = source;
  for (size_t i = 0; i < angles_deg.size(); ++i) {
    const double a = angles_deg[i], v = values[i];
    if (!(a > 0 && a <= 180) || (i > 0 && !(a > angles_deg[i - 1])))
      throw std::invalid_argument(source + ": row " + std::to_string(i) + ": angle " + fmt(a) +
                                  " deg: angles must increase strictly within (0, 180]");
    if (!(v > 0 && std::isfinite(v)))
      throw std::invalid_argument(source + ": row " + std::to_string(i) + ": value " + fmt(v) +
                                  " must be finite and > 0");
    p.table_ln_psi_.push_back(std::log(a * kPi / 180));
    p.table_ln_value_.push_back(std::log(v));
  }
  const double slope = (p.table_ln_value_[1] - p.table_ln_value_[0]) / (p.table_ln_psi_[1] - p.table_ln_psi_[0]);
  p.table_head_slope_ = slope > -2 ? slope : 0.0;  // a non-integrable power law: held constant instead
  p.table_scale_ = 1;
  p.buildQuadrature();
  // buildQuadrature normalised the cumulative; the values follow.
  return p;
}

PhaseFunction PhaseFunction::loadTable(const std::string& path) {
  const CsvTable t = loadCsv(path);
  const bool named = t.find("angle_deg") >= 0 && t.find("phase_per_sr") >= 0;
  if (!named && t.names.size() < 2)
    throw RuntimeError(path + ":1: a phase table needs two columns, angle_deg and phase_per_sr");
  const std::vector<double>& a = named ? t.column("angle_deg") : t.columns[0];
  const std::vector<double>& v = named ? t.column("phase_per_sr") : t.columns[1];
  for (size_t r = 0; r < t.rows(); ++r) {
    const std::string where = path + ":" + std::to_string(t.lines[r]) + ": ";
    if (std::isnan(a[r]) || std::isnan(v[r])) throw RuntimeError(where + "empty cell in a phase table");
    if (!(a[r] > 0 && a[r] <= 180) || (r > 0 && !(a[r] > a[r - 1])))
      throw RuntimeError(where + "angle " + fmt(a[r]) + " deg: angles must increase strictly within (0, 180]");
    if (!(v[r] > 0 && std::isfinite(v[r])))
      throw RuntimeError(where + "phase value " + fmt(v[r]) + " must be finite and > 0");
  }
  if (t.rows() < 2) throw RuntimeError(path + ": a phase table needs at least two rows");
  return table(a, v, path);
}

PhaseFunction PhaseFunction::petzold() {
  PhaseFunction p = loadTable(dataDir() + "/phase/petzold_average_particle.csv");
  p.name_ = "petzold";
  return p;
}

double PhaseFunction::rawValue(double psi) const {
  psi = std::clamp(psi, 0.0, kPi);
  const double s = std::sin(0.5 * psi), omc = 2 * s * s;  // 1 - cos ψ without cancellation
  switch (kind_) {
    case Kind::HenyeyGreenstein: return kmath_d::hg_phase(std::cos(psi), g_);
    case Kind::RayleighLike: return kmath_d::phase_rayleigh_like(std::cos(psi));
    case Kind::FournierForand: return kmath_d::phase_fournier_forand(omc, ff_nu_, ff_k_);
    case Kind::Table: {
      const double lp = std::log(std::max(psi, 1e-9));
      const size_t n = table_ln_psi_.size();
      if (lp <= table_ln_psi_[0]) return std::exp(table_ln_value_[0] + table_head_slope_ * (lp - table_ln_psi_[0]));
      if (lp >= table_ln_psi_[n - 1]) return std::exp(table_ln_value_[n - 1]);
      const size_t i = std::upper_bound(table_ln_psi_.begin(), table_ln_psi_.end(), lp) - table_ln_psi_.begin() - 1;
      const double t = (lp - table_ln_psi_[i]) / (table_ln_psi_[i + 1] - table_ln_psi_[i]);
      return std::exp(table_ln_value_[i] + t * (table_ln_value_[i + 1] - table_ln_value_[i]));
    }
  }
  return 0;
}

double PhaseFunction::evaluate(double psi) const { return table_scale_ * rawValue(psi); }

void PhaseFunction::buildQuadrature() {
  // Nodes: logarithmic on [ψ_low, ψ_split], linear on [ψ_split, π] (the split node once).
  q_psi_.clear();
  const double step_ln = std::log(kPsiSplit / kPsiLow) / kLogNodes;
  for (int i = 0; i <= kLogNodes; ++i) q_psi_.push_back(kPsiLow * std::exp(i * step_ln));
  const double step_lin = (kPi - kPsiSplit) / kLinearNodes;
  for (int i = 1; i <= kLinearNodes; ++i) q_psi_.push_back(kPsiSplit + i * step_lin);
  q_psi_.back() = kPi;
  const size_t n = q_psi_.size();
  // Trapezoid weights of β̃ 2π sin ψ: dψ = ψ d(ln ψ) on the log part.
  std::vector<double> f(n);
  for (size_t q = 0; q < n; ++q) f[q] = rawValue(q_psi_[q]) * 2 * kPi * std::sin(q_psi_[q]);
  q_weight_.assign(n, 0.0);
  for (int i = 0; i < kLogNodes; ++i) {
    const double half = 0.5 * step_ln;
    q_weight_[i] += half * q_psi_[i] * f[i];
    q_weight_[i + 1] += half * q_psi_[i + 1] * f[i + 1];
  }
  for (size_t q = kLogNodes; q + 1 < n; ++q) {
    const double half = 0.5 * (q_psi_[q + 1] - q_psi_[q]);
    q_weight_[q] += half * f[q];
    q_weight_[q + 1] += half * f[q + 1];
  }
  // The head below ψ_low: the power law through the first two nodes, 2π ∫_0^ψ0 β̃0 (ψ/ψ0)^m ψ dψ.
  const double b0 = rawValue(q_psi_[0]), b1 = rawValue(q_psi_[1]);
  const double m = std::log(b1 / b0) / std::log(q_psi_[1] / q_psi_[0]);
  head_exponent_ = m > -2 ? m + 2 : 2.0;
  head_probability_ = 2 * kPi * b0 * q_psi_[0] * q_psi_[0] / head_exponent_;
  // The cumulative at each node (segment by segment, the same trapezoids).
  q_cdf_.assign(n, 0.0);
  q_cdf_[0] = head_probability_;
  for (size_t q = 0; q + 1 < n; ++q) {
    const double seg = q < static_cast<size_t>(kLogNodes)
                           ? 0.5 * step_ln * (q_psi_[q] * f[q] + q_psi_[q + 1] * f[q + 1])
                           : 0.5 * (q_psi_[q + 1] - q_psi_[q]) * (f[q] + f[q + 1]);
    q_cdf_[q + 1] = q_cdf_[q] + seg;
  }
  const double total = q_cdf_.back();
  if (kind_ == Kind::Table) table_scale_ = 1 / total;  // normalised on load
  // Moments and sampling use the quadrature normalised to itself (the analytic kinds' totals differ from 1
  // by the quadrature's error alone, which χ_0 = 1 then absorbs).
  for (double& w : q_weight_) w /= total;
  for (double& c : q_cdf_) c /= total;
  head_probability_ /= total;
}

std::vector<double> PhaseFunction::legendreMoments(int count) const {
  if (count < 1) throw std::invalid_argument("legendreMoments: count must be >= 1");
  std::vector<double> chi(count, 0.0);
  if (kind_ == Kind::HenyeyGreenstein) {
    double gl = 1;
    for (int l = 0; l < count; ++l, gl *= g_) chi[l] = gl;
    return chi;
  }
  // The head: cos ψ ≈ 1 below 1e-7 rad, P_l = 1 there to l² 1e-14.
  for (int l = 0; l < count; ++l) chi[l] = head_probability_;
  for (size_t q = 0; q < q_psi_.size(); ++q) {
    const double x = std::cos(q_psi_[q]), w = q_weight_[q];
    double p0 = 1, p1 = x;
    chi[0] += w;
    if (count > 1) chi[1] += w * x;
    for (int l = 2; l < count; ++l) {
      const double p2 = ((2 * l - 1) * x * p1 - (l - 1) * p0) / l;
      chi[l] += w * p2;
      p0 = p1;
      p1 = p2;
    }
  }
  const double norm = chi[0];
  for (double& c : chi) c /= norm;
  return chi;
}

std::vector<double> PhaseFunction::valueTable(int size) const {
  if (size < 2) throw std::invalid_argument("valueTable: size must be >= 2");
  std::vector<double> v(size);
  const double lo = 1e-9, ratio = std::log(2 / lo);
  for (int i = 0; i < size; ++i) {
    const double omc = std::min(lo * std::exp(ratio * i / (size - 1)), 2.0);
    v[i] = evaluate(2 * std::asin(std::sqrt(omc / 2)));  // ψ from 1 - cos ψ without cancellation
  }
  return v;
}

std::vector<float> PhaseFunction::pathTracerTables() const {
  const std::vector<double> v = valueTable(PHASE_PT_VALUES), u = samplingTable(PHASE_PT_SAMPLES);
  std::vector<float> out(v.begin(), v.end());
  out.insert(out.end(), u.begin(), u.end());
  return out;
}

double PhaseFunction::asymmetry() const {
  return kind_ == Kind::HenyeyGreenstein ? g_ : legendreMoments(2)[1];
}

double PhaseFunction::backscatterRatio() const { return 1 - probabilityBetween(0, 0.5 * kPi); }

double PhaseFunction::probabilityBetween(double psi0, double psi1) const {
  auto cdf = [&](double psi) {
    if (psi <= 0) return 0.0;
    if (psi <= q_psi_[0]) return head_probability_ * std::pow(psi / q_psi_[0], head_exponent_);
    if (psi >= kPi) return 1.0;
    const size_t i = std::upper_bound(q_psi_.begin(), q_psi_.end(), psi) - q_psi_.begin() - 1;
    // Within a node interval the integrand is near linear: the cumulative is near quadratic, but the
    // intervals (≤ 1.6e-4 rad, ≤ 0.35 % of ψ) make linear interpolation good to their own size squared.
    const double t = (psi - q_psi_[i]) / (q_psi_[i + 1] - q_psi_[i]);
    return q_cdf_[i] + t * (q_cdf_[i + 1] - q_cdf_[i]);
  };
  return std::max(cdf(std::min(psi1, kPi)) - cdf(std::max(psi0, 0.0)), 0.0);
}

std::vector<double> PhaseFunction::samplingTable(int size) const {
  if (size < 2) throw std::invalid_argument("samplingTable: size must be >= 2");
  std::vector<double> omc(size, 0.0);
  for (int i = 1; i < size - 1; ++i) {
    const double u = static_cast<double>(i) / (size - 1);
    double psi;
    if (u <= head_probability_) {
      psi = q_psi_[0] * std::pow(u / head_probability_, 1 / head_exponent_);
    } else {
      const size_t q = std::upper_bound(q_cdf_.begin(), q_cdf_.end(), u) - q_cdf_.begin() - 1;
      const size_t k = std::min(q, q_cdf_.size() - 2);
      const double span = q_cdf_[k + 1] - q_cdf_[k];
      const double t = span > 0 ? std::clamp((u - q_cdf_[k]) / span, 0.0, 1.0) : 0.0;
      psi = q_psi_[k] + t * (q_psi_[k + 1] - q_psi_[k]);
    }
    const double s = std::sin(0.5 * psi);
    omc[i] = 2 * s * s;
  }
  omc[size - 1] = 2;
  for (int i = 1; i < size; ++i) omc[i] = std::max(omc[i], omc[i - 1]);  // monotone despite rounding
  return omc;
}

}  // namespace seasim
