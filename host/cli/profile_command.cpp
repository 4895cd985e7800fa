#include "cli/profile_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "io/atomic_file.h"
#include "io/csv.h"
#include "io/image_io.h"
#include "io/svg_plot.h"
#include "radiometry/canonical_problems.h"
#include "radiometry/light_profile.h"
#include "radiometry/light_profile_mc.h"
#include "radiometry/radiance_distribution.h"
#include "radiometry/scene_profile.h"
#include "scene/scene_parser.h"
#include "scene/set_option.h"
#include "scene/water_phase.h"
#include "spectral/sensor.h"
#include "spectral/wavelength_grid.h"
#include "util/error.h"

namespace seasim {

int cmdProfile(const ProfileCmd& cmd) {
  if (cmd.depths.empty()) throw RuntimeError("profile: --depths needs at least one depth (m)");
  for (double z : cmd.depths)
    if (!(z >= 0 && std::isfinite(z))) throw RuntimeError("profile: depths must be finite and >= 0 m");
  if (cmd.streams < 2 || cmd.streams > 128) throw RuntimeError("profile: --streams must be in [2, 128]");
  const bool mc = cmd.solver == "monte_carlo";
  if (!mc && cmd.solver != "discrete_ordinates")
    throw RuntimeError("profile: --solver must be discrete_ordinates or monte_carlo, got '" + cmd.solver + "'");
  if (mc && cmd.photons < 100) throw RuntimeError("profile: --photons must be >= 100");
  if (!cmd.radiance_exr.empty() && (cmd.radiance_rows < 2 || cmd.radiance_rows % 2 || cmd.radiance_rows > 1800))
    throw RuntimeError("profile: --radiance-rows must be even, in [2, 1800]");
  if (!cmd.radiance_exr.empty() && cmd.radiance_photons < 100)
    throw RuntimeError("profile: --radiance-photons must be >= 100");
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
  SceneProfileOptions options;
  options.monte_carlo = mc;
  options.streams = cmd.streams;
  options.photons = cmd.photons;
  std::vector<RadianceDistribution> radiance;  // per band, when the EXR is asked for
  const SceneProfile profile =
      sceneLightProfile(scene, depths, options, [&](size_t i, const PlaneParallelWater& w) {
        if (cmd.radiance_exr.empty()) return;
        RadianceDistributionSettings rs;
        rs.n_theta = cmd.radiance_rows;
        rs.n_phi = 2 * cmd.radiance_rows;
        rs.photons = cmd.radiance_photons;
        rs.seed = static_cast<unsigned>(i + 1);
        radiance.push_back(solveRadianceDistribution(w, phase, depths, rs));
      });
  const std::vector<ProfileChannel>& channels = profile.channels;
  const std::vector<ProfileChannel> bands(channels.begin(), channels.end() - 3);
  // The radiance EXR: per depth the sensor's R, G, B and their standard errors (independent bands: the
  // variances add with the weights squared), layers named z<depth>m and z<depth>m_se.
  Image radiance_image;
  if (!radiance.empty()) {
    const int rows = cmd.radiance_rows, cols = 2 * cmd.radiance_rows;
    radiance_image.resize(cols, rows, static_cast<int>(6 * depths.size()));
    for (size_t k = 0; k < depths.size(); ++k) {
      char layer[48];
      std::snprintf(layer, sizeof layer, "z%gm", depths[k]);
      for (const char* ch : {".R", ".G", ".B"}) radiance_image.channel_names.push_back(std::string(layer) + ch);
      for (const char* ch : {".R", ".G", ".B"}) radiance_image.channel_names.push_back(std::string(layer) + "_se" + ch);
      const std::vector<double>* weights[3] = {&sensor.to_r, &sensor.to_g, &sensor.to_b};
      for (int y = 0; y < rows; ++y)
        for (int x = 0; x < cols; ++x) {
          const size_t q = static_cast<size_t>(y) * cols + x;
          for (int ch = 0; ch < 3; ++ch) {
            double v = 0, var = 0;
            for (size_t i = 0; i < radiance.size(); ++i) {
              const double wi = (*weights[ch])[i];
              v += wi * radiance[i].radiance[k][q];
              var += wi * wi * radiance[i].standard_error[k][q] * radiance[i].standard_error[k][q];
            }
            radiance_image.at(x, y, static_cast<int>(6 * k) + ch) = static_cast<float>(v);
            radiance_image.at(x, y, static_cast<int>(6 * k) + 3 + ch) = static_cast<float>(std::sqrt(var));
          }
        }
    }
  }
  const CsvWriter csv = sceneProfileCsv(profile);
  // Written before the CSV and the plot: a failure here leaves none of them.
  if (!radiance.empty()) writeExr(cmd.radiance_exr, radiance_image);
  if (!cmd.plot.empty()) {
    PlotSpec spec;
    spec.title = "Light profile of " + cmd.scene + " (" + phase.name() + " phase, " +
                 (mc ? std::to_string(cmd.photons) + " photons" : std::to_string(cmd.streams) + " streams") + ")";
    spec.x_label = "depth (m)";
    spec.y_label = "W m^-2 nm^-1 (per band), sensor units (channel g); L_u per sr";
    spec.log_y = true;
    // E_d of at most eight bands (every k-th) and the sensor's green channel's E_d, E_u and L_u.
    auto series = [&](const ProfileChannel& c, const std::string& name, double LightAtDepth::*field) {
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
    const ProfileChannel& g = channels[channels.size() - 2];
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

namespace {
std::string streamList(const std::vector<int>& streams) {
  std::string s;
  for (int n : streams) s += (s.empty() ? "" : ",") + std::to_string(n);
  return s;
}
}  // namespace

int cmdCanonicalProblems(const CanonicalProblemsCmd& cmd) {
  if (cmd.streams.empty()) throw RuntimeError("canonical-problems: --streams needs at least one count");
  for (int n : cmd.streams)
    if (n < 2 || n > 128) throw RuntimeError("canonical-problems: stream counts must be in [2, 128]");
  const std::string values =
      cmd.values.empty() ? std::string(SEASIM_SOURCE_DIR) + "/tests/data/mobley1993/problems.csv" : cmd.values;
  const std::vector<CanonicalValue> published = loadCanonicalValues(values);
  std::string md =
      "# Mobley et al. (1993) canonical problems: seasim's light profiles\n\n"
      "Made by `build/seasim canonical-problems --streams " + streamList(cmd.streams) + " --photons " +
      std::to_string(cmd.photons) +
      " --out results/canonical_problems/README.md`\n(photons per problem and albedo). Published means and the codes' coefficient of variation (cv) from\n"
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
          "The next-event estimator of host/radiometry/light_profile_mc.h (expected scores at every collision,\n"
          "L_u the mean radiance within 5 deg of the nadir, a weight window in depth); standard errors from 64\n"
          "independent batches of photons (host/reference/batch_error.h).\n\n" +
          canonicalTableMarkdown(mc, "Monte Carlo, " + std::to_string(cmd.photons) + " photons per problem", mc_seconds) +
          "\n";
    int fails = 0, judged = 0;
    for (const CanonicalResult& x : mc) {
      fails += x.resolved && !x.pass;
      judged += x.resolved;
    }
    std::printf("monte carlo: %.1f s, %d of %d resolved values outside the rule\n", mc_seconds, fails, judged);
    failed += fails;  // the exit status speaks for both solvers
  }
  md += tables;
  if (!cmd.out.empty()) writeTextAtomic(cmd.out, md);
  else std::fputs(md.c_str(), stdout);
  return failed ? 1 : 0;
}

}  // namespace seasim
