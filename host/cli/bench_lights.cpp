// bench_lights.cpp — `seasim bench --scene S --lights 1,2,4`: spotlight shafts' cost against the number
// of lights (001 §5: "cost linear in the number of lights"). The scene with its first k spotlights, ms
// per frame of the shadow-map and shafts kernels (median of --repeat after a warm-up), a least-squares
// line t(k) = a + b k with R² (math/line_fit.h), and optionally a CSV table and an SVG plot.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "device/device.h"
#include "io/csv.h"
#include "io/svg_plot.h"
#include "math/line_fit.h"
#include "plan/pass_descriptor.h"
#include "quality/auto_quality.h"
#include "render/renderer.h"
#include "scene/scene_parser.h"
#include "util/error.h"
#include "util/statistics.h"

namespace fs = std::filesystem;

namespace seasim {

namespace {

struct LightsTiming {
  double total_ms, shadow_ms, shafts_ms;  // medians over the repeats
};

// The scene with its first k spotlights: the shadow maps' and the shafts kernel's ms per frame.
LightsTiming timeLights(Device& device, const Scene& full, int k, int repeat, const std::string& shadow_maps,
                        const std::string& shafts_pass) {
  Scene scene = full;
  scene.spotlights.resize(k);
  Renderer renderer(device, scene, shippedPasses());
  (void)renderer.render();  // warm-up (PoCL compiles lazily; auto quality searches once)
  std::vector<double> totals, shadow, shafts;
  for (int r = 0; r < std::max(1, repeat); ++r) {
    renderer.rerunAll();
    const FrameResult frame = renderer.render();
    double sm = 0, sh = 0;
    for (const auto& t : frame.timings) {
      if (t.name == shadow_maps) sm += t.ms;
      if (t.name == shafts_pass) sh += t.ms;
    }
    totals.push_back(sm + sh);
    shadow.push_back(sm);
    shafts.push_back(sh);
  }
  return {median(totals), median(shadow), median(shafts)};
}

}  // namespace

int benchLights(Device& device, const BenchCmd& cmd, const std::vector<Override>& overrides) {
  const Scene full = loadScene(cmd.scene, overrides);
  const std::string& shadow_maps = descriptorFor(PassRole::ShadowMaps).name;
  const std::string& shafts_pass = descriptorFor(PassRole::Spotlights).name;
  CsvWriter table({"lights", "kernel_ms_median", shadow_maps + "_ms", shafts_pass + "_ms"});
  PlotSeries total_series{"shadow maps + shafts", {}, {}}, shafts_series{"shafts kernel", {}, {}};
  for (int k : cmd.lights) {
    if (k < 1 || k > static_cast<int>(full.spotlights.size())) {
      throw RuntimeError("--lights " + std::to_string(k) + ": " + cmd.scene + " has " +
                         std::to_string(full.spotlights.size()) + " spotlights; give counts from 1 to that");
    }
    const LightsTiming t = timeLights(device, full, k, cmd.repeat, shadow_maps, shafts_pass);
    std::printf("lights = %d  %10.3f ms per frame  [shadow maps %.3f, shafts %.3f ms]\n", k, t.total_ms, t.shadow_ms,
                t.shafts_ms);
    table.addRow({k, t.total_ms, t.shadow_ms, t.shafts_ms});
    total_series.x.push_back(k);
    total_series.y.push_back(t.total_ms);
    shafts_series.x.push_back(k);
    shafts_series.y.push_back(t.shafts_ms);
  }
  if (total_series.x.size() >= 2) {  // how straight the line is: R²
    const LineFit fit = fitLine(total_series.x, total_series.y);
    std::printf("fit: t(k) = %.4g + %.4g k ms per frame (R^2 = %.4f)\n", fit.intercept, fit.slope, fit.r2);
  }
  if (!cmd.csv.empty()) table.write(cmd.csv);
  if (!cmd.plot.empty()) {
    PlotSpec spec;
    spec.title = "Shafts time vs light count: " + fs::path(cmd.scene).stem().string() + " (" + device.info().name + ")";
    spec.x_label = "spotlights";
    spec.y_label = "ms per frame";
    spec.series = {total_series, shafts_series};
    writeSvgPlot(cmd.plot, spec);
  }
  return 0;
}

}  // namespace seasim
