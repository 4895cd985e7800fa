#include "cli/commands.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <sstream>

#include <unistd.h>

#include "device/device.h"
#include "io/csv.h"
#include "io/image_io.h"
#include "io/svg_plot.h"
#include "jobs/file_errors.h"
#include "jobs/job.h"
#include "jobs/job_inputs.h"
#include "jobs/recorded_settings.h"
#include "jobs/render_item.h"
#include "jobs/runner.h"
#include "plan/memory_budget.h"
#include "plan/plan.h"
#include "quality/auto_quality.h"
#include "quality/expected_error.h"
#include "quality/shafts_method_auto.h"
#include "reference/compare.h"
#include "reference/reference_image.h"
#include "reference/sea_reference.h"
#include "reference/sea_second_reference.h"
#include "reference/shafts_reference.h"
#include "reference/underwater_reference.h"
#include "render/renderer.h"
#include "scene/output_layers.h"
#include "scene/scene_inputs.h"
#include "scene/toml_reader.h"
#include "util/error.h"
#include "util/paths.h"
#include "util/statistics.h"

namespace fs = std::filesystem;

namespace seasim {

namespace {

std::vector<Override> parseSets(const std::vector<std::string>& sets) {
  std::vector<Override> out;
  for (const auto& s : sets) out.push_back(parseSetOption(s));
  return out;
}

std::vector<std::string> split(const std::string& text, char sep) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(text);
  while (std::getline(in, part, sep)) parts.push_back(part);
  return parts;
}

// "ref.exr" -> "ref<suffix>.exr" beside it: ".stderr" (the standard-error image), ".direct".
std::string besidePath(const std::string& out, const std::string& suffix) {
  const fs::path p(out);
  return (p.parent_path() / (p.stem().string() + suffix + p.extension().string())).string();
}

std::string stderrPath(const std::string& out) { return besidePath(out, ".stderr"); }

double kernelMs(const FrameResult& frame) {
  double total = 0;
  for (const auto& t : frame.timings) total += t.ms;
  return total;
}

}  // namespace

int cmdDevices() {
  const auto devices = listDevices();
  if (devices.empty()) {
    std::printf("no OpenCL devices (install pocl-opencl-icd, or a GPU driver's OpenCL ICD)\n");
    return 1;
  }
  const DeviceInfo chosen = chooseDevice("");
  for (const auto& d : devices) {
    const bool is_default = d.platform_index == chosen.platform_index && d.device_index == chosen.device_index;
    std::printf("%s %s\n    platform: %s | driver %s\n", is_default ? "*" : " ", d.label().c_str(),
                d.platform_name.c_str(), d.driver.c_str());
  }
  std::printf("(* = default choice: first GPU, else PoCL)\n");
  return 0;
}

int cmdValidate(const std::vector<std::string>& files) {
  // Every file is checked even when one fails, and every error of a file is listed
  // (jobs/file_errors.h), so one run shows every problem.
  int failures = 0;
  for (const auto& f : files) {
    try {
      const bool job_file = isJobFile(f);
      const std::vector<std::string> errors = job_file ? jobFileErrors(f) : sceneFileErrors(f);
      for (const auto& e : errors) std::fprintf(stderr, "%s\n", e.c_str());
      if (!errors.empty()) {
        if (errors.size() > 1) std::fprintf(stderr, "%s: %zu errors\n", f.c_str(), errors.size());
        ++failures;
        continue;
      }
      if (job_file) {
        const Job job = loadJob(f);
        const std::map<std::string, std::string> bad = checkJobInputs(job.items);
        for (const auto& [item, error] : bad) std::fprintf(stderr, "%s\n", error.c_str());
        if (!bad.empty()) {
          ++failures;
          continue;
        }
        std::printf("%s: ok (job '%s', %zu renders)\n", f.c_str(), job.name.c_str(), job.items.size());
      } else {
        const Scene scene = loadScene(f);
        checkSceneInputs(scene);
        std::printf("%s: ok (scene '%s')\n", f.c_str(), scene.name.c_str());
      }
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s\n", e.what());
      ++failures;
    }
  }
  return failures == 0 ? 0 : 1;
}

