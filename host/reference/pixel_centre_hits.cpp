#include "reference/pixel_centre_hits.h"

#include "math/kernel_math.h"

namespace seasim {

namespace kd = kmath_d;

std::vector<PixelCentreHit> pixelCentreHits(const UnderwaterSetup& setup) {
  const UwParams& p = setup.params;
  std::vector<PixelCentreHit> out(size_t(p.width) * p.height);
  const kd::real3 o{p.cam_pos[0], p.cam_pos[1], p.cam_pos[2]};
  const kd::real3 s_w{p.sun_dir_water[0], p.sun_dir_water[1], p.sun_dir_water[2]};
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x) {
      const kd::real3 d = kd::uw_screen_dir(&p, (x + 0.5) / p.width, (y + 0.5) / p.height);
      kd::real3 n{};
      PixelCentreHit& hit = out[size_t(y) * p.width + x];
      hit.distance = kd::uw_scene_hit(setup.objects.data(), p.object_count, p.bottom_depth, o, d, 0.0, &n,
                                      &hit.material);
      hit.dir_y = d.y;
      hit.cos_sun = kd::dot(d, s_w);
    }
  return out;
}

}  // namespace seasim
