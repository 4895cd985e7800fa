#include "radiometry/light_profile_mc.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "math/kernel_math.h"
#include "reference/batch_error.h"

namespace seasim {
namespace {

namespace kd = kmath_d;
constexpr double kPi = 3.14159265358979323846;
constexpr double kInf = std::numeric_limits<double>::infinity();

// The scored quantities, in the order of LightAtDepth's fields; one photon's scores at [field * depths + k].
enum Field { kEd, kEu, kE0d, kE0u, kLu, kFields };

struct Geometry {
  const std::vector<double>& z;  // the depths
  std::vector<double> lo, hi;    // the E_0 layers [z - Δ, z + Δ] clipped to the water
  double bottom;                 // m; 0: none
  double c;
  double cap_cos, cap_solid;     // L_u's cap: cos of its half-angle, its solid angle
  // Depths on the bottom: E_0u there is the Lambertian bottom's exactly, 2 E_u (the layer's mean would be
  // low by ~1.5 %: E_0u falls as E_2(c x) above the bottom, steepest at it).
  std::vector<char> on_bottom;
  size_t n() const { return z.size(); }
  bool layerScores(size_t k, double mu) const { return !(mu < 0 && on_bottom[k]); }
};

// The analog estimator's scores of what a photon does (light_profile_mc.h).
struct AnalogWalk {
  const Geometry& g;
  std::vector<double>& s;

