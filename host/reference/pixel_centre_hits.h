// pixel_centre_hits.h — every pixel's centre ray cast in double through the underwater scene, with the
// kernels' own geometry (common/underwater.h uw_screen_dir, uw_scene_hit): what the froxel reference
// and the region judge (underwater_regions.h) need of the camera's view.
#pragma once
#include <vector>

#include "underwater/underwater_setup.h"

namespace seasim {

struct PixelCentreHit {
  double distance = 0.0;  // S to the first hit; >= UW_INFINITE (1e30) for a ray into deep water
  int material = 0;       // uw_scene_hit's: an object's index (>= 0) or a UW_MAT_* value
  double dir_y = 0.0;     // the ray's vertical direction (> 0: towards the surface)
  double cos_sun = 0.0;   // its cosine with the direction to the refracted sun (UwParams.sun_dir_water)
};

// Row-major, width × height of setup.params.
std::vector<PixelCentreHit> pixelCentreHits(const UnderwaterSetup& setup);

}  // namespace seasim
