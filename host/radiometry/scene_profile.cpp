#include "radiometry/scene_profile.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "radiometry/light_profile_mc.h"
#include "scene/water_phase.h"
#include "sky/sky_light.h"
#include "spectral/jerlov.h"
#include "spectral/sensor.h"
#include "spectral/wavelength_grid.h"
#include "util/error.h"

namespace seasim {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

ProfileChannel weighted(const std::string& name, const std::vector<ProfileChannel>& bands, const std::vector<double>& w) {
  ProfileChannel c;
  c.name = name;
  c.wavelength_nm = kNaN;
  c.p = bands.front().p;
  for (LightAtDepth& r : c.p.rows) r = LightAtDepth{r.depth};
  c.p.e_d_air = c.p.l_w = 0;
  for (size_t i = 0; i < bands.size(); ++i) {
    const LightProfile& b = bands[i].p;
    for (size_t k = 0; k < b.rows.size(); ++k) {
      c.p.rows[k].e_d += w[i] * b.rows[k].e_d;
      c.p.rows[k].e_u += w[i] * b.rows[k].e_u;
      c.p.rows[k].e_0d += w[i] * b.rows[k].e_0d;
      c.p.rows[k].e_0u += w[i] * b.rows[k].e_0u;
      c.p.rows[k].l_u += w[i] * b.rows[k].l_u;
    }
    c.p.e_d_air += w[i] * b.e_d_air;
    c.p.l_w += w[i] * b.l_w;
  }
  // Independent bands: the variances add with the weights squared.
  if (!bands.front().se.empty()) {
    c.se.assign(c.p.rows.size(), LightAtDepth{});
    double lw2 = 0;
    for (size_t k = 0; k < c.se.size(); ++k) {
      double v[5] = {0, 0, 0, 0, 0};
      for (size_t i = 0; i < bands.size(); ++i) {
        const LightAtDepth& e = bands[i].se[k];
        const double w2 = w[i] * w[i];
        v[0] += w2 * e.e_d * e.e_d, v[1] += w2 * e.e_u * e.e_u, v[2] += w2 * e.e_0d * e.e_0d;
        v[3] += w2 * e.e_0u * e.e_0u, v[4] += w2 * e.l_u * e.l_u;
      }
      c.se[k] = LightAtDepth{c.p.rows[k].depth, std::sqrt(v[0]), std::sqrt(v[1]), std::sqrt(v[2]), std::sqrt(v[3]),
                             std::sqrt(v[4])};
    }
    for (size_t i = 0; i < bands.size(); ++i) lw2 += w[i] * w[i] * bands[i].l_w_se * bands[i].l_w_se;
    c.l_w_se = std::sqrt(lw2);
  }
  c.p.r_rs = c.p.e_d_air > 0 ? c.p.l_w / c.p.e_d_air : 0.0;
  return c;
}

// ln(E(z0) / E(z1)) / (z1 - z0): NaN where either is not positive or the depths coincide.
double attenuation(double e0, double e1, double z0, double z1) {
  return e0 > 0 && e1 > 0 && z1 > z0 ? std::log(e0 / e1) / (z1 - z0) : kNaN;
}

}  // namespace

std::string sceneProfileProblem(const Scene& scene, const std::vector<double>& depths) {
  if (!scene.water.present) return "the scene has no [water]";
  if (scene.bottom.type == BottomDesc::Type::HeightField)
    return "a plane-parallel profile needs a flat bottom or none (got a height field)";
  if (depths.empty()) return "no depths asked";
  for (double z : depths)
    if (!(z >= 0 && std::isfinite(z))) return "depths must be finite and >= 0 m";
  const double deepest = *std::max_element(depths.begin(), depths.end());
  if (scene.bottom.type == BottomDesc::Type::Flat && deepest > scene.bottom.depth)
    return "depth " + std::to_string(deepest) + " m lies below the bottom (" + std::to_string(scene.bottom.depth) +
           " m)";
  return "";
}

