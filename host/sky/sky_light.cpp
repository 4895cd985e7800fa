#include "sky/sky_light.h"

#include <cmath>

#include "math/kernel_math.h"
#include "spectral/sensor.h"

namespace seasim {

static_assert(sizeof(SkyParams) == 32 && offsetof(SkyParams, scale) == 16 && offsetof(SkyParams, height) == 28,
              "SkyParams layout changed: update common/sky_params.h users");

namespace kd = kmath_d;

namespace {

kd::real3 bandWeights(const SeaSky& shape, std::size_t band) {
  const auto& w = shape.band_weights[band];
  return kd::real3{w[0], w[1], w[2]};
}

// Σ over the midpoints of (s = cos²θ, φ) ∈ [0, 1] × [0, 2π) of shape(d) · weight(cos θ), divided by
// their count: (1/π) ∫ shape · weight cos θ dω (cos θ dω = ½ ds dφ). The shape is linear in what a
// band takes of it, so one pass serves every band.
template <class Weight>
kd::real3 cosineMeanShape(const SkyLight& sky, const std::vector<double>& buffer, int n_s, int n_phi, Weight weight) {
  kd::real3 sum{0, 0, 0};
  for (int i = 0; i < n_s; ++i) {
    const double s = (i + 0.5) / n_s;
    const double ct = std::sqrt(s), st = std::sqrt(1.0 - s);
    const double w = weight(ct);
    kd::real3 row{0, 0, 0};
    for (int k = 0; k < n_phi; ++k) {
      const double phi = 2.0 * M_PI * (k + 0.5) / n_phi;
      row = row + kd::sky_view_shape(&sky.params, buffer.data(), kd::real3{st * std::cos(phi), ct, st * std::sin(phi)});
    }
    sum = sum + w * row;
  }
  return sum * (1.0 / (double(n_s) * n_phi));
}

}  // namespace

double skyFresnelMean(double ior) {
  const int steps = 2000;
  double sum = 0;
  for (int i = 0; i < steps; ++i) {  // midpoint rule in θ
    const double t = (i + 0.5) * (M_PI / 2) / steps;
    sum += kd::fresnel_reflectance(std::cos(t), 1.0, ior) * std::cos(t) * std::sin(t);
  }
  return 2.0 * sum * (M_PI / 2) / steps;
}

double SkyLight::radiance(std::size_t band, const std::array<double, 3>& d) const {
  if (shape.model == SEASIM_SKY_UNIFORM) return level[band];
  const kd::real3 s = kd::sky_view_shape(&params, shape.texels.data(), kd::real3{d[0], d[1], d[2]});
  return level[band] * kd::sky_view_band(shape.model, bandWeights(shape, band), s);
}

double SkyLight::sunDiskRadiance(std::size_t band) const {
  return sun_solid_angle > 0 ? sun_irradiance[band] / sun_solid_angle : 0.0;
}

std::vector<double> SkyLight::horizontalIrradiance(int n_s, int n_phi) const {
  std::vector<double> e(level.size());
  if (shape.model == SEASIM_SKY_UNIFORM) {
    for (std::size_t i = 0; i < e.size(); ++i) e[i] = M_PI * level[i];
    return e;
  }
  const kd::real3 mean = cosineMeanShape(*this, shape.texels, n_s, n_phi, [](double) { return 1.0; });
  for (std::size_t i = 0; i < e.size(); ++i)
    e[i] = M_PI * level[i] * kd::sky_view_band(shape.model, bandWeights(shape, i), mean);
  return e;
}

std::vector<double> SkyLight::transmittedIrradiance(double ior, int n_s, int n_phi) const {
  std::vector<double> e(level.size());
  if (shape.model == SEASIM_SKY_UNIFORM) {
    const double r_mean = skyFresnelMean(ior);
    for (std::size_t i = 0; i < e.size(); ++i) e[i] = M_PI * level[i] * (1.0 - r_mean);
    return e;
  }
  const kd::real3 mean = cosineMeanShape(*this, shape.texels, n_s, n_phi,
                                         [ior](double ct) { return 1.0 - kd::fresnel_reflectance(ct, 1.0, ior); });
  for (std::size_t i = 0; i < e.size(); ++i)
    e[i] = M_PI * level[i] * kd::sky_view_band(shape.model, bandWeights(shape, i), mean);
  return e;
}

std::vector<float> SkyLight::kernelBuffer() const { return std::vector<float>(shape.texels.begin(), shape.texels.end()); }

std::array<float, 12> SkyLight::rgbMatrix(const std::vector<double>& to_r, const std::vector<double>& to_g,
                                          const std::vector<double>& to_b) const {
  const bool coloured = shape.model == SEASIM_SKY_IMAGE || shape.model == SEASIM_SKY_PREETHAM;
  double m[3][3] = {};
  const std::vector<double>* to[3] = {&to_r, &to_g, &to_b};
  for (std::size_t i = 0; i < level.size(); ++i)
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) {
        const double w = coloured ? shape.band_weights[i][static_cast<std::size_t>(k)] : (k == 0 ? 1.0 : 0.0);
        m[c][k] += (*to[c])[i] * level[i] * w;
      }
  std::array<float, 12> out{};
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < 3; ++k) out[static_cast<std::size_t>(4 * c + k)] = static_cast<float>(m[c][k]);
  return out;
}

SkyLight makeSkyLight(const Scene& scene, const WavelengthGrid& grid) {
  SkyLight s;
  const SunDesc& sun = scene.sun;
  s.sun_dir = {std::sin(sun.zenith) * std::cos(sun.azimuth), std::cos(sun.zenith),
               std::sin(sun.zenith) * std::sin(sun.azimuth)};
  s.shape = makeSeaSky(scene.sky, s.sun_dir.data(), grid, scene.files.get());
  s.level = sunIrradianceBands(grid, scene.sky.radiance);  // D65 shape
  const bool sun_up = sun.enabled && sun.irradiance > 0 && s.sun_dir[1] > 1e-6;
  s.sun_irradiance = sunIrradianceBands(grid, sun_up ? sun.irradiance : 0.0);
  s.sun_solid_angle = 2 * M_PI * (1 - std::cos(sun.angular_radius));
  SkyParams& p = s.params;
  for (int k = 0; k < 3; ++k) p.sun_dir[k] = static_cast<float>(s.sun_dir[static_cast<std::size_t>(k)]);
  p.scale = static_cast<float>(s.shape.model == SEASIM_SKY_UNIFORM ? 1.0 : s.shape.scale);
  p.model = s.shape.model;
  p.width = s.shape.width;
  p.height = s.shape.height;
  return s;
}

}  // namespace seasim
