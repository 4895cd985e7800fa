// underwater_setup.h — the scene turned into the parameter blocks every underwater pass reads
// (kernels/common/underwater_params.h): camera, refracted sun, per-band water IOPs and the light just
// below the surface, analytic objects and their albedo per band. Built once per frame and shared by
// the raycast, froxel, kd_multiple and path-tracer (reference.cl) passes so they see the same scene.
#pragma once
#include <vector>

#include "math/vec3.h"
#include "scene/scene.h"
#include "sky/sky_light.h"  // skyFresnelMean, SkyParams
#include "spectral/sensor.h"
#include "spectral/wavelength_grid.h"

extern "C" {
#include "common/underwater_params.h"
#include "common/underwater_ordinates_params.h"
}

namespace seasim {

struct UnderwaterSetup {
  UwParams params{};
  std::vector<UwBand> bands;     // one per wavelength band
  std::vector<UwObject> objects; // analytic objects (sphere, box, plane)
  std::vector<float> albedo;     // [object * band_count + band]; at least one entry (OpenCL buffers)
  Vec3 sun_air{0, 1, 0};         // unit, towards the sun in air
  Vec3 sun_water{0, 1, 0};       // unit, towards the sun after refraction (y = μ_w)
  double sky_fresnel = 0.0;      // r̄: the uniform sky's cosine-weighted Fresnel reflectance at the surface
  SkyParams sky_params{};        // the [sky] for Snell's window in kd_multiple.cl (common/sky_view.h)
  std::vector<float> sky_buffer; // its image texels or Preetham's reals; at least one entry
  bool single_scattering = true; // the froxel pass runs (L_MS and L_s then leave out the direct beam)
  std::vector<UwiBand> ordinates; // underwater.model = "discrete_ordinates": one per band (underwater_ordinates_setup.h); else empty
};

// RuntimeError for what the underwater passes cannot render (a height-field object, naming it).
UnderwaterSetup makeUnderwaterSetup(const Scene& scene, const WavelengthGrid& grid, const Sensor& sensor);

// The set-up of `scene` made from `setup`, made before for the same scene but another camera, when the
// camera's depth is the same: only the camera's fields change (its frame, field of view and image
// size), as makeUnderwaterSetup would set them; the per-band tables, which follow the camera's depth
// alone, are kept. Returns false, changing nothing, when the depth differs: make the set-up again.
// (A camera orbiting at one depth, as the preview's, costs no discrete-ordinates solve per frame.)
bool moveUnderwaterCamera(UnderwaterSetup& setup, const Scene& scene);

// The unit direction towards the sun after refraction into the water at the flat surface (004 eq. 40–44);
// (0, 1, 0) when the sun is off or below the horizon. UnderwaterSetup::sun_water.
Vec3 sunInWater(const Scene& scene);

}  // namespace seasim
