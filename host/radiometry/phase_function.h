// phase_function.h — the water's scattering phase function β̃(ψ) (per sr, ∫ β̃ dΩ = 1) as a scene names it,
// with what each solver takes from it:
//
// | kind             | parameters                 | formula (kernels/common/phase.h)                        |
// |------------------|----------------------------|---------------------------------------------------------|
// | henyey_greenstein| g in (-1, 1)               | optics.h hg_phase                                       |
// | rayleigh_like    | none                       | (1 + 0.835 cos²ψ) / (4π (1 + 0.835/3)), Mobley 1993 pb 1 |
// | fournier_forand  | b_b/b in [0.001, 0.5]      | Fournier & Forand 1994 with n = 1.10, ν solved from b_b/b|
// | table            | CSV (angle_deg, value)     | log-log interpolation, normalised on load               |
//
// Tables: between nodes ln β̃ is linear in ln ψ (the power laws of measured forward peaks); below the
// first angle the first segment's power law continues to ψ = 0 when it is integrable (slope > -2; else
// β̃ is held at the first value), and beyond the last angle the last value holds. The table is then
// normalised so ∫ β̃ dΩ = 1.
//
// What the solvers take:
//   - the path tracer samples the phase exactly up to its inverse-CDF table's resolution
//     (samplingTable; phase.h phase_table_sample_omc); HG keeps its closed-form sampler;
//   - the discrete-ordinates solver takes the first 2N Legendre moments χ_l (legendreMoments) and
//     delta-M scales them (Wiscombe 1977, f = χ_2N);
//   - the closed-form K_d / froxel models take only g = χ_1 (asymmetry()) as an HG phase's g: what that
//     costs is measured in docs/radiometry.md (HG of the same g against the phase itself).
//
// Moments, backscatter ratio and the sampling table come from one quadrature over ψ: 4000 nodes
// logarithmic in ψ from 1e-7 rad to 0.1 rad (the trapezoid rule in ln ψ, exact for power laws in the
// limit), 20000 linear from 0.1 rad to π (l up to 512 resolved), and the power law's closed form below
// 1e-7 rad (for Fournier–Forand at b_b/b = 0.001 that head holds most of the scattering).
#pragma once
#include <string>
#include <vector>

namespace seasim {

class PhaseFunction {
 public:
  enum class Kind { HenyeyGreenstein, RayleighLike, FournierForand, Table };

  // Throws std::invalid_argument outside the ranges in the table above.
  static PhaseFunction henyeyGreenstein(double g);
  static PhaseFunction rayleighLike();
  static PhaseFunction fournierForand(double bb_ratio);
  // angles_deg strictly increasing in (0, 180], values > 0 and finite, at least two; `source` names the
  // data in messages. Throws std::invalid_argument with the offending row (0-based) otherwise.
  static PhaseFunction table(const std::vector<double>& angles_deg, const std::vector<double>& values,
                             const std::string& source);
  // A CSV file with columns angle_deg and phase_per_sr (or the first two columns); RuntimeError
  // "FILE:LINE: ..." on a malformed or out-of-range row.
  static PhaseFunction loadTable(const std::string& path);
  // data/phase/petzold_average_particle.csv (provenance in data/phase/README.md).
  static PhaseFunction petzold();

  Kind kind() const { return kind_; }
  const std::string& name() const { return name_; }
  // β̃ at the scattering angle ψ in [0, π] (rad), per sr, normalised. Finite at ψ = 0 for every kind
  // (phase.h's clamps; a table's power law at ψ = 1e-9 rad).
  double evaluate(double psi) const;
  // χ_0 .. χ_{count-1}: χ_l = 2π ∫ β̃ P_l(cos ψ) sin ψ dψ (χ_0 = 1; HG's exactly g^l).
  std::vector<double> legendreMoments(int count) const;
  double asymmetry() const;           // g = χ_1
  double backscatterRatio() const;    // b_b/b = 2π ∫_{π/2}^{π} β̃ sin ψ dψ
  // The Fournier–Forand parameters (phase.h): ν and k (0 for the other kinds).
  double ffNu() const { return ff_nu_; }
  double ffK() const { return ff_k_; }
  // The inverse CDF for phase_table_sample_omc: `size` (>= 2) values of 1 - cos ψ at u_i = i / (size - 1).
  std::vector<double> samplingTable(int size) const;
  // The values for phase_table_value: `size` (>= 2) values of β̃ at log-spaced 1 - cos ψ (phase.h).
  std::vector<double> valueTable(int size) const;
  // The image path tracer's tables (reference.cl): valueTable(PHASE_PT_VALUES) then
  // samplingTable(PHASE_PT_SAMPLES), in float.
  std::vector<float> pathTracerTables() const;
  // The probability that ψ lies in [psi0, psi1] (rad), from the quadrature (tests' χ² bins).
  double probabilityBetween(double psi0, double psi1) const;

 private:
  double rawValue(double psi) const;  // before the table's normalisation
  void buildQuadrature();

  Kind kind_ = Kind::HenyeyGreenstein;
  std::string name_;
  double g_ = 0, ff_nu_ = 0, ff_k_ = 0;
  std::vector<double> table_ln_psi_, table_ln_value_;  // the table's nodes
  double table_head_slope_ = 0;                        // d ln β̃ / d ln ψ below the first node
  double table_scale_ = 1;                             // normalisation
  // The quadrature: nodes ψ_q (ascending), the weight of each (β̃ 2π sin ψ dψ summed there), and the
  // cumulative probability at each node including the head below the first.
  std::vector<double> q_psi_, q_weight_, q_cdf_;
  double head_probability_ = 0, head_exponent_ = 0;  // below q_psi_[0]: P ∝ ψ^head_exponent_
};

}  // namespace seasim