namespace {

// quality.shafts_method = "auto": the method cached for the default device when one was measured
// (then the plan is that method's), else the rule's, with a line saying which.
Scene withCachedShaftsMethod(const Scene& scene) {
  if (!shaftsMethodMeasured(scene)) return scene;
  std::string where = "no OpenCL device";
  try {
    Device device(chooseDevice(""));
    where = device.info().label();
    ShaftsMethodOptions options;
    options.search = false;
    const auto budget = scene.quality.find("shafts_error_budget");
    if (budget != scene.quality.end()) options.budget_levels = budget->second.value;
    if (const std::optional<ShaftsMethodChoice> c = chooseShaftsMethod(device, scene, options)) {
      std::printf("shafts method \"auto\": %s, measured on %s (RMS %.3f levels at %dx%d, budget %g%s; %s)\n",
                  describeShaftsSetting(c->chosen).c_str(), where.c_str(), c->chosen.rmse_8bit, c->search_width,
                  c->search_height, c->budget_levels, c->met_budget ? "" : ", not met", c->cache_file.c_str());
      return withShaftsMethod(scene, c->chosen);
    }
  } catch (const std::exception&) {
    // No device to key the cache: the rule's plan, as below.
  }
  std::printf("shafts method \"auto\": not measured yet on %s; the first render measures it (the plan below "
              "shows the rule's method)\n",
              where.c_str());
  return scene;
}

}  // namespace

int cmdPlan(const std::string& scene_file, const std::vector<std::string>& sets) {
  const Scene scene = withCachedShaftsMethod(loadScene(scene_file, parseSets(sets)));
  const Plan plan = makePlan(scene);
  std::printf("%s", plan.toText().c_str());
  // The big buffers with the settings that size them (the froxel grid as the image sizes it, the maps).
  for (const BufferEstimate& b : estimateBuffers(scene, plan)) {
    if (b.host) continue;
    std::string sizes;
    for (size_t i = 0; i < b.settings.size() && i < b.values.size(); ++i)
      sizes += (i ? ", " : "") + b.settings[i] + " " + formatNumber(b.values[i]);
    std::printf("buffer: %s: %s, %.1f MiB (%s)\n", b.pass.c_str(), b.what.c_str(), b.bytes / (1024.0 * 1024.0),
                sizes.c_str());
  }
  std::printf("%s", expectedErrorText(expectedErrors(scene)).c_str());
  return 0;
}

int cmdRender(const RenderCmd& cmd) {
  // --output names formats and layers alike: a layer adds to the scene's outputs.layers; the
  // formats stay the default (exr, png) when only layers are named.
  std::vector<std::string> formats, layers;
  const std::vector<std::string> known_formats = {"exr", "png", "spectral_exr", "npy"};
  for (const auto& o : cmd.formats) {
    const bool format = std::find(known_formats.begin(), known_formats.end(), o) != known_formats.end();
    if (!format && !findOutputLayer(o)) {  // neither: the error names both lists, before anything runs
      OutputsDesc unknown;
      addOutputLayers(unknown, {o}, "--output (formats: exr, png, spectral_exr, npy)");
    }
    (format ? formats : layers).push_back(o);
  }
  if (formats.empty()) formats = RenderCmd{}.formats;
  Scene scene = loadScene(cmd.scene, parseSets(cmd.sets));
  addOutputLayers(scene.outputs, layers, "--output");
  checkSceneInputs(scene);
  const std::string out_abs = fs::absolute(cmd.out_dir).lexically_normal().string();
  if (const std::string problem = outputDirProblem(out_abs); !problem.empty())
    throw RuntimeError("-o " + cmd.out_dir + ": cannot write results there: " + problem);
  Device device(chooseDevice(cmd.device));
  ItemOutputs outputs;
  outputs.formats = formats;
  outputs.reference = cmd.reference;
  const auto report = renderItem(device, scene, outputs, cmd.out_dir);
  std::printf("%s: %s kernels %.2f ms (build %.1f ms) on %s\n", scene.name.c_str(), cmd.out_dir.c_str(),
              report["kernel_ms_total"].get<double>(), report["kernel_build_ms"].get<double>(),
              device.info().label().c_str());
  if (report.contains("error")) std::printf("error vs reference: %s\n", report["error"].dump().c_str());
  return 0;
}

