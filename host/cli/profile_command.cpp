#include "cli/profile_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "io/atomic_file.h"
#include "io/csv.h"
#include "io/svg_plot.h"
#include "radiometry/canonical_problems.h"
#include "radiometry/light_profile.h"
#include "scene/scene_parser.h"
#include "scene/set_option.h"
#include "scene/water_phase.h"
#include "sky/sky_light.h"
#include "spectral/jerlov.h"
#include "spectral/sensor.h"
#include "spectral/wavelength_grid.h"
#include "util/error.h"

namespace seasim {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// One channel's profile: a band's or the sensor's weighted sum of the bands'.
struct Channel {
  std::string name;
  double wavelength_nm = kNaN;
  LightProfile p;
};

Channel weighted(const std::string& name, const std::vector<Channel>& bands, const std::vector<double>& w) {
  Channel c;
  c.name = name;
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
  c.p.r_rs = c.p.e_d_air > 0 ? c.p.l_w / c.p.e_d_air : 0.0;
  return c;
}

// ln(E(z0) / E(z1)) / (z1 - z0): NaN where either is not positive or the depths coincide.
double attenuation(double e0, double e1, double z0, double z1) {
  return e0 > 0 && e1 > 0 && z1 > z0 ? std::log(e0 / e1) / (z1 - z0) : kNaN;
}

}  // namespace

int cmdProfile(const ProfileCmd& cmd) {
  if (cmd.depths.empty()) throw RuntimeError("profile: --depths needs at least one depth (m)");
  for (double z : cmd.depths)
    if (!(z >= 0 && std::isfinite(z))) throw RuntimeError("profile: depths must be finite and >= 0 m");
  if (cmd.streams < 2 || cmd.streams > 128) throw RuntimeError("profile: --streams must be in [2, 128]");
  std::vector<Override> overrides;
  for (const std::string& s : cmd.sets) overrides.push_back(parseSetOption(s));
  const Scene scene = loadScene(cmd.scene, overrides);
  if (!scene.water.present) throw RuntimeError("profile: '" + cmd.scene + "' has no [water]");
  if (scene.bottom.type == BottomDesc::Type::HeightField)
    throw RuntimeError("profile: '" + cmd.scene + "': a plane-parallel profile needs a flat bottom or none (got a height field)");
  std::vector<double> depths = cmd.depths;
  std::sort(depths.begin(), depths.end());
  depths.erase(std::unique(depths.begin(), depths.end()), depths.end());
  const bool bottom = scene.bottom.type == BottomDesc::Type::Flat;
  if (bottom && depths.back() > scene.bottom.depth)
    throw RuntimeError("profile: depth " + std::to_string(depths.back()) + " m lies below the bottom (" +
                       std::to_string(scene.bottom.depth) + " m)");

  const WavelengthGrid grid = makeGrid(scene.spectral.count, scene.spectral.min_nm, scene.spectral.max_nm);
  const Sensor sensor = makeSensor(scene.spectral.sensor, grid, scene.spectral.white_balance, scene.spectral.camera_dir);
  const PhaseFunction phase = waterPhase(scene.water);
  const bool sun_up = scene.sun.enabled && scene.sun.irradiance > 0 && std::cos(scene.sun.zenith) > 1e-6;
  const double mu_w = sun_up ? std::sqrt(1 - std::pow(std::sin(scene.sun.zenith) / scene.water.ior, 2)) : 0.85;
  const BandOptics water = resolveWater(scene.water, grid, std::clamp(mu_w, 0.6, 1.0));
  const std::vector<double> sun_e = sunIrradianceBands(grid, sun_up ? scene.sun.irradiance : 0.0);
  const SkyLight sky = makeSkyLight(scene, grid);
  const std::vector<double> sky_air = sky.horizontalIrradiance(), sky_water = sky.transmittedIrradiance(scene.water.ior);

  std::vector<Channel> bands;
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
    Channel c;
    char name[32];
    std::snprintf(name, sizeof name, "band_%.1f", grid.centers_nm[i]);
    c.name = name;
    c.wavelength_nm = grid.centers_nm[i];
    c.p = solveLightProfile(w, phase, depths, cmd.streams);
    bands.push_back(std::move(c));
  }
  std::vector<Channel> channels = bands;
  channels.push_back(weighted("sensor_r", bands, sensor.to_r));
  channels.push_back(weighted("sensor_g", bands, sensor.to_g));
  channels.push_back(weighted("sensor_b", bands, sensor.to_b));

  CsvWriter csv({"channel", "wavelength_nm", "depth_m", "E_d", "E_u", "E_0d", "E_0u", "L_u", "R", "K_d", "K_u",
                 "E_d_air", "L_w", "R_rs"});
  for (const Channel& c : channels) {
    for (size_t k = 0; k < c.p.rows.size(); ++k) {
      const LightAtDepth& r = c.p.rows[k];
      const LightAtDepth* prev = k > 0 ? &c.p.rows[k - 1] : nullptr;
      csv.addRow({c.name, c.wavelength_nm, r.depth, r.e_d, r.e_u, r.e_0d, r.e_0u, r.l_u, r.e_d > 0 ? r.e_u / r.e_d : kNaN,
                  prev ? attenuation(prev->e_d, r.e_d, prev->depth, r.depth) : kNaN,
                  prev ? attenuation(prev->e_u, r.e_u, prev->depth, r.depth) : kNaN, c.p.e_d_air, c.p.l_w, c.p.r_rs});
    }
  }
  if (!cmd.plot.empty()) {
    PlotSpec spec;
    spec.title = "Light profile of " + cmd.scene + " (" + phase.name() + " phase, " + std::to_string(cmd.streams) +
                 " streams)";
    spec.x_label = "depth (m)";
    spec.y_label = "irradiance through the sensor (W m^-2), radiance (W m^-2 sr^-1)";
    spec.log_y = true;
    for (size_t ch = channels.size() - 3; ch < channels.size(); ++ch) {
      const Channel& c = channels[ch];
      const std::string tag = c.name.substr(7);
      PlotSeries ed{"E_d " + tag, {}, {}}, eu{"E_u " + tag, {}, {}}, lu{"L_u " + tag, {}, {}};
      for (const LightAtDepth& r : c.p.rows) {
        ed.x.push_back(r.depth), ed.y.push_back(r.e_d);
        eu.x.push_back(r.depth), eu.y.push_back(r.e_u);
        lu.x.push_back(r.depth), lu.y.push_back(r.l_u);
      }
      spec.series.push_back(ed);
      spec.series.push_back(eu);
      spec.series.push_back(lu);
    }
    // Both files are built before either is written: a failure leaves neither half-made.
    const std::string svg = renderSvgPlot(spec);
    if (!cmd.csv.empty()) csv.write(cmd.csv);
    writeTextAtomic(cmd.plot, svg);
  } else if (!cmd.csv.empty()) {
    csv.write(cmd.csv);
  }
  if (cmd.csv.empty()) std::fputs(csv.str().c_str(), stdout);
  for (size_t ch = channels.size() - 3; ch < channels.size(); ++ch)
    std::printf("%s: L_w %.5g, R_rs %.5g 1/sr\n", channels[ch].name.c_str(), channels[ch].p.l_w, channels[ch].p.r_rs);
  return 0;
}

