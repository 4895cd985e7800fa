#include "cli/seashore_study_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "cli/commands.h"
#include "device/device.h"
#include "io/csv.h"
#include "io/svg_plot.h"
#include "io/tonemap.h"
#include "math/kernel_math.h"
#include "quality/render_frame.h"
#include "passes/sea_heightfield.h"
#include "plan/plan.h"
#include "reference/compare.h"
#include "scene/scene_parser.h"
#include "util/error.h"

namespace seasim {

namespace {

Override set(const std::string &key, const std::string &value) { return {key, value, {"seashore-study", 0}}; }

// Luminance of linear RGB with sRGB/Rec. 709 primaries (the cie1931 sensor's
// output space).
double luma(const float *c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

// Hue (degrees) of a linear colour, normalised to its largest component (hue
// does not depend on scale).
double hue(const double rgb[3]) {
  const double m = std::max({rgb[0], rgb[1], rgb[2], 1e-30});
  const float c[3] = {float(std::max(rgb[0], 0.0) / m), float(std::max(rgb[1], 0.0) / m),
                      float(std::max(rgb[2], 0.0) / m)};
  double h, s, v;
  rgbToHsv(c, h, s, v);
  return h;
}

// z_Q of every pixel (m; -1 for sky pixels): the refracted view ray walked to
// the floor as the kernels do (common/sea_bottom.h, double).
std::vector<double> floorDepths(const Scene &scene, const HeightField &floor) {
  namespace k = kmath_d;
  const CameraDesc &cam = scene.camera;
  const Vec3 fwd = normalize(cam.look_at - cam.position);
  const Vec3 right = normalize(cross(fwd, cam.up));
  const Vec3 up = cross(right, fwd);
  const double tan_half = std::tan(cam.fov_y / 2), aspect = double(cam.width) / cam.height;
  std::vector<double> z(static_cast<size_t>(cam.width) * cam.height, -1.0);
  for (int y = 0; y < cam.height; ++y) {
    for (int x = 0; x < cam.width; ++x) {
      const Vec3 dv = normalize(fwd + right * ((2.0 * (x + 0.5) / cam.width - 1.0) * tan_half * aspect) +
                                up * ((1.0 - 2.0 * (y + 0.5) / cam.height) * tan_half));
      if (dv.y >= 0) continue;
      const k::real3 d{dv.x, dv.y, dv.z};
      k::real3 v{};
      k::refract_dir(d, k::real3{0, 1, 0}, 1.0 / scene.water.ior, &v);
      const double t_p = cam.position.y / -d.y;
      double t_q = 0;
      k::real3 n{};
      k::sea_hf_intersect(&floor.params, floor.depth.data(),
                          k::real3{cam.position.x + t_p * d.x, 0.0, cam.position.z + t_p * d.z}, v, 1e30, &t_q, &n);
      z[static_cast<size_t>(y) * cam.width + x] = -v.y * t_q;
    }
  }
  return z;
}

// The pixels' sums per bin of floor depth z_Q (edges: increasing; pixels outside them left out): the
// images' parts as luminance, the water-leaving colour without and with L^(2), and the 8-bit difference.
struct DepthBin {
  long pixels = 0;
  double z = 0, y1 = 0, yb = 0, y2 = 0, yr = 0, levels = 0;
  double water1[3] = {0, 0, 0}, water2[3] = {0, 0, 0};  // water-leaving colour without / with L^(2)
};

std::vector<DepthBin> binByFloorDepth(const std::vector<double> &edges, const std::vector<double> &z_q,
                                      const Image &full, const Image &single, const Image &scatter,
                                      const Image &reflect, const std::vector<std::uint8_t> &full8,
                                      const std::vector<std::uint8_t> &single8) {
  const size_t bins = edges.size() - 1;
  std::vector<DepthBin> bin(bins);
  for (size_t p = 0; p < z_q.size(); ++p) {
    if (z_q[p] < edges.front() || z_q[p] > edges.back()) continue;
    size_t b = std::upper_bound(edges.begin(), edges.end(), z_q[p]) - edges.begin() - 1;
    b = std::min(b, bins - 1);
    const float *f2 = &full.pixels[3 * p];
    const float *f1 = &single.pixels[3 * p];
    const float *s = &scatter.pixels[3 * p];
    const float *r = &reflect.pixels[3 * p];
    DepthBin &B = bin[b];
    ++B.pixels;
    B.z += z_q[p];
    float l2[3], lb[3];
    for (int c = 0; c < 3; ++c) {
      l2[c] = f2[c] - f1[c];
      lb[c] = f1[c] - s[c] - r[c];  // eq. 9: what the floor adds
      B.water1[c] += s[c] + lb[c];
      B.water2[c] += s[c] + lb[c] + l2[c];
      B.levels += std::fabs(double(full8[3 * p + c]) - double(single8[3 * p + c])) / 3.0;
    }
    B.y1 += luma(s);
    B.yb += luma(lb);
    B.y2 += luma(l2);
    B.yr += luma(r);
  }
  return bin;
}

}  // namespace

int cmdSeashoreStudy(const SeashoreStudyCmd &cmd) {
  if (cmd.edges.size() < 2 || !std::is_sorted(cmd.edges.begin(), cmd.edges.end())) {
    throw RuntimeError("seashore-study: --edges needs at least two increasing depths (m)");
  }
  Device device(chooseDevice(cmd.device));
  std::printf("device: %s\n", device.info().label().c_str());
  std::vector<Override> common;
  for (const std::string &s : cmd.sets) common.push_back(parseSetOption(s));
  common.push_back(set("camera.width", std::to_string(cmd.width)));
  common.push_back(set("camera.height", std::to_string(cmd.height)));
  const Scene original = loadScene(cmd.scene, common);
  if (original.bottom.type != BottomDesc::Type::HeightField || original.camera.position.y <= 0) {
    throw RuntimeError("seashore-study: '" + cmd.scene + "' needs a [bottom] type = \"heightfield\" seen from above");
  }
  std::vector<double> max_depths = cmd.max_depths;
  if (max_depths.empty()) max_depths.push_back(original.bottom.max_depth);

  CsvWriter table({"max_depth_m", "depth_lo_m", "depth_hi_m", "pixels", "mean_depth_m", "L1_single_scattering",
                   "L_bottom", "L2_second_order", "L_sky_reflection", "ratio_L2_over_L1", "share_L2_of_water_leaving",
                   "hue_single_deg", "hue_with_second_deg", "hue_shift_deg", "mean_abs_diff_8bit"});
  std::vector<PlotSeries> plot_series;
  for (const double max_depth : max_depths) {
    std::vector<Override> base = common;
    char max_text[32];
    std::snprintf(max_text, sizeof max_text, "%.6g", max_depth);
    base.push_back(set("bottom.max_depth", max_text));
    const Scene scene = loadScene(cmd.scene, base);
    std::printf("\n%s, floor %g m to %g m deep:\n", scene.name.c_str(), scene.bottom.min_depth, scene.bottom.max_depth);

    // The parts of the image, each its own render of the same scene.
    auto part = [&](const char *name, std::vector<Override> over) {
      std::vector<Override> o = base;
      o.insert(o.end(), over.begin(), over.end());
      const Scene s = loadScene(cmd.scene, o);
      const FrameResult f = renderFrame(device, s, makePlan(s));
      if (f.nonfinite != 0) throw RuntimeError("seashore-study: NaN/Inf in the render '" + std::string(name) + "'");
      double pass_ms = 0;
      for (const PassTiming &t : f.timings) pass_ms += t.ms;
      std::printf("%-22s %9.1f ms in passes, %9.1f ms wall\n", name, pass_ms, f.wall_ms);
      std::fflush(stdout);
      return f.rgb;
    };
    const Image full = part("single + second", {set("sea.second_order", "true")});
    const Image single = part("single only", {set("sea.second_order", "false")});
    const Image scatter = part("single scattering", {set("sea.second_order", "false"), set("sea.reflection", "false"),
                                                     set("bottom.albedo", "0")});
    const Image reflect = part("sky reflection", {set("sea.second_order", "false"),
                                                  set("sea.single_scattering", "false"), set("bottom.albedo", "0")});
    const std::vector<double> z_q = floorDepths(scene, loadHeightField(scene.bottom));

    // Display images for the 8-bit difference (the scene's exposure, the PNG's
    // tone map).
    std::vector<std::uint8_t> full8, single8;
    toneMapImage8(full, scene.camera.exposure_ev, full8);
    toneMapImage8(single, scene.camera.exposure_ev, single8);

    const size_t bins = cmd.edges.size() - 1;
    const std::vector<DepthBin> bin = binByFloorDepth(cmd.edges, z_q, full, single, scatter, reflect, full8, single8);

    PlotSeries ratio{"L2/L1, floor to " + std::string(max_text) + " m", {}, {}};
    PlotSeries share{"L2 share of water-leaving, floor to " + std::string(max_text) + " m", {}, {}};
    std::printf(
        "\n  z_Q (m)     pixels  L2/L1   L2 share  hue 1 -> 1+2 (deg)  "
        "|d| 8-bit\n");
    for (size_t b = 0; b < bins; ++b) {
      const DepthBin &B = bin[b];
      if (B.pixels == 0) continue;
      const double n = double(B.pixels);
      const double r = B.y2 / std::max(B.y1, 1e-30), sh = B.y2 / std::max(B.y1 + B.yb + B.y2, 1e-30);
      const double h1 = hue(B.water1), h2 = hue(B.water2);
      double dh = h2 - h1;
      if (dh > 180) dh -= 360;
      if (dh < -180) dh += 360;
      table.addRow({max_depth, cmd.edges[b], cmd.edges[b + 1], B.pixels, B.z / n, B.y1 / n, B.yb / n, B.y2 / n,
                    B.yr / n, r, sh, h1, h2, dh, B.levels / n});
      std::printf("  %4.1f-%-5.1f %7ld  %.4f  %.4f    %6.1f -> %6.1f      %.2f\n", cmd.edges[b], cmd.edges[b + 1],
                  B.pixels, r, sh, h1, h2, B.levels / n);
      ratio.x.push_back(B.z / n);
      ratio.y.push_back(r);
      share.x.push_back(B.z / n);
      share.y.push_back(sh);
    }
    plot_series.push_back(ratio);
    plot_series.push_back(share);
  }
  if (!cmd.csv.empty()) table.write(cmd.csv);
  if (!cmd.plot.empty()) {
    PlotSpec spec;
    spec.title = "Second order vs floor depth z_Q: " + original.name + " (" + std::to_string(cmd.width) + "x" +
                 std::to_string(cmd.height) + ")";
    spec.x_label = "z_Q, depth where the view ray meets the floor (m; bin means)";
    spec.y_label = "ratio";
    spec.series = plot_series;
    writeSvgPlot(cmd.plot, spec);
  }
  return 0;
}

}  // namespace seasim
