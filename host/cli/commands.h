// commands.h — the subcommands behind `seasim`, as plain functions over plain option structs, so
// main() only wires CLI11 to them and tests can call them. Each returns the process exit code.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "scene/scene_parser.h"
#include "scene/set_option.h"

namespace seasim {


int cmdDevices();
int cmdValidate(const std::vector<std::string>& files);
int cmdPlan(const std::string& scene, const std::vector<std::string>& sets);

struct RenderCmd {
  std::string scene, out_dir, device, reference;
  std::vector<std::string> sets;
  std::vector<std::string> formats = {"exr", "png"};  // and layer names (scene/output_layers.h)
};
int cmdRender(const RenderCmd& cmd);

// `sets` (--set key=value) are applied to every item of the job, after the item's own overrides.
int cmdRun(const std::string& job, const std::string& device, const std::string& shard, bool resume,
           const std::string& output_dir = "", const std::vector<std::string>& sets = {},
           const std::vector<std::string>& layers = {});

// The tone map's exposure is --exposure when given, else the one recorded with the test image (its
// render's report.json), else the reference's (REF.settings.json), as `sweep` uses the scene's; 0 when
// neither is recorded. With REF.stderr.exr beside the reference, its noise is reported with the part
// of the error it explains. Recorded settings that differ between the two are warned about.
int cmdCompare(const std::string& test, const std::string& reference, std::optional<double> exposure_ev);

struct SweepCmd {
  std::string scene, csv, plot, device;
  std::string reference;  // "": the scene's own reference (with --set, not --param) is made beside the CSV
  std::vector<std::string> params;  // "KEY=v1,v2,..." (several: the grid of all combinations)
  std::vector<std::string> sets;
};
int cmdSweep(const SweepCmd& cmd);

struct BenchCmd {
  std::string scene, csv, plot, device;
  std::vector<std::string> sets;  // --set key=value overrides on the scene
  std::vector<int> wavelengths = {3, 8, 16, 32, 64};
  std::vector<int> lights;  // --lights 1,2,3: shafts time vs light count, keeping the first k spotlights
  std::vector<int> sea_maps;  // --sea-maps 32,64: sea second order, maps vs accumulation ms per map size
  int repeat = 5;
  bool limits = false;
  int frames = 0;                   // --frames N: an animation of N frames over --time-range (bench_frames.cpp)
  std::vector<double> time_range;   // --time-range t0,t1 (s) for surface.time
  bool fresh = false;               // --fresh: a new renderer per frame (everything set up each frame)
  std::vector<std::string> devices; // --devices pocl,intel: per-pass times on each (bench_devices.cpp)
};
int cmdBench(const BenchCmd& cmd);
// The --sea-maps mode of bench (host/cli/bench_sea.cpp).
class Device;
int benchSeaSecond(Device& device, const BenchCmd& cmd, const std::vector<Override>& overrides);
// The --frames mode of bench (host/cli/bench_frames.cpp).
int benchFrames(Device& device, const BenchCmd& cmd, const std::vector<Override>& overrides);
// The --devices mode of bench (host/cli/bench_devices.cpp): one table of per-pass times and ratios.
int benchDevices(const BenchCmd& cmd, const std::vector<Override>& overrides);
// The --lights mode of bench (host/cli/bench_lights.cpp): shafts time against spotlight count.
int benchLights(Device& device, const BenchCmd& cmd, const std::vector<Override>& overrides);
// bench's default mode (host/cli/bench_wavelengths.cpp): time against wavelength count; exp_rate > 0
// (from --limits) adds each band loop's share of the exp/s bound.
int benchWavelengths(Device& device, const BenchCmd& cmd, const std::vector<Override>& overrides, double exp_rate);

struct ReferenceCmd {
  std::string scene, out, device;
  std::vector<std::string> sets;
  int steps = 0;      // 0: the scene's quality.reference_spp (under water) or quality.reference_steps
  long long seed = -1;  // under water: the path tracer's seed; -1: not given (seed 1)
  bool all_orders = false;  // the sea seen from above: the path tracer refracting in, not 000's quadrature
  int max_bounces = 0;      // path tracer: scattering vertices per path (0: its default, 64)
  bool plain_lamp_sampling = false;  // path tracer: lamps by the equiangular sample alone (no MIS)
  bool pixel_centre = false;         // path tracer: every path through the pixel's centre
  bool sun_single_quadrature = false;  // under water: the sun beam's single scattering by quadrature
  int subpixels = 4;                   // its rays per pixel: subpixels²
};
int cmdReference(const ReferenceCmd& cmd);
// The reference of `scene` (the model's brute-force method, as `seasim reference` picks it) written to
// `out`, with OUT.stderr.exr (path tracer) and OUT.settings.json beside it; returns a line describing it.
std::string writeSceneReference(const Scene& scene, const ReferenceCmd& cmd, const std::string& out);

}  // namespace seasim
