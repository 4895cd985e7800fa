#include "cli/underwater_study_command.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>

#include "cli/commands.h"
#include "device/device.h"
#include "io/csv.h"
#include "io/svg_plot.h"
#include "quality/render_frame.h"
#include "plan/plan.h"
#include "reference/compare.h"
#include "reference/underwater_reference.h"
#include "scene/scene_parser.h"
#include "spectral/sensor.h"
#include "spectral/wavelength_grid.h"
#include "underwater/underwater_setup.h"
#include "util/error.h"

namespace seasim {

namespace {

Override set(const std::string& key, const std::string& value) { return {key, value, {"underwater-study", 0}}; }

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3f", v);
  return b;
}

// scenes/seabed.toml's geometry moved to a bottom at `depth` m (as jobs/jerlov_table.toml does).
std::vector<Override> seabedAt(double depth) {
  return {set("bottom.depth", num(depth)),
          set("camera.position", "[0.0, " + num(-(depth - 1.2)) + ", 0.0]"),
          set("camera.look_at", "[0.0, " + num(-(depth - 0.5)) + ", -8.0]"),
          set("objects[0].center", "[-1.4, " + num(-(depth - 0.5)) + ", -5.0]"),
          set("objects[1].min", "[0.8, " + num(-depth) + ", -7.5]"),
          set("objects[1].max", "[2.2, " + num(-(depth - 1.2)) + ", -6.3]"),
          set("objects[2].center", "[0.3, " + num(-(depth - 0.8)) + ", -10.5]")};
}

double ms(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int cmdUnderwaterStudy(const UnderwaterStudyCmd& cmd) {
  Device device(chooseDevice(cmd.device));
  std::printf("device: %s\n", device.info().label().c_str());
  CsvWriter table({"water", "depth_m", "camera", "method", "bands", "rmse_8bit", "hue_sat_distance", "rel_l2",
                   "reference_noise_8bit", "render_ms", "reference_ms"});
  // Per method: mean over cameras per (water, depth), for the plot.
  std::map<std::string, PlotSeries> rmse, hsv;
  for (const char* m : {"spectral", "rgb"}) {
    rmse[m].name = std::string(m) + " RMSE";
    hsv[m].name = std::string(m) + " hue+sat x100";
  }
  std::vector<std::string> labels;
  int scene_index = 0;
  for (const std::string& water : cmd.waters) {
    for (double depth : cmd.depths) {
      std::map<std::string, double> sum_rmse, sum_hsv;
      for (const std::string& camera : cmd.cameras) {
        std::vector<Override> base = seabedAt(depth);
        // The thesis's §6.1 study: its model, pinned (the default is "discrete_ordinates"); --set may change it.
        base.push_back(set("underwater.model", "\"thesis\""));
        for (const std::string& s : cmd.sets) base.push_back(parseSetOption(s));
        base.push_back(set("water.jerlov", "\"" + water + "\""));
        if (!cmd.camera_dir.empty()) base.push_back(set("spectral.camera_dir", "\"" + cmd.camera_dir + "\""));
        base.push_back(set("spectral.sensor", "\"" + camera + "\""));
        base.push_back(set("camera.width", std::to_string(cmd.width)));
        base.push_back(set("camera.height", std::to_string(cmd.height)));
        // The reference's surface is flat and still: no caustic textures in the fast renders either.
        base.push_back(set("underwater.caustics", "\"none\""));

        // Reference: two independent path-traced runs; their mean is the reference, half their
        // difference its noise (RMSE of the mean against the true image, in 8-bit levels).
        std::vector<Override> ref_over = base;
        ref_over.push_back(set("spectral.count", std::to_string(cmd.reference_bands)));
        const Scene ref_scene = loadScene(cmd.scene, ref_over);
        const WavelengthGrid grid = makeGrid(cmd.reference_bands, ref_scene.spectral.min_nm, ref_scene.spectral.max_nm);
        const UnderwaterSetup setup = makeUnderwaterSetup(
            ref_scene, grid, makeSensor(ref_scene.spectral.sensor, grid, ref_scene.spectral.white_balance, ref_scene.spectral.camera_dir));
        UnderwaterReferenceSettings settings;
        settings.samples_per_pixel = cmd.spp;
        const auto t_ref = std::chrono::steady_clock::now();
        settings.seed = 1;
        const UnderwaterReferenceResult a = renderUnderwaterReference(device, setup, settings);
        settings.seed = 2;
        const UnderwaterReferenceResult b = renderUnderwaterReference(device, setup, settings);
        const double ref_ms = ms(t_ref);
        Image ref = a.rgb;
        for (size_t i = 0; i < ref.pixels.size(); ++i) ref.pixels[i] = 0.5f * (a.rgb.pixels[i] + b.rgb.pixels[i]);
        const double exposure = ref_scene.camera.exposure_ev;
        const double noise = 0.5 * compareImages(a.rgb, b.rgb, exposure).rmse_8bit;

        for (const char* method : {"spectral", "rgb"}) {
          std::vector<Override> over = base;
          const int n = std::string(method) == "rgb" ? 3 : cmd.spectral_bands;
          over.push_back(set("spectral.count", std::to_string(n)));
          const Scene scene = loadScene(cmd.scene, over);
          const auto t0 = std::chrono::steady_clock::now();
          const FrameResult frame = renderFrame(device, scene, makePlan(scene));
          const double render_ms = ms(t0);
          if (frame.nonfinite != 0) throw RuntimeError("underwater-study: NaN/Inf in a render");
          const CompareResult c = compareImages(frame.rgb, ref, exposure);
          table.addRow({water, depth, camera, std::string(method), n, c.rmse_8bit, c.hue_sat_distance, c.rel_l2, noise,
                        render_ms, ref_ms});
          sum_rmse[method] += c.rmse_8bit;
          sum_hsv[method] += c.hue_sat_distance;
          std::printf("%-4s %4.1f m %-28s %-8s n=%-3d RMSE %7.3f  hue+sat %.4f  rel.L2 %.3f  (reference noise %.3f, %.0f ms)\n",
                      water.c_str(), depth, camera.c_str(), method, n, c.rmse_8bit, c.hue_sat_distance, c.rel_l2, noise,
                      ref_ms);
          std::fflush(stdout);
        }
      }
      char depth_text[32];
      std::snprintf(depth_text, sizeof depth_text, "%g", depth);
      labels.push_back(water + ", " + depth_text + "\u00a0m");  // no-break space: "5 m" stays on one line
      for (const char* m : {"spectral", "rgb"}) {
        rmse[m].x.push_back(scene_index);
        rmse[m].y.push_back(sum_rmse[m] / cmd.cameras.size());
        hsv[m].x.push_back(scene_index);
        hsv[m].y.push_back(100.0 * sum_hsv[m] / cmd.cameras.size());
      }
      std::printf("%s: mean over %zu cameras: spectral RMSE %.3f hue+sat %.4f | rgb RMSE %.3f hue+sat %.4f\n",
                  labels.back().c_str(), cmd.cameras.size(), rmse["spectral"].y.back(), hsv["spectral"].y.back() / 100,
                  rmse["rgb"].y.back(), hsv["rgb"].y.back() / 100);
      ++scene_index;
    }
  }
  if (!cmd.csv.empty()) table.write(cmd.csv);
  if (!cmd.plot.empty()) {
    PlotSpec spec;
    spec.title = "Spectral vs RGB against the path tracer (mean over cameras)";
    spec.x_categories = labels;  // the x values are scene_index: one category per water and depth
    spec.x_label = "Jerlov water type, seabed depth";
    spec.y_label = "RMSE (8-bit levels); hue+sat distance x100";
    for (const char* m : {"spectral", "rgb"}) {
      spec.series.push_back(rmse[m]);
      spec.series.push_back(hsv[m]);
    }
    writeSvgPlot(cmd.plot, spec);
  }
  return 0;
}

}  // namespace seasim
