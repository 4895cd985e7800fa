// bench_wavelengths.cpp — `seasim bench --scene S --wavelengths 4,16,64`: kernel time against the
// number of wavelength bands (002 §6.3), median of --repeat frames after a warm-up, every pass but the
// NaN check; with --limits each band loop's share of the measured exp/s bound. Under water it also
// times the same G-buffer + K_d shading as a plain C++/oneTBB loop on this CPU, scalar and vectorised
// (host/underwater/underwater_cpu.cpp, float, no froxel term), interleaved run by run, for the ratio.
// Least-squares lines t(n) = a + b n (math/line_fit.h); optionally a CSV table and an SVG plot.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "device/device.h"
#include "io/csv.h"
#include "io/svg_plot.h"
#include "math/line_fit.h"
#include "plan/pass_descriptor.h"
#include "plan/plan.h"
#include "plan/scene_facts.h"
#include "quality/auto_quality.h"
#include "render/renderer.h"
#include "scene/scene_parser.h"
#include "scene/set_option.h"
#include "spectral/sensor.h"
#include "spectral/wavelength_grid.h"
#include "underwater/underwater_cpu.h"
#include "underwater/underwater_setup.h"
#include "util/statistics.h"

namespace seasim {

namespace {

// Per-pass times of repeated frames of one renderer.
struct FrameTimes {
  std::vector<double> totals;  // ms per frame, every pass but the check
  std::map<std::string, std::vector<double>> per_pass;

  // A pass's median ms; a name ending in '*' sums every timing with that prefix (the froxel pass's
  // kernels: its name followed by '*').
  double passMs(std::string name) const {
    if (!name.empty() && name.back() == '*') {
      name.pop_back();
      double sum = 0;
      for (const auto& [k, v] : per_pass)
        if (k.rfind(name, 0) == 0) sum += median(v);
      return sum;
    }
    const auto it = per_pass.find(name);
    return it != per_pass.end() ? median(it->second) : 0.0;
  }
};

FrameTimes timeFrames(Renderer& renderer, int repeat, const std::string& check_pass) {
  FrameTimes times;
  for (int r = 0; r < std::max(1, repeat); ++r) {
    renderer.rerunAll();
    const FrameResult frame = renderer.render();
    double total = 0;
    for (const auto& t : frame.timings) {
      if (t.name == check_pass) continue;
      total += t.ms;
      times.per_pass[t.name].push_back(t.ms);
    }
    times.totals.push_back(total);
  }
  return times;
}

// Each band-loop kernel's own rate (items x bands per second of its time) over the exp bound: the
// fraction of the bound it reaches if it spent exactly one exp per item and band.
void printExpBoundShares(const Scene& scene, int n, const FrameTimes& times, double exp_rate) {
  for (PassRole role : {PassRole::SeaShading, PassRole::UnderwaterShading, PassRole::UnderwaterSingleScattering}) {
    const PassDescriptor& d = descriptorFor(role);
    const double pass_ms = times.passMs(d.band_loop_timing);
    if (pass_ms > 0)
      std::printf("  [%s %.3g of the exp bound]", d.band_loop_timing.c_str(),
                  d.band_loop_items(scene, n) / (pass_ms * 1e-3) / exp_rate);
  }
}

// The scalar TBB loop and the vectorised one (underwater_cpu_simd.cpp), interleaved run by run: median ms.
std::pair<double, double> timeUnderwaterCpu(const Scene& scene, const Plan& plan, int repeat) {
  const WavelengthGrid grid = makeGrid(scene.spectral.count, scene.spectral.min_nm, scene.spectral.max_nm);
  const UnderwaterSetup setup = makeUnderwaterSetup(
      scene, grid, makeSensor(scene.spectral.sensor, grid, scene.spectral.white_balance, scene.spectral.camera_dir));
  UnderwaterCpuOptions options;
  options.use_double = false;
  options.multiple = scene.underwater.multiple_scattering;
  options.single_split = plan.produces("froxel_volume");
  std::vector<double> cpu, cpu_simd;
  for (int r = 0; r < std::max(1, repeat); ++r) {
    auto c0 = std::chrono::steady_clock::now();
    (void)renderUnderwaterCpu(setup, options);
    cpu.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - c0).count());
    c0 = std::chrono::steady_clock::now();
    (void)renderUnderwaterCpuSimd(setup, options);
    cpu_simd.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - c0).count());
  }
  return {median(cpu), median(cpu_simd)};
}

// What the OpenCL side of the comparison does that the C++ peers do not (they cast their own rays without
// caustics and leave the froxels' single scattering out): the ratios compare like with like only without it.
void printPeerScope(const Scene& scene) {
  const Plan plan = makePlan(scene);
  std::vector<std::string> parts;
  if (underwaterCausticsMode(scene) != 0) parts.emplace_back(" the caustics at each hit");
  if (plan.produces("froxel_volume")) parts.emplace_back(" the froxel volume's read per pixel");
  std::string extra;
  for (const std::string& part : parts) extra += (extra.empty() ? "" : ",") + part;
  if (extra.empty())
    std::printf("peer: the same work as %s + %s\n", descriptorFor(PassRole::UnderwaterGBuffer).name.c_str(),
                descriptorFor(PassRole::UnderwaterShading).name.c_str());
  else
    std::printf("peer: not the same work (OpenCL also evaluates%s); the same work: "
                "--set 'underwater.caustics=\"none\"' --set underwater.single_scattering=false\n",
                extra.c_str());
}

