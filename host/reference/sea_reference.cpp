#include "reference/sea_reference.h"

#include <tbb/parallel_for.h>

#include <cmath>
#include <vector>

#include "math/kernel_math.h"
#include "ocean/ocean_cpu.h"
#include "passes/sea_heightfield.h"
#include "passes/sea_sky.h"
#include "reference/sea_floor_reference.h"
#include "spectral/jerlov.h"
#include "spectral/sensor.h"
#include "spectral/wavelength_grid.h"
#include "underwater/underwater_setup.h"
#include "util/error.h"

namespace seasim {

namespace k = kmath_d;

namespace {

// The wave filter's moment maps (common/sea_lean.h) from a normal map (4 doubles per texel), as
// kernels/sea_single.cl builds them: the point map (folded facets turned up), level 0's cell moments of
// the bilinear slope field, then 2 x 2 box averages.
std::vector<double> slopeMomentMips(const std::vector<double>& normals, int n) {
  std::vector<double> mips(k::sea_lean_level_offset(n, k::sea_lean_levels(n)));
  for (int t = 0; t < n * n; ++t) {
    k::real3 nn{normals[4 * t], normals[4 * t + 1], normals[4 * t + 2]};
    if (nn.y < 0) nn = -nn;
    double sx, sz;
    k::sea_lean_slope(nn, &sx, &sz);
    double* m = &mips[SEA_LEAN_STRIDE * t];
    m[0] = sx, m[1] = sz, m[2] = sx * sx, m[3] = sz * sz, m[4] = sx * sz;
  }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      auto p = [&](int ii, int jj) { return &mips[SEA_LEAN_STRIDE * ((jj % n) * n + (ii % n))]; };
      const double *a = p(i, j), *b = p(i + 1, j), *c = p(i, j + 1), *e = p(i + 1, j + 1);
      k::sea_lean_cell_moments(a[0], a[1], b[0], b[1], c[0], c[1], e[0], e[1],
                               &mips[k::sea_lean_level_offset(n, 0) + SEA_LEAN_STRIDE * (j * n + i)]);
    }
  for (int l = 0; (n >> l) > 1; ++l) {
    const int src = n >> l, dst = src / 2;
    const double* s = &mips[k::sea_lean_level_offset(n, l)];
    double* d = &mips[k::sea_lean_level_offset(n, l + 1)];
    for (int j = 0; j < dst; ++j)
      for (int i = 0; i < dst; ++i)
        for (int q = 0; q < SEA_LEAN_STRIDE; ++q) {
          auto at = [&](int ii, int jj) { return s[SEA_LEAN_STRIDE * (jj * src + ii) + q]; };
          d[SEA_LEAN_STRIDE * (j * dst + i) + q] =
              0.25 * ((at(2 * i, 2 * j) + at(2 * i + 1, 2 * j)) + (at(2 * i, 2 * j + 1) + at(2 * i + 1, 2 * j + 1)));
        }
  }
  return mips;
}

double qualityValue(const Scene& scene, const char* name, double fallback) {
  const auto it = scene.quality.find(name);
  return it == scene.quality.end() ? fallback : it->second.value;
}

}  // namespace