int cmdRun(const std::string& job_arg, const std::string& device, const std::string& shard, bool resume,
           const std::string& output_dir, const std::vector<std::string>& sets,
           const std::vector<std::string>& layers) {
  RunOptions options;
  options.overrides = parseSets(sets);
  OutputsDesc asked;  // unknown names fail here, before the job loads
  addOutputLayers(asked, layers, "--output");
  options.layers = asked.layers;
  options.device = device;
  options.resume = resume;
  options.output_dir = output_dir;
  // `seasim run jobs/quickstart.toml` outside the source tree runs the installed example; its outputs
  // go where the source tree would put them, under the current folder (the install is read-only).
  std::string job = job_arg;
  if (!std::filesystem::exists(job)) {
    const std::string example = installedExample(job);
    if (example.empty()) throw RuntimeError("job file not found: " + job);
    job = example;
    if (options.output_dir.empty())
      options.output_dir = (std::filesystem::current_path() / "results" / loadJob(job).name).string();
    std::printf("%s is not here: running the installed example %s, writing to %s\n", job_arg.c_str(), job.c_str(),
                options.output_dir.c_str());
    std::fflush(stdout);  // before the job's progress lines on stderr
  }
  if (!shard.empty()) {
    const auto parts = split(shard, '/');
    try {
      if (parts.size() != 2) throw std::invalid_argument("shard");
      options.shard_index = std::stoi(parts[0]);
      options.shard_count = std::stoi(parts[1]);
    } catch (const std::exception&) {
      throw RuntimeError("--shard expects i/N, e.g. --shard 0/4; got '" + shard + "'");
    }
  }
  const RunSummary s = runJob(job, options);
  std::printf("job done: %d rendered, %d finished earlier, %d left to other shards, %zu failed -> %s\n", s.rendered,
              s.skipped, s.other_shards, s.failed.size(), s.output_dir.c_str());
  if (!s.contact_sheet.empty()) std::printf("contact sheet: %s\n", s.contact_sheet.c_str());
  if (s.failed.empty()) return 0;
  std::fprintf(stderr, "seasim: %zu item(s) failed (recorded in %s):\n", s.failed.size(), s.manifest.c_str());
  for (const auto& f : s.failed) std::fprintf(stderr, "  %s: %s\n", f.name.c_str(), f.error.c_str());
  std::fprintf(stderr, "fix them and run again with --resume: only failed and unfinished items are rendered\n");
  return 1;
}

int cmdCompare(const std::string& test, const std::string& reference, std::optional<double> exposure_ev) {
  const nlohmann::json test_settings = recordedSettings(test), ref_settings = recordedSettings(reference);
  auto recordedExposure = [](const nlohmann::json& s) -> std::optional<double> {
    if (s.is_object() && s.contains("exposure_ev") && s["exposure_ev"].is_number()) return s["exposure_ev"].get<double>();
    return std::nullopt;
  };
  std::string exposure_from = "--exposure";
  if (!exposure_ev) {
    if ((exposure_ev = recordedExposure(test_settings))) exposure_from = "the image's recorded settings";
    else if ((exposure_ev = recordedExposure(ref_settings))) exposure_from = "the reference's recorded settings";
    else exposure_ev = 0.0, exposure_from = "no settings recorded with either image; give --exposure";
  }
  const Image ref_image = readImage(reference);
  const CompareResult c = compareImages(readImage(test), ref_image, *exposure_ev);
  std::printf("rmse_8bit %.4f\nmax_abs_8bit %.4f\nrel_l2 %.6g\nhue_sat_distance %.6g\nexposure_ev %g (%s)\n",
              c.rmse_8bit, c.max_abs_8bit, c.rel_l2, c.hue_sat_distance, *exposure_ev, exposure_from.c_str());
  const std::string se_path = stderrPath(reference);
  if (fs::is_regular_file(se_path) || fs::is_regular_file(se_path + ".npy")) {  // .npy: builds without OpenImageIO
    // rmse² ≈ bias² + noise² (reference/compare.h): the share of rmse² the reference's noise explains.
    const double noise = referenceNoise8bit(ref_image, readImage(se_path), *exposure_ev);
    const double share = c.rmse_8bit > 0 ? std::min(1.0, noise * noise / (c.rmse_8bit * c.rmse_8bit)) : 0.0;
    const double rest = std::sqrt(std::max(0.0, c.rmse_8bit * c.rmse_8bit - noise * noise));
    std::printf("reference_noise_8bit %.4f (RMS of one standard error, %s)\n", noise, se_path.c_str());
    std::printf("noise_share_of_rmse2 %.3f\nrmse_less_noise_8bit %.4f\n", share, rest);
    if (share > 0.5)
      std::fprintf(stderr, "seasim: warning: the reference's noise explains %.0f %% of rmse^2; trace it with more paths "
                           "(reference --steps) to measure the image rather than the reference\n", 100 * share);
  }
  // Settings recorded with both images that differ: the error then measures the difference in the
  // scene, not the method. Quality knobs and the wavelength count differ on purpose (listed only).
  std::vector<std::string> scene_diffs, knob_diffs;
  for (const SettingsDifference& d : settingsDifferences(test_settings, ref_settings))
    (d.knob ? knob_diffs : scene_diffs).push_back(d.key + " " + d.test + " vs " + d.reference);
  for (const auto& d : scene_diffs)
    std::fprintf(stderr, "seasim: warning: the image and the reference were made with different settings: %s\n", d.c_str());
  if (!knob_diffs.empty()) {
    std::printf("knobs that differ from the reference's:");
    for (const auto& d : knob_diffs) std::printf(" %s;", d.c_str());
    std::printf("\n");
  }
  if (test_settings.is_null() || ref_settings.is_null())
    std::printf("settings not recorded with %s: not compared\n",
                test_settings.is_null() && ref_settings.is_null() ? "either image"
                : test_settings.is_null()                        ? "the image"
                                                                 : "the reference");
  return c.nonfinite == 0 ? 0 : 1;
}