void printFit(const std::vector<double>& n, const std::vector<double>& t, const char* what) {
  if (n.size() < 2 || t.size() != n.size()) return;
  const LineFit fit = fitLine(n, t);
  std::printf("fit (%s): t(n) = %.4g + %.4g n ms\n", what, fit.intercept, fit.slope);
}

// The plot's series: all passes, and under water the OpenCL G-buffer + K_d against the CPU loops.
struct WavelengthSeries {
  PlotSeries all, kd, tbb, simd;
};

}  // namespace

int benchWavelengths(Device& device, const BenchCmd& cmd, const std::vector<Override>& overrides, double exp_rate) {
  const bool underwater = cameraUnderwater(loadScene(cmd.scene, overrides));
  const std::string& gbuffer_pass = descriptorFor(PassRole::UnderwaterGBuffer).name;
  const std::string& froxel_pass = descriptorFor(PassRole::UnderwaterSingleScattering).name;
  const std::string& kd_pass = descriptorFor(PassRole::UnderwaterShading).name;
  const std::string& check_pass = descriptorFor(PassRole::Check).name;
  std::vector<std::string> columns = {"wavelengths", "kernel_ms_median", "pixel_wavelengths_per_s"};
  if (underwater) {
    for (const std::string& c : {gbuffer_pass + "_ms", froxel_pass + "_ms", kd_pass + "_ms",
                                 std::string("tbb_gbuffer_kd_ms"), std::string("tbb_over_opencl"),
                                 std::string("tbb_simd_gbuffer_kd_ms"), std::string("tbb_simd_over_opencl")})
      columns.push_back(c);
  }
  CsvWriter table(columns);
  WavelengthSeries s{{underwater ? "all passes (OpenCL)" : "kernels (OpenCL)", {}, {}},
                     {gbuffer_pass + " + " + kd_pass + " (OpenCL)", {}, {}},
                     {"same on C++/oneTBB", {}, {}},
                     {"same on C++/oneTBB, vectorised", {}, {}}};
  for (int n : cmd.wavelengths) {
    std::vector<Override> with_count = overrides;
    with_count.push_back(parseSetOption("spectral.count=" + std::to_string(n)));
    const Scene scene = loadScene(cmd.scene, with_count);
    Renderer renderer(device, scene, shippedPasses());
    (void)renderer.render();  // warm-up
    const FrameTimes times = timeFrames(renderer, cmd.repeat, check_pass);
    const double ms = median(times.totals);
    const double pixels = static_cast<double>(scene.camera.width) * scene.camera.height;
    const double rate = pixels * n / (ms * 1e-3);
    std::printf("n = %5d  %10.3f ms  %.3e pixel*wavelength/s", n, ms, rate);
    if (exp_rate > 0) std::printf("  = %.3g x the exp/s bound", rate / exp_rate);
    if (exp_rate > 0) printExpBoundShares(scene, n, times, exp_rate);
    std::vector<CsvCell> row = {n, ms, rate};
    if (underwater) {
      const auto [tbb_ms, simd_ms] = timeUnderwaterCpu(scene, renderer.plan(), cmd.repeat);
      const double gbuffer_ms = times.passMs(gbuffer_pass), froxel_ms = times.passMs(froxel_pass + "*");
      const double pass_kd_ms = times.passMs(kd_pass);
      const double kd_ms = gbuffer_ms + pass_kd_ms;
      std::printf("  [%s %.3f, %s %.3f, kd %.3f ms; TBB %.3f ms = %.2fx; TBB vectorised %.3f ms = %.2fx]",
                  gbuffer_pass.c_str(), gbuffer_ms, froxel_pass.c_str(), froxel_ms, pass_kd_ms, tbb_ms, tbb_ms / kd_ms,
                  simd_ms, simd_ms / kd_ms);
      for (double v : {gbuffer_ms, froxel_ms, pass_kd_ms, tbb_ms, tbb_ms / kd_ms, simd_ms, simd_ms / kd_ms})
        row.push_back(v);
      for (auto [series, v] : {std::pair{&s.kd, kd_ms}, std::pair{&s.tbb, tbb_ms}, std::pair{&s.simd, simd_ms}}) {
        series->x.push_back(n);
        series->y.push_back(v);
      }
    }
    std::printf("\n");
    table.addRow(row);
    s.all.x.push_back(n);
    s.all.y.push_back(ms);
  }
  printFit(s.all.x, s.all.y, "all passes");
  if (underwater) {
    printFit(s.all.x, s.kd.y, "raycast + kd_multiple");
    printFit(s.all.x, s.tbb.y, "C++/oneTBB");
    printFit(s.all.x, s.simd.y, "C++/oneTBB vectorised");
    printPeerScope(loadScene(cmd.scene, overrides));
  }
  if (!cmd.csv.empty()) table.write(cmd.csv);
  if (!cmd.plot.empty()) {
    PlotSpec spec;
    spec.title = "Kernel time vs wavelength count (" + device.info().name + ")";
    spec.x_label = "wavelength bands";
    spec.y_label = "ms per frame";
    spec.log_x = true;
    spec.series = {s.all};
    if (underwater) spec.series.insert(spec.series.end(), {s.kd, s.tbb, s.simd});
    writeSvgPlot(cmd.plot, spec);
  }
  return 0;
}

}  // namespace seasim
