#include "reference/sea_reference.h"

#include <tbb/parallel_for.h>

#include <cmath>
#include <vector>

#include "math/kernel_math.h"
#include "ocean/ocean_cpu.h"
#include "passes/sea_heightfield.h"
#include "passes/sea_ordinates_table.h"
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

namespace {

// What every pixel of the reference shares: the scene's bands, camera, sun, floor, waves and sky.
struct SeaReferenceScene {
  const Scene* scene = nullptr;
  int steps = 0;
  WavelengthGrid grid;
  Sensor sensor;
  BandOptics water;
  std::vector<double> sun_e, sky_l;  // the sky's uniform level: D65 shape
  size_t bands = 0;
  Vec3 fwd, right, up;
  double tan_half = 0, aspect = 1;
  k::real3 sun{};
  bool has_sun = false;
  double cos_sun_radius = 1, sun_solid_angle = 0, ior = 1, g = 0;
  bool bottom = false, height_field = false;
  HeightField floor;
  double floor_step = 0;
  bool waves = false, filter = false, multiple = false;
  std::vector<double> normals, mips;
  OceanConfig ocean_config;
  int supersample = 1;
  double pixel_angle = 0, sun_slope_variance = 0;
  SeaSky sea_sky;
  double sky_fresnel = 0, mu_sky = 0, r_below = 0, mu_ret = 0;
  // sea.model "multiple": the light and bands of its closed form and κ (passes/sea_ordinates_table.h),
  // node-major.
  SeaOrdinatesLight ordinate_light;
  std::vector<SeaOrdinatesBand> ordinate_bands;
  std::vector<double> ordinates;

