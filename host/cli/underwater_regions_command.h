// underwater_regions_command.h — `seasim underwater-regions`: the fast underwater model's error by
// region (reference/underwater_regions.h) against the path tracer (kernels/reference.cl), over a grid
// of one-band waters (a, b), phase asymmetries g, bottom depths and camera views, for each
// `underwater.model`; the path tracer's images are cached (they are the slow part). Prints and writes
// a CSV: ratio fast/reference per region with the reference's relative standard error, and times.
#pragma once
#include <string>
#include <vector>

namespace seasim {

struct UnderwaterRegionsCmd {
  std::string scene = "tests/perf/underwater_regions.toml";  // one band, explicit a and b
  std::string device;
  std::vector<std::string> waters = {"0.03:0.05", "0.1:0.3", "0.4:1.2"};  // a:b in 1/m
  std::vector<double> gs = {0.0, 0.5, 0.9, 0.95};
  std::vector<double> depths = {2, 5, 20, 0};  // bottom depth in m; 0 = no bottom (deep water)
  std::vector<std::string> views = {"level", "up"};
  std::vector<std::string> models = {"thesis", "improved"};
  int spp = 2048;         // path tracer samples per pixel
  std::string cache_dir;  // reference images (default: $SEASIM_CACHE_DIR/underwater_regions or build/)
  std::string csv;
  std::vector<std::string> sets;  // extra scene overrides (applied to every render and reference)
  std::vector<std::string> model_sets;  // overrides for the fast models' renders only (not the references)
  std::string dump_dir;  // per case a CSV of every pixel: region, d_y, reference, fast renders, improved terms
};

int cmdUnderwaterRegions(const UnderwaterRegionsCmd& cmd);

}  // namespace seasim