Image renderSeaReference(const Scene& scene, int steps) {
  if (!scene.water.present || scene.camera.position.y <= 0) {
    throw RuntimeError("the sea reference renders scenes seen from above the water only");
  }
  if (steps < 1) throw RuntimeError("--steps must be at least 1");
  if (scene.sea.bottom_caustics && scene.surface.type == SurfaceDesc::Type::Fft) {
    throw RuntimeError("the sea reference does not model the ocean's caustics on the bottom: render the reference "
                       "with --set sea.bottom_caustics=false (tests/kernels/sea_bottom_caustics_test.cpp checks the "
                       "caustic term on its own)");
  }
  const WavelengthGrid grid = makeGrid(scene.spectral.count, scene.spectral.min_nm, scene.spectral.max_nm);
  const Sensor sensor = makeSensor(scene.spectral.sensor, grid, scene.spectral.white_balance, scene.spectral.camera_dir);
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
  // 000 §5.4: a height-field floor, met by a fine march (sea_floor_reference.h) independent of the
  // kernels' cell walk, in steps of 1/64 of a cell.
  const bool height_field = scene.bottom.type == BottomDesc::Type::HeightField;
  HeightField floor;
  double floor_step = 0;
  if (height_field) {
    floor = loadHeightField(scene.bottom, scene.files.get());
    floor_step = floor.params.extent / std::max(floor.params.nx, floor.params.ny) / 64.0;
  }

  // FFT waves: the same ocean evaluated on the CPU in double (ocean_cpu.h), its normal map read as the
  // kernel reads OceanPass's (common/sea_waves.h: mean-surface hit, bilinear, wrap-around).
  const bool waves = scene.surface.type == SurfaceDesc::Type::Fft;
  std::vector<double> normals;
  OceanConfig ocean_config;
  if (waves) {
    ocean_config = oceanConfigFromSurface(scene.surface);
    OceanCpu ocean(ocean_config, OceanCpu::Precision::Double);
    ocean.run(scene.surface.time);
    normals = ocean.normal();
  }
  // The wave filter (common/sea_lean.h) as the kernel runs it, or its reference: n x n rays per pixel.
  const int supersample = static_cast<int>(qualityValue(scene, "sea_supersample", 1));
  const bool filter = waves && qualityValue(scene, "wave_filter", 1) != 0 && supersample == 1;
  const std::vector<double> mips = filter ? slopeMomentMips(normals, ocean_config.grid) : std::vector<double>{};
  const double pixel_angle = 2 * tan_half / cam.height;
  const double sun_slope_variance = scene.sun.angular_radius * scene.sun.angular_radius / 16;
  const double sun_dir[3] = {sun.x, sun.y, sun.z};
  const SeaSky sea_sky = makeSeaSky(scene.sky, sun_dir, grid, scene.files.get());
  const bool multiple = scene.sea.model == SeaDesc::Model::Multiple;
  const double sky_fresnel = skyFresnelMean(ior), mu_sky = k::sea_sky_mean_cosine(ior);
  const double r_below = k::sea_surface_reflectance_below(sky_fresnel, ior);
  const double mu_ret = k::sea_reflected_mean_cosine(r_below, ior);

  // The sky's shape towards d (common/sky.h), then one band's radiance with the sun's disk.
  auto shape = [&](k::real3 d) -> k::real3 {
    if (sea_sky.model == 1) {
      const double s = sea_sky.scale * k::sky_cie_clear_shape(d, sun);
      return {s, s, s};
    }
    if (sea_sky.model == 2) return k::sky_latlong_rgb(sea_sky.texels.data(), sea_sky.width, sea_sky.height, d) * sea_sky.scale;
    if (sea_sky.model == 3) return k::sky_preetham_daylight(sea_sky.texels.data(), d, sun) * sea_sky.scale;
    return {1, 1, 1};
  };
  auto sky_only = [&](size_t i, k::real3 s) {
    const auto& w = sea_sky.band_weights[i];
    return sea_sky.model >= 2 ? sky_l[i] * std::max(w[0] * s.x + w[1] * s.y + w[2] * s.z, 0.0) : sky_l[i] * s.x;
  };
  auto sky = [&](size_t i, k::real3 s, k::real3 d) {
    double L = sky_only(i, s);
    if (has_sun && sun_solid_angle > 0 && k::dot(d, sun) >= cos_sun_radius) L += sun_e[i] / sun_solid_angle;
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
      double rgb[3] = {0, 0, 0};
      const double sub_weight = 1.0 / (supersample * supersample);
      for (int sub = 0; sub < supersample * supersample; ++sub) {
      const double ox = (sub % supersample + 0.5) / supersample, oy = (sub / supersample + 0.5) / supersample;
      const double u = (2.0 * (x + ox) / cam.width - 1.0) * tan_half * aspect;
      const double v = (1.0 - 2.0 * (y + oy) / cam.height) * tan_half;
      const Vec3 dv = normalize(fwd + right * u + up * v);
      const k::real3 d{dv.x, dv.y, dv.z};
      auto add = [&](size_t i, double L) {
        rgb[0] += sub_weight * L * sensor.to_r[i];
        rgb[1] += sub_weight * L * sensor.to_g[i];
        rgb[2] += sub_weight * L * sensor.to_b[i];
      };
      if (d.y >= 0) {
        const k::real3 s = shape(d);
        for (size_t i = 0; i < bands; ++i) add(i, sky(i, s, d));
      } else {
        k::real3 n{0, 1, 0};
        // The filter: the footprint's statistics, the facets' Fresnel-weighted sky (3 x 3 nodes) and
        // the glint, as kernels/sea_single.cl with SEASIM_WAVE_FILTER.
        double R_mean = 0, glint = 0;
        std::vector<k::real3> node_dirs;
        std::vector<double> node_weights;
        if (filter) {
          const double t_hit = k::sea_mean_surface_distance(cam.position.y, d);
          const k::real3 fw{fwd.x, fwd.y, fwd.z};
          const double minor = t_hit * pixel_angle * std::max(k::dot(d, fw), 0.1);
          const double major = minor / std::max(-d.y, 1e-6);
          const double horizontal = std::sqrt(d.x * d.x + d.z * d.z);
          const double dir_x = horizontal > 1e-6 ? d.x / horizontal : 1.0, dir_z = horizontal > 1e-6 ? d.z / horizontal : 0.0;
          double st[SEA_LEAN_STRIDE];
          k::sea_lean_footprint(mips.data(), ocean_config.grid, ocean_config.patch_size, cam.position.x + t_hit * d.x,
                                cam.position.z + t_hit * d.z, dir_x, dir_z, minor, major, st);
          double cxx, czz, cxz, l11, l21, l22;
          k::sea_lean_covariance(st[2], st[3], st[4], sun_slope_variance, &cxx, &czz, &cxz, &l11, &l21, &l22);
          n = k::sea_facing_normal(d, k::sea_lean_normal(st[0], st[1]));
          const k::SeaLeanRule rule = k::sea_lean_rule(d, st[0], st[1], l11, l21, l22);
          R_mean = rule.back;  // facets turned away: F = 1 towards the horizon's sky
          node_weights.push_back(rule.back);
          node_dirs.push_back(k::sea_sky_direction(d));
          for (int q = 0; q < k::sea_lean_rule_nodes(&rule); ++q) {
            double sx, sz;
            const double w = k::sea_lean_rule_node(&rule, q, &sx, &sz);
            const k::real3 nk = k::sea_facing_normal(d, k::sea_lean_normal(sx, sz));
            const double wf = w * k::fresnel_reflectance(-k::dot(d, nk), 1.0, ior);
            R_mean += wf;
            node_weights.push_back(wf);
            node_dirs.push_back(k::sea_sky_direction(k::reflect_dir(d, nk)));
          }
          if (has_sun && sun.y > 0 && sun_solid_angle > 0) glint = k::sea_lean_glint(d, sun, ior, st[0], st[1], cxx, czz, cxz);
        } else if (waves) {
          const double t_hit = k::sea_mean_surface_distance(cam.position.y, d);
          n = k::sea_facing_normal(d, k::sea_wave_normal(normals.data(), ocean_config.grid, ocean_config.patch_size,
                                                         cam.position.x + t_hit * d.x, cam.position.z + t_hit * d.z));
        }
        double R_view = 0;
        k::real3 reflected{}, view_in_water{};
        const double cos_ji = k::sea_view_interaction(d, n, ior, &R_view, &reflected, &view_in_water);
        if (filter) R_view = R_mean;
        const k::real3 reflected_shape = shape(reflected);
        const k::real3 flat_n{0, 1, 0};  // sunlight enters through the flat mean surface (000 §3)
        double t_in = 0, cos_io = 1, cos_alpha = 1, e_h = 0;
        if (has_sun && sun.y > 0) {
          t_in = 1 - k::fresnel_reflectance(sun.y, 1.0, ior);
          e_h = sun.y;
          k::real3 sun_in_water{};
          k::refract_dir(-sun, flat_n, 1.0 / ior, &sun_in_water);
          cos_io = std::max(-sun_in_water.y, 1e-4);
          cos_alpha = k::dot(sun_in_water, -view_in_water);
        }
        const double phase = k::hg_phase(cos_alpha, g);
        const double c_f = k::hg_forward_fraction(g);
        // Water-leaving radiance reaches the air as L_w (1 - R) / n²: radiance / n² is conserved across
        // the surface (docs/radiometry.md).
        const double t_out = (1 - R_view) / (ior * ior);
        // The floor along the refracted view ray: z_Q and cos(gamma) (000 §5.4); flat: z_d, cos_io.
        double z_floor = bottom ? scene.bottom.depth : -1.0, cos_gamma = cos_io;
        if (height_field) {
          const double t_p = cam.position.y / -d.y;  // P on the mean surface
          const double o[3] = {cam.position.x + t_p * d.x, 0.0, cam.position.z + t_p * d.z};
          const double v[3] = {view_in_water.x, view_in_water.y, view_in_water.z};
          const double t_q = view_in_water.y < 0 ? fineMarchFloor(floor, o, v, 1e30, floor_step) : 0.0;
          z_floor = std::max(-view_in_water.y, 0.0) * std::max(t_q, 0.0);
          double nq[3];
          floorNormalAt(floor, o[0] + t_q * v[0], o[2] + t_q * v[2], nq);
          cos_gamma = 0;
          if (e_h > 0) {
            k::real3 sun_travel{};
            k::refract_dir(-sun, flat_n, 1.0 / ior, &sun_travel);
            cos_gamma = std::max(-(nq[0] * sun_travel.x + nq[1] * sun_travel.y + nq[2] * sun_travel.z), 0.0);
          }
        }
        for (size_t i = 0; i < bands; ++i) {
          double L = 0;
          if (scene.sea.reflection && filter) {
            for (size_t q = 0; q < node_dirs.size(); ++q) L += node_weights[q] * sky_only(i, shape(node_dirs[q]));
            L += glint * sun_e[i];
          } else if (scene.sea.reflection) {
            L += R_view * sky(i, reflected_shape, reflected);
          }
          const double c = water.c[i], albedo = c > 0 ? water.b[i] / c : 0.0;
          const double kk = c * (1 - albedo * c_f);  // 000 eq. 5's effective attenuation
          if (multiple) {
            // sea.model = "multiple": the closed form in double (common/sea_multiple.h), the kernel's
            // float evaluation is tested against it (tests/kernels/sea_multiple_kernel_test.cpp).
            const double e_sky = M_PI * sky_only(i, k::real3{1, 1, 1}) * (1 - sky_fresnel);
            const double e_sun = sun_e[i] * e_h;
            if (scene.sea.single_scattering) {
              L += t_out * k::sea_multiple_column(e_sun, t_in, e_sky, water.a[i], water.b[i], c_f, z_floor, cos_io,
                                                  cos_ji, phase, mu_sky);
            }
            if (z_floor >= 0) {
              L += t_out * k::sea_multiple_bottom(e_sun, t_in, e_sky, water.a[i], water.b[i], c_f,
                                                  scene.bottom.albedo.at(grid.centers_nm[i]), z_floor, cos_io, cos_ji,
                                                  mu_sky, 1.0);
            }
            if (scene.sea.single_scattering || z_floor >= 0) {
              const double albedo = z_floor >= 0 ? scene.bottom.albedo.at(grid.centers_nm[i]) : 0.0;
              L += t_out * k::sea_multiple_surface_return(e_sun, t_in, e_sky, water.a[i], water.b[i], c_f, albedo,
                                                          z_floor, cos_io, cos_ji, mu_sky, 1.0, r_below, mu_ret,
                                                          scene.sea.single_scattering ? 1 : 0);
            }
          } else if (scene.sea.single_scattering && e_h > 0) {
            // Beam irradiance in the water E T_i / cos_io, scattered by beta into the view ray,
            // attenuated down and back up; midpoint rule over depth.
            const double sec_sum = 1 / cos_io + 1 / cos_ji;
            // Below 40 optical depths (down and back) the integrand is < e^-40 of its surface value.
            const double z_optical = 40.0 / std::max(kk * sec_sum, 1e-12);
            const double z_end = z_floor >= 0 ? std::min(z_floor, z_optical) : z_optical;
            const double dz = z_end / steps;
            double sum = 0;
            for (int s = 0; s < steps; ++s) sum += std::exp(-kk * (s + 0.5) * dz * sec_sum);
            const double beam = sun_e[i] * e_h * t_in / cos_io;
            L += beam * water.b[i] * phase * t_out * sum * dz / cos_ji;
          }
          if (!multiple && z_floor >= 0 && e_h > 0) {  // cos_gamma = cos_io on a flat floor: eq. 9 as it stands
            L += k::sea_bottom_reflection_tilted(sun_e[i] * e_h, t_in, t_out,
                                                 scene.bottom.albedo.at(grid.centers_nm[i]), c, z_floor, cos_io,
                                                 cos_ji, cos_gamma);
          }
          add(i, L);
        }
      }
      }  // sub-pixel rays
      float* px = &img.pixels[(static_cast<size_t>(y) * cam.width + x) * 3];
      for (int ch = 0; ch < 3; ++ch) px[ch] = static_cast<float>(rgb[ch]);
    }
  });
  return img;
}

