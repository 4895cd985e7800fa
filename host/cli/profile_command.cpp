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
#include "radiometry/light_profile_mc.h"
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
  std::vector<LightAtDepth> se;  // the Monte Carlo's standard errors (empty for the discrete ordinates)
  double l_w_se = 0;
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

int cmdProfile(const ProfileCmd& cmd) {
  if (cmd.depths.empty()) throw RuntimeError("profile: --depths needs at least one depth (m)");
  for (double z : cmd.depths)
    if (!(z >= 0 && std::isfinite(z))) throw RuntimeError("profile: depths must be finite and >= 0 m");
  if (cmd.streams < 2 || cmd.streams > 128) throw RuntimeError("profile: --streams must be in [2, 128]");
  const bool mc = cmd.solver == "monte_carlo";
  if (!mc && cmd.solver != "discrete_ordinates")
    throw RuntimeError("profile: --solver must be discrete_ordinates or monte_carlo, got '" + cmd.solver + "'");
  if (mc && cmd.photons < 100) throw RuntimeError("profile: --photons must be >= 100");
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
    if (mc) {
      // Depth 0 is always traced: L_w and R_rs come from L_u there.
      std::vector<double> zs = depths;
      if (zs.front() > 0) zs.insert(zs.begin(), 0.0);
      MonteCarloSettings settings;
      settings.photons = cmd.photons;
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
      c.p = solveLightProfile(w, phase, depths, cmd.streams);
    }
    bands.push_back(std::move(c));
  }
  std::vector<Channel> channels = bands;
  channels.push_back(weighted("sensor_r", bands, sensor.to_r));
  channels.push_back(weighted("sensor_g", bands, sensor.to_g));
  channels.push_back(weighted("sensor_b", bands, sensor.to_b));

  std::vector<std::string> header = {"channel", "wavelength_nm", "depth_m", "E_d", "E_u", "E_0d", "E_0u", "L_u", "R",
                                     "K_d", "K_u", "E_d_air", "L_w", "R_rs"};
  if (mc)
    for (const char* k : {"E_d_se", "E_u_se", "E_0d_se", "E_0u_se", "L_u_se", "L_w_se"}) header.push_back(k);
  CsvWriter csv(header);
  for (const Channel& c : channels) {
    for (size_t k = 0; k < c.p.rows.size(); ++k) {
      const LightAtDepth& r = c.p.rows[k];
      const LightAtDepth* prev = k > 0 ? &c.p.rows[k - 1] : nullptr;
      std::vector<CsvCell> row = {c.name, c.wavelength_nm, r.depth, r.e_d, r.e_u, r.e_0d, r.e_0u, r.l_u,
                                  r.e_d > 0 ? r.e_u / r.e_d : kNaN,
                                  prev ? attenuation(prev->e_d, r.e_d, prev->depth, r.depth) : kNaN,
                                  prev ? attenuation(prev->e_u, r.e_u, prev->depth, r.depth) : kNaN, c.p.e_d_air, c.p.l_w,
                                  c.p.r_rs};
      if (mc) {
        const LightAtDepth& e = c.se[k];
        for (double v : {e.e_d, e.e_u, e.e_0d, e.e_0u, e.l_u, c.l_w_se}) row.push_back(v);
      }
      csv.addRow(std::move(row));
    }
  }
  if (!cmd.plot.empty()) {
    PlotSpec spec;
    spec.title = "Light profile of " + cmd.scene + " (" + phase.name() + " phase, " +
                 (mc ? std::to_string(cmd.photons) + " photons" : std::to_string(cmd.streams) + " streams") + ")";
    spec.x_label = "depth (m)";
    spec.y_label = "W m^-2 nm^-1 (per band), sensor units (channel g); L_u per sr";
    spec.log_y = true;
    // E_d of at most eight bands (every k-th) and the sensor's green channel's E_d, E_u and L_u.
    auto series = [&](const Channel& c, const std::string& name, double LightAtDepth::*field) {
      PlotSeries out{name, {}, {}};
      for (const LightAtDepth& r : c.p.rows) {
        out.x.push_back(r.depth);
        out.y.push_back(r.*field);
      }
      return out;
    };
    const size_t step = (bands.size() + 7) / 8;
    for (size_t i = 0; i < bands.size(); i += step) {
      char name[48];
      std::snprintf(name, sizeof name, "E_d %.0f nm", bands[i].wavelength_nm);
      spec.series.push_back(series(bands[i], name, &LightAtDepth::e_d));
    }
    const Channel& g = channels[channels.size() - 2];
    spec.series.push_back(series(g, "E_d sensor g", &LightAtDepth::e_d));
    spec.series.push_back(series(g, "E_u sensor g", &LightAtDepth::e_u));
    spec.series.push_back(series(g, "L_u sensor g", &LightAtDepth::l_u));
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
  if (cmd.streams.empty()) throw RuntimeError("canonical-problems: --streams needs at least one count");
  for (int n : cmd.streams)
    if (n < 2 || n > 128) throw RuntimeError("canonical-problems: stream counts must be in [2, 128]");
  const std::string values =
      cmd.values.empty() ? std::string(SEASIM_SOURCE_DIR) + "/tests/data/mobley1993/problems.csv" : cmd.values;
  const std::vector<CanonicalValue> published = loadCanonicalValues(values);
  std::string md =
      "# Mobley et al. (1993) canonical problems: seasim's light profiles\n\n"
      "Made by `build/seasim canonical-problems --out results/canonical_problems/README.md` (" +
      std::to_string(cmd.photons) +
      " photons per problem and albedo). Published means and the codes' coefficient of variation (cv) from\n"
      "Mobley et al. (1993), Appl. Opt. 32(36), 7484-7504 (provenance: tests/data/mobley1993/README.md).\n"
      "Rule: |seasim/mean - 1| <= max(cv, 2 %) for E_d and E_0u, max(cv, 10 %) for L_u (the Monte Carlo: plus 3\n"
      "standard errors). Problem 1: Rayleigh-like phase; 2: Petzold; 6: Petzold over a Lambertian bottom R = 0.5\n"
      "at c z = 5. Flat surface, n = 1.34, sun 60 deg, black sky, 1 W m^-2 normal to the beam; c = 1 m^-1.\n"
      "Timings: one run on a loaded 2-core VM; re-measure on a quiet machine.\n\n";
  std::vector<CanonicalResult> mc;
  double mc_seconds = 0;
  if (cmd.photons > 0) mc = monteCarloCanonicalProblems(published, cmd.photons, &mc_seconds);
  int failed = 0;
  std::string sweep =
      "## Discrete ordinates against the Monte Carlo by stream count\n\n"
      "Over the values the Monte Carlo resolves (standard error < 2 %): |DO/MC - 1|, and the discrete\n"
      "ordinates' time for all problems.\n\n| streams | time (s) | values | mean abs diff | max abs diff |\n"
      "|---|---|---|---|---|\n";
  std::string tables;
  for (int n : cmd.streams) {
    double seconds = 0;
    const std::vector<CanonicalResult> r = solveCanonicalProblems(published, n, &seconds);
    tables += "## Discrete ordinates, " + std::to_string(n) + " streams\n\n" +
              canonicalTableMarkdown(r, "Discrete ordinates, " + std::to_string(n) + " streams per hemisphere", seconds) +
              "\n";
    int fails = 0;
    for (const CanonicalResult& x : r) fails += !x.pass;
    double sum = 0, worst = 0;
    int count = 0;
    for (size_t i = 0; i < mc.size(); ++i) {
      if (!(mc[i].standard_error < 0.02 * mc[i].computed)) continue;
      const double d = std::abs(r[i].computed / mc[i].computed - 1);
      sum += d;
      worst = std::max(worst, d);
      ++count;
    }
    char buf[160];
    std::snprintf(buf, sizeof buf, "| %d | %.3f | %d | %.2f %% | %.2f %% |\n", n, seconds, count,
                  count ? 100 * sum / count : 0.0, 100 * worst);
    sweep += buf;
    std::printf("streams %d: %.3f s, %d of %zu outside the rule; vs Monte Carlo: max %.2f %% over %d values\n", n,
                seconds, fails, r.size(), 100 * worst, count);
    if (n == cmd.streams.back()) failed = fails;
  }
  if (!mc.empty()) {
    md += sweep + "\n## Monte Carlo reference\n\n" +
          canonicalTableMarkdown(mc, "Monte Carlo, " + std::to_string(cmd.photons) + " photons per problem", mc_seconds) +
          "\n";
    int fails = 0, judged = 0;
    for (const CanonicalResult& x : mc) {
      fails += x.resolved && !x.pass;
      judged += x.resolved;
    }
    std::printf("monte carlo: %.1f s, %d of %d resolved values outside the rule\n", mc_seconds, fails, judged);
  }
  md += tables;
  if (!cmd.out.empty()) writeTextAtomic(cmd.out, md);
  else std::fputs(md.c_str(), stdout);
  return failed ? 1 : 0;
}

}  // namespace seasim
