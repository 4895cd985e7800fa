#include "underwater/lamps_ms_table.h"

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
  std::vector<float> rows(static_cast<size_t>(orders) * UW_MS_ROW, 0.0f);
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
  return rows;
}

std::vector<float> lampMsTable(const std::vector<UwLamp>& lamps, double g, double beta, int orders) {
  std::vector<float> table;
  const size_t stride = static_cast<size_t>(orders) * UW_MS_ROW;
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
