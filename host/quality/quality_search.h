// quality_search.h — what the per-scene `auto` quality searches (shafts_auto, sea_auto) share: the
// reduced resolution they render at, and their cache files (one "key value" per line, "#" comments
// recording the inputs of the decision).
#pragma once
#include <map>
#include <string>

#include "scene/scene.h"

namespace seasim {

// The camera's size scaled by 1/downscale, the long side kept within [min_long_side, max_long_side]
// and never above the full size; the aspect ratio kept.
void searchResolution(const CameraDesc& camera, int downscale, int min_long_side, int max_long_side, int& width,
                      int& height);

// A search's cache file for the inputs `description`: folder/PREFIX<hex FNV-1a 64 of description>.txt,
// folder = `dir`, or when empty the cache folder `subfolder` (util/paths.h cacheDir); "" when there is none.
std::string searchCacheFile(const std::string& dir, const std::string& subfolder, const std::string& prefix,
                            const std::string& description);

// When no candidate of a search meets its error budget, the error floor (what every setting shares: the
// shadow-map, table or texel limits, or the search size's own) is the least error found, and candidates
// within this fraction of it count as at the floor: the cheapest of them is taken, and a ladder stops at a
// candidate no better than the best before it by more than this. On stage at a 0.25-level budget the
// intervals are 0.3846 levels at the search size and the planes at n = 80, m = 12 0.3844, for 13x the time.
constexpr double kErrorFloorTolerance = 0.02;
inline double errorFloorBar(double least_error) { return least_error * (1.0 + kErrorFloorTolerance); }
// A candidate with `error` is at the floor of those before it (least error `least_before`, < 0 for none).
inline bool atErrorFloor(double error, double least_before) {
  return least_before >= 0 && errorFloorBar(error) >= least_before && error <= errorFloorBar(least_before);
}

// The "key value" lines of a cache file; empty when it cannot be read.
std::map<std::string, std::string> readCacheEntries(const std::string& path);

// Writes `title` and every line of `inputs` as comments, then `entries` (lines of "key value"),
// atomically. Best effort: a cache that cannot be written only costs the search next time.
void writeCacheEntries(const std::string& path, const std::string& title, const std::string& inputs,
                       const std::string& entries);

}  // namespace seasim
