// underwater_study_command.h — `seasim underwater-study`: the thesis's §6.1 evaluation. For each Jerlov
// water and seabed depth, and each camera, the spectral render (n bands) and the "RGB" render (n = 3)
// are compared with the spectral path-traced reference (kernels/reference.cl): RMSE in 8-bit levels
// and the hue+saturation distance of 002 §6.1, beside the reference's own noise. CSV + SVG plot.
#pragma once
#include <string>
#include <vector>

namespace seasim {

struct UnderwaterStudyCmd {
  std::string scene;      // the seabed scene (its depth-dependent geometry is moved as in jobs/jerlov_table.toml)
  std::string device;
  std::vector<std::string> waters = {"3C", "II", "I", "IA", "IB"};
  std::vector<double> depths = {3, 5, 9};
  // The shipped (BSD) cameras by default. The thesis's sweep over many cameras reads curves that may
  // not ship (e.g. the CC BY-NC-SA camspec database) from camera_dir: with it and no --cameras, every
  // <name>.csv in that folder is used.
  std::vector<std::string> cameras = {"canon_eos_5d_mark_ii_rawtoaces", "nikon_d5100_npl", "sigma_sdmerrill_npl"};
  std::string camera_dir;
  int width = 64, height = 36;
  int spectral_bands = 32;   // the fast method's n
  int reference_bands = 32;  // the path tracer's bands
  int spp = 64;              // path tracer samples per pixel, per run (two runs with different seeds)
  std::string csv, plot;
  std::vector<std::string> sets;  // extra scene overrides
};

int cmdUnderwaterStudy(const UnderwaterStudyCmd& cmd);

}  // namespace seasim