  // The segment from z0 to z1 travelled with direction cosine mu (> 0 down) by weight w.
  void segment(double z0, double z1, double mu, double w) const {
    const double lo = std::min(z0, z1), hi = std::max(z0, z1);
    for (size_t k = 0; k < g.n(); ++k) {
      const double z = g.z[k];
      // A crossing counts when the plane lies between the start (excluded: leaving a boundary is counted
      // by leaves()) and the end (included: arriving on the surface or the bottom is a crossing).
      if (mu > 0 ? (z > z0 && z <= z1) : (z >= z1 && z < z0)) cross(k, mu, w);
      const double overlap = std::min(hi, g.hi[k]) - std::max(lo, g.lo[k]);
      if (overlap > 0 && g.layerScores(k, mu)) s[(mu > 0 ? kE0d : kE0u) * g.n() + k] += w * overlap / (std::abs(mu) * (g.hi[k] - g.lo[k]));
    }
  }
  // A photon leaving a boundary plane z_b (0 or the bottom) with direction cosine mu: the planes at z_b.
  void leaves(double z_b, double mu, double w) const {
    for (size_t k = 0; k < g.n(); ++k)
      if (g.z[k] == z_b) {
        cross(k, mu, w);
        if (g.on_bottom[k] && mu < 0) s[kE0u * g.n() + k] += 2 * w;  // a Lambertian bottom: E_0u = 2 E_u
      }
  }
  void cross(size_t k, double mu, double w) const {
    if (mu > 0) {
      s[kEd * g.n() + k] += w;
    } else {
      s[kEu * g.n() + k] += w;
      if (-mu >= g.cap_cos) s[kLu * g.n() + k] += w / (-mu * g.cap_solid);
    }
  }
};

// The next-event estimator's expected scores of a flight from z0 with direction cosine mu and weight w,
// over its exponential free path (P(s) = e^{-c s}) until the surface or the bottom: planes ahead (the
// start included) their transmittance, layers ahead their expected track length, and, going up within the
// cap, the radiance each plane sees along it. Adds w times these to s.
void expectedFlight(const Geometry& g, double z0, double mu, double w, std::vector<double>& s) {
  if (std::abs(mu) < 1e-12 || w == 0) return;
  const double s_max = mu > 0 ? (g.bottom > 0 ? (g.bottom - z0) / mu : kInf) : z0 / -mu;
  const bool in_cap = -mu >= g.cap_cos;
  const size_t n = g.n();
  for (size_t k = 0; k < n; ++k) {
    const double dist = (g.z[k] - z0) / mu;
    if (dist >= 0 && dist <= s_max) {
      const double t = std::exp(-g.c * dist);
      if (mu > 0) {
        s[kEd * n + k] += w * t;
      } else {
        s[kEu * n + k] += w * t;
        if (in_cap) s[kLu * n + k] += w * t / (-mu * g.cap_solid);
      }
    }
    double sa = mu > 0 ? (g.lo[k] - z0) / mu : (z0 - g.hi[k]) / -mu;
    double sb = mu > 0 ? (g.hi[k] - z0) / mu : (z0 - g.lo[k]) / -mu;
    sa = std::max(sa, 0.0);
    sb = std::min(sb, s_max);
    if (sb > sa && g.layerScores(k, mu)) {
      // ∫_{sa}^{sb} e^{-c s} ds without cancellation when the layer is thin.
      const double track = std::exp(-g.c * sa) * -std::expm1(-g.c * (sb - sa)) / g.c;
      s[(mu > 0 ? kE0d : kE0u) * n + k] += w * track / (g.hi[k] - g.lo[k]);
    }
  }
}

// One particle of the next-event walk: a photon or a split copy, with its own random stream.
struct Particle {
  double z, mu, w;
  unsigned key, dim;
};

// The checks of solveLightProfileMonteCarlo's inputs.
void validate(const PlaneParallelWater& water, const std::vector<double>& depths, const MonteCarloSettings& s) {
  if (s.photons < s.batches || s.batches < 2) throw std::invalid_argument("monte carlo: need photons >= batches >= 2");
  if (!(water.a >= 0 && water.b >= 0 && water.a + water.b > 0))
    throw std::invalid_argument("monte carlo: a, b must be >= 0 with c > 0");
  if (!(s.cap_deg > 0 && s.cap_deg < 90 && s.local_cap_deg > 0 && s.local_cap_deg < 90))
    throw std::invalid_argument("monte carlo: cap half-angles must be in (0, 90) degrees");
  for (double z : depths)
    if (!(z >= 0) || (water.bottom_depth > 0 && z > water.bottom_depth))
      throw std::invalid_argument("monte carlo: depths must lie in the water");
}

// The sources just below the surface (as light_profile.cpp's): the sun's refracted beam and a uniform
// sky's transmitted light, in W m^-2.
struct Sources {
  double mu_air, mu_w;  // the sun's direction cosine in air and in the water
  double e_sun0, e_sky0, t_sky;
  double flux() const { return e_sun0 + e_sky0; }
};

Sources surfaceSources(const PlaneParallelWater& water) {
  const double n = water.ior;
  Sources src;
  src.mu_air = std::cos(water.sun_zenith);
  const double sin_w = std::sin(water.sun_zenith) / n;
  src.mu_w = std::sqrt(1 - sin_w * sin_w);
  src.e_sun0 = water.sun_irradiance * src.mu_air * (1 - kd::fresnel_reflectance(src.mu_air, 1.0, n));
  src.t_sky = uniformSkyTransmittance(n);
  src.e_sky0 = water.sky_transmitted >= 0 ? water.sky_transmitted : water.sky_irradiance * src.t_sky;
  return src;
}

// The photon tracer of one water, phase and estimator: the samplers, the weight window and the bottom's
// expected scores, shared by every photon.
class PhotonTracer {
 public:
  PhotonTracer(const PlaneParallelWater& water, const PhaseFunction& phase, const std::vector<double>& depths,
               const MonteCarloSettings& s)
      : water_(water), nee_(s.estimator == MonteCarloSettings::Estimator::NextEvent), c_(water.a + water.b),
        omega_(water.b / c_), n_(water.ior), bottom_(water.bottom_depth > 0 ? water.bottom_depth : 0.0),
        geo_{depths, {}, {}, bottom_, c_, 0, 0, {}}, src_(surfaceSources(water)), w0_(src_.flux()),
        hg_(phase.kind() == PhaseFunction::Kind::HenyeyGreenstein), g_(hg_ ? phase.asymmetry() : 0.0) {
    for (double z : depths) deepest_ = std::max(deepest_, z);
    z_kill_ = bottom_ > 0 ? 2 * bottom_ + 1 : deepest_ + 40 / c_;  // below it no light returns (e^-40)
    const double layer = 0.005 / c_;
    for (double z : depths) {
      geo_.on_bottom.push_back(bottom_ > 0 && z == bottom_);
      geo_.lo.push_back(std::max(z - layer, 0.0));
      geo_.hi.push_back(bottom_ > 0 ? std::min(z + layer, bottom_) : z + layer);
    }
    geo_.cap_cos = std::cos((nee_ ? s.local_cap_deg : s.cap_deg) * kPi / 180);
    geo_.cap_solid = 2 * kPi * (1 - geo_.cap_cos);
    if (!hg_) table_ = phase.samplingTable(kTableSize);
    if (nee_) values_ = phase.valueTable(kValueSize);
    // The bottom's expected scores per unit reflected weight: the flight's over the Lambertian direction,
    // 2 μ dμ (midpoint rule; the integrands are bounded).
    bottom_scores_.assign(fields(), 0.0);
    if (nee_ && bottom_ > 0) {
      const int nodes = 20000;
      for (int i = 0; i < nodes; ++i) {
        const double mu = (i + 0.5) / nodes;
        expectedFlight(geo_, bottom_, -mu, 2 * mu / nodes, bottom_scores_);
      }
      for (size_t k = 0; k < geo_.n(); ++k)
        if (geo_.on_bottom[k]) bottom_scores_[kE0u * geo_.n() + k] = 2;
    }
    // The weight window's target W(z) = w0 e^{-κ min(z, deepest)} (light_profile_mc.h).
    kappa_ = !nee_ ? 0.0
             : s.importance_per_m >= 0
                 ? s.importance_per_m
                 : c_ * std::min(1.0, std::sqrt(3 * (1 - omega_) * (1 - omega_ * phase.asymmetry())));
    spacing_ = kappa_ > 0 ? 0.5 / kappa_ : 0.0;
    plane_limit_ = bottom_ > 0 ? std::min(deepest_, bottom_) : deepest_;
  }

