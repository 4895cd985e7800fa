// bench_devices.cpp — `seasim bench --scene S --devices pocl,intel [--repeat N] [--csv F]`: the same
// scene on several OpenCL devices in one run, per pass the median kernel milliseconds (OpenCL profiling
// events) on each and their ratio to the first device, so two drivers on one machine (PoCL and Intel's
// CPU runtime) or a CPU and a GPU are compared pass by pass. Each repetition is a fresh Renderer on the
// device, so every pass runs; kernels are built once per device, before the timed repetitions.
#include <algorithm>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "device/device.h"
#include "io/csv.h"
#include "quality/auto_quality.h"
#include "render/renderer.h"
#include "util/error.h"
#include "util/statistics.h"

namespace seasim {
namespace {

struct DeviceRun {
  std::string label;
  std::map<std::string, std::vector<double>> pass_ms;  // per pass, one value per repetition
  std::vector<double> total_ms;
};

DeviceRun timeOnDevice(const std::string& selector, const BenchCmd& cmd, const std::vector<Override>& overrides,
                       std::vector<std::string>& pass_order) {
  Device device(chooseDevice(selector));
  DeviceRun run{device.info().label(), {}, {}};
  std::printf("device %s: %s\n", selector.c_str(), run.label.c_str());
  for (int r = 0; r <= std::max(1, cmd.repeat); ++r) {  // r = 0 builds kernels and warms up
    Renderer renderer(device, cmd.scene, overrides, shippedPasses());
    const FrameResult frame = renderer.render();
    if (frame.nonfinite) throw RuntimeError(cmd.scene + " produced NaN/Inf values on " + run.label);
    if (r == 0) continue;
    double total = 0;
    for (const auto& timing : frame.timings) {
      run.pass_ms[timing.name].push_back(timing.ms);
      total += timing.ms;
      if (std::find(pass_order.begin(), pass_order.end(), timing.name) == pass_order.end())
        pass_order.push_back(timing.name);
    }
    run.total_ms.push_back(total);
  }
  return run;
}

}  // namespace

int benchDevices(const BenchCmd& cmd, const std::vector<Override>& overrides) {
  if (cmd.scene.empty()) throw RuntimeError("bench --devices needs --scene");
  std::vector<std::string> passes;
  std::vector<DeviceRun> runs;
  for (const auto& selector : cmd.devices) runs.push_back(timeOnDevice(selector, cmd, overrides, passes));

  std::vector<std::string> columns{"pass"};
  for (size_t d = 0; d < runs.size(); ++d) {
    columns.push_back(cmd.devices[d] + "_ms");
    if (d > 0) columns.push_back(cmd.devices[d] + "_over_" + cmd.devices[0]);
  }
  CsvWriter table(columns);
  std::printf("\nmedian kernel ms over %d repetitions\n%-20s", std::max(1, cmd.repeat), "pass");
  for (size_t d = 0; d < runs.size(); ++d) {
    std::printf(" %12s", (cmd.devices[d] + " ms").c_str());
    if (d > 0) std::printf(" %12s", ("/" + cmd.devices[0]).c_str());
  }
  std::printf("\n");
  std::vector<std::string> rows = passes;
  rows.push_back("total");
  for (const auto& pass : rows) {
    std::vector<CsvCell> cells{pass};
    std::printf("%-20s", pass.c_str());
    const auto ms = [&](const DeviceRun& run) {
      if (pass == "total") return median(run.total_ms);
      auto it = run.pass_ms.find(pass);
      return it == run.pass_ms.end() ? 0.0 : median(it->second);
    };
    const double first = ms(runs.front());
    for (size_t d = 0; d < runs.size(); ++d) {
      const double value = ms(runs[d]);
      cells.emplace_back(value);
      std::printf(" %12.3f", value);
      if (d > 0) {
        const double ratio = first > 0 ? value / first : 0.0;
        cells.emplace_back(ratio);
        std::printf(" %12.3f", ratio);
      }
    }
    std::printf("\n");
    table.addRow(cells);
  }
  if (!cmd.csv.empty()) table.write(cmd.csv);
  return 0;
}

}  // namespace seasim
