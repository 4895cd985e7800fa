#include "reference/sea_second_reference.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "math/kernel_math.h"
#include "passes/sea_heightfield.h"
#include "reference/sea_floor_reference.h"
#include "spectral/jerlov.h"
#include "spectral/sensor.h"
#include "spectral/wavelength_grid.h"
#include "util/error.h"

namespace seasim {

namespace {

namespace k = kmath_d;

// Direction at polar cosine mu and azimuth phi about the unit axis a.
k::real3 aroundAxis(k::real3 a, double mu, double phi) {
  const k::real3 helper = std::fabs(a.x) < 0.9 ? k::real3{1, 0, 0} : k::real3{0, 1, 0};
  const k::real3 t1 = k::normalize(k::cross(a, helper));
  const k::real3 t2 = k::cross(a, t1);
  const double s = std::sqrt(std::max(0.0, 1 - mu * mu));
  return a * mu + t1 * (s * std::cos(phi)) + t2 * (s * std::sin(phi));
}

// Inverse CDF of Henyey–Greenstein in the cosine to its axis, u in (0, 1) -> mu in (-1, 1).
double hgInverseCdf(double u, double g) {
  if (std::fabs(g) < 1e-6) return 1 - 2 * u;
  const double q = (1 - g * g) / (1 - g + 2 * g * u);
  return std::clamp((1 + g * g - q * q) / (2 * g), -1.0, 1.0);
}

// One quadrature node of the in-scatter's directions.
struct SecondNode {
  k::real3 omega;
  double factor;  // p1 p2 / (p1 + p2) / N^2: the balance-heuristic weight of one lobe's node
};

// N x N nodes per lobe. Lobe 1: p1(omega) = p(s . -omega), peaked at omega = -s. Lobe 2: p2 = p(omega . view).
void secondOrderNodes(k::real3 s, k::real3 view, double g, int N, std::vector<SecondNode>& nodes) {
  size_t idx = 0;
  for (int lobe = 0; lobe < 2; ++lobe) {
    const k::real3 axis = lobe == 0 ? -s : view;
    for (int i = 0; i < N; ++i) {
      const double mu = hgInverseCdf((i + 0.5) / N, g);
      for (int j = 0; j < N; ++j) {
        const k::real3 omega = aroundAxis(axis, mu, 2 * M_PI * (j + 0.5) / N);
        const double p1 = k::hg_phase(k::dot(s, -omega), g), p2 = k::hg_phase(k::dot(omega, view), g);
        nodes[idx++] = {omega, p1 * p2 / (p1 + p2) / (double(N) * N)};
      }
    }
  }
}

// What every pixel shares: the bands, the refracted sun, the floor.
struct SecondOrderScene {
  const Scene* scene = nullptr;
  Sensor sensor;
  BandOptics water;
  std::vector<double> sun_e;
  size_t bands = 0;
  bool bottom = false, height_field = false;
  HeightField floor;
  double floor_step = 0, c_min = 1e30;
  double cos_io = 1, e_beam_unit = 0;
  int depth_steps = 1;
};

// Band b's water-leaving L^(2) into rgb through the sensor's weights.
void addBand(const SecondOrderScene& r, size_t b, double L, double rgb[3]) {
  rgb[0] += L * r.sensor.to_r[b];
  rgb[1] += L * r.sensor.to_g[b];
  rgb[2] += L * r.sensor.to_b[b];
}

// Over a height field: the view ray from P = o ends at its z_Q, each node's ray where it leaves the
// water; geometric depth nodes shared by the bands.
void heightFieldSecondOrder(const SecondOrderScene& r, const double o[3], k::real3 view, double cos_ji, double t_out,
                            const std::vector<SecondNode>& nodes, double rgb[3]) {
  const int D = r.depth_steps;
  const double vv[3] = {view.x, view.y, view.z};
  const double z_q = -view.y * std::max(fineMarchFloor(r.floor, o, vv, 1e30, r.floor_step), 0.0);
  const double s_ref = 1 + 1 / r.cos_io, span = -std::expm1(-s_ref * r.c_min * z_q);
  std::vector<double> sum(r.bands, 0.0), ends(nodes.size());
  for (int kz = 0; kz < D && span > 0; ++kz) {
    const double frac = (kz + 0.5) / D * span;
    const double z = -std::log1p(-frac) / (s_ref * r.c_min);
    const double dz = span / (D * s_ref * r.c_min * (1 - frac));
    const k::real3 pz{o[0] + vv[0] * z / -view.y, -z, o[2] + vv[2] * z / -view.y};
    for (size_t q = 0; q < nodes.size(); ++q) {
      const k::real3 w = nodes[q].omega;
      k::real3 normal{};
      k::sea_hf_intersect(&r.floor.params, r.floor.depth.data(), pz, w, w.y > 0 ? z / w.y : 1e30, &ends[q], &normal);
    }
    for (size_t b = 0; b < r.bands; ++b) {
      const double c = r.water.c[b], albedo = c > 0 ? r.water.b[b] / c : 0.0;
      if (albedo == 0) continue;
      double j_over_c = 0;  // albedo int p2 L^(1) d omega
      for (size_t q = 0; q < nodes.size(); ++q) {
        j_over_c += nodes[q].factor * k::sea_radiance_map_path(r.sun_e[b] * r.e_beam_unit, albedo, 1.0, r.cos_io,
                                                               nodes[q].omega.y, c * z, c * ends[q]);
      }
      sum[b] += c * dz * k::sea_attenuation(c * z, cos_ji) * albedo * j_over_c;
    }
  }
  for (size_t b = 0; b < r.bands; ++b) addBand(r, b, t_out * sum[b] / cos_ji, rgb);
}

// Over a flat bottom (or none): the planes' depth nodes per band (sea_plane_depth).
void flatSecondOrder(const SecondOrderScene& r, double cos_ji, double t_out, const std::vector<SecondNode>& nodes,
                     double rgb[3]) {
  const int D = r.depth_steps;
  for (size_t b = 0; b < r.bands; ++b) {
    const double c = r.water.c[b], albedo = c > 0 ? r.water.b[b] / c : 0.0;
    if (albedo == 0) continue;
    const double tau_d = r.bottom ? c * r.scene->bottom.depth : -1.0;
    const double e_beam = r.sun_e[b] * r.e_beam_unit;
    double sum = 0;  // int exp(-tau sec_ji) (J/c) dtau
    for (int kz = 0; kz < D; ++kz) {
      double w = 0;
      const double tau = k::sea_plane_depth(kz, D, r.cos_io, tau_d, &w);
      double j_over_c = 0;  // albedo int p2 L^(1) d omega
      for (const SecondNode& node : nodes) {
        j_over_c += node.factor * k::sea_radiance_map(e_beam, albedo, 1.0, r.cos_io, node.omega.y, tau, tau_d);
      }
      sum += w * k::sea_attenuation(tau, cos_ji) * albedo * j_over_c;
    }
    addBand(r, b, t_out * sum / cos_ji, rgb);
  }
}

}  // namespace

Image renderSeaSecondReference(const Scene& scene, const SeaSecondReferenceSettings& settings) {
  if (!scene.water.present || scene.camera.position.y <= 0) {
    throw RuntimeError("the sea reference renders scenes seen from above the water only");
  }
  if (scene.surface.type != SurfaceDesc::Type::Flat || scene.sky.model != SkyDesc::Model::Uniform) {
    throw RuntimeError("the sea reference models a flat surface and a uniform sky only");
  }
  if (settings.depth_steps < 1 || settings.angle_steps < 1) {
    throw RuntimeError("second-order reference: depth_steps and angle_steps must be at least 1");
  }
  SecondOrderScene r;
  r.scene = &scene;
  const WavelengthGrid grid = makeGrid(scene.spectral.count, scene.spectral.min_nm, scene.spectral.max_nm);
  r.sensor = makeSensor(scene.spectral.sensor, grid, scene.spectral.white_balance, scene.spectral.camera_dir);
  r.water = resolveWater(scene.water, grid);
  r.sun_e = sunIrradianceBands(grid, scene.sun.irradiance);
  r.bands = grid.centers_nm.size();
  const double ior = scene.water.ior, g = scene.water.g;
  r.bottom = scene.bottom.type == BottomDesc::Type::Flat;
  // 000 §5.4: over a height field each pixel's view ray ends at its own z_Q (a fine march of the
  // floor, reference/sea_floor_reference.h) and each sampling ray where it leaves the water (the
  // floor, or the surface) — walked exactly (common/sea_bottom.h) from every quadrature node, no
  // tables. The depth nodes are then geometric, shared by the bands: midpoints in the transmittance
  // exp(-(1 + sec theta_io) c_min z) over [0, z_Q], c_min the clearest band's attenuation.
  r.height_field = scene.bottom.type == BottomDesc::Type::HeightField;
  if (r.height_field) {
    r.floor = loadHeightField(scene.bottom, scene.files.get());
    r.floor_step = r.floor.params.extent / std::max(r.floor.params.nx, r.floor.params.ny) / 64.0;
    for (double c : r.water.c) r.c_min = std::min(r.c_min, c);
    r.c_min = std::max(r.c_min, 1e-6);
  }

  const CameraDesc& cam = scene.camera;
  const Vec3 fwd = normalize(cam.look_at - cam.position);
  const Vec3 right = normalize(cross(fwd, cam.up));
  const Vec3 up = cross(right, fwd);
  const double tan_half = std::tan(cam.fov_y / 2), aspect = double(cam.width) / cam.height;

  Image img;
  img.width = cam.width;
  img.height = cam.height;
  img.channels = 3;
  img.channel_names = {"R", "G", "B"};
  img.pixels.assign(static_cast<size_t>(cam.width) * cam.height * 3, 0.0f);

  const k::real3 sun{std::sin(scene.sun.zenith) * std::cos(scene.sun.azimuth), std::cos(scene.sun.zenith),
                     std::sin(scene.sun.zenith) * std::sin(scene.sun.azimuth)};
  if (!(scene.sun.enabled && scene.sun.irradiance > 0 && sun.y > 0)) return img;  // no sun in the water
  const k::real3 n{0, 1, 0};
  k::real3 s{};  // travel direction of the refracted sunlight
  k::refract_dir(-sun, n, 1.0 / ior, &s);
  r.cos_io = std::max(-s.y, 1e-4);
  r.e_beam_unit = sun.y * (1 - k::fresnel_reflectance(sun.y, 1.0, ior)) / r.cos_io;
  r.depth_steps = settings.depth_steps;

  const int N = settings.angle_steps;
  tbb::parallel_for(0, cam.height, [&](int y) {
    std::vector<SecondNode> nodes(2 * static_cast<size_t>(N) * N);
    for (int x = 0; x < cam.width; ++x) {
      const double u = (2.0 * (x + 0.5) / cam.width - 1.0) * tan_half * aspect;
      const double v = (1.0 - 2.0 * (y + 0.5) / cam.height) * tan_half;
      const Vec3 dv = normalize(fwd + right * u + up * v);
      const k::real3 d{dv.x, dv.y, dv.z};
      if (d.y >= 0) continue;  // sky
      const double t_out = (1 - k::fresnel_reflectance(-d.y, 1.0, ior)) / (ior * ior);  // T_o and the n² law
      k::real3 view{};
      k::refract_dir(d, n, 1.0 / ior, &view);
      const double cos_ji = std::max(-view.y, 1e-4);
      secondOrderNodes(s, view, g, N, nodes);
      double rgb[3] = {0, 0, 0};
      if (r.height_field) {
        const double t_p = cam.position.y / -d.y;  // P on the surface
        const double o[3] = {cam.position.x + t_p * d.x, 0.0, cam.position.z + t_p * d.z};
        heightFieldSecondOrder(r, o, view, cos_ji, t_out, nodes, rgb);
      } else {
        flatSecondOrder(r, cos_ji, t_out, nodes, rgb);
      }
      float* px = &img.pixels[(static_cast<size_t>(y) * cam.width + x) * 3];
      for (int ch = 0; ch < 3; ++ch) px[ch] = static_cast<float>(rgb[ch]);
    }
  });
  return img;
}

}  // namespace seasim