  size_t fields() const { return kFields * geo_.n(); }
  const Sources& sources() const { return src_; }

  // Photon i's scores (W m^-2, one sample of each estimate) added into `scores`.
  void photon(unsigned seed, long long i, std::vector<double>& scores) {
    const unsigned key = kd::pt_path_key(seed, static_cast<unsigned>(i >> 32), static_cast<unsigned>(i));
    unsigned dim = 0;
    double w = w0_, mu;
    if (kd::pt_uniform(key, dim++) * src_.flux() < src_.e_sun0) {
      mu = src_.mu_w;
    } else {
      // A uniform sky: cosine-distributed in air, weighted by its transmittance relative to the mean, refracted.
      const double mu_a = std::sqrt(std::max(kd::pt_uniform(key, dim++), 1e-300));
      w *= (1 - kd::fresnel_reflectance(mu_a, 1.0, n_)) / src_.t_sky;
      mu = std::sqrt(1 - (1 - mu_a * mu_a) / (n_ * n_));
    }
    if (nee_)
      nextEventPhoton(Particle{0, mu, w, key, dim}, scores);
    else
      analogPhoton(key, dim, mu, w, scores);
  }

  long long collisions() const { return collisions_; }

 private:
  static constexpr int kTableSize = 8192, kValueSize = 4096;
  static constexpr int kMaxSplit = 16;
  static constexpr size_t kMaxParticles = 1 << 16;  // per photon: beyond it copies are not split (still unbiased)

