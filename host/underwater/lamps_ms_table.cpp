#include "underwater/lamps_ms_table.h"

#include <algorithm>
#include <cmath>

#include "math/kernel_math.h"

namespace seasim {

namespace {

// cos β of HG(h) at its CDF value u (the inverse of ∫_{cos β}^{1} 2π p dμ = u from the forward end);
// uniform in cos β at h = 0.
double hgInverseCdf(double h, double u) {
  if (std::fabs(h) < 1e-6) return 1.0 - 2.0 * u;
  const double f = (1.0 - h * h) / (1.0 + h - 2.0 * h * u);
  return std::fmax(-1.0, std::fmin(1.0, (1.0 + h * h - f * f) / (2.0 * h)));
}

}  // namespace

std::vector<float> lampMsProfiles(double cos_cone, double cos_inner, double g, double beta, int orders, int u_steps,
                                  int phi_steps) {
  std::vector<float> rows(static_cast<size_t>(kmath_d::uw_ms_lamp_rows(orders)), 0.0f);
  // The azimuth about the direction ψ: symmetric, so half the circle, midpoints; their cosines once.
  std::vector<double> cos_phi(phi_steps);
  for (int k = 0; k < phi_steps; ++k) cos_phi[k] = std::cos((k + 0.5) * M_PI / phi_steps);
  for (int n = 1; n <= orders; ++n) {
    const double h = kmath_d::uw_ms_spread(g, n, beta);
    for (int i = 0; i < UW_MS_TABLE; ++i) {
      const double psi = i * M_PI / 180.0;
      const double cp = std::cos(psi), sp = std::sin(psi);
      double acc = 0.0;
      for (int iu = 0; iu < u_steps; ++iu) {
        const double cb = hgInverseCdf(h, (iu + 0.5) / u_steps);
        const double sb = std::sqrt(std::fmax(0.0, 1.0 - cb * cb));
        for (int k = 0; k < phi_steps; ++k) {
          const double c = cp * cb + sp * sb * cos_phi[k];
          acc += kmath_d::shafts_cone_profile(c, cos_cone, cos_inner);
        }
      }
      rows[static_cast<size_t>(n - 1) * UW_MS_ROW + i] = static_cast<float>(acc / (double(u_steps) * phi_steps));
    }
    // The irradiance factor F(g^n, cos θ_i) after the profile (uw_ms_irradiance_exact; 4096 midpoints of
    // HG's inverse CDF: the unit test holds it to the Legendre series).
    const double gn = std::pow(std::fmax(g, 0.0), n);
    for (int j = 0; j < UW_MS_IRRADIANCE; ++j)
      rows[static_cast<size_t>(n - 1) * UW_MS_ROW + UW_MS_TABLE + j] =
          static_cast<float>(kmath_d::uw_ms_irradiance_exact(gn, -1.0 + 2.0 * j / (UW_MS_IRRADIANCE - 1), 4096));
  }
  const std::vector<float> q = lampMsOrder1(cos_cone, cos_inner, g);
  std::copy(q.begin(), q.end(), rows.begin() + static_cast<size_t>(orders) * UW_MS_ROW);
  return rows;
}

std::vector<float> lampMsOrder1(double cos_cone, double cos_inner, double g, int n_gamma, int n_delta, int n_phi) {
  std::vector<float> out(static_cast<size_t>(UW_MS_ORDER1_PLANES) * UW_MS_ORDER1_PLANE, 0.0f);
  // The line integrals over δ once per τ on γ_m = π (m / (M - 1))²: fine near γ = 0, where the HG peak
  // (at δ = γ) makes them steep; read back linearly in √γ.
  constexpr int M = 1024;
  std::vector<kmath_d::UwMsOrder1> line(static_cast<size_t>(M));
  const double cone = std::acos(std::clamp(cos_cone, -1.0, 1.0));
  // The rings at each ψ's γ nodes do not depend on τ: once.
  const size_t nodes = static_cast<size_t>(UW_MS_TABLE) * n_gamma;
  std::vector<double> ring(nodes), toward(nodes), at_m(nodes), dg(UW_MS_TABLE);
  for (int i = 0; i < UW_MS_TABLE; ++i) {
    const double psi = i * M_PI / 180.0, g0 = std::fmax(psi - cone, 0.0), g1 = std::fmin(psi + cone, M_PI);
    dg[i] = (g1 - g0) / n_gamma;
    for (int k = 0; k < n_gamma; ++k) {
      const size_t at = static_cast<size_t>(i) * n_gamma + k;
      const double gamma = g0 + (k + 0.5) * dg[i];
      kmath_d::uw_ms_order1_ring(gamma, std::cos(psi), cos_cone, cos_inner, n_phi, &ring[at], &toward[at]);
      at_m[at] = std::sqrt(gamma / M_PI) * (M - 1);
    }
  }
  for (int t = 0; t < UW_MS_ORDER1_TAUS; ++t) {
    const double tau = kmath_d::uw_ms_order1_tau(t);
    for (int m = 0; m < M; ++m) {
      const double x = double(m) / (M - 1);
      line[m] = kmath_d::uw_ms_order1_line(tau, M_PI * x * x, g, n_delta);
    }
    for (int i = 0; i < UW_MS_TABLE; ++i) {
      double q = 0.0, par = 0.0, perp = 0.0;
      for (int k = 0; k < n_gamma; ++k) {
        const size_t at = static_cast<size_t>(i) * n_gamma + k;
        if (!(ring[at] > 0.0)) continue;
        const int m = std::min(static_cast<int>(at_m[at]), M - 2);
        const double f = at_m[at] - m;
        q += ring[at] * ((1.0 - f) * line[m].q + f * line[m + 1].q);
        par += ring[at] * ((1.0 - f) * line[m].par + f * line[m + 1].par);
        perp -= toward[at] * ((1.0 - f) * line[m].perp + f * line[m + 1].perp);
      }
      const size_t e = static_cast<size_t>(t) * UW_MS_TABLE + i;
      out[e] = static_cast<float>(q * dg[i]);
      out[UW_MS_ORDER1_PLANE + e] = static_cast<float>(par * dg[i]);
      out[2 * UW_MS_ORDER1_PLANE + e] = static_cast<float>(perp * dg[i]);
    }
  }
  return out;
}

std::vector<float> lampMsTable(const std::vector<UwLamp>& lamps, double g, double beta, int orders) {
  std::vector<float> table;
  const size_t stride = static_cast<size_t>(kmath_d::uw_ms_lamp_rows(orders));
  for (size_t l = 0; l < lamps.size(); ++l) {
    // Lamps of the same cone share their rows (an ROV's pair of lamps).
    size_t same = 0;
    while (same < l && !(lamps[same].cos_cone == lamps[l].cos_cone && lamps[same].cos_inner == lamps[l].cos_inner)) ++same;
    if (same < l) {
      table.insert(table.end(), table.begin() + same * stride, table.begin() + (same + 1) * stride);
      continue;
    }
    const std::vector<float> rows = lampMsProfiles(lamps[l].cos_cone, lamps[l].cos_inner, g, beta, orders);
    table.insert(table.end(), rows.begin(), rows.end());
  }
  if (table.empty()) table.push_back(0.0f);
  return table;
}

}  // namespace seasim