SceneProfile sceneLightProfile(const Scene& scene, const std::vector<double>& depths, const SceneProfileOptions& options,
                               const std::function<void(size_t, const PlaneParallelWater&)>& each_band) {
  if (const std::string problem = sceneProfileProblem(scene, depths); !problem.empty())
    throw RuntimeError("profile: " + problem);
  const WavelengthGrid grid = makeGrid(scene.spectral.count, scene.spectral.min_nm, scene.spectral.max_nm);
  const Sensor sensor = makeSensor(scene.spectral.sensor, grid, scene.spectral.white_balance, scene.spectral.camera_dir);
  const PhaseFunction phase = waterPhase(scene.water);
  const bool sun_up = scene.sun.enabled && scene.sun.irradiance > 0 && std::cos(scene.sun.zenith) > 1e-6;
  const double mu_w = sun_up ? std::sqrt(1 - std::pow(std::sin(scene.sun.zenith) / scene.water.ior, 2)) : 0.85;
  const BandOptics water = resolveWater(scene.water, grid, std::clamp(mu_w, 0.6, 1.0));
  const std::vector<double> sun_e = sunIrradianceBands(grid, sun_up ? scene.sun.irradiance : 0.0);
  const SkyLight sky = makeSkyLight(scene, grid);
  const std::vector<double> sky_air = sky.horizontalIrradiance(), sky_water = sky.transmittedIrradiance(scene.water.ior);
  const bool bottom = scene.bottom.type == BottomDesc::Type::Flat;

  SceneProfile out;
  out.phase_name = phase.name();
  out.monte_carlo = options.monte_carlo;
  std::vector<ProfileChannel> bands;
  for (size_t i = 0; i < grid.size(); ++i) {
    PlaneParallelWater w;
    w.a = water.a[i];
    w.b = water.b[i];
    w.ior = scene.water.ior;
    w.bottom_depth = bottom ? scene.bottom.depth : 0.0;
    w.bottom_albedo = bottom ? scene.bottom.albedo.at(grid.centers_nm[i]) : 0.0;
    w.sun_zenith = sun_up ? scene.sun.zenith : 0.0;
    w.sun_irradiance = sun_e[i];
    w.sky_irradiance = sky_air[i];
    w.sky_transmitted = sky_water[i];
    ProfileChannel c;
    char name[32];
    std::snprintf(name, sizeof name, "band_%.1f", grid.centers_nm[i]);
    c.name = name;
    c.wavelength_nm = grid.centers_nm[i];
    if (options.monte_carlo) {
      // Depth 0 is always traced: L_w and R_rs come from L_u there.
      std::vector<double> zs = depths;
      if (zs.front() > 0) zs.insert(zs.begin(), 0.0);
      MonteCarloSettings settings;
      settings.photons = options.photons;
      settings.seed = static_cast<unsigned>(i + 1);
      LightProfileMc r = solveLightProfileMonteCarlo(w, phase, zs, settings);
      if (zs.size() > depths.size()) {
        r.mean.rows.erase(r.mean.rows.begin());
        r.standard_error.erase(r.standard_error.begin());
      }
      c.p = r.mean;
      c.se = r.standard_error;
      c.l_w_se = r.l_w_se;
    } else {
      c.p = solveLightProfile(w, phase, depths, options.streams);
    }
    bands.push_back(std::move(c));
    if (each_band) each_band(i, w);
  }
  out.channels = bands;
  out.channels.push_back(weighted("sensor_r", bands, sensor.to_r));
  out.channels.push_back(weighted("sensor_g", bands, sensor.to_g));
  out.channels.push_back(weighted("sensor_b", bands, sensor.to_b));
  return out;
}

CsvWriter sceneProfileCsv(const SceneProfile& profile) {
  std::vector<std::string> header = {"channel", "wavelength_nm", "depth_m", "E_d", "E_u", "E_0d", "E_0u", "L_u", "R",
                                     "K_d", "K_u", "E_d_air", "L_w", "R_rs"};
  if (profile.monte_carlo)
    for (const char* k : {"E_d_se", "E_u_se", "E_0d_se", "E_0u_se", "L_u_se", "L_w_se"}) header.push_back(k);
  CsvWriter csv(header);
  for (const ProfileChannel& c : profile.channels) {
    for (size_t k = 0; k < c.p.rows.size(); ++k) {
      const LightAtDepth& r = c.p.rows[k];
      const LightAtDepth* prev = k > 0 ? &c.p.rows[k - 1] : nullptr;
      std::vector<CsvCell> row = {c.name, c.wavelength_nm, r.depth, r.e_d, r.e_u, r.e_0d, r.e_0u, r.l_u,
                                  r.e_d > 0 ? r.e_u / r.e_d : kNaN,
                                  prev ? attenuation(prev->e_d, r.e_d, prev->depth, r.depth) : kNaN,
                                  prev ? attenuation(prev->e_u, r.e_u, prev->depth, r.depth) : kNaN, c.p.e_d_air, c.p.l_w,
                                  c.p.r_rs};
      if (profile.monte_carlo) {
        const LightAtDepth& e = c.se[k];
        for (double v : {e.e_d, e.e_u, e.e_0d, e.e_0u, e.l_u, c.l_w_se}) row.push_back(v);
      }
      csv.addRow(std::move(row));
    }
  }
  return csv;
}

}  // namespace seasim
