// bench_frames.cpp — `seasim bench --scene S --frames N [--time-range t0,t1] [--fresh]`: an animation of
// N frames of surface.time through one Renderer (render/renderer.h), as a job's frame range or the
// preview would run it. Per frame: wall ms of Renderer::update() + render() (the scene file read
// again with the new time, set-up of what changed, kernels, NaN check, image read-back) against the
// sum of the times the passes report (OpenCL profiling events; the ocean reports its own wall time,
// FFTs included), and which passes ran. With
// --fresh every frame gets a new Renderer, so everything is set up again (what each frame cost before
// the renderer kept its passes). The first frame builds kernels and tables; the summary is over the
// frames after it.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "io/csv.h"
#include "quality/auto_quality.h"
#include "render/renderer.h"
#include "util/error.h"
#include "util/statistics.h"

namespace seasim {

int benchFrames(Device& device, const BenchCmd& cmd, const std::vector<Override>& overrides) {
  if (cmd.frames < 2) throw RuntimeError("--frames needs at least 2 frames");
  const double t0 = cmd.time_range.size() > 0 ? cmd.time_range[0] : 0.0;
  const double t1 = cmd.time_range.size() > 1 ? cmd.time_range[1] : 5.0;
  if (cmd.time_range.size() > 2) throw RuntimeError("--time-range expects t0,t1");
  CsvWriter table({"frame", "time_s", "wall_ms", "kernel_ms", "wall_over_kernel", "passes_run"});
  std::unique_ptr<Renderer> renderer;
  std::vector<double> ratios, walls, kernels;
  std::printf("%5s %8s %10s %10s %7s  %s\n", "frame", "t (s)", "wall ms", "kernel ms", "ratio", "passes run");
  for (int f = 0; f < cmd.frames; ++f) {
    const double t = t0 + (t1 - t0) * f / (cmd.frames - 1);
    char value[64];
    std::snprintf(value, sizeof value, "%.17g", t);
    const Override time{"surface.time", value, SourceLoc{"<bench --frames>", 0}};
    const auto start = std::chrono::steady_clock::now();  // the frame's cost includes the update
    if (!renderer || cmd.fresh) {
      std::vector<Override> all = overrides;
      all.push_back(time);
      renderer = std::make_unique<Renderer>(device, cmd.scene, all, shippedPasses());
    } else {
      renderer->update({time});
    }
    const FrameResult frame = renderer->render();
    const double wall = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (frame.nonfinite) throw RuntimeError("frame " + std::to_string(f) + " produced NaN/Inf values");
    double kernel = 0;
    for (const auto& timing : frame.timings) kernel += timing.ms;
    std::string passes;
    for (const auto& name : renderer->lastExecuted()) passes += (passes.empty() ? "" : " ") + name;
    const double ratio = kernel > 0 ? wall / kernel : 0.0;
    std::printf("%5d %8.3f %10.3f %10.3f %7.3f  %s\n", f, t, wall, kernel, ratio, passes.c_str());
    table.addRow({f, t, wall, kernel, ratio, passes});
    if (f > 0) {
      ratios.push_back(ratio);
      walls.push_back(wall);
      kernels.push_back(kernel);
    }
  }
  std::vector<double> sorted = ratios;
  std::sort(sorted.begin(), sorted.end());
  const size_t within = std::count_if(ratios.begin(), ratios.end(), [](double r) { return r <= 1.1; });
  std::printf("frames 1..%d (%s): median wall %.3f ms, median kernels %.3f ms; wall/kernel median %.3f, "
              "90th percentile %.3f, max %.3f; %zu of %zu frames within 1.1x\n",
              cmd.frames - 1, cmd.fresh ? "new renderer per frame" : "one renderer", median(walls), median(kernels),
              median(ratios), sorted[sorted.size() * 9 / 10], sorted.back(), within, ratios.size());
  if (!cmd.csv.empty()) table.write(cmd.csv);
  return 0;
}

}  // namespace seasim
