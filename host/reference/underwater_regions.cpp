#include "reference/underwater_regions.h"

#include <cmath>

#include "math/kernel_math.h"
#include "util/error.h"

namespace seasim {

namespace kd = kmath_d;

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
  const UwParams& p = setup.params;
  std::vector<UwRegion> out(size_t(p.width) * p.height);
  const kd::real3 o{p.cam_pos[0], p.cam_pos[1], p.cam_pos[2]};
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x) {
      const kd::real3 d = kd::uw_screen_dir(&p, (x + 0.5) / p.width, (y + 0.5) / p.height);
      kd::real3 n{};
      int mat = 0;
      const double S = kd::uw_scene_hit(setup.objects.data(), p.object_count, p.bottom_depth, o, d, 0.0, &n, &mat);
      UwRegion r;
      if (mat >= 0) r = UwRegion::Objects;
      else if (mat == UW_MAT_BOTTOM) r = S < kUwNearBottomM ? UwRegion::BottomNear : UwRegion::BottomFar;
      else r = d.y > 0 ? UwRegion::WaterUp : UwRegion::WaterDown;
      out[size_t(y) * p.width + x] = r;
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
