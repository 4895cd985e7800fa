#include "cli/ocean_command.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "cli/commands.h"
#include "device/device.h"
#include "io/csv.h"
#include "io/image_io.h"
#include "io/svg_plot.h"
#include "ocean/ocean_cpu.h"
#include "passes/caustics_pass.h"
#include "passes/sea_heightfield.h"
#include "passes/ocean_pass.h"
#include "scene/scene_parser.h"
#include "util/error.h"
#include "util/statistics.h"

namespace seasim {

namespace {

Image mapImage(int n, const std::vector<float>& data, int stride, const std::vector<int>& take,
               std::vector<std::string> names) {
  Image img;
  img.resize(n, n, static_cast<int>(take.size()));
  img.channel_names = std::move(names);
  for (size_t t = 0; t < static_cast<size_t>(n) * n; ++t)
    for (size_t c = 0; c < take.size(); ++c) img.pixels[t * take.size() + c] = data[t * stride + take[c]];
  return img;
}

std::string depthLabel(double d) {
  std::ostringstream s;
  s << d;
  return s.str();
}

int runBench(const OceanCmd& cmd, const OceanConfig& base, Device& device) {
  CsvWriter table({"n", "device", "device_ms", "fftw_float_ms", "fftw_over_device"});
  PlotSeries dev_series{"OpenCL + VkFFT (" + device.info().name + ")", {}, {}};
  PlotSeries cpu_series{"C++/TBB + FFTW float (1 thread FFT)", {}, {}};
  for (int n : cmd.bench_sizes) {
    OceanConfig c = base;
    c.grid = n;
    OceanPass pass(device, c);
    pass.run(0.0);  // PoCL compiles lazily on the first launch (toolchain.md pitfall 7)
    pass.run(0.1);
    std::vector<double> dev_ms, cpu_ms;
    for (int r = 0; r < cmd.repeat; ++r) dev_ms.push_back(pass.run(0.5 + r * 0.1));
    OceanCpu cpu(c, OceanCpu::Precision::Float, OceanCpu::Transform::Fftw);
    cpu.run(0.0);
    for (int r = 0; r < cmd.repeat; ++r) {
      const auto start = std::chrono::steady_clock::now();
      cpu.run(0.5 + r * 0.1);
      cpu_ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    }
    const double d = median(dev_ms), h = median(cpu_ms);
    std::printf("ocean N=%4d: device %9.3f ms/frame, FFTW float %9.3f ms/frame, FFTW/device %.2f\n", n, d, h, h / d);
    table.addRow({n, device.info().name, d, h, h / d});
    dev_series.x.push_back(n);
    dev_series.y.push_back(d);
    cpu_series.x.push_back(n);
    cpu_series.y.push_back(h);
  }
  const std::filesystem::path out(cmd.out_dir);
  table.write((out / "bench_ocean.csv").string());
  PlotSpec plot;
  plot.title = "Ocean frame (evolve + 4 batched FFTs + all maps)";
  plot.x_label = "grid N (N x N)";
  plot.y_label = "ms per frame (median of " + std::to_string(cmd.repeat) + ")";
  plot.log_x = plot.log_y = true;
  plot.series = {dev_series, cpu_series};
  writeSvgPlot((out / "bench_ocean.svg").string(), plot);
  std::printf("wrote %s and %s\n", (out / "bench_ocean.csv").c_str(), (out / "bench_ocean.svg").c_str());
  return 0;
}

}  // namespace

int cmdOcean(const OceanCmd& cmd) {
  if (cmd.out_dir.empty()) throw RuntimeError("seasim ocean: -o DIR is required");
  Scene scene;
  if (!cmd.scene.empty()) {
    std::vector<Override> overrides;
    for (const auto& s : cmd.sets) overrides.push_back(parseSetOption(s));
    scene = loadScene(cmd.scene, overrides);
  } else if (!cmd.sets.empty()) {
    throw RuntimeError("seasim ocean: --set needs a scene file");
  }
  const OceanConfig config = oceanConfigFromSurface(scene.surface);
  validateOceanConfig(config);
  if (cmd.repeat < 1) throw RuntimeError("seasim ocean: --repeat must be >= 1");
  for (double d : cmd.caustic_depths)
    if (!(d >= 0)) throw RuntimeError("seasim ocean: caustic depths must be >= 0 m");
  for (int n : cmd.bench_sizes)
    if (n < 16 || n > 2048 || (n & (n - 1)) != 0) throw RuntimeError("seasim ocean: bench sizes must be powers of two in 16..2048");

  Device device(chooseDevice(cmd.device));
  std::printf("device: %s\n", device.info().label().c_str());
  if (cmd.bench) return runBench(cmd, config, device);

  const double t = cmd.time >= 0 ? cmd.time : scene.surface.time;
  OceanPass ocean(device, config);
  const double ocean_ms = ocean.run(t);
  const int n = ocean.n();
  const std::filesystem::path out(cmd.out_dir);

  // Read everything first, write afterwards: a failure leaves no partial set of maps.
  const auto height = ocean.readHeight();
  const auto slope = ocean.readSlope();
  const auto disp = ocean.readDisplacement();
  const auto normal = ocean.readNormal();
  const auto jac = ocean.readJacobian();
  const auto fold = ocean.readFolding();
  std::vector<float> folding(static_cast<size_t>(n) * n * 5);
  size_t folded = 0;
  double sum2 = 0;
  for (size_t i = 0; i < jac.size(); ++i) {
    folding[5 * i] = jac[i];
    for (int c = 0; c < 4; ++c) folding[5 * i + 1 + c] = fold[4 * i + c];
    folded += jac[i] < 0;
    sum2 += static_cast<double>(height[i]) * height[i];
  }

  CausticsConfig cc;
  cc.sun_zenith = scene.sun.zenith;
  cc.sun_azimuth = scene.sun.azimuth;
  cc.ior = scene.water.ior;
  cc.attenuation = cmd.attenuation;
  cc.supersample = cmd.caustic_supersample;
  CausticsPass caustics(device, ocean.maps(), cc);
  std::vector<std::vector<float>> caustic_maps;
  std::vector<double> caustic_ms;
  for (double d : cmd.caustic_depths) {
    caustic_ms.push_back(caustics.run(d));
    caustic_maps.push_back(caustics.readMap());
  }
  // A height-field bottom (000 §5.4) gets its own map over the floor's square (004 §5.2.1 onto it).
  std::vector<float> floor_map;
  double floor_ms = 0;
  if (scene.bottom.type == BottomDesc::Type::HeightField) {
    floor_ms = caustics.runFloor(loadHeightField(scene.bottom));
    floor_map = caustics.readFloorMap();
  }

  writeExr((out / "height.exr").string(), mapImage(n, height, 1, {0}, {"Y"}));
  writeExr((out / "slope.exr").string(), mapImage(n, slope, 2, {0, 1}, {"dhdx", "dhdz"}));
  writeExr((out / "displacement.exr").string(), mapImage(n, disp, 4, {0, 1, 2}, {"R", "G", "B"}));
  writeExr((out / "normal.exr").string(), mapImage(n, normal, 4, {0, 1, 2}, {"R", "G", "B"}));
  writeExr((out / "folding.exr").string(), mapImage(n, folding, 5, {0, 1, 2, 3, 4}, {"J", "Jminus", "Jplus", "ex", "ez"}));
  const int m = caustics.mapSize();
  const int bins = 60;
  const double max_ratio = 6.0;
  std::vector<std::string> header = {"intensity_over_mean"};
  std::vector<std::vector<double>> pdfs;
  std::vector<double> ratios;
  PlotSpec plot;
  plot.title = "Caustic intensity PDF (004 §5.2.1, Figure 29)";
  plot.x_label = "I / <I>";
  plot.y_label = "probability density";
  plot.log_y = true;
  for (size_t k = 0; k < cmd.caustic_depths.size(); ++k) {
    const std::string label = depthLabel(cmd.caustic_depths[k]);
    writeExr((out / ("caustics_" + label + "m.exr")).string(), mapImage(m, caustic_maps[k], 1, {0}, {"Y"}));
    pdfs.push_back(causticIntensityPdf(caustic_maps[k], bins, max_ratio, &ratios));
    header.push_back("pdf_" + label + "m");
    plot.series.push_back({"depth " + label + " m", ratios, pdfs.back()});
  }
  if (!floor_map.empty())
    writeExr((out / "caustics_floor.exr").string(), mapImage(m, floor_map, 1, {0}, {"Y"}));
  if (!pdfs.empty()) {
    CsvWriter table(header);
    for (int b = 0; b < bins; ++b) {
      std::vector<CsvCell> row = {ratios[b]};
      for (const auto& p : pdfs) row.push_back(p[b]);
      table.addRow(row);
    }
    table.write((out / "caustic_pdf.csv").string());
    writeSvgPlot((out / "caustic_pdf.svg").string(), plot);
  }
  std::printf("ocean N=%d L=%g m V=%g m/s t=%g s: RMS height %.4g m, folded %.2f %% of texels, %.2f ms\n", n,
              config.patch_size, config.wind_speed, t, std::sqrt(sum2 / height.size()),
              100.0 * folded / height.size(), ocean_ms);
  for (size_t k = 0; k < caustic_ms.size(); ++k)
    std::printf("caustics at %g m: %.2f ms\n", cmd.caustic_depths[k], caustic_ms[k]);
  if (!floor_map.empty()) std::printf("caustics on the height-field floor: %.2f ms\n", floor_ms);
  std::printf("wrote maps to %s\n", out.c_str());
  return 0;
}

}  // namespace seasim
