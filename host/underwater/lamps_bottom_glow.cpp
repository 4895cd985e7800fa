#include "underwater/lamps_bottom_glow.h"

#include <algorithm>
#include <cmath>

#include "math/kernel_math.h"

namespace seasim {

namespace {

using kmath_d::real3;

// Where the lamp's direct light lands on the bottom: per band ∫ ρ E/π dA and the band-summed weights'
// first and second moments of position, for the centre and radius.
struct GlowSums {
  std::vector<double> direct;
  double w = 0.0;
  real3 m1{0.0, 0.0, 0.0};
  double m2 = 0.0;  // Σ w |x|²

  explicit GlowSums(size_t bands) : direct(bands, 0.0) {}

  void addPoint(const real3& x, double weight) {
    w += weight;
    m1 = m1 + weight * x;
    m2 += weight * kmath_d::dot(x, x);
  }
};

// The direct light over the lamp's solid angle: dA cos θ_i / s² = dω, so ∫ E/π dA = ∫ P e^{-σ_t s}/π dω
// over the directions that reach the bottom (s = h / -ω_y). Midpoints in cos θ over the cone (hard or
// soft edge) and in azimuth.
void addDirect(const UwLamp& L, const std::vector<UwBand>& bands, double depth, GlowSums* sums) {
  const real3 lamp{L.position[0], L.position[1], L.position[2]};
  const real3 axis{L.direction[0], L.direction[1], L.direction[2]};
  const double h = lamp.y + depth;
  real3 u, v;
  kmath_d::pt_basis(axis, &u, &v);
  constexpr int kTheta = 256, kPhi = 256;
  const double c0 = std::clamp(double(L.cos_cone), -1.0, 1.0);
  const double d_cos = (1.0 - c0) / kTheta, d_phi = 2.0 * M_PI / kPhi;
  for (int it = 0; it < kTheta; ++it) {
    const double ct = c0 + (it + 0.5) * d_cos, st = std::sqrt(std::max(0.0, 1.0 - ct * ct));
    const double profile = kmath_d::shafts_cone_profile(ct, L.cos_cone, L.cos_inner);
    if (!(profile > 0.0)) continue;
    for (int ip = 0; ip < kPhi; ++ip) {
      const double phi = (ip + 0.5) * d_phi;
      const real3 w = ct * axis + (st * std::cos(phi)) * u + (st * std::sin(phi)) * v;
      if (!(w.y < 0.0)) continue;
      const double s = h / -w.y;
      const double dw = profile * d_cos * d_phi / M_PI;
      double weight = 0.0;
      for (size_t i = 0; i < bands.size(); ++i) {
        const double e = bands[i].bottom_albedo * dw * std::exp(-double(bands[i].c) * s);
        sums->direct[i] += e;
        weight += e;
      }
      sums->addPoint(lamp + s * w, weight);
    }
  }
}

}  // namespace

std::vector<float> lampBottomGlow(const UwLamp& lamp, const UwParams& params, const std::vector<UwBand>& bands,
                                  double s_min) {
  const int nb = static_cast<int>(bands.size());
  std::vector<float> out(static_cast<size_t>(lampGlowStride(nb)), 0.0f);
  const double depth = params.bottom_depth;
  if (!(depth > 0.0) || nb == 0 || !(lamp.position[1] + depth > 0.0)) return out;
  GlowSums sums(bands.size());
  addDirect(lamp, bands, depth, &sums);
  if (!(sums.w > 0.0)) return out;
  const real3 c = sums.m1 / sums.w;
  // Var = E|x|² - |E x|²; the centre sits on the plane, lifted by nothing (the source's cos ψ is 0 there).
  const double radius = std::sqrt(std::max(sums.m2 / sums.w - kmath_d::dot(c, c), 0.0));
  out[0] = static_cast<float>(c.x);
  out[1] = static_cast<float>(-depth);
  out[2] = static_cast<float>(c.z);
  out[3] = static_cast<float>(std::max(radius, s_min));
  for (int i = 0; i < nb; ++i) out[4 + i] = static_cast<float>(sums.direct[i]);
  return out;
}

std::vector<float> lampBottomGlowTable(const std::vector<UwLamp>& lamps, const UwParams& params,
                                       const std::vector<UwBand>& bands, double s_min) {
  std::vector<float> table;
  for (const UwLamp& lamp : lamps) {
    const std::vector<float> one = lampBottomGlow(lamp, params, bands, s_min);
    table.insert(table.end(), one.begin(), one.end());
  }
  if (table.empty()) table.push_back(0.0f);
  return table;
}

}  // namespace seasim
