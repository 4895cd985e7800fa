#include "underwater/sky_window_modes.h"

#include <algorithm>
#include <cmath>

#include "math/kernel_math.h"

namespace seasim {

namespace kd = kmath_d;

std::array<double, 3> SkyWindowModes::at(double mu, const std::array<double, 3>& band_weights) const {
  std::array<double, 3> out{0, 0, 0};
  const int n = static_cast<int>(modes.size());
  if (n < 2 || !(mu >= mu_min)) return out;
  const double x = std::clamp((mu - mu_min) / (1 - mu_min), 0.0, 1.0) * (n - 1);
  const int i = std::min(static_cast<int>(x), n - 2);
  const double f = x - i;
  for (int m = 0; m < 3; ++m) {
    double lo = 0, hi = 0;
    for (int c = 0; c < (grey ? 1 : 3); ++c) {
      const double w = grey ? 1.0 : band_weights[c];
      lo += w * modes[i][m][c];
      hi += w * modes[i + 1][m][c];
    }
    out[m] = lo + f * (hi - lo);
  }
  return out;
}

SkyWindowModes makeSkyWindowModes(const SkyLight& sky, double ior, int samples, int azimuths) {
  SkyWindowModes out;
  out.mu_min = std::sqrt(std::max(1 - 1 / (ior * ior), 0.0));
  out.grey = sky.shape.model != SEASIM_SKY_IMAGE && sky.shape.model != SEASIM_SKY_PREETHAM;
  out.modes.assign(std::max(samples, 2), {});
  // The sun's horizontal direction and the one across it (the sun at the zenith: +x and +z).
  const double sx = sky.sun_dir[0], sz = sky.sun_dir[2], h = std::hypot(sx, sz);
  const double ux = h > 1e-9 ? sx / h : 1.0, uz = h > 1e-9 ? sz / h : 0.0;
  const int n = static_cast<int>(out.modes.size());
  if (sky.shape.model == SEASIM_SKY_UNIFORM) {
    for (auto& m : out.modes) m = {{{1, 1, 1}, {0, 0, 0}, {0, 0, 0}}};
    return out;
  }
  for (int k = 0; k < n; ++k) {
    const double mu = out.mu_min + (1 - out.mu_min) * k / (n - 1);
    const double sin_a = std::min(ior * std::sqrt(std::max(1 - mu * mu, 0.0)), 1.0);
    const double cos_a = std::sqrt(std::max(1 - sin_a * sin_a, 0.0));
    std::array<std::array<double, 3>, 3> m{};
    for (int j = 0; j < azimuths; ++j) {
      const double phi = 2 * M_PI * (j + 0.5) / azimuths, c = std::cos(phi), s = std::sin(phi);
      const kd::real3 a{sin_a * (c * ux - s * uz), cos_a, sin_a * (c * uz + s * ux)};
      const kd::real3 shape = kd::sky_view_shape(&sky.params, sky.shape.texels.data(), a);
      const double ch[3] = {shape.x, shape.y, shape.z};
      for (int mode = 0; mode < 3; ++mode) {
        const double weight = (mode == 0 ? 1.0 : 2.0) * std::cos(mode * phi) / azimuths;
        for (int q = 0; q < 3; ++q) m[mode][q] += weight * ch[q];
      }
    }
    out.modes[k] = m;
  }
  return out;
}

}  // namespace seasim