namespace {

// One --param KEY=v1,v2,... of sweep.
struct SweepAxis {
  std::string key;
  std::vector<std::string> values;
};

std::vector<SweepAxis> parseSweepAxes(const std::vector<std::string>& params) {
  std::vector<SweepAxis> axes;
  for (const auto& p : params) {
    const size_t eq = p.find('=');
    if (eq == std::string::npos) throw RuntimeError("--param expects KEY=v1,v2,...; got '" + p + "'");
    axes.push_back({p.substr(0, eq), split(p.substr(eq + 1), ',')});
    if (axes.back().values.empty()) throw RuntimeError("--param '" + p + "' has no values");
  }
  return axes;
}

// The grid of all combinations of the axes' values, the last axis fastest.
std::vector<std::vector<std::string>> sweepGrid(const std::vector<SweepAxis>& axes) {
  std::vector<std::vector<std::string>> grid = {{}};
  for (const auto& axis : axes) {
    std::vector<std::vector<std::string>> next;
    for (const auto& row : grid)
      for (const auto& v : axis.values) {
        auto r = row;
        r.push_back(v);
        next.push_back(r);
      }
    grid = next;
  }
  return grid;
}

// --reference, or (what a user running `sweep --param` expects) the scene's own reference, made first
// beside the CSV.
std::string sweepReference(const SweepCmd& cmd, const std::vector<Override>& base) {
  if (!cmd.reference.empty()) return cmd.reference;
  const fs::path csv(cmd.csv);
  const std::string path = (csv.parent_path() / (csv.stem().string() + ".reference.exr")).string();
  ReferenceCmd ref_cmd;
  ref_cmd.device = cmd.device;
  std::printf("sweep: no --reference given: making the scene's reference first (seasim reference %s -o %s)\n",
              cmd.scene.c_str(), path.c_str());
  std::fflush(stdout);
  std::printf("%s\n", writeSceneReference(loadScene(cmd.scene, base), ref_cmd, path).c_str());
  return path;
}

// The frame of median kernel time of three runs of the whole frame: single timings on a shared machine
// are noisy. After a warm-up (PoCL compiles lazily; set-up of what changed).
FrameResult medianFrame(Renderer& renderer) {
  (void)renderer.render();
  std::vector<FrameResult> runs;
  for (int r = 0; r < 3; ++r) {
    renderer.rerunAll();
    runs.push_back(renderer.render());
  }
  std::sort(runs.begin(), runs.end(), [](const FrameResult& a, const FrameResult& b) { return kernelMs(a) < kernelMs(b); });
  return runs[1];
}

// quality.fast_math: the same setting rendered with exact maths, and the fast image's distance from it.
CompareResult fastVsExact(Device& device, const Scene& scene, const Image& fast_rgb) {
  Scene exact_scene = scene;
  exact_scene.quality["fast_math"] = Knob{false, 0.0};
  Renderer exact_renderer(device, exact_scene, shippedPasses());
  const FrameResult exact = exact_renderer.render();
  return compareImages(fast_rgb, exact.rgb, scene.camera.exposure_ev);
}

std::vector<std::string> sweepColumns(const std::vector<SweepAxis>& axes) {
  std::vector<std::string> header;
  for (const auto& a : axes) header.push_back(a.key);
  for (const char* h : {"kernel_ms", "wall_ms", "rmse_8bit", "max_abs_8bit", "rel_l2", "hue_sat_distance"})
    header.emplace_back(h);
  header.emplace_back("max_diff_prev_8bit");  // max |image - previous setting's| (000 §6.1, Fig. 7/8)
  for (const char* h : {"fast_math", "fast_vs_exact_rmse_8bit", "fast_vs_exact_max_8bit"}) header.emplace_back(h);
  return header;
}

// Error against time, and (one numeric axis) the 000 §6.1 plot: difference to the next setting vs the knob.
void writeSweepPlots(const SweepCmd& cmd, const std::string& axis_key, const PlotSeries& series,
                     const PlotSeries& steps) {
  PlotSpec spec;
  spec.title = "Error vs time: " + fs::path(cmd.scene).stem().string();
  spec.x_label = "kernel time (ms)";
  spec.y_label = "RMSE (8-bit levels)";
  spec.log_y = true;  // errors span decades; a zero error (exact match) is left off the log axis
  spec.series.push_back(series);
  writeSvgPlot(cmd.plot, spec);
  if (steps.x.empty()) return;
  PlotSpec step_spec;
  step_spec.title = "Difference to the next setting: " + fs::path(cmd.scene).stem().string();
  step_spec.x_label = axis_key;
  step_spec.y_label = "max difference (8-bit levels)";
  step_spec.log_y = true;
  step_spec.series.push_back(steps);
  step_spec.series.push_back({"1 level (1/255)", {steps.x.front(), steps.x.back()}, {1.0, 1.0}});
  const fs::path plot(cmd.plot);
  writeSvgPlot((plot.parent_path() / (plot.stem().string() + "_steps.svg")).string(), step_spec);
}

}  // namespace