  // The sky's shape towards d (common/sky.h).
  k::real3 shape(k::real3 d) const {
    if (sea_sky.model == 1) {
      const double s = sea_sky.scale * k::sky_cie_clear_shape(d, sun);
      return {s, s, s};
    }
    if (sea_sky.model == 2) return k::sky_latlong_rgb(sea_sky.texels.data(), sea_sky.width, sea_sky.height, d) * sea_sky.scale;
    if (sea_sky.model == 3) return k::sky_preetham_daylight(sea_sky.texels.data(), d, sun) * sea_sky.scale;
    return {1, 1, 1};
  }
  // Band i's sky radiance for shape s, then with the sun's disk along d.
  double skyOnly(size_t i, k::real3 s) const {
    const auto& w = sea_sky.band_weights[i];
    return sea_sky.model >= 2 ? sky_l[i] * std::max(w[0] * s.x + w[1] * s.y + w[2] * s.z, 0.0) : sky_l[i] * s.x;
  }
  double sky(size_t i, k::real3 s, k::real3 d) const {
    double L = skyOnly(i, s);
    if (has_sun && sun_solid_angle > 0 && k::dot(d, sun) >= cos_sun_radius) L += sun_e[i] / sun_solid_angle;
    return L;
  }
};

SeaReferenceScene seaReferenceScene(const Scene& scene, int steps) {
  SeaReferenceScene r;
  r.scene = &scene;
  r.steps = steps;
  r.grid = makeGrid(scene.spectral.count, scene.spectral.min_nm, scene.spectral.max_nm);
  r.sensor = makeSensor(scene.spectral.sensor, r.grid, scene.spectral.white_balance, scene.spectral.camera_dir);
  r.water = resolveWater(scene.water, r.grid);
  r.sun_e = sunIrradianceBands(r.grid, scene.sun.irradiance);
  r.sky_l = sunIrradianceBands(r.grid, scene.sky.radiance);
  r.bands = r.grid.centers_nm.size();
  const CameraDesc& cam = scene.camera;
  r.fwd = normalize(cam.look_at - cam.position);
  r.right = normalize(cross(r.fwd, cam.up));
  r.up = cross(r.right, r.fwd);
  r.tan_half = std::tan(cam.fov_y / 2), r.aspect = double(cam.width) / cam.height;
  r.sun = k::real3{std::sin(scene.sun.zenith) * std::cos(scene.sun.azimuth), std::cos(scene.sun.zenith),
                   std::sin(scene.sun.zenith) * std::sin(scene.sun.azimuth)};
  r.has_sun = scene.sun.enabled && scene.sun.irradiance > 0;
  r.cos_sun_radius = std::cos(scene.sun.angular_radius);
  r.sun_solid_angle = 2 * M_PI * (1 - r.cos_sun_radius);
  r.ior = scene.water.ior, r.g = scene.water.g;
  r.bottom = scene.bottom.type == BottomDesc::Type::Flat;
  // 000 §5.4: a height-field floor, met by a fine march (sea_floor_reference.h) independent of the
  // kernels' cell walk, in steps of 1/64 of a cell.
  r.height_field = scene.bottom.type == BottomDesc::Type::HeightField;
  if (r.height_field) {
    r.floor = loadHeightField(scene.bottom, scene.files.get());
    r.floor_step = r.floor.params.extent / std::max(r.floor.params.nx, r.floor.params.ny) / 64.0;
  }
  // FFT waves: the same ocean evaluated on the CPU in double (ocean_cpu.h), its normal map read as the
  // kernel reads OceanPass's (common/sea_waves.h: mean-surface hit, bilinear, wrap-around).
  r.waves = scene.surface.type == SurfaceDesc::Type::Fft;
  if (r.waves) {
    r.ocean_config = oceanConfigFromSurface(scene.surface);
    OceanCpu ocean(r.ocean_config, OceanCpu::Precision::Double);
    ocean.run(scene.surface.time);
    r.normals = ocean.normal();
  }
  // The wave filter (common/sea_lean.h) as the kernel runs it, or its reference: n x n rays per pixel.
  r.supersample = static_cast<int>(qualityValue(scene, "sea_supersample", 1));
  r.filter = r.waves && qualityValue(scene, "wave_filter", 1) != 0 && r.supersample == 1;
  if (r.filter) r.mips = slopeMomentMips(r.normals, r.ocean_config.grid);
  r.pixel_angle = 2 * r.tan_half / cam.height;
  r.sun_slope_variance = scene.sun.angular_radius * scene.sun.angular_radius / 16;
  const double sun_dir[3] = {r.sun.x, r.sun.y, r.sun.z};
  r.sea_sky = makeSeaSky(scene.sky, sun_dir, r.grid, scene.files.get());
  r.multiple = scene.sea.model == SeaDesc::Model::Multiple;
  r.sky_fresnel = skyFresnelMean(r.ior), r.mu_sky = k::sea_sky_mean_cosine(r.ior);
  r.r_below = k::sea_surface_reflectance_below(r.sky_fresnel, r.ior);
  r.mu_ret = k::sea_reflected_mean_cosine(r.r_below, r.ior);
  if (r.multiple) {
    const Vec3 sun = r.has_sun ? Vec3{r.sun.x, r.sun.y, r.sun.z} : Vec3{0, -1, 0};
    r.ordinate_light = seaOrdinatesLight(scene, sun, r.sky_fresnel, scene.sea.single_scattering, true);
    for (size_t i = 0; i < r.bands; ++i)
      r.ordinate_bands.push_back({r.water.a[i], r.water.b[i], r.sun_e[i],
                                  M_PI * r.skyOnly(i, k::real3{1, 1, 1}) * (1 - r.sky_fresnel),
                                  scene.bottom.albedo.at(r.grid.centers_nm[i])});
    r.ordinates = seaOrdinatesTable(r.ordinate_light, r.ordinate_bands);
  }
  return r;
}

// One ray below the horizon: where it meets the surface, the sun's entry and the floor.
struct SeaReferenceRay {
  k::real3 n{0, 1, 0};
  double R_view = 0, cos_ji = 0, glint = 0;
  k::real3 reflected{}, view_in_water{}, reflected_shape{};
  std::vector<k::real3> node_dirs;  // the filter's facets: reflected directions and Fresnel weights
  std::vector<double> node_weights;
  double t_in = 0, cos_io = 1, cos_alpha = 1, e_h = 0, phase = 0, c_f = 0, t_out = 0;
  double z_floor = -1, cos_gamma = 1;
};

// The filter: the footprint's statistics, the facets' Fresnel-weighted sky (3 x 3 nodes) and the glint,
// as kernels/sea_single.cl with SEASIM_WAVE_FILTER; returns R_mean.
double filteredFacets(const SeaReferenceScene& r, k::real3 d, SeaReferenceRay& ray) {
  const CameraDesc& cam = r.scene->camera;
  const double t_hit = k::sea_mean_surface_distance(cam.position.y, d);
  const k::real3 fw{r.fwd.x, r.fwd.y, r.fwd.z};
  const double minor = t_hit * r.pixel_angle * std::max(k::dot(d, fw), 0.1);
  const double major = minor / std::max(-d.y, 1e-6);
  const double horizontal = std::sqrt(d.x * d.x + d.z * d.z);
  const double dir_x = horizontal > 1e-6 ? d.x / horizontal : 1.0, dir_z = horizontal > 1e-6 ? d.z / horizontal : 0.0;
  double st[SEA_LEAN_STRIDE];
  k::sea_lean_footprint(r.mips.data(), r.ocean_config.grid, r.ocean_config.patch_size, cam.position.x + t_hit * d.x,
                        cam.position.z + t_hit * d.z, dir_x, dir_z, minor, major, st);
  double cxx, czz, cxz, l11, l21, l22;
  k::sea_lean_covariance(st[2], st[3], st[4], r.sun_slope_variance, &cxx, &czz, &cxz, &l11, &l21, &l22);
  ray.n = k::sea_facing_normal(d, k::sea_lean_normal(st[0], st[1]));
  k::SeaLeanRule rule;
  k::sea_lean_rule(d, st[0], st[1], l11, l21, l22, &rule);
  double R_mean = rule.back;  // facets turned away: F = 1 towards the horizon's sky
  ray.node_weights.push_back(rule.back);
  ray.node_dirs.push_back(k::sea_sky_direction(d));
  for (int q = 0; q < k::sea_lean_rule_nodes(&rule); ++q) {
    double sx, sz;
    const double w = k::sea_lean_rule_node(&rule, q, &sx, &sz);
    const k::real3 nk = k::sea_facing_normal(d, k::sea_lean_normal(sx, sz));
    const double wf = w * k::fresnel_reflectance(-k::dot(d, nk), 1.0, r.ior);
    R_mean += wf;
    ray.node_weights.push_back(wf);
    ray.node_dirs.push_back(k::sea_sky_direction(k::reflect_dir(d, nk)));
  }
  if (r.has_sun && r.sun.y > 0 && r.sun_solid_angle > 0)
    ray.glint = k::sea_lean_pixel_glint(d, fw, r.pixel_angle * k::real3{r.right.x, r.right.y, r.right.z},
                                        -r.pixel_angle * k::real3{r.up.x, r.up.y, r.up.z}, r.sun, r.ior, st[0], st[1], cxx,
                                        czz, cxz);
  return R_mean;
}

// The floor along the refracted view ray: z_Q and cos(gamma) (000 §5.4); flat: z_d, cos_io.
void floorAlong(const SeaReferenceScene& r, k::real3 d, SeaReferenceRay& ray) {
  const CameraDesc& cam = r.scene->camera;
  ray.z_floor = r.bottom ? r.scene->bottom.depth : -1.0, ray.cos_gamma = ray.cos_io;
  if (!r.height_field) return;
  const double t_p = cam.position.y / -d.y;  // P on the mean surface
  const double o[3] = {cam.position.x + t_p * d.x, 0.0, cam.position.z + t_p * d.z};
  const double v[3] = {ray.view_in_water.x, ray.view_in_water.y, ray.view_in_water.z};
  const double t_q = ray.view_in_water.y < 0 ? fineMarchFloor(r.floor, o, v, 1e30, r.floor_step) : 0.0;
  ray.z_floor = std::max(-ray.view_in_water.y, 0.0) * std::max(t_q, 0.0);
  double nq[3];
  floorNormalAt(r.floor, o[0] + t_q * v[0], o[2] + t_q * v[2], nq);
  ray.cos_gamma = 0;
  if (ray.e_h > 0) {
    k::real3 sun_travel{};
    k::refract_dir(-r.sun, k::real3{0, 1, 0}, 1.0 / r.ior, &sun_travel);
    ray.cos_gamma = std::max(-(nq[0] * sun_travel.x + nq[1] * sun_travel.y + nq[2] * sun_travel.z), 0.0);
  }
}

SeaReferenceRay traceBelowHorizon(const SeaReferenceScene& r, k::real3 d) {
  const CameraDesc& cam = r.scene->camera;
  SeaReferenceRay ray;
  double R_mean = 0;
  if (r.filter) {
    R_mean = filteredFacets(r, d, ray);
  } else if (r.waves) {
    const double t_hit = k::sea_mean_surface_distance(cam.position.y, d);
    ray.n = k::sea_facing_normal(d, k::sea_wave_normal(r.normals.data(), r.ocean_config.grid, r.ocean_config.patch_size,
                                                       cam.position.x + t_hit * d.x, cam.position.z + t_hit * d.z));
  }
  ray.cos_ji = k::sea_view_interaction(d, ray.n, r.ior, &ray.R_view, &ray.reflected, &ray.view_in_water);
  if (r.filter) ray.R_view = R_mean;
  ray.reflected_shape = r.shape(ray.reflected);
  const k::real3 flat_n{0, 1, 0};  // sunlight enters through the flat mean surface (000 §3)
  if (r.has_sun && r.sun.y > 0) {
    ray.t_in = 1 - k::fresnel_reflectance(r.sun.y, 1.0, r.ior);
    ray.e_h = r.sun.y;
    k::real3 sun_in_water{};
    k::refract_dir(-r.sun, flat_n, 1.0 / r.ior, &sun_in_water);
    ray.cos_io = std::max(-sun_in_water.y, 1e-4);
    ray.cos_alpha = k::dot(sun_in_water, -ray.view_in_water);
  }
  ray.phase = k::hg_phase(ray.cos_alpha, r.g);
  ray.c_f = k::hg_forward_fraction(r.g);
  // Water-leaving radiance reaches the air as L_w (1 - R) / n²: radiance / n² is conserved across
  // the surface (docs/radiometry.md).
  ray.t_out = (1 - ray.R_view) / (r.ior * r.ior);
  floorAlong(r, d, ray);
  return ray;
}

// sea.model = "multiple": the closed form in double (common/sea_multiple.h), the kernel's float
// evaluation is tested against it (tests/kernels/sea_multiple_kernel_test.cpp): the column, the bottom and the
// return below the surface (seaClosedFormBelowAlong), times κ and T_o, added to L.
double addMultipleBand(const SeaReferenceScene& r, size_t i, const SeaReferenceRay& ray, double L) {
  const double z_floor = ray.z_floor, t_out = ray.t_out;
  const double below =
      seaClosedFormBelowAlong(r.ordinate_light, r.ordinate_bands[i], z_floor, ray.cos_ji, ray.phase);
  // Held to the flat layer's discrete-ordinates solution (common/sea_ordinates.h), as the kernel.
  const double cos_phi = k::sea_ord_azimuth_cosine(ray.view_in_water.x, ray.view_in_water.z, r.sun.x, r.sun.z);
  const double kappa =
      seaOrdinatesFactor(r.ordinates, static_cast<int>(r.bands), static_cast<int>(i), z_floor, ray.cos_ji, cos_phi);
  return L + t_out * kappa * below;
}

// Band i's radiance along a ray below the horizon: the reflected sky, then single scattering (midpoint
// rule over depth) and the bottom (eq. 9), or sea.model "multiple".
double bandBelowHorizon(const SeaReferenceScene& r, size_t i, const SeaReferenceRay& ray) {
  const Scene& scene = *r.scene;
  double L = 0;
  if (scene.sea.reflection && r.filter) {
    for (size_t q = 0; q < ray.node_dirs.size(); ++q) L += ray.node_weights[q] * r.skyOnly(i, r.shape(ray.node_dirs[q]));
    L += ray.glint * r.sun_e[i];
  } else if (scene.sea.reflection) {
    L += ray.R_view * r.sky(i, ray.reflected_shape, ray.reflected);
  }
  const double c = r.water.c[i], albedo = c > 0 ? r.water.b[i] / c : 0.0;
  const double kk = c * (1 - albedo * ray.c_f);  // 000 eq. 5's effective attenuation
  const double z_floor = ray.z_floor;
  if (r.multiple) {
    L = addMultipleBand(r, i, ray, L);
  } else if (scene.sea.single_scattering && ray.e_h > 0) {
    // Beam irradiance in the water E T_i / cos_io, scattered by beta into the view ray,
    // attenuated down and back up; midpoint rule over depth.
    const double sec_sum = 1 / ray.cos_io + 1 / ray.cos_ji;
    // Below 40 optical depths (down and back) the integrand is < e^-40 of its surface value.
    const double z_optical = 40.0 / std::max(kk * sec_sum, 1e-12);
    const double z_end = z_floor >= 0 ? std::min(z_floor, z_optical) : z_optical;
    const double dz = z_end / r.steps;
    double sum = 0;
    for (int s = 0; s < r.steps; ++s) sum += std::exp(-kk * (s + 0.5) * dz * sec_sum);
    const double beam = r.sun_e[i] * ray.e_h * ray.t_in / ray.cos_io;
    L += beam * r.water.b[i] * ray.phase * ray.t_out * sum * dz / ray.cos_ji;
  }
  if (!r.multiple && z_floor >= 0 && ray.e_h > 0) {  // cos_gamma = cos_io on a flat floor: eq. 9 as it stands
    L += k::sea_bottom_reflection_tilted(r.sun_e[i] * ray.e_h, ray.t_in, ray.t_out,
                                         scene.bottom.albedo.at(r.grid.centers_nm[i]), c, z_floor, ray.cos_io,
                                         ray.cos_ji, ray.cos_gamma);
  }
  return L;
}

// Pixel (x, y): its n x n sub-pixel rays' radiance, band by band into sensor RGB.
void seaReferencePixel(const SeaReferenceScene& r, int x, int y, double rgb[3]) {
  const CameraDesc& cam = r.scene->camera;
  const int supersample = r.supersample;
  const double sub_weight = 1.0 / (supersample * supersample);
  for (int sub = 0; sub < supersample * supersample; ++sub) {
    const double ox = (sub % supersample + 0.5) / supersample, oy = (sub / supersample + 0.5) / supersample;
    const double u = (2.0 * (x + ox) / cam.width - 1.0) * r.tan_half * r.aspect;
    const double v = (1.0 - 2.0 * (y + oy) / cam.height) * r.tan_half;
    const Vec3 dv = normalize(r.fwd + r.right * u + r.up * v);
    const k::real3 d{dv.x, dv.y, dv.z};
    auto add = [&](size_t i, double L) {
      rgb[0] += sub_weight * L * r.sensor.to_r[i];
      rgb[1] += sub_weight * L * r.sensor.to_g[i];
      rgb[2] += sub_weight * L * r.sensor.to_b[i];
    };
    if (d.y >= 0) {
      const k::real3 s = r.shape(d);
      for (size_t i = 0; i < r.bands; ++i) add(i, r.sky(i, s, d));
      continue;
    }
    const SeaReferenceRay ray = traceBelowHorizon(r, d);
    for (size_t i = 0; i < r.bands; ++i) add(i, bandBelowHorizon(r, i, ray));
  }
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
  const SeaReferenceScene r = seaReferenceScene(scene, steps);
  const CameraDesc& cam = scene.camera;
  Image img;
  img.width = cam.width;
  img.height = cam.height;
  img.channels = 3;
  img.channel_names = {"R", "G", "B"};
  img.pixels.assign(static_cast<size_t>(cam.width) * cam.height * 3, 0.0f);
  tbb::parallel_for(0, cam.height, [&](int y) {
    for (int x = 0; x < cam.width; ++x) {
      double rgb[3] = {0, 0, 0};
      seaReferencePixel(r, x, y, rgb);
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