  double phaseValue(double omc) const { return kd::phase_table_value(values_.data(), kValueSize, omc); }
  // 1 - cos ψ of a phase sample.
  double sampleOmc(double u) const {
    const double omc = hg_ ? kd::pt_hg_one_minus_cos(std::abs(g_), u) : kd::phase_table_sample_omc(table_.data(), kTableSize, u);
    return hg_ && g_ < 0 ? 2 - omc : omc;
  }
  double window(double z) const { return w0_ * std::exp(-kappa_ * std::min(z, deepest_)); }

  // The analog walk of one photon from the surface (light_profile_mc.h, "Analog").
  void analogPhoton(unsigned key, unsigned dim, double mu, double w, std::vector<double>& scores) {
    const AnalogWalk walk{geo_, scores};
    auto u = [&] { return kd::pt_uniform(key, dim++); };
    double z = 0;
    walk.leaves(0, mu, w);
    for (int step = 0; step < 100000; ++step) {
      const double dist = kd::pt_sample_distance(c_, u());
      double z1 = z + mu * dist;
      if (z1 <= 0) {  // the surface from below: Fresnel reflection or escape
        walk.segment(z, 0, mu, w);
        if (u() >= kd::fresnel_reflectance(-mu, n_, 1.0)) break;
        mu = -mu;
        z = 0;
        walk.leaves(0, mu, w);
        continue;
      }
      if (bottom_ > 0 && z1 >= bottom_) {  // the Lambertian bottom
        walk.segment(z, bottom_, mu, w);
        w *= water_.bottom_albedo;
        mu = -std::sqrt(std::max(u(), 1e-300));  // cosine-distributed up
        z = bottom_;
        walk.leaves(bottom_, mu, w);
      } else {
        walk.segment(z, z1, mu, w);
        z = z1;
        if (z > z_kill_) break;
        ++collisions_;
        w *= omega_;
        // The new direction: 1 - cos ψ from the phase, azimuth uniform; μ' = μ cos ψ + sin θ sin ψ cos φ.
        const double omc = sampleOmc(u());
        const double sin_psi = std::sqrt(std::max(omc * (2 - omc), 0.0));
        const double sin_mu = std::sqrt(std::max(1 - mu * mu, 0.0));
        mu = std::clamp(mu * (1 - omc) + sin_mu * sin_psi * std::cos(2 * kPi * u()), -1.0, 1.0);
      }
      if (w < 1e-3 * w0_) {  // Russian roulette: unbiased, weight restored on survival
        if (u() >= 0.1) break;
        w *= 10;
      }
      if (mu == 0) mu = 1e-12;  // a horizontal photon would never cross a plane
    }
  }

  // Splitting or Russian roulette of `p` about the window's weight at its depth; false: killed.
  bool windowed(Particle& p, size_t& spawned) {
    const double target = kappa_ > 0 ? window(p.z) : 1e-3 * w0_;
    if (kappa_ > 0 && p.w > 2 * target && spawned < kMaxParticles) {
      const int copies = std::min(static_cast<int>(p.w / target), kMaxSplit);
      p.w /= copies;
      for (int j = 1; j < copies; ++j) {
        const unsigned child = kd::pt_hash(p.key ^ kd::pt_hash(p.dim * 0x9e3779b9u + static_cast<unsigned>(j)));
        stack_.push_back(Particle{p.z, p.mu, p.w, child, 0});
      }
      spawned += copies - 1;
      p.dim++;
    } else if (p.w < 0.25 * target) {
      if (kd::pt_uniform(p.key, p.dim++) * target >= p.w) return false;
      p.w = target;
    }
    return true;
  }

