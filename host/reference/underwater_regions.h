// underwater_regions.h — an underwater frame split into the regions the fast model is judged by
// against the path tracer: the bottom near and far, the water looking up and down, the objects. Each pixel's centre
// ray is cast in double with the kernels' own geometry (common/underwater.h uw_screen_dir,
// uw_scene_hit), so the regions are exact and independent of the renders they judge.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "io/image.h"
#include "underwater/underwater_setup.h"

namespace seasim {

enum class UwRegion { BottomNear = 0, BottomFar, WaterUp, WaterDown, Objects, Count };
constexpr int kUwRegionCount = static_cast<int>(UwRegion::Count);

const char* uwRegionName(UwRegion r);  // "bottom_near", "bottom_far", "water_up", "water_down", "objects"

// The bottom is "near" closer than this along the view ray: the seabed view's foreground (2–6 m) and
// its far bottom (beyond, where in-scattering outweighs the bottom's own radiance).
constexpr double kUwNearBottomM = 6.0;

// One region per pixel (row-major, width × height of setup.params): objects (any analytic object),
// the bottom by distance, else the water by the ray's direction (up: it ends at the surface).
std::vector<UwRegion> underwaterRegions(const UnderwaterSetup& setup);

struct UwRegionStat {
  int pixels = 0;
  double fast = 0.0;       // Σ over the region's pixels and channels of the fast render
  double reference = 0.0;  // the same for the reference
  double noise = 0.0;      // standard error of `reference` (pixels independent; channels of one pixel
                           // share its paths, so their errors add)
  double ratio() const { return reference > 0 ? fast / reference : 0.0; }
  double relNoise() const { return reference > 0 ? noise / reference : 0.0; }
};

// Region sums of a fast render against a reference with its per-pixel standard error (3 channels each).
std::array<UwRegionStat, kUwRegionCount> underwaterRegionStats(const std::vector<UwRegion>& regions, const Image& fast,
                                                             const Image& reference, const Image& std_error);

}  // namespace seasim
