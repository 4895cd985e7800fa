// ocean_command.h — `seasim ocean`: the FFT ocean (004 §3) and its caustics (§5.2.1) as files, and a
// benchmark of the ocean pass against FFTW on the same CPU.
#pragma once
#include <string>
#include <vector>

namespace seasim {

struct OceanCmd {
  std::string scene;                 // scene file: its [surface], [sun], [water].ior; "" = defaults
  std::string out_dir;               // output folder (created)
  std::string device;                // device selector ("" = auto)
  std::vector<std::string> sets;     // key=value scene overrides
  double time = -1.0;                // s; < 0 = the scene's surface.time
  std::vector<double> caustic_depths = {2.0, 10.0};  // m: caustic maps + intensity PDF (Figure 29)
  double attenuation = 0.0;          // c, 1/m along the refracted path for the caustic maps
  int caustic_supersample = 2;       // rays per surface cell per side
  bool bench = false;                // benchmark instead of maps
  std::vector<int> bench_sizes = {256, 512, 1024, 2048};
  int repeat = 5;                    // timed frames per size (median reported)
};

// Maps mode writes into out_dir: height.exr (Y, m), slope.exr (dhdx, dhdz), displacement.exr
// (R,G,B = λDx, h, λDz, m), normal.exr (R,G,B = nx, ny, nz), folding.exr (J, Jminus, Jplus, ex, ez),
// caustics_<d>m.exr (Y: irradiance / sun irradiance on a horizontal surface), caustic_pdf.csv and
// caustic_pdf.svg (PDF of I/<I> per depth); with a height-field bottom also caustics_floor.exr (the
// irradiance on the floor over its square, CausticsPass::runFloor). Bench mode writes bench_ocean.csv and bench_ocean.svg.
// Returns 0; throws InputError/RuntimeError/DeviceError (main prints them).
int cmdOcean(const OceanCmd& cmd);

}  // namespace seasim