  // The next-event walk of one photon and its split copies (light_profile_mc.h, "Next event").
  void nextEventPhoton(Particle start, std::vector<double>& scores) {
    expectedFlight(geo_, 0, start.mu, start.w, scores);
    stack_.assign(1, start);
    size_t spawned = 1;
    while (!stack_.empty()) {
      Particle p = stack_.back();
      stack_.pop_back();
      auto u = [&] { return kd::pt_uniform(p.key, p.dim++); };
      for (int step = 0; step < 100000; ++step) {
        const double z1 = p.z + p.mu * kd::pt_sample_distance(c_, u());
        if (kappa_ > 0) {
          // The window's planes every `spacing` down to the deepest depth asked: a flight that reaches one
          // stops there for the window (the free path is memoryless, so the next flight starts afresh).
          const double zp = p.mu > 0 ? (std::floor(p.z / spacing_ + 1e-9) + 1) * spacing_
                                     : (std::ceil(p.z / spacing_ - 1e-9) - 1) * spacing_;
          if (zp > 0 && zp < plane_limit_ && (p.mu > 0 ? zp < z1 : zp > z1)) {
            p.z = zp;
            if (!windowed(p, spawned)) break;
            continue;
          }
        }
        if (z1 <= 0) {  // the surface: the reflected share goes on as a weight
          p.w *= kd::fresnel_reflectance(-p.mu, n_, 1.0);
          p.mu = -p.mu;
          p.z = 0;
          expectedFlight(geo_, 0, p.mu, p.w, scores);
          if (p.w == 0 || !windowed(p, spawned)) break;
          continue;
        }
        if (bottom_ > 0 && z1 >= bottom_) {  // the Lambertian bottom: its exact expectation, then a direction
          p.w *= water_.bottom_albedo;
          for (size_t v = 0; v < scores.size(); ++v) scores[v] += p.w * bottom_scores_[v];
          p.mu = -std::sqrt(std::max(u(), 1e-300));
          p.z = bottom_;
          if (p.w == 0 || !windowed(p, spawned)) break;
          continue;
        }
        p.z = z1;
        if (p.z > z_kill_) break;
        ++collisions_;
        scatter(p, scores);
        if (!windowed(p, spawned)) break;
      }
    }
  }

  // A collision of `p`: next-event estimates over the scattered direction, the phase's sample (also the
  // walk's next direction), a uniform one and one in the cap, by the balance heuristic; then p goes on
  // in the phase's direction with its weight times ω.
  void scatter(Particle& p, std::vector<double>& scores) {
    auto u = [&] { return kd::pt_uniform(p.key, p.dim++); };
    const double cap_cos = geo_.cap_cos, inv_cap = 1 / geo_.cap_solid, inv_sphere = 1 / (4 * kPi);
    const double w_out = p.w * omega_;
    const double sin_mu = std::sqrt(std::max(1 - p.mu * p.mu, 0.0));
    const double omc = sampleOmc(u());
    const double sin_psi = std::sqrt(std::max(omc * (2 - omc), 0.0));
    const double mu_next = std::clamp(p.mu * (1 - omc) + sin_mu * sin_psi * std::cos(2 * kPi * u()), -1.0, 1.0);
    const double mu_sphere = 1 - 2 * u(), phi_sphere = 2 * kPi * u();
    const double mu_cap = -(1 - u() * (1 - cap_cos)), phi_cap = 2 * kPi * u();
    auto density = [&](double mu_o, double p_o) { return p_o + inv_sphere + (-mu_o >= cap_cos ? inv_cap : 0.0); };
    // β̃ towards a direction given by μ_o and the azimuth difference φ: 1 - cos ψ from the two.
    auto phase_towards = [&](double mu_o, double phi) {
      const double sin_o = std::sqrt(std::max(1 - mu_o * mu_o, 0.0));
      return phaseValue(1 - (p.mu * mu_o + sin_mu * sin_o * std::cos(phi)));
    };
    const double p_next = phaseValue(omc);
    const double p_sphere = phase_towards(mu_sphere, phi_sphere), p_cap = phase_towards(mu_cap, phi_cap);
    expectedFlight(geo_, p.z, mu_next, w_out * p_next / density(mu_next, p_next), scores);
    expectedFlight(geo_, p.z, mu_sphere, w_out * p_sphere / density(mu_sphere, p_sphere), scores);
    expectedFlight(geo_, p.z, mu_cap, w_out * p_cap / density(mu_cap, p_cap), scores);
    p.w = w_out;
    p.mu = mu_next == 0 ? 1e-12 : mu_next;
  }

