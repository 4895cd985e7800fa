#include "passes/sea_ordinates_table.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <utility>
#include <cmath>
#include <numbers>

#include "math/kernel_math.h"
#include "underwater/ordinates_high_order.h"

namespace seasim {

namespace k = kmath_d;

namespace {

// 16 streams per hemisphere (delta-M order 16: f = g^32, 0.034 at g 0.9): the radiance at the surface is
// within 3e-4 of 32 streams' (a 0.07, b 1.07, g 0.9, sun 40°; deep and over 5 m), at a third of the time.
constexpr int kStreams = 16;
// The closed form's azimuth modes 0-2 by the midpoint rule over [0, π]: it is smooth in azimuth (the HG
// phase between 90° and 180° and constants).
constexpr int kAzimuthSamples = 24;
// κ is held to [1/5, 5]: the measured range is 0.97–1.08; the bound only keeps a failed solve finite.
constexpr double kMinFactor = 0.2, kMaxFactor = 5.0;

// The depth nodes some pixel reads: those around every depth from depth_min to depth_max, and no bottom.
std::vector<int> depthNodesRead(const SeaOrdinatesLight& light) {
  std::vector<int> nodes;
  if (light.bottom) {
    int lo0 = 0, lo1 = 0, hi0 = 0, hi1 = 0;
    k::sea_ord_depth_taps(std::max(light.depth_min, 0.0), &lo0, &lo1);
    k::sea_ord_depth_taps(std::max(light.depth_max, light.depth_min), &hi0, &hi1);
    for (int j = lo0; j <= hi1; ++j) nodes.push_back(j);
  }
  if (light.deep && (nodes.empty() || nodes.back() != SEA_ORD_DEPTHS - 1)) nodes.push_back(SEA_ORD_DEPTHS - 1);
  return nodes;
}

bool hasFactor(const SeaOrdinatesLight& light, const SeaOrdinatesBand& band) {
  const bool lit = (light.sun_up > 0 && band.e_sun > 0 && light.t_in > 0) || band.e_sky > 0;
  // No scattering: nothing to correct. No absorption: the deep layer's solution is singular (K∞ = 0).
  return light.column && lit && band.b > 0 && band.a > 1e-6 * (band.a + band.b) && std::abs(light.g) < 1;
}

// κ at every zenith and azimuth node of one depth layer (bottom depth H, < 0: none), into kappa (node-major,
// `bands` per node) from node SEA_ORD_ROW(layer, 0, 0).
void solveDepthLayer(const SeaOrdinatesLight& light, const SeaOrdinatesBand& band, double H, int layer_index,
                     int bands, int band_index, std::vector<double>& kappa) {
  const bool bottom = H >= 0;
  DiscreteOrdinatesLayer layer;
  layer.a = band.a;
  layer.b = band.b;
  layer.g = light.g;
  layer.bottom_depth = bottom ? std::max(H, 1e-3) : 0.0;
  layer.bottom_albedo = bottom ? band.albedo : 0.0;
  layer.ior = light.ior;
  layer.mu_sun = std::clamp(light.cos_io, 1e-4, 1.0);
  layer.e_sun0 = light.sun_up > 0 ? band.e_sun * light.sun_up * light.t_in : 0.0;
  layer.e_sky0 = band.e_sky;
  // Upwelling at the zenith nodes, and their mirror images (the solver wants cosines symmetric about 0).
  std::vector<double> nus(2 * SEA_ORD_ZENITHS);
  for (int j = 0; j < SEA_ORD_ZENITHS; ++j) {
    nus[j] = -k::sea_ord_zenith_cosine(j);
    nus[2 * SEA_ORD_ZENITHS - 1 - j] = -nus[j];
  }
  const double y_end = bottom ? layer.bottom_depth : 30.0 / (band.a + band.b);
  const HighOrderField field = solveHighOrderField(layer, kStreams, 3, nus, y_end);
  for (int z = 0; z < SEA_ORD_ZENITHS; ++z) {
    const double cos_up = k::sea_ord_zenith_cosine(z);
    // The closed form in the solution's azimuth modes 0-2.
    std::array<double, 3> closed{0, 0, 0};
    for (int s = 0; s < kAzimuthSamples; ++s) {
      const double psi = std::numbers::pi * (s + 0.5) / kAzimuthSamples;
      const double v = seaClosedFormBelow(light, band, H, cos_up, std::cos(psi));
      closed[0] += v / kAzimuthSamples;
      closed[1] += 2 * v * std::cos(psi) / kAzimuthSamples;
      closed[2] += 2 * v * std::cos(2 * psi) / kAzimuthSamples;
    }
    for (int a = 0; a < SEA_ORD_AZIMUTHS; ++a) {
      const double phi = std::acos(k::sea_ord_azimuth_cosine_node(a));
      double solved = 0, model = 0;
      for (int m = 0; m < 3; ++m) {
        solved += field.radiance[m][static_cast<size_t>(z)] * std::cos(m * phi);  // depth 0, cosine z
        model += closed[m] * std::cos(m * phi);
      }
      const double ratio = model > 0 && std::isfinite(solved) ? solved / model : 1.0;
      kappa[static_cast<size_t>(SEA_ORD_ROW(layer_index, z, a)) * bands + band_index] =
          std::clamp(ratio, kMinFactor, kMaxFactor);
    }
  }
}

}  // namespace

SeaOrdinatesLight seaOrdinatesLight(const Scene& scene, const Vec3& sun, double sky_fresnel_mean, bool column,
                                    bool bottom) {
  SeaOrdinatesLight light;
  light.ior = scene.water.ior;
  light.g = scene.water.g;
  light.sky_fresnel_mean = sky_fresnel_mean;
  light.column = column;
  if (sun.y > 0) {
    light.sun_up = sun.y;
    light.t_in = 1 - k::fresnel_reflectance(sun.y, 1.0, light.ior);
    k::real3 sun_in_water{};
    k::refract_dir(-k::real3{sun.x, sun.y, sun.z}, k::real3{0, 1, 0}, 1.0 / light.ior, &sun_in_water);
    light.cos_io = std::max(-sun_in_water.y, 1e-4);
  }
  const BottomDesc& b = scene.bottom;
  light.bottom = bottom && b.type != BottomDesc::Type::None;
  light.deep = !light.bottom;
  light.depth_grid = light.bottom && b.type == BottomDesc::Type::HeightField;
  if (light.bottom) {
    light.depth_min = b.type == BottomDesc::Type::Flat ? b.depth : std::min(b.min_depth, b.max_depth);
    light.depth_max = b.type == BottomDesc::Type::Flat ? b.depth : std::max(b.min_depth, b.max_depth);
  }
  return light;
}

double seaClosedFormBelowAlong(const SeaOrdinatesLight& light, const SeaOrdinatesBand& band, double H, double cos_ji,
                               double phase) {
  const double c_f = k::hg_forward_fraction(light.g);
  const double e_sun = band.e_sun * std::max(light.sun_up, 0.0);
  const double t_in = light.sun_up > 0 ? light.t_in : 0.0;
  const double mu_sky = k::sea_sky_mean_cosine(light.ior);
  const double r_below = k::sea_surface_reflectance_below(light.sky_fresnel_mean, light.ior);
  const double mu_ret = k::sea_reflected_mean_cosine(r_below, light.ior);
  const double albedo = H >= 0 ? band.albedo : 0.0;
  double L = 0;
  if (light.column)
    L += k::sea_multiple_column(e_sun, t_in, band.e_sky, band.a, band.b, c_f, H, light.cos_io, cos_ji, phase, mu_sky);
  if (H >= 0)
    L += k::sea_multiple_bottom(e_sun, t_in, band.e_sky, band.a, band.b, c_f, albedo, H, light.cos_io, cos_ji, mu_sky,
                                1.0);
  L += k::sea_multiple_surface_return(e_sun, t_in, band.e_sky, band.a, band.b, c_f, albedo, H, light.cos_io, cos_ji,
                                      mu_sky, 1.0, r_below, mu_ret, light.column ? 1 : 0);
  return L;
}

double seaClosedFormBelow(const SeaOrdinatesLight& light, const SeaOrdinatesBand& band, double H, double cos_up,
                          double cos_phi) {
  const double sin_up = std::sqrt(std::max(1 - cos_up * cos_up, 0.0));
  const double sin_io = std::sqrt(std::max(1 - light.cos_io * light.cos_io, 0.0));
  // The beam travels along (sin_io, -cos_io, 0), the light towards the eye along (sin_up cos φ, cos_up, ...).
  const double phase = k::hg_phase(sin_io * sin_up * cos_phi - light.cos_io * cos_up, light.g);
  return seaClosedFormBelowAlong(light, band, H, std::max(cos_up, 1e-4), phase);
}

std::vector<double> seaOrdinatesTable(const SeaOrdinatesLight& light, const std::vector<SeaOrdinatesBand>& bands) {
  const int count = static_cast<int>(bands.size());
  std::vector<double> kappa(static_cast<size_t>(light.depth_grid ? SEA_ORD_NODES : SEA_ORD_LAYER) * count, 1.0);
  // The depth layers to solve, as (bottom depth, layer index): the grid's nodes the scene reads, or its one depth.
  std::vector<std::pair<double, int>> layers;
  if (light.depth_grid) {
    for (int node : depthNodesRead(light))
      layers.push_back({node < SEA_ORD_DEPTHS - 1 ? k::sea_ord_depth_node(node) : -1.0, node});
  } else {
    layers.push_back({light.bottom ? std::max(light.depth_min, 0.0) : -1.0, 0});
  }
  const int tasks = count * static_cast<int>(layers.size());
  tbb::parallel_for(0, tasks, [&](int t) {
    const int band = t % count;
    const auto [H, layer] = layers[t / count];
    // Under 1e-3 optical depths of water the closed form is the bottom–surface series itself, exact; the
    // solver's own Fresnel quadrature would move it by 6e-4.
    const bool water = H < 0 || (bands[band].a + bands[band].b) * H >= 1e-3;
    if (water && hasFactor(light, bands[band])) solveDepthLayer(light, bands[band], H, layer, count, band, kappa);
  });
  return kappa;
}

double seaOrdinatesFactor(const std::vector<double>& kappa, int bands, int band, double H, double cos_up,
                          double cos_phi) {
  int rows[SEA_ORD_TAPS];
  double weights[SEA_ORD_TAPS];
  const bool depth_grid = kappa.size() == static_cast<size_t>(SEA_ORD_NODES) * bands;
  k::sea_ord_taps(H, depth_grid ? 1 : 0, cos_up, cos_phi, rows, weights);
  double v = 0;
  for (int c = 0; c < SEA_ORD_TAPS; ++c) v += weights[c] * kappa[static_cast<size_t>(rows[c]) * bands + band];
  return v;
}

}  // namespace seasim