int cmdCanonicalProblems(const CanonicalProblemsCmd& cmd) {
  const std::string values =
      cmd.values.empty() ? std::string(SEASIM_SOURCE_DIR) + "/tests/data/mobley1993/problems.csv" : cmd.values;
  const std::vector<CanonicalValue> published = loadCanonicalValues(values);
  std::string md =
      "# Mobley et al. (1993) canonical problems: seasim's discrete-ordinates light profile\n\n"
      "Made by `seasim canonical-problems --out results/canonical_problems.md`. Published means and the codes'\n"
      "coefficient of variation (cv) from Mobley et al. (1993), Appl. Opt. 32(36), 7484-7504 (provenance:\n"
      "tests/data/mobley1993/README.md). Rule: |seasim/mean - 1| <= max(cv, 2 %) for E_d and E_0u, max(cv, 10 %)\n"
      "for L_u. Problem 1: Rayleigh-like phase; 2: Petzold; 6: Petzold over a Lambertian bottom R = 0.5 at\n"
      "c z = 5. Flat surface, n = 1.34, sun 60 deg, black sky, 1 W m^-2 normal to the beam.\n\n";
  int failed = 0;
  for (int n : cmd.streams) {
    double seconds = 0;
    const std::vector<CanonicalResult> r = solveCanonicalProblems(published, n, &seconds);
    md += "## " + std::to_string(n) + " streams per hemisphere\n\n" + canonicalTableMarkdown(r, n, seconds) + "\n";
    double worst = 0;
    int fails = 0;
    for (const CanonicalResult& x : r) {
      worst = std::max(worst, std::abs(x.relative_error));
      fails += !x.pass;
    }
    std::printf("streams %d: %.3f s, worst |seasim/mean - 1| %.1f %%, %d of %zu outside the rule\n", n, seconds,
                100 * worst, fails, r.size());
    if (n == cmd.streams.back()) failed = fails;
  }
  if (!cmd.out.empty()) writeTextAtomic(cmd.out, md);
  else std::fputs(md.c_str(), stdout);
  return failed ? 1 : 0;
}

}  // namespace seasim