  const PlaneParallelWater& water_;
  const bool nee_;
  const double c_, omega_, n_, bottom_;
  Geometry geo_;
  Sources src_;
  const double w0_;  // each photon's scores are one sample of the estimate
  const bool hg_;
  const double g_;
  double deepest_ = 0, z_kill_ = 0, kappa_ = 0, spacing_ = 0, plane_limit_ = 0;
  std::vector<double> table_, values_, bottom_scores_;
  std::vector<Particle> stack_;
  long long collisions_ = 0;
};

// The batches' means and standard errors per depth, and L_w and R_rs from L_u just below the surface
// when depth 0 is among those asked.
LightProfileMc summarise(const PlaneParallelWater& water, const Sources& src, const std::vector<double>& depths,
                         const BatchMeans& batches) {
  const size_t nd = depths.size();
  const double n = water.ior;
  LightProfileMc out;
  out.mean.e_d_air = water.sun_irradiance * src.mu_air + water.sky_irradiance;
  for (size_t k = 0; k < nd; ++k) {
    LightAtDepth m, e;
    m.depth = e.depth = depths[k];
    double LightAtDepth::*fields[kFields] = {&LightAtDepth::e_d, &LightAtDepth::e_u, &LightAtDepth::e_0d,
                                             &LightAtDepth::e_0u, &LightAtDepth::l_u};
    for (int f = 0; f < kFields; ++f) {
      const BatchEstimate b = batches.estimate(f * nd + k);
      m.*fields[f] = b.mean;
      e.*fields[f] = b.std_error;
    }
    out.mean.rows.push_back(m);
    out.standard_error.push_back(e);
  }
  const double t0_up = (1 - kd::fresnel_reflectance(1.0, n, 1.0)) / (n * n);
  for (size_t k = 0; k < nd; ++k)
    if (depths[k] == 0) {
      out.mean.l_w = out.mean.rows[k].l_u * t0_up;
      out.l_w_se = out.standard_error[k].l_u * t0_up;
    }
  out.mean.r_rs = out.mean.e_d_air > 0 ? out.mean.l_w / out.mean.e_d_air : 0.0;
  out.r_rs_se = out.mean.e_d_air > 0 ? out.l_w_se / out.mean.e_d_air : 0.0;
  return out;
}

}  // namespace

LightProfileMc solveLightProfileMonteCarlo(const PlaneParallelWater& water, const PhaseFunction& phase,
                                           const std::vector<double>& depths, const MonteCarloSettings& s) {
  validate(water, depths, s);
  const auto t0 = std::chrono::steady_clock::now();
  PhotonTracer tracer(water, phase, depths, s);
  const size_t nv = tracer.fields();
  BatchMeans batches(nv);
  std::vector<double> scores(nv), block_mean(nv), block_m2(nv);
  long long block_n = 0;
  int block = 0;
  for (long long i = 0; i < s.photons; ++i) {
    std::fill(scores.begin(), scores.end(), 0.0);
    tracer.photon(s.seed, i, scores);
    // Welford's update of the block's mean and M2; a block handed over at its last photon.
    ++block_n;
    for (size_t v = 0; v < nv; ++v) {
      const double d = scores[v] - block_mean[v];
      block_mean[v] += d / static_cast<double>(block_n);
      block_m2[v] += d * (scores[v] - block_mean[v]);
    }
    const long long block_end = (s.photons / s.batches) * (block + 1) + std::min<long long>(block + 1, s.photons % s.batches);
    if (i + 1 == block_end) {
      batches.addBlock(block_mean.data(), block_m2.data(), block_n);
      std::fill(block_mean.begin(), block_mean.end(), 0.0);
      std::fill(block_m2.begin(), block_m2.end(), 0.0);
      block_n = 0;
      ++block;
    }
  }
  LightProfileMc out = summarise(water, tracer.sources(), depths, batches);
  out.collisions = tracer.collisions();
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace seasim
