#include "reference/sea_reference.h"

#include <tbb/parallel_for.h>

#include <cmath>

#include "math/kernel_math.h"
#include "spectral/jerlov.h"
#include "spectral/sensor.h"
#include "spectral/wavelength_grid.h"
#include "util/error.h"

namespace seasim {

namespace k = kmath_d;

Image renderSeaReference(const Scene& scene, int steps) {
  if (!scene.water.present || scene.camera.position.y <= 0) {
    throw RuntimeError("the sea reference renders scenes seen from above the water only");
  }
  if (scene.surface.type != SurfaceDesc::Type::Flat || scene.bottom.type == BottomDesc::Type::HeightField ||
      scene.sky.model != SkyDesc::Model::Uniform) {
    throw RuntimeError("the sea reference models a flat surface, flat or no bottom and a uniform sky only");
  }
  if (steps < 1) throw RuntimeError("--steps must be at least 1");
  const WavelengthGrid grid = makeGrid(scene.spectral.count, scene.spectral.min_nm, scene.spectral.max_nm);
  const Sensor sensor = makeSensor(scene.spectral.sensor, grid, scene.spectral.white_balance);
  const BandOptics water = resolveWater(scene.water, grid);
  const std::vector<double> sun_e = sunIrradianceBands(grid, scene.sun.irradiance);
  const std::vector<double> sky_l = sunIrradianceBands(grid, scene.sky.radiance);  // uniform sky: D65 shape
  const size_t bands = grid.centers_nm.size();

  const CameraDesc& cam = scene.camera;
  const Vec3 fwd = normalize(cam.look_at - cam.position);
  const Vec3 right = normalize(cross(fwd, cam.up));
  const Vec3 up = cross(right, fwd);
  const double tan_half = std::tan(cam.fov_y / 2), aspect = double(cam.width) / cam.height;
  const k::real3 sun{std::sin(scene.sun.zenith) * std::cos(scene.sun.azimuth), std::cos(scene.sun.zenith),
                     std::sin(scene.sun.zenith) * std::sin(scene.sun.azimuth)};
  const bool has_sun = scene.sun.enabled && scene.sun.irradiance > 0;
  const double cos_sun_radius = std::cos(scene.sun.angular_radius);
  const double sun_solid_angle = 2 * M_PI * (1 - cos_sun_radius);
  const double ior = scene.water.ior, g = scene.water.g;
  const bool bottom = scene.bottom.type == BottomDesc::Type::Flat;

  auto sky = [&](size_t i, k::real3 d) {
    double L = sky_l[i];
    if (has_sun && k::dot(d, sun) >= cos_sun_radius) L += sun_e[i] / sun_solid_angle;
    return L;
  };

  Image img;
  img.width = cam.width;
  img.height = cam.height;
  img.channels = 3;
  img.channel_names = {"R", "G", "B"};
  img.pixels.assign(static_cast<size_t>(cam.width) * cam.height * 3, 0.0f);
  tbb::parallel_for(0, cam.height, [&](int y) {
    for (int x = 0; x < cam.width; ++x) {
      const double u = (2.0 * (x + 0.5) / cam.width - 1.0) * tan_half * aspect;
      const double v = (1.0 - 2.0 * (y + 0.5) / cam.height) * tan_half;
      const Vec3 dv = normalize(fwd + right * u + up * v);
      const k::real3 d{dv.x, dv.y, dv.z};
      double rgb[3] = {0, 0, 0};
      auto add = [&](size_t i, double L) {
        rgb[0] += L * sensor.to_r[i];
        rgb[1] += L * sensor.to_g[i];
        rgb[2] += L * sensor.to_b[i];
      };
      if (d.y >= 0) {
        for (size_t i = 0; i < bands; ++i) add(i, sky(i, d));
      } else {
        const k::real3 n{0, 1, 0};
        const double R_view = k::fresnel_reflectance(-d.y, 1.0, ior);
        k::real3 view_in_water{};
        k::refract_dir(d, n, 1.0 / ior, &view_in_water);
        const double cos_ji = std::max(-view_in_water.y, 1e-4);
        double t_in = 0, cos_io = 1, cos_alpha = 1, e_h = 0;
        if (has_sun && sun.y > 0) {
          t_in = 1 - k::fresnel_reflectance(sun.y, 1.0, ior);
          e_h = sun.y;
          k::real3 sun_in_water{};
          k::refract_dir(-sun, n, 1.0 / ior, &sun_in_water);
          cos_io = std::max(-sun_in_water.y, 1e-4);
          cos_alpha = k::dot(sun_in_water, -view_in_water);
        }
        const k::real3 reflected = k::reflect_dir(d, n);
        const double phase = k::hg_phase(cos_alpha, g);
        const double c_f = k::hg_forward_fraction(g);
        for (size_t i = 0; i < bands; ++i) {
          double L = scene.sea.reflection ? R_view * sky(i, reflected) : 0.0;
          const double c = water.c[i], albedo = c > 0 ? water.b[i] / c : 0.0;
          const double kk = c * (1 - albedo * c_f);  // 000 eq. 5's effective attenuation
          if (scene.sea.single_scattering && e_h > 0) {
            // Beam irradiance in the water E T_i / cos_io, scattered by beta into the view ray,
            // attenuated down and back up; midpoint rule over depth.
            const double sec_sum = 1 / cos_io + 1 / cos_ji;
            // Below 40 optical depths (down and back) the integrand is < e^-40 of its surface value.
            const double z_optical = 40.0 / std::max(kk * sec_sum, 1e-12);
            const double z_end = bottom ? std::min(scene.bottom.depth, z_optical) : z_optical;
            const double dz = z_end / steps;
            double sum = 0;
            for (int s = 0; s < steps; ++s) sum += std::exp(-kk * (s + 0.5) * dz * sec_sum);
            const double beam = sun_e[i] * e_h * t_in / cos_io;
            L += beam * water.b[i] * phase * (1 - R_view) * sum * dz / cos_ji;
          }
          if (bottom && e_h > 0) {
            L += k::sea_bottom_reflection(sun_e[i] * e_h, t_in, 1 - R_view, scene.bottom.albedo.at(grid.centers_nm[i]),
                                          c, scene.bottom.depth, cos_io, cos_ji);
          }
          add(i, L);
        }
      }
      float* px = &img.pixels[(static_cast<size_t>(y) * cam.width + x) * 3];
      for (int ch = 0; ch < 3; ++ch) px[ch] = static_cast<float>(rgb[ch]);
    }
  });
  return img;
}

}  // namespace seasim
