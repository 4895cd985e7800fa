// discrete_ordinates.h — the diffuse light of a plane-parallel water layer by discrete ordinates
// (Chandrasekhar 1960; the eigen-solution of Stamnes & Swanson 1981, as DISORT solves it), for
// underwater.model = "discrete_ordinates": the depth profiles of the diffuse plane irradiances E_d, E_u and the
// scalar irradiance E_0, and the in-scatter towards any direction, that the model's closed form is fitted
// to (underwater_ordinates_solver.*).
//
// The layer: homogeneous water (absorption a, scattering b, Henyey-Greenstein g) from the flat surface
// (y = 0) to a Lambertian bottom of albedo rho at depth H, or without a bottom (semi-infinite). Lit by the
// refracted sun beam (horizontal irradiance e_sun0 just below the surface, direction cosine mu_sun) and
// the sky seen through Snell's window (transmitted irradiance e_sky0; uniform, or its zenith and
// azimuth shape by mode, sky_shape). The surface reflects the
// upwelling light back down by Fresnel's law (total internal reflection outside the window).
//
// One azimuth mode of the radiance: the average (m = 0, all that plane irradiances and the scalar
// irradiance need) or the cos φ part (m = 1), on a quadrature of `streams` cosines per hemisphere:
// Gauss-Legendre split at the edge of Snell's window where the phase's moments allow (total internal
// reflection beyond it), double-Gauss otherwise (surfaceQuadrature in the .cpp). The HG phase is delta-M
// scaled to the 2 streams moments it resolves (Wiscombe 1977: f = g^(2 streams), so at 16 streams and
// g = 0.95 f = 0.19, and the unscattered beam then carries the peak's f), or to fewer (phase_moments). Solved in closed
// form per depth (eigenvalues of a symmetric N x N matrix by Jacobi rotations, the beam's particular
// solution and the boundary conditions by Gaussian elimination), in double.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <vector>

