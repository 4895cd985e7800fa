#include "underwater/underwater_setup.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "geometry/kernel_camera.h"
#include "math/kernel_math.h"
#include "spectral/jerlov.h"
#include "underwater/underwater_ordinates_solver.h"
#include "underwater/underwater_ordinates_setup.h"
#include "underwater/sky_window_modes.h"
#include "util/error.h"

namespace seasim {

static_assert(sizeof(UwParams) == 6 * 16 + 12 * 4 + 8 * 4, "UwParams layout changed: update underwater_params.h users");
static_assert(offsetof(UwParams, tan_half_fov_y) == 96);
static_assert(offsetof(UwParams, width) == 144);
static_assert(sizeof(UwBand) == 64, "UwBand must stay 64 bytes");
static_assert(sizeof(UwObject) == 48 && offsetof(UwObject, a) == 16, "UwObject must stay 48 bytes");

namespace {

namespace kd = kmath_d;

}  // namespace

namespace {

// The sun in air (azimuth from +x towards +z), unit, towards the sun.
Vec3 sunInAir(const Scene& scene) {
  return {std::sin(scene.sun.zenith) * std::cos(scene.sun.azimuth), std::cos(scene.sun.zenith),
          std::sin(scene.sun.zenith) * std::sin(scene.sun.azimuth)};
}

bool sunIsUp(const Scene& scene, const Vec3& sun) {
  return scene.sun.enabled && scene.sun.irradiance > 0 && sun.y > 1e-6;
}

}  // namespace

Vec3 sunInWater(const Scene& scene) {
  const Vec3 sun = sunInAir(scene);
  if (!sunIsUp(scene, sun)) return {0, 1, 0};
  kd::real3 in_water{};
  kd::refract_dir(kd::real3{-sun.x, -sun.y, -sun.z}, kd::real3{0, 1, 0}, 1.0 / scene.water.ior, &in_water);
  return normalize(Vec3{-in_water.x, -in_water.y, -in_water.z});
}

namespace {

// Every field of the set-up that follows the camera (moveUnderwaterCamera relies on this list being
// whole): its frame, field of view, image size, and where no bottom bounds the caustic layers, their
// depth from the camera's. The camera's depth also enters the discrete-ordinates tables (s.ordinates,
// diffuseViewDepth), which makeUnderwaterSetup builds below.
void setUnderwaterCamera(UwParams& p, const CameraDesc& cam) {
  setKernelCamera(p, cam);
  p.tan_half_fov_y = static_cast<float>(std::tan(cam.fov_y / 2));
  p.aspect = static_cast<float>(cam.width) / static_cast<float>(cam.height);
  p.width = cam.width;
  p.height = cam.height;
  p.caustic_depth_max = p.bottom_depth > 0 ? p.bottom_depth
                                           : static_cast<float>(std::max(20.0, -2.0 * cam.position.y));
}

}  // namespace

bool moveUnderwaterCamera(UnderwaterSetup& setup, const Scene& scene) {
  UwParams& p = setup.params;
  if (static_cast<float>(scene.camera.position.y) != p.cam_pos[1]) return false;  // the tables follow the depth
  setUnderwaterCamera(p, scene.camera);
  return true;
}

UnderwaterSetup makeUnderwaterSetup(const Scene& scene, const WavelengthGrid& grid, const Sensor& sensor) {
  UnderwaterSetup s;
  UwParams& p = s.params;
  const CameraDesc& cam = scene.camera;

  const Vec3 sun = sunInAir(scene);
  const bool sun_up = sunIsUp(scene, sun);
  s.sun_air = sun;
  s.sun_water = sunInWater(scene);
  const double t_sun = sun_up ? 1.0 - kd::fresnel_reflectance(sun.y, 1.0, scene.water.ior) : 0.0;
  set4(p.sun_dir_air, s.sun_air);
  set4(p.sun_dir_water, s.sun_water);
  p.ior = static_cast<float>(scene.water.ior);
  p.g = static_cast<float>(scene.water.g);
  p.bottom_depth = scene.bottom.type == BottomDesc::Type::Flat ? static_cast<float>(scene.bottom.depth) : 0.0f;
  setUnderwaterCamera(p, cam);
  p.time = static_cast<float>(scene.surface.time);
  const UnderwaterDesc& uw = scene.underwater;
  p.caustic_period = static_cast<float>(uw.caustic_period);
  p.caustic_speed = static_cast<float>(uw.caustic_speed);
  p.caustic_extent = static_cast<float>(scene.surface.patch_size);
  p.band_count = static_cast<int>(grid.size());
  p.caustic_mode = uw.caustics == UnderwaterDesc::Caustics::None      ? UW_CAUSTICS_NONE
                   : uw.caustics == UnderwaterDesc::Caustics::Texture ? UW_CAUSTICS_TEXTURE
                                                                      : UW_CAUSTICS_MAP;
  const auto map_size = scene.quality.find("caustic_map_size");
  p.caustic_map_size = map_size != scene.quality.end() ? static_cast<int>(map_size->second.value) : 256;
  const auto layers = scene.quality.find("caustic_layers");
  p.caustic_layers = layers != scene.quality.end() ? static_cast<int>(layers->second.value) : 8;
  s.single_scattering = uw.single_scattering && sun_up;

  // Per band: IOPs, the light just below the surface, sensor weights.
  const BandOptics water = resolveWater(scene.water, grid, sun_up ? s.sun_water.y : 0.85);
  const std::vector<double> sun_e = sunIrradianceBands(grid, sun_up ? scene.sun.irradiance : 0.0);
  // The sky (host/sky): its level per band for Snell's window (times its shape in the kernel), and
  // the irradiance it sends through the flat surface for E_D0.
  const SkyLight sky = makeSkyLight(scene, grid);
  const std::vector<double>& sky_l = sky.level;
  const std::vector<double> e_sky0 = sky.transmittedIrradiance(scene.water.ior);
  s.sky_fresnel = skyFresnelMean(scene.water.ior);
  s.sky_params = sky.params;
  s.sky_buffer = sky.kernelBuffer();
  s.bands.resize(grid.size());
  for (size_t i = 0; i < grid.size(); ++i) {
    UwBand& b = s.bands[i];
    b.a = static_cast<float>(water.a[i]);
    b.b = static_cast<float>(water.b[i]);
    b.c = static_cast<float>(water.c[i]);
    b.kd = static_cast<float>(water.kd[i]);
    b.e_sky0 = static_cast<float>(e_sky0[i]);
    const double e_sun0 = sun_e[i] * std::max(sun.y, 0.0) * t_sun;
    b.e_sun0 = static_cast<float>(e_sun0);
    b.e_beam0 = sun_up ? static_cast<float>(e_sun0 / s.sun_water.y) : 0.0f;
    b.sky_radiance = static_cast<float>(sky_l[i]);
    b.sky_w_r = static_cast<float>(sky.shape.band_weights[i][0]);
    b.sky_w_g = static_cast<float>(sky.shape.band_weights[i][1]);
    b.sky_w_b = static_cast<float>(sky.shape.band_weights[i][2]);
    b.bottom_albedo = static_cast<float>(scene.bottom.albedo.at(grid.centers_nm[i]));
    b.w_r = static_cast<float>(sensor.to_r[i]);
    b.w_g = static_cast<float>(sensor.to_g[i]);
    b.w_b = static_cast<float>(sensor.to_b[i]);
  }

  for (const ObjectDesc& o : scene.objects) {
    UwObject u{};
    switch (o.type) {
      case ObjectDesc::Type::Sphere:
        u.type = UW_SPHERE;
        set4(u.a, o.center, o.radius);
        break;
      case ObjectDesc::Type::Box:
        u.type = UW_BOX;
        set4(u.a, o.box_min);
        set4(u.b, o.box_max);
        break;
      case ObjectDesc::Type::Plane:
        u.type = UW_PLANE;
        set4(u.a, o.point);
        set4(u.b, normalize(o.normal));
        break;
      case ObjectDesc::Type::HeightField:
        throw RuntimeError(o.loc.file + ":" + std::to_string(o.loc.line) +
                           ": height-field objects are not supported under water yet (use spheres, boxes "
                           "and planes, or a flat [bottom])");
    }
    s.objects.push_back(u);
    for (size_t i = 0; i < grid.size(); ++i) s.albedo.push_back(static_cast<float>(o.albedo.at(grid.centers_nm[i])));
  }
  if (uw.model == UnderwaterDesc::Model::DiscreteOrdinates) {
    // A sky that is not uniform keeps its shape at the solver's surface (sky_window_modes.h).
    const SkyWindowModes window_sky =
        sky.shape.model == SEASIM_SKY_UNIFORM ? SkyWindowModes{} : makeSkyWindowModes(sky, scene.water.ior);
    DiffuseMeanCosines mean = diffuseMeanCosines(p.g);
    if (uw.mean_cosine_down > 0) mean.down = uw.mean_cosine_down;
    if (uw.mean_cosine_up > 0) mean.up = uw.mean_cosine_up;
    if (uw.beam_mean_cosine_down > 0) mean.beam_down = uw.beam_mean_cosine_down;
    if (uw.beam_mean_cosine_up > 0) mean.beam_up = uw.beam_mean_cosine_up;
    const TwoStreamClosure closure = uw.two_stream_closure == UnderwaterDesc::TwoStream::Quadrature
                                         ? TwoStreamClosure::Quadrature
                                     : uw.two_stream_closure == UnderwaterDesc::TwoStream::Asymptotic
                                         ? TwoStreamClosure::Asymptotic
                                         : twoStreamClosure();
    // The camera's depth enters k here (diffuseViewDepth): set per frame, with the camera.
    s.ordinates = uw.diffuse == UnderwaterDesc::Diffuse::TwoStream
                     ? makeUwiBands(p, s.bands, mean, closure, uw.asymptotic_share, uw.flux_scale)
                     : makeUwiBandsFromOrdinates(p, s.bands, uw.source_streams,
                                                 sky.shape.model == SEASIM_SKY_UNIFORM ? nullptr : &window_sky);
  }
  p.object_count = static_cast<int>(s.objects.size());
  if (s.objects.empty()) s.objects.push_back(UwObject{});  // OpenCL buffers cannot be empty
  if (s.albedo.empty()) s.albedo.push_back(0.0f);
  return s;
}

}  // namespace seasim