int cmdSweep(const SweepCmd& cmd) {
  const std::vector<SweepAxis> axes = parseSweepAxes(cmd.params);
  const std::vector<std::vector<std::string>> grid = sweepGrid(axes);
  const std::vector<Override> base = parseSets(cmd.sets);
  // Validate every setting before rendering any, so a typo fails fast.
  std::vector<Scene> scenes;
  for (const auto& row : grid) {
    std::vector<Override> overrides = base;
    for (size_t i = 0; i < axes.size(); ++i) overrides.push_back(parseSetOption(axes[i].key + "=" + row[i]));
    scenes.push_back(loadScene(cmd.scene, overrides));
  }
  const std::string reference_path = sweepReference(cmd, base);
  const Image reference = readImage(reference_path);
  for (const SettingsDifference& d : settingsDifferences(settingsJson(scenes.front()), recordedSettings(reference_path)))
    if (!d.knob)
      std::fprintf(stderr, "seasim: warning: the reference was made with %s = %s, the sweep's scene has %s\n",
                   d.key.c_str(), d.reference.c_str(), d.test.c_str());
  Device device(chooseDevice(cmd.device));
  CsvWriter table(sweepColumns(axes));
  PlotSeries series{"rmse (8-bit levels)", {}, {}};
  PlotSeries steps{"max |L(v) - L(next v)| (8-bit levels)", {}, {}};
  Image previous;
  // One renderer for the whole grid: each setting sets up again only the passes its keys touch.
  Renderer renderer(device, scenes.front(), shippedPasses());
  for (size_t k = 0; k < scenes.size(); ++k) {
    if (k > 0) {
      std::vector<std::string> changed;
      for (size_t i = 0; i < axes.size(); ++i)
        if (grid[k][i] != grid[k - 1][i]) changed.push_back(axes[i].key);
      renderer.update(scenes[k], changed);
    }
    const FrameResult frame = medianFrame(renderer);
    if (frame.nonfinite) throw RuntimeError("sweep setting produced NaN/Inf values");
    const CompareResult c = compareImages(frame.rgb, reference, scenes[k].camera.exposure_ev);
    std::vector<CsvCell> row(grid[k].begin(), grid[k].end());
    for (double v : {kernelMs(frame), frame.wall_ms, c.rmse_8bit, c.max_abs_8bit, c.rel_l2, c.hue_sat_distance})
      row.emplace_back(v);
    const double step = k > 0 ? compareImages(frame.rgb, previous, scenes[k].camera.exposure_ev).max_abs_8bit : 0.0;
    row.emplace_back(step);
    const bool fast = fastMathFor(scenes[k]);
    const CompareResult vs_exact = fast ? fastVsExact(device, scenes[k], frame.rgb) : CompareResult{};
    for (double v : {fast ? 1.0 : 0.0, vs_exact.rmse_8bit, vs_exact.max_abs_8bit}) row.emplace_back(v);
    if (k > 0 && axes.size() == 1) {
      try {
        steps.x.push_back(std::stod(grid[k - 1][0]));
        steps.y.push_back(step);
      } catch (const std::exception&) {  // a non-numeric axis: no step plot
      }
    }
    previous = frame.rgb;
    std::string label;
    for (size_t i = 0; i < axes.size(); ++i) label += (i ? " " : "") + axes[i].key + "=" + grid[k][i];
    std::printf("%-40s kernel %9.3f ms  rmse %8.4f  max %8.3f  relL2 %.3g", label.c_str(), kernelMs(frame),
                c.rmse_8bit, c.max_abs_8bit, c.rel_l2);
    if (fast) std::printf("  fast maths vs exact: rmse %.4f max %.4f levels", vs_exact.rmse_8bit, vs_exact.max_abs_8bit);
    std::printf("\n");
    table.addRow(row);
    series.x.push_back(kernelMs(frame));
    series.y.push_back(c.rmse_8bit);
    std::string point;  // the knob values beside the point: "sea_nz=8" (the key's last part)
    for (size_t i = 0; i < axes.size(); ++i)
      point += (i ? ", " : "") + axes[i].key.substr(axes[i].key.rfind('.') + 1) + "=" + grid[k][i];
    series.labels.push_back(point);
  }
  table.write(cmd.csv);
  if (!cmd.plot.empty()) writeSweepPlots(cmd, axes.empty() ? "" : axes[0].key, series, steps);
  return 0;
}