namespace seasim {

struct DiscreteOrdinatesLayer {
  double a = 0, b = 0, g = 0;  // 1/m, 1/m, HG asymmetry in (-1, 1)
  double bottom_depth = 0;     // m; <= 0: no bottom
  double bottom_albedo = 0;    // Lambertian, in [0, 1]
  double bottom_sunlit = 1;    // the share of the beam's irradiance the bottom reflects, in [0, 1] (0: a
                               // bottom in shadow, lit by the diffuse light alone)
  double ior = 1.34;           // the water's refractive index (the surface's Fresnel reflection)
  double mu_sun = 1;           // the refracted sun's direction cosine with the downward vertical, (0, 1]
  double e_sun0 = 0;           // the beam's irradiance on a horizontal plane just below the surface
  double e_sky0 = 0;           // the sky's transmitted irradiance just below the surface
  // The sky's shape below the surface by azimuth mode (S_0, S_1, S_2 of its radiance along the downward
  // cosine μ in water, φ from the sun beam's azimuth; underwater/sky_window_modes.h), any scale: the
  // surface's boundary is then (1 − R) S_m(μ), scaled so that mode 0 carries e_sky0. Empty: a uniform
  // sky (S_0 = 1, no azimuth modes).
  std::function<std::array<double, 3>(double mu)> sky_shape;
  // Any phase by its Legendre moments χ_0 = 1, χ_1 = g, ... (host/radiometry/phase_function.h); the
  // moments past the last given are 0. Empty: Henyey-Greenstein of g (χ_l = g^l).
  std::vector<double> moments;
};

// The diffuse light at one depth: the radiance without the (delta-M scaled) unscattered beam,
// integrated over the hemispheres. The beam's own part is beam_down (its horizontal irradiance) and
// beam_scalar (its scalar irradiance, beam_down / mu_sun).
// horizontal (azimuth mode 1 only; the others mode 0 only): the diffuse light's net flux along the
// sun's horizontal direction, ∫ L sinθ cos φ dΩ; beam_horizontal the beam's, beam_scalar √(1 - μ_sun²).
struct DiscreteOrdinatesIrradiance {
  double down = 0, up = 0, scalar = 0, horizontal = 0;
  double scalar_down = 0, scalar_up = 0;  // the diffuse scalar irradiance of each hemisphere (mode 0)
  double beam_down = 0, beam_scalar = 0, beam_horizontal = 0;
};

// ∫_0^{2π} max(0, ν n_y + √((1 - ν²)(1 - n_y²)) cos ψ) cos(m ψ) dψ, m in 0..2: what a plane of normal n
// (upward vertical n_y) collects of radiance L^m(ν) cos(m φ) travelling at downward cosine ν, ψ = φ - φ_n
// (φ_n the azimuth of -n). Closed form over the arc where the cosine factor is positive.
double tiltedIrradianceKernel(int mode, double nu, double n_y);

// The Henyey-Greenstein phase between downward cosines nu and mu in azimuth mode 0, 1 or 2, as the
// coefficient of cos(m Δφ): (2 - δ_m0) Σ_l (2l + 1) g^l q_l^m(ν) q_l^m(μ) / (4π) (the addition theorem,
// q_l^m the normalised associated Legendre functions), summed until g^l < 1e-10. Per sr.
double hgAzimuthMode(double g, int mode, double nu, double mu);

// Any function of the scattering angle's cosine, f(cos Θ) with cos Θ = ν μ + √(1 - ν²) √(1 - μ²) cos Δφ
// between downward cosines nu and mu, in azimuth modes 0, 1, 2 as coefficients of cos(m Δφ) (the same
// convention): the midpoint rule on `azimuths` points over [0, π], f being even in Δφ. For the phases the
// kernel uses that have no series (its capped TMS phase, the forward peak's aureole).
template <class F>
std::array<double, 3> azimuthModes(double nu, double mu, int azimuths, F f) {
  std::array<double, 3> m{0, 0, 0};
  const double sin_nu = std::sqrt(std::max(1 - nu * nu, 0.0)), sin_mu = std::sqrt(std::max(1 - mu * mu, 0.0));
  for (int i = 0; i < azimuths; ++i) {
    const double c1 = std::cos(3.14159265358979323846 * (i + 0.5) / azimuths);
    const double v = f(std::clamp(nu * mu + sin_nu * sin_mu * c1, -1.0, 1.0));
    // cos(m Δφ) for m = 0, 1, 2 from the one cosine (the host's set-up spent a tenth of a frame in cos here).
    const double cos_m[3] = {1.0, c1, 2 * c1 * c1 - 1};
    for (int mode = 0; mode < 3; ++mode) m[mode] += (mode == 0 ? 1.0 : 2.0) * cos_m[mode] * v / azimuths;
  }
  return m;
}

// Which light of the field a profile holds: all of it; or only the light a Lambertian bottom sends per unit
// of the irradiance it reflects first (W m^-2 on the sand; its albedo/π), with what that then sends back and
// forth between the bottom and the surface (0 without a bottom, over a black one and in modes 1, 2). The
// whole field is the black bottom's plus (bottom_sunlit sandBeam() + sandDiffuse()) times sand_unit.
enum class FieldPart { whole, sand_unit };

class DiscreteOrdinates {
 public:
  // streams: cosines per hemisphere, >= 2. azimuth_mode: 0 the azimuth-averaged radiance (down, up,
  // scalar), 1 its cos φ part (horizontal). Throws std::invalid_argument on negative IOPs, |g| >= 1,
  // mu_sun outside (0, 1], an albedo outside [0, 1] or another mode.
  // phase_moments: the delta-M order M (Wiscombe 1977: f = g^M, the phase's first M Legendre moments
  // kept, the rest 0), in [1, 2 streams]; 0: 2 streams, the most the quadrature integrates.
  explicit DiscreteOrdinates(const DiscreteOrdinatesLayer& layer, int streams = 16, int azimuth_mode = 0,
                             int phase_moments = 0);

