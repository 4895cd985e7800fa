// scene_profile.h — the plane-parallel light profile (light_profile.h) of a scene: its water's a(λ), b(λ)
// and phase, its sun, sky, flat surface and flat bottom (or none), per wavelength band and through its
// sensor, as `seasim profile` prints it and the light_profile pass writes it beside a render
// (host/passes/nodes/light_profile_node.cpp). Quantities: docs/radiometry.md.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "io/csv.h"
#include "radiometry/light_profile.h"
#include "scene/scene.h"

namespace seasim {

// One channel's profile: a band's, or the sensor's weighted sum of the bands'.
struct ProfileChannel {
  std::string name;              // "band_450.0", "sensor_r", ...
  double wavelength_nm;          // NaN for the sensor's channels
  LightProfile p;
  std::vector<LightAtDepth> se;  // the Monte Carlo's standard errors (empty for the discrete ordinates)
  double l_w_se = 0;
};

struct SceneProfileOptions {
  bool monte_carlo = false;      // else the discrete ordinates
  int streams = 16;              // discrete ordinates: cosines per hemisphere
  long long photons = 1000000;   // Monte Carlo: per band
};

struct SceneProfile {
  std::vector<ProfileChannel> channels;  // every band, then sensor_r, sensor_g, sensor_b
  std::string phase_name;
  bool monte_carlo = false;
};

// Why the scene cannot have a plane-parallel profile at `depths` (no water, a height-field bottom, a
// depth below the bottom or negative), or "" when it can.
std::string sceneProfileProblem(const Scene& scene, const std::vector<double>& depths);

// The profile at `depths` (m, sorted, distinct, checked by sceneProfileProblem; RuntimeError otherwise).
// `each_band`, when given, is called with every band's plane-parallel water (its index, the water) for
// what else the caller computes per band (the radiance distribution).
SceneProfile sceneLightProfile(const Scene& scene, const std::vector<double>& depths, const SceneProfileOptions& options,
                               const std::function<void(size_t, const PlaneParallelWater&)>& each_band = {});

// The CSV of `seasim profile`: channel, wavelength_nm, depth_m, E_d, E_u, E_0d, E_0u, L_u, R, K_d, K_u,
// E_d_air, L_w, R_rs (and the standard errors for the Monte Carlo).
CsvWriter sceneProfileCsv(const SceneProfile& profile);

}  // namespace seasim
