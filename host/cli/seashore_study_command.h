// seashore_study_command.h — `seasim seashore-study`: does second-order scattering matter more with
// depth over a height-field floor (000 §6, Fig. 11: "It becomes important when the bottom becomes
// deeper")? Renders the scene's parts (single + second, single only, single scattering alone, sky
// reflection alone), walks each pixel's refracted view ray to the floor for z_Q (the same cell walk
// the kernels use, in double), and bins by z_Q: L^(2) / L^(1) (second over single scattering), the
// second order's share of the water-leaving radiance (single + bottom + second), the hue shift of the
// water-leaving colour it causes, and the mean displayed difference in 8-bit levels. CSV + SVG plot.
// Across one image z_Q and the viewing angle change together (the deep floor is far off, seen at grazing
// angles), so --max-depths repeats the study with the floor's grey mapped onto other depth ranges
// (bottom.max_depth), the paper's Fig. 11(b) comparison (7.9 m vs 39.9 m): the same pixels, deeper water.
#pragma once
#include <string>
#include <vector>

namespace seasim {

struct SeashoreStudyCmd {
  std::string scene;    // a scene with [bottom] type = "heightfield" seen from above (scenes/seashore.toml)
  std::string device;
  int width = 240, height = 135;
  std::vector<double> edges = {1, 2, 3, 5, 7.5, 10, 15, 20, 30, 40};  // z_Q bin edges, m
  std::vector<double> max_depths;  // bottom.max_depth values to study (empty: the scene's own)
  std::string csv, plot;
  std::vector<std::string> sets;  // extra scene overrides
};

int cmdSeashoreStudy(const SeashoreStudyCmd& cmd);

}  // namespace seasim