std::vector<double> seaUpwellingBelow(const Scene& scene, Vec3 view_in_water, double z0, int steps) {
  if (!scene.water.present) throw RuntimeError("seaUpwellingBelow: the scene has no [water]");
  if (scene.bottom.type == BottomDesc::Type::HeightField) throw RuntimeError("seaUpwellingBelow: flat bottoms only");
  if (!(view_in_water.y < 0) || steps < 1 || z0 < 0) throw RuntimeError("seaUpwellingBelow: needs a downward view");
  const WavelengthGrid grid = makeGrid(scene.spectral.count, scene.spectral.min_nm, scene.spectral.max_nm);
  const BandOptics water = resolveWater(scene.water, grid);
  const std::vector<double> sun_e = sunIrradianceBands(grid, scene.sun.irradiance);
  const Vec3 vn = normalize(view_in_water);
  const k::real3 view{vn.x, vn.y, vn.z};
  const double cos_ji = -view.y, ior = scene.water.ior, g = scene.water.g;
  const k::real3 sun{std::sin(scene.sun.zenith) * std::cos(scene.sun.azimuth), std::cos(scene.sun.zenith),
                     std::sin(scene.sun.zenith) * std::sin(scene.sun.azimuth)};
  std::vector<double> L(grid.centers_nm.size(), 0.0);
  if (!(scene.sun.enabled && scene.sun.irradiance > 0 && sun.y > 0)) return L;
  const double t_in = 1 - k::fresnel_reflectance(sun.y, 1.0, ior);
  k::real3 sun_in_water{};
  k::refract_dir(-sun, k::real3{0, 1, 0}, 1.0 / ior, &sun_in_water);
  const double cos_io = std::max(-sun_in_water.y, 1e-4);
  const double phase = k::hg_phase(k::dot(sun_in_water, -view), g), c_f = k::hg_forward_fraction(g);
  const bool bottom = scene.bottom.type == BottomDesc::Type::Flat;
  const double z_floor = scene.bottom.depth;
  for (size_t i = 0; i < L.size(); ++i) {
    const double c = water.c[i], albedo = c > 0 ? water.b[i] / c : 0.0;
    const double kk = c * (1 - albedo * c_f);  // 000 eq. 5's effective attenuation, on both legs
    const double e_beam = sun_e[i] * sun.y * t_in / cos_io;  // beam irradiance just below the surface
    if (scene.sea.single_scattering) {
      // ∫_{z0}^{z_end} β E_beam e^{-kk z / cos_io} e^{-kk (z - z0) / cos_ji} dz / cos_ji, midpoint rule.
      const double z_optical = z0 + 40.0 / std::max(kk * (1 / cos_io + 1 / cos_ji), 1e-12);
      const double z_end = bottom ? std::min(z_floor, z_optical) : z_optical;
      const double dz = (z_end - z0) / steps;
      double sum = 0;
      for (int s = 0; s < steps; ++s) {
        const double z = z0 + (s + 0.5) * dz;
        sum += std::exp(-kk * (z / cos_io + (z - z0) / cos_ji));
      }
      L[i] += e_beam * water.b[i] * phase * sum * dz / cos_ji;
    }
    if (bottom && z0 < z_floor) {  // 000 eq. 9 without T_o: Lambertian floor under the attenuated beam
      L[i] += e_beam * cos_io * std::exp(-c * z_floor / cos_io) * scene.bottom.albedo.at(grid.centers_nm[i]) / M_PI *
              std::exp(-c * (z_floor - z0) / cos_ji);
    }
  }
  return L;
}

}  // namespace seasim