  DiscreteOrdinatesIrradiance at(double depth) const;
  // at() at `samples` (>= 2) evenly spaced depths from 0 to depth_end, each mode's exponentials taken as
  // geometric sequences (one exp per mode rather than one per depth).
  std::vector<DiscreteOrdinatesIrradiance> profile(double depth_end, int samples) const;
  // The quadrature's cosines (N, ascending in (0, 1)) and the diffuse radiance of this azimuth mode along
  // them at depth y: down[i] travelling down at cosines()[i], up[i] up.
  const std::vector<double>& cosines() const { return mu_; }
  void radiances(double depth, std::vector<double>& down, std::vector<double>& up) const;
  // The slowest decay of the homogeneous solution, 1/m: the diffuse field's asymptotic K∞.
  double asymptoticK() const { return k_min_; }
  // The unscattered beam's decay with depth, c_hat / mu_sun, 1/m (c_hat: the delta-M extinction).
  double beamK() const { return m_; }
  // The delta-M extinction c_hat = a + b (1 - f), f = g^(2 streams), 1/m: what the radiance along a ray
  // decays by between the in-scatter it gathers (inscatterProfile).
  double extinction() const { return c_hat_; }
  // The diffuse light's in-scatter towards the downward direction cosines `nus` (in [-1, 1]) at `samples`
  // (>= 2) evenly spaced depths from 0 to depth_end, per m per sr: this azimuth mode's
  // b_hat ∫ p^m(ν, μ') L^m(μ') dΩ' (the delta-M phase's 2 streams Legendre terms against the quadrature's
  // radiance; the beam's own scattering left out: the caller adds it with the exact phase, Nakajima &
  // Tanaka 1988's TMS). Mode 1's is the coefficient of cos φ, φ from the sun's azimuth. Integrated along
  // a ray with extinction() it gives the radiance at any angle (the source-function integration of
  // DISORT's user angles). Row-major, samples x nus.size(). part: the whole field's in-scatter, or only that of
  // the light the bottom reflects, per unit of what it reflects first (FieldPart).
  std::vector<double> inscatterProfile(const std::vector<double>& nus, double depth_end, int samples,
                                       FieldPart part = FieldPart::whole) const;
  // The diffuse light's irradiance on a plane whose unit normal has the upward vertical component n_y (in
  // [-1, 1]) at `samples` (>= 2) evenly spaced depths from 0 to depth_end: this azimuth mode's
  // ∫ L^m(ω) cos(m φ) max(0, -ω·n) dΩ with the normal's azimuth φ_n at 0, so the coefficient of cos(m φ_n),
  // φ_n the azimuth of -n from the sun beam's (tiltedIrradianceKernel). n_y = 1 gives E_d (mode 0), -1 E_u;
  // at n_y = 0 mode 1 gives half the horizontal flux. Row-major, samples x n_ys.size(). part: the whole
  // field's, or only the bottom's per unit of what it reflects first (FieldPart; times sandBeam(): what a face
  // seeing the bottom in shadow lacks).
  std::vector<double> tiltedIrradianceProfile(const std::vector<double>& n_ys, double depth_end, int samples,
                                              FieldPart part = FieldPart::whole) const;
  // The irradiance the bottom reflects first, W m^-2 on the sand (0 without a bottom, over a black one and in
  // modes 1, 2): of the whole beam, whatever bottom_sunlit is (e_sun0 e^{-m H}); of the diffuse light, E_d(H)
  // of the field over a black bottom.
  double sandBeam() const { return sand_beam_; }
  double sandDiffuse() const { return sand_diffuse_; }

 private:
  // The modes' amplitudes from the surface's and the bottom's conditions (the constructor's last step).
  void solveBoundaries(const DiscreteOrdinatesLayer& layer);
  // The irradiances at depth y from the modes' exponentials there (e_grow: e^{-λ (H - y)}, 0 without a bottom).
  DiscreteOrdinatesIrradiance irradianceFrom(double y, const double* e_dec, const double* e_grow) const;
  // The depth clamped to the layer, and each mode's e^{-λ y} (e_dec) and e^{-λ (H - y)} (e_grow, 0 without
  // a bottom) there.
  double exponentialsAt(double depth, std::vector<double>& e_dec, std::vector<double>& e_grow) const;
  // The quadrature's radiances at depth y, down (L+) and up (L-), from the modes' exponentials there
  // (part: the whole field's, or the part a FieldPart brings).
  void radiancesFrom(double y, const double* e_dec, const double* e_grow, double* down, double* up,
                     FieldPart part = FieldPart::whole) const;
  // The depths of profile(depth_end, samples) (clamped to the layer) and each mode's e^{-λ y_s} (dec) and
  // e^{-λ (H - y_s)} (grow, 0 without a bottom), samples x N, as geometric sequences.
  double sampleExponentials(double depth_end, int samples, std::vector<double>& dec, std::vector<double>& grow) const;

  int n_ = 0, mode_ = 0;
  double bottom_ = 0, m_ = 0, m_particular_ = 0, k_min_ = 0, mu_sun_ = 1, e_sun0_ = 0, b_hat_ = 0, c_hat_ = 0;
  std::vector<double> chi_;                    // the delta-M phase's Legendre moments, 2N
  std::vector<double> mu_, w_;                 // the N positive cosines and their weights
  std::vector<double> lambda_;                 // N decay rates, 1/m
  std::vector<double> x_plus_, x_minus_;       // N x N: mode j's down (x_plus_) and up radiances at cosine i
  std::vector<double> z_plus_, z_minus_;       // N: the particular solution's down and up radiances
  std::vector<double> c_decay_, c_grow_;       // N each: the modes' amplitudes
  std::vector<double> c_decay_sand_, c_grow_sand_;  // N each: those of FieldPart::sand_unit
  double sand_beam_ = 0, sand_diffuse_ = 0;         // sandBeam(), sandDiffuse()
};

}  // namespace seasim