// Operations per second of one kernels/limits.cl kernel (exp_throughput or fma_throughput: independent
// operations, vectorisable across work items), median of `repeat` runs after a warm-up.
double measureThroughput(Device& device, const char* kernel_name, int ops_per_item, int repeat) {
  const size_t items = size_t(1) << 20;
  cl::Kernel kernel(device.program("limits.cl", {"EXP_PER_ITEM=256", "FMA_PER_ITEM=4096"}).program, kernel_name);
  cl::Buffer out(device.context(), CL_MEM_WRITE_ONLY, sizeof(float) * items);
  kernel.setArg(0, out);
  kernel.setArg(1, 0.5f);
  std::vector<double> ms;
  for (int r = 0; r < repeat + 1; ++r) {  // the first run is a warm-up (PoCL compiles lazily)
    cl::Event done;
    device.queue().enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(items), cl::NullRange, nullptr, &done);
    done.wait();
    if (r > 0) ms.push_back(eventMs(done));
  }
  return double(items) * ops_per_item / (median(ms) * 1e-3);
}

int cmdBench(const BenchCmd& cmd) {
  if (!cmd.devices.empty()) return benchDevices(cmd, parseSets(cmd.sets));  // bench_devices.cpp
  Device device(chooseDevice(cmd.device));
  std::printf("device: %s\n", device.info().label().c_str());
  double exp_rate = 0;
  if (cmd.limits) {
    exp_rate = measureThroughput(device, "exp_throughput", 256, std::max(1, cmd.repeat));
    const double fma_rate = measureThroughput(device, "fma_throughput", 4096, std::max(1, cmd.repeat));
    std::printf("limit: %.3e exp/s, %.3e FMA/s (float, default math, independent operations; kernels/limits.cl)\n",
                exp_rate, fma_rate);
  }
  if (cmd.scene.empty()) {
    if (!cmd.limits) throw RuntimeError("bench needs --scene or --limits");
    return 0;
  }
  if (!cmd.sea_maps.empty()) return benchSeaSecond(device, cmd, parseSets(cmd.sets));  // bench_sea.cpp
  if (cmd.frames > 0) return benchFrames(device, cmd, parseSets(cmd.sets));            // bench_frames.cpp
  if (!cmd.lights.empty()) return benchLights(device, cmd, parseSets(cmd.sets));  // bench_lights.cpp
  return benchWavelengths(device, cmd, parseSets(cmd.sets), exp_rate);              // bench_wavelengths.cpp
}

