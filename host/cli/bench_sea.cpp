// bench_sea.cpp — `seasim bench --scene S --sea-maps 32,64`: ms per frame of the sea's second-order
// scattering (kernels/sea_second.cl, 000 eq. 6–8) split into the scattering maps (VSF map + radiance
// map + scattering maps: n_z x M^2 x n_d x bands) and the plane-wise accumulation into the view
// (pixels x n_z x bands), per map size M, at the scene's n_z and n_d (the paper's §6.1 values are
// n_z = 12, n_d = 128: give them with --set quality.sea_nz=12 --set quality.sea_nd=128). The pass
// runs alone (its rgb target is a zeroed buffer): sea_single and the read-back are not timed.
// OpenCL profiling times, median of --repeat runs after one warm-up run.
#include <algorithm>
#include <cstdio>
#include <vector>

#include "cli/commands.h"
#include "io/csv.h"
#include "passes/sea_second_pass.h"
#include "plan/pass_descriptor.h"
#include "plan/plan.h"
#include "quality/sea_auto.h"
#include "scene/scene_parser.h"
#include "spectral/sensor.h"
#include "spectral/wavelength_grid.h"
#include "util/error.h"

namespace seasim {

namespace {

double medianOf(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

}  // namespace

int benchSeaSecond(Device& device, const BenchCmd& cmd, const std::vector<Override>& overrides) {
  CsvWriter table({"map_size", "n_z", "n_d", "bands", "width", "height", "maps_ms", "accumulate_ms", "total_ms"});
  for (int m : cmd.sea_maps) {
    if (m < 1) throw RuntimeError("--sea-maps: map sizes must be positive integers, got " + std::to_string(m));
    std::vector<Override> o = overrides;
    o.push_back(parseSetOption("quality.sea_map_size=" + std::to_string(m)));
    o.push_back(parseSetOption("sea.second_order=true"));
    const Scene scene = loadScene(cmd.scene, o);
    const Plan plan = makePlan(scene);
    const PassPlan* second = plan.find(descriptorFor(PassRole::SeaSecondOrder).name);
    if (!second) throw RuntimeError("--sea-maps: " + cmd.scene + " has no sea second-order pass (no water in view?)");
    const WavelengthGrid grid = makeGrid(scene.spectral.count, scene.spectral.min_nm, scene.spectral.max_nm);
    const Sensor sensor = makeSensor(scene.spectral.sensor, grid, scene.spectral.white_balance, scene.spectral.camera_dir);
    const size_t pixels = static_cast<size_t>(scene.camera.width) * scene.camera.height;
    std::vector<float> zeros(3 * pixels, 0.0f);
    cl::Buffer rgb(device.context(), CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, sizeof(float) * zeros.size(),
                   zeros.data());
    cl::Buffer spectral;
    if (scene.spectral.spectral_exr) {
      spectral = cl::Buffer(device.context(), CL_MEM_READ_WRITE, sizeof(float) * pixels * grid.size());
    }
    SeaSecondPass pass(device, scene, *second, seaSecondConfigWithAuto(device, scene), grid, sensor, rgb,
                       scene.spectral.spectral_exr ? &spectral : nullptr);
    (void)pass.run();  // warm-up: PoCL compiles lazily; height-field depth tables are built here
    std::vector<double> maps, acc;
    for (int r = 0; r < std::max(1, cmd.repeat); ++r) {
      (void)pass.run();
      maps.push_back(pass.mapsMs());
      acc.push_back(pass.accumulateMs());
    }
    const SeaSecondPass::Config& c = pass.config();
    const int n_d = c.n_theta * c.n_phi;
    const double maps_ms = medianOf(maps), acc_ms = medianOf(acc);
    std::printf("sea second order %dx%d, map %dx%d, n_z = %d, n_d = %d (%dx%d), %zu bands: scattering maps %.3f ms, "
                "accumulation %.3f ms, total %.3f ms per frame\n",
                scene.camera.width, scene.camera.height, c.map_size, c.map_size, c.n_z, n_d, c.n_theta, c.n_phi,
                grid.size(), maps_ms, acc_ms, maps_ms + acc_ms);
    table.addRow({c.map_size, c.n_z, n_d, static_cast<int>(grid.size()), scene.camera.width, scene.camera.height,
                  maps_ms, acc_ms, maps_ms + acc_ms});
  }
  if (!cmd.csv.empty()) table.write(cmd.csv);
  return 0;
}

}  // namespace seasim
