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
  // false: every reference path through the pixel's centre, the one ray per pixel that the fast models
  // shade and that underwaterRegions classifies; true: over the pixel's area, as `seasim reference`
  // does, where an object's edge pixels mix in the sand or water beside it.
  bool jitter = false;
  // > 0: where a region of at least kRegionsJudgedMinPixels pixels has a reference noisier than this
  // (relative standard error) at `spp`, the case is traced again at the path count that noise implies
  // for the target (spp (noise/target)², rounded up to a power of two), if that is at most max_spp;
  // cases that would need more keep `spp` and their noise (reported, not hidden). 0: off.
  double target_noise = 0;
  int max_spp = 16384;
  std::string cache_dir;  // reference images (default: $SEASIM_CACHE_DIR/underwater_regions or build/)
  std::string csv;
  std::vector<std::string> sets;  // extra scene overrides (applied to every render and reference)
  std::vector<std::string> model_sets;  // overrides for the fast models' renders only (not the references)
  std::string dump_dir;  // per case a CSV of every pixel: region, d_y, reference, fast renders, improved terms
};

// The smallest region whose ratio tests/perf/underwater_regions_summary.py judges (its MIN_PIXELS).
inline constexpr int kRegionsJudgedMinPixels = 40;

// The path count at which a reference of relative noise `noise` at `spp` paths reaches `target`
// (noise falls as 1/√paths): spp (noise/target)² rounded up to a power-of-two multiple of spp; spp
// itself when noise <= target or target <= 0; 0 when that is more than max_spp.
int refinedPathCount(int spp, double noise, double target, int max_spp);

int cmdUnderwaterRegions(const UnderwaterRegionsCmd& cmd);

}  // namespace seasim
