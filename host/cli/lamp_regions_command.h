// lamp_regions_command.h — `seasim lamp-regions`: the lamps' fast models under water by region against
// the all-orders path tracer, over a grid of one-band waters (a, b, g), lamp cones and heights of the
// lamp above the bottom, on tests/perf/lamp_glow.toml's camera and lamp. Regions by each pixel centre's
// ray (as tests/validate/mitsuba_lamps.py): the bottom inside the lamp's cone ("lit bottom"), water whose
// ray crosses the cone before it ends ("beam"), everything else ("outside"), and the whole image. The
// references trace every path through the pixel centre (the ray the fast models shade) and are cached.
// Prints and writes a CSV: per case and model the ratio fast / reference per region with the
// reference's relative standard error, and the lamp pass's kernel time (median of interleaved rounds).
// --max-bounces limits the reference to that many scattering vertices per path (cached apart) and --means
// prints each region's mean radiance: with a fast model cut to the same orders, each order's share by
// difference.
#pragma once
#include <string>
#include <vector>

namespace seasim {

struct LampRegionsCmd {
  std::string scene = "tests/perf/lamp_glow.toml";
  std::string device;
  // a:b:g:cone_deg:height_m per case (height of the lamp above the bottom).
  std::vector<std::string> cases = {"0.1:0.3:0.9:20:3"};
  std::vector<std::string> models = {"delta_m", "orders"};  // quality.lamps_model values
  int spp = 4096;
  int max_bounces = 0;  // the reference's scattering vertices per path (0: all orders); orders by difference
  bool means = false;   // also print each region's mean radiance, fast and reference (orders by difference)
  int rounds = 3;  // interleaved timing rounds per case
  std::string cache_dir;
  std::string csv;
  std::vector<std::string> sets;        // overrides for every render and reference
  std::vector<std::string> model_sets;  // overrides for the fast renders only
};

int cmdLampRegions(const LampRegionsCmd& cmd);

}  // namespace seasim
