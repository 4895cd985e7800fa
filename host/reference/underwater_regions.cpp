#include "reference/underwater_regions.h"

#include <cmath>

#include "math/kernel_math.h"
#include "reference/pixel_centre_hits.h"
#include "util/error.h"

namespace seasim {

const char* uwRegionName(UwRegion r) {
  switch (r) {
    case UwRegion::BottomNear: return "bottom_near";
    case UwRegion::BottomFar: return "bottom_far";
    case UwRegion::WaterUp: return "water_up";
    case UwRegion::WaterDown: return "water_down";
    case UwRegion::Objects: return "objects";
    default: return "?";
  }
}

std::vector<UwRegion> underwaterRegions(const UnderwaterSetup& setup) {
  const std::vector<PixelCentreHit> hits = pixelCentreHits(setup);
  std::vector<UwRegion> out(hits.size());
  for (size_t i = 0; i < hits.size(); ++i) {
    const PixelCentreHit& h = hits[i];
    if (h.material >= 0) out[i] = UwRegion::Objects;
    else if (h.material == UW_MAT_BOTTOM)
      out[i] = h.distance < kUwNearBottomM ? UwRegion::BottomNear : UwRegion::BottomFar;
    else out[i] = h.dir_y > 0 ? UwRegion::WaterUp : UwRegion::WaterDown;
  }
  return out;
}

std::array<UwRegionStat, kUwRegionCount> underwaterRegionStats(const std::vector<UwRegion>& regions, const Image& fast,
                                                             const Image& reference, const Image& std_error) {
  for (const Image* im : {&fast, &reference, &std_error})
    if (im->pixelCount() != regions.size() || im->channels != 3)
      throw RuntimeError("underwater regions: the images must be RGB and match the region map's size");
  std::array<UwRegionStat, kUwRegionCount> s{};
  std::array<double, kUwRegionCount> var{};
  for (size_t i = 0; i < regions.size(); ++i) {
    UwRegionStat& r = s[static_cast<int>(regions[i])];
    double se = 0.0;
    for (int c = 0; c < 3; ++c) {
      r.fast += fast.pixels[3 * i + c];
      r.reference += reference.pixels[3 * i + c];
      se += std_error.pixels[3 * i + c];
    }
    var[static_cast<int>(regions[i])] += se * se;
    ++r.pixels;
  }
  for (int k = 0; k < kUwRegionCount; ++k) s[k].noise = std::sqrt(var[k]);
  return s;
}

}  // namespace seasim
