#include "underwater/lamps_bottom_glow.h"

#include <algorithm>
#include <cmath>

#include "math/kernel_math.h"

namespace seasim {

namespace {

using kmath_d::real3;

// Where the lamp's light lands on the bottom: per band ∫ ρ E/π dA (all light, direct alone) and the
// band-summed weights' first and second moments of position, for the centre and radius.
struct GlowSums {
  std::vector<double> total, direct;
  double w = 0.0;
  real3 m1{0.0, 0.0, 0.0};
  double m2 = 0.0;  // Σ w |x|²

  explicit GlowSums(size_t bands) : total(bands, 0.0), direct(bands, 0.0) {}

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
        sums->total[i] += e;
        weight += e;
      }
      sums->addPoint(lamp + s * w, weight);
    }
  }
}

// The orders' light over the plane: polar about the lamp's foot point, radii r = h sinh(u) (dense under
// the lamp, out to 30 optical depths of the clearest band), uw_ms_surface per band.
void addOrders(const UwLamp& L, const std::vector<UwBand>& bands, double depth, const float* rows, double s_min,
               const LampGlowModel& model, GlowSums* sums) {
  const real3 lamp{L.position[0], L.position[1], L.position[2]};
  const real3 axis{L.direction[0], L.direction[1], L.direction[2]};
  const real3 up{0.0, 1.0, 0.0};
  const double h = lamp.y + depth;
  double c_min = bands[0].c;
  for (const UwBand& b : bands) c_min = std::min(c_min, double(b.c));
  const double r_max = kmath_d::uw_ms_ray_cap(c_min);
  constexpr int kRadii = 160, kPhi = 96;
  const double u_max = std::asinh(r_max / h), du = u_max / kRadii, d_phi = 2.0 * M_PI / kPhi;
  for (int ir = 0; ir < kRadii; ++ir) {
    const double uu = (ir + 0.5) * du, r = h * std::sinh(uu), dr = h * std::cosh(uu) * du;
    for (int ip = 0; ip < kPhi; ++ip) {
      const double phi = (ip + 0.5) * d_phi;
      const real3 x{lamp.x + r * std::cos(phi), -depth, lamp.z + r * std::sin(phi)};
      const double dA = r * dr * d_phi;
      double weight = 0.0;
      for (size_t i = 0; i < bands.size(); ++i) {
        if (!(bands[i].b > 0.0f)) continue;
        const double e = bands[i].bottom_albedo * dA *
                         kmath_d::uw_ms_surface(x, up, lamp, axis, s_min, bands[i].a, bands[i].b, model.g, model.kappa,
                                                rows, model.orders);
        sums->total[i] += e;
        weight += e;
      }
      sums->addPoint(x, weight);
    }
  }
}

}  // namespace

std::vector<float> lampBottomGlow(const UwLamp& lamp, const UwParams& params, const std::vector<UwBand>& bands,
                                  const float* ms_rows, double s_min, const LampGlowModel& model) {
  const int nb = static_cast<int>(bands.size());
  std::vector<float> out(static_cast<size_t>(lampGlowStride(nb)), 0.0f);
  const double depth = params.bottom_depth;
  if (!(depth > 0.0) || nb == 0 || !(lamp.position[1] + depth > 0.0)) return out;
  GlowSums sums(bands.size());
  addDirect(lamp, bands, depth, &sums);
  addOrders(lamp, bands, depth, ms_rows, s_min, model, &sums);
  if (!(sums.w > 0.0)) return out;
  const real3 c = sums.m1 / sums.w;
  // Var = E|x|² - |E x|²; the centre sits on the plane, lifted by nothing (the source's cos ψ is 0 there).
  const double radius = std::sqrt(std::max(sums.m2 / sums.w - kmath_d::dot(c, c), 0.0));
  out[0] = static_cast<float>(c.x);
  out[1] = static_cast<float>(-depth);
  out[2] = static_cast<float>(c.z);
  out[3] = static_cast<float>(std::max(radius, s_min));
  for (int i = 0; i < nb; ++i) {
    out[4 + i] = static_cast<float>(sums.total[i]);
    out[4 + nb + i] = static_cast<float>(sums.direct[i]);
  }
  return out;
}

std::vector<float> lampBottomGlowTable(const std::vector<UwLamp>& lamps, const UwParams& params,
                                       const std::vector<UwBand>& bands, const std::vector<float>& ms_table, double s_min,
                                       const LampGlowModel& model) {
  std::vector<float> table;
  for (size_t l = 0; l < lamps.size(); ++l) {
    const std::vector<float> one =
        lampBottomGlow(lamps[l], params, bands, ms_table.data() + l * model.orders * UW_MS_TABLE, s_min, model);
    table.insert(table.end(), one.begin(), one.end());
  }
  if (table.empty()) table.push_back(0.0f);
  return table;
}

}  // namespace seasim