// The reference of `scene` written to `out` (with OUT.stderr.exr for the path tracer, and
// OUT.settings.json: the settings `compare` checks); returns the line that describes it.
std::string writeSceneReference(const Scene& scene, const ReferenceCmd& cmd, const std::string& out) {
  ReferenceOptions options;
  options.device = cmd.device;
  options.steps = cmd.steps;
  options.seed = cmd.seed;
  options.all_orders = cmd.all_orders;
  options.max_bounces = cmd.max_bounces;
  options.lamp_mis = !cmd.plain_lamp_sampling;
  options.pixel_centre = cmd.pixel_centre;
  options.sun_single_subpixels = cmd.sun_single_quadrature ? cmd.subpixels : 0;
  const bool tty = isatty(fileno(stderr));
  // The path tracer's samples per pixel; its total is known at the first call.
  options.progress = [tty, next = 0](int done, int total) mutable {
    if (tty) {  // one line, redrawn
      std::fprintf(stderr, "\rpath tracing: %d/%d samples per pixel", done, total);
      if (done == total) std::fprintf(stderr, "\n");
    } else if (done >= next || done == total) {  // logs: about every 10 %
      std::fprintf(stderr, "path tracing: %d/%d samples per pixel\n", done, total);
      next = done + std::max(1, total / 10);
    }
  };
  const ReferenceImage r = renderReference(scene, options);
  char line[1024];
  writeExr(out, r.rgb);
  if (r.method == "path tracer") {
    const std::string se_path = writeExr(stderrPath(out), r.std_error);
    // Under water the unscattered part too (docs/layers.md: the fast model's direct layer's reference).
    if (!r.direct.pixels.empty()) {
      const std::string direct_path = besidePath(out, ".direct");
      writeExr(direct_path, r.direct);
      writeExr(stderrPath(direct_path), r.direct_std_error);
    }
    writeSettingsSidecar(out, scene, "seasim reference (path tracer)");
    std::snprintf(line, sizeof line,
                  "reference %s: %d paths per pixel%s (%s, seed %u), %.1f ms on %s; noise: mean standard error %.3g "
                  "(image mean %.3g +- %.3g; from %d blocks of paths, worth %.0f independent paths per pixel), "
                  "per pixel in %s",
                  out.c_str(), r.steps, cmd.pixel_centre ? " through its centre" : "",
                  r.max_bounces == 1 ? "single scattering" : "multiple scattering", r.seed, r.ms,
                  r.device_name.c_str(), r.mean_std_error, r.image_mean, r.image_mean_std_error, r.blocks,
                  r.effective_samples, se_path.c_str());
    return line;
  }
  if (cmd.seed >= 0) std::fprintf(stderr, "reference: --seed ignored: this reference is deterministic (no random paths)\n");
  writeSettingsSidecar(out, scene, "seasim reference (quadrature)");
  std::snprintf(line, sizeof line, "reference %s: %d %s steps, %.1f ms (CPU, double, TBB)", out.c_str(), r.steps,
                r.method.c_str(), r.ms);
  return line;
}

int cmdReference(const ReferenceCmd& cmd) {
  const Scene scene = loadScene(cmd.scene, parseSets(cmd.sets));
  std::printf("%s\n", writeSceneReference(scene, cmd, cmd.out).c_str());
  return 0;
}

}  // namespace seasim
