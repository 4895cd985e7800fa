#include "reference/froxel_reference.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "math/kernel_math.h"
#include "util/error.h"

namespace seasim {

namespace {

namespace kd = kmath_d;

int knob(const Scene& scene, const char* name, int fallback) {
  const auto it = scene.quality.find(name);
  if (it == scene.quality.end() || it->second.automatic) return fallback;
  return static_cast<int>(it->second.value);
}

void set4(float out[4], Vec3 v) {
  out[0] = static_cast<float>(v.x);
  out[1] = static_cast<float>(v.y);
  out[2] = static_cast<float>(v.z);
  out[3] = 0.0f;
}

Vec3 sunWater(const UwParams& p) { return {p.sun_dir_water[0], p.sun_dir_water[1], p.sun_dir_water[2]}; }

kd::real3 toReal3(Vec3 v) { return kd::real3{v.x, v.y, v.z}; }

}  // namespace

FroxelConfig froxelConfigFromScene(const Scene& scene) {
  FroxelConfig c;
  c.nx = knob(scene, "froxel_x", c.nx);
  c.ny = knob(scene, "froxel_y", c.ny);
  c.nz = knob(scene, "froxel_z", c.nz);
  c.shadow_map_size = knob(scene, "shadow_map_size", c.shadow_map_size);
  c.z_near = scene.underwater.froxel_near;
  c.z_far = scene.underwater.froxel_far;
  c.rgb_injection = scene.underwater.injection == UnderwaterDesc::Injection::Rgb;
  return c;
}

std::vector<UwBand> froxelRgbPseudoBands(const UnderwaterSetup& setup) {
  std::vector<UwBand> out(3);
  for (int k = 0; k < 3; ++k) {
    double sum_w = 0, sum_c = 0, sum_albedo = 0, e = 0;
    for (const UwBand& b : setup.bands) {
      const double w = k == 0 ? b.w_r : (k == 1 ? b.w_g : b.w_b);
      const double omega = std::max(w, 0.0);
      sum_w += omega;
      sum_c += omega * b.c;
      sum_albedo += omega * (b.c > 0 ? double(b.b) / b.c : 0.0);
      e += w * b.e_beam0;
    }
    UwBand& p = out[k];
    p = UwBand{};
    if (sum_w > 0) {
      const double c = sum_c / sum_w, albedo = std::clamp(sum_albedo / sum_w, 0.0, 1.0);
      p.c = static_cast<float>(c);
      p.b = static_cast<float>(albedo * c);
      p.a = p.c - p.b;
      p.e_beam0 = static_cast<float>(e);
    }
    p.w_r = k == 0 ? 1.0f : 0.0f;
    p.w_g = k == 1 ? 1.0f : 0.0f;
    p.w_b = k == 2 ? 1.0f : 0.0f;
  }
  return out;
}

FroxelParams makeFroxelParams(const UnderwaterSetup& setup, const FroxelConfig& config) {
  if (config.nx < 1 || config.ny < 1 || config.nz < 1) {
    throw RuntimeError("froxel pass: the grid needs at least 1 froxel per axis, got " + std::to_string(config.nx) +
                       "x" + std::to_string(config.ny) + "x" + std::to_string(config.nz) +
                       " (quality froxel_x, froxel_y, froxel_z)");
  }
  const double froxels = double(config.nx) * config.ny * config.nz;
  if (froxels > double(1 << 29)) {  // 4 floats each must stay within int indexing (and memory)
    throw RuntimeError("froxel pass: grid " + std::to_string(config.nx) + "x" + std::to_string(config.ny) + "x" +
                       std::to_string(config.nz) + " has more than 2^29 froxels; lower quality froxel_x/y/z");
  }
  if (!(config.z_near > 0) || !(config.z_far > config.z_near)) {
    throw RuntimeError("froxel pass: need 0 < froxel_near_m < froxel_far_m, got " + std::to_string(config.z_near) +
                       " and " + std::to_string(config.z_far));
  }
  if (config.shadow_map_size < 1) throw RuntimeError("froxel pass: shadow_map_size must be at least 1");

  FroxelParams fp{};
  fp.nx = config.nx;
  fp.ny = config.ny;
  fp.nz = config.nz;
  fp.z_near = static_cast<float>(config.z_near);
  fp.z_far = static_cast<float>(config.z_far);
  fp.log_far_near = static_cast<float>(std::log(config.z_far / config.z_near));
  fp.injection = config.rgb_injection ? FROXEL_INJECTION_RGB : FROXEL_INJECTION_SPECTRAL;
  const std::vector<UwBand> rgb = froxelRgbPseudoBands(setup);
  for (int k = 0; k < 3; ++k) {
    fp.sigma_t_rgb[k] = rgb[k].c;
    fp.sigma_s_rgb[k] = rgb[k].b;
    fp.e_beam_rgb[k] = rgb[k].e_beam0;
  }

  // The shadow map over the bounded objects (spheres, boxes).
  Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  bool any = false;
  for (int k = 0; k < setup.params.object_count; ++k) {
    const UwObject& o = setup.objects[k];
    Vec3 a{o.a[0], o.a[1], o.a[2]}, b = a;
    if (o.type == UW_SPHERE) {
      const Vec3 r{o.a[3], o.a[3], o.a[3]};
      b = a + r;
      a = a - r;
    } else if (o.type == UW_BOX) {
      b = Vec3{o.b[0], o.b[1], o.b[2]};
    } else {
      continue;
    }
    lo = {std::min(lo.x, a.x), std::min(lo.y, a.y), std::min(lo.z, a.z)};
    hi = {std::max(hi.x, b.x), std::max(hi.y, b.y), std::max(hi.z, b.z)};
    any = true;
  }
  if (any) {
    const Vec3 s = sunWater(setup.params);
    const Vec3 centre = (lo + hi) * 0.5;
    const double radius = 0.5 * length(hi - lo) + 1e-3;
    const Vec3 axis = std::fabs(s.z) < 0.9 ? Vec3{0, 0, 1} : Vec3{1, 0, 0};
    const Vec3 right = normalize(cross(s, axis));
    const Vec3 up = cross(right, s);
    set4(fp.shadow_origin, centre + s * (radius + 1.0));
    set4(fp.shadow_right, right);
    set4(fp.shadow_up, up);
    fp.shadow_half_extent = static_cast<float>(radius);
    fp.shadow_bias = static_cast<float>(1e-4 * (radius + 1.0));
    fp.shadow_size = config.shadow_map_size;
  }
  return fp;
}

std::vector<UwBand> froxelIntegrationBands(const UnderwaterSetup& setup, const FroxelParams& params) {
  return params.injection == FROXEL_INJECTION_RGB ? froxelRgbPseudoBands(setup) : setup.bands;
}

FroxelCpuVolume froxelEvaluateCpu(const UnderwaterSetup& setup, const FroxelParams& fp,
                                  const std::vector<float>* caustic_maps) {
  FroxelCpuVolume out;
  const UwParams& p = setup.params;
  const kd::real3 s_w = toReal3(sunWater(p));
  const int n = fp.shadow_size;
  out.shadow_map.resize(size_t(n) * n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      out.shadow_map[size_t(j) * n + i] =
          static_cast<float>(kd::froxel_shadow_texel(&fp, setup.objects.data(), p.object_count, s_w, i, j));

  const size_t froxels = size_t(fp.nx) * fp.ny * fp.nz;
  out.light.assign(froxels, 0.0f);
  const bool caustics = p.caustic_mode == UW_CAUSTICS_TEXTURE;
  if (p.caustic_mode == UW_CAUSTICS_MAP && !caustic_maps)
    throw RuntimeError("froxelEvaluateCpu: the scene has caustics = \"map\"; pass the caustic maps");
  const bool maps = p.caustic_mode == UW_CAUSTICS_MAP;
  tbb::parallel_for(tbb::blocked_range<int>(0, fp.nz), [&](const tbb::blocked_range<int>& r) {
    for (int k = r.begin(); k < r.end(); ++k)
      for (int j = 0; j < fp.ny; ++j)
        for (int i = 0; i < fp.nx; ++i) {
          const kd::real3 q = kd::froxel_center(&p, &fp, i, j, k);
          if (q.y > 0) continue;  // above the surface
          double v = kd::froxel_shadow_visibility(&fp, out.shadow_map.data(), s_w, q) *
                     kd::froxel_plane_visibility(setup.objects.data(), p.object_count, s_w, q);
          if (caustics) {
            const double t_up = -q.y / std::max(s_w.y, 1e-4);
            v *= kd::caustic_modulation(q.x + t_up * s_w.x, q.z + t_up * s_w.z, p.time, p.caustic_period,
                                        p.caustic_speed);
          }
          if (maps)
            v *= kd::caustic_map_sample(caustic_maps->data(), p.caustic_map_size, p.caustic_layers, p.caustic_extent,
                                        p.caustic_depth_max, q.x, -q.y, q.z);
          out.light[(size_t(k) * fp.ny + j) * fp.nx + i] = static_cast<float>(v);
        }
  });

  const std::vector<UwBand> bands = froxelIntegrationBands(setup, fp);
  std::vector<double> slice_factors(size_t(fp.nz) * bands.size());
  kd::froxel_fill_slice_factors(&fp, bands.data(), static_cast<int>(bands.size()), slice_factors.data());
  out.volume.assign(4 * froxels, 0.0f);
  tbb::parallel_for(tbb::blocked_range<int>(0, fp.ny), [&](const tbb::blocked_range<int>& r) {
    for (int j = r.begin(); j < r.end(); ++j)
      for (int i = 0; i < fp.nx; ++i)
        kd::froxel_integrate_column(&p, &fp, bands.data(), static_cast<int>(bands.size()), slice_factors.data(),
                                    out.light.data(), out.volume.data(), i, j);
  });
  return out;
}

std::vector<double> froxelPixelDistances(const UnderwaterSetup& setup) {
  const UwParams& p = setup.params;
  std::vector<double> out(size_t(p.width) * p.height);
  const kd::real3 o{p.cam_pos[0], p.cam_pos[1], p.cam_pos[2]};
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x) {
      const kd::real3 d = kd::uw_screen_dir(&p, (x + 0.5) / p.width, (y + 0.5) / p.height);
      kd::real3 n{};
      int mat = 0;
      out[size_t(y) * p.width + x] =
          kd::uw_scene_hit(setup.objects.data(), p.object_count, p.bottom_depth, o, d, 0.0, &n, &mat);
    }
  return out;
}

std::vector<double> froxelResolveCpu(const FroxelParams& fp, const std::vector<float>& volume,
                                     const std::vector<double>& distances, int width, int height) {
  std::vector<double> out(size_t(3) * width * height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const size_t pixel = size_t(y) * width + x;
      const kd::real3 v = kd::froxel_lookup(&fp, volume.data(), x, y, width, height, distances[pixel]);
      out[3 * pixel + 0] = v.x;
      out[3 * pixel + 1] = v.y;
      out[3 * pixel + 2] = v.z;
    }
  return out;
}

double froxelBruteForceRay(const UnderwaterSetup& setup, int band_index, Vec3 origin, Vec3 dir, double S, int steps) {
  const UwParams& p = setup.params;
  const UwBand& band = setup.bands.at(band_index);
  const double b = band.b, c = band.c;
  if (b <= 0 || c <= 0 || steps < 1 || !(S > 0)) return 0.0;
  const kd::real3 s_w = toReal3(sunWater(p));
  const double mu_w = std::max(s_w.y, 1e-4);
  const kd::real3 o = toReal3(origin), d = toReal3(dir);
  const double phase = kd::hg_phase(kd::dot(s_w, d), p.g);
  const bool caustics = p.caustic_mode == UW_CAUSTICS_TEXTURE;
  // u = 1 - e^{-c z}: dz e^{-c z} = du / c, z = -log(1 - u)/c, u over [0, 1 - e^{-c S}].
  const double u_max = S >= 1e30 ? 1.0 : -std::expm1(-c * S);
  double sum = 0;
  for (int k = 0; k < steps; ++k) {
    const double u = (k + 0.5) / steps * u_max;
    const double z = -std::log1p(-u) / c;
    const kd::real3 x = o + z * d;
    const double y = -x.y;
    if (y < 0) continue;
    const double e = kd::uw_beam_irradiance(band.e_beam0, c, mu_w, y);
    if (e <= 0) continue;
    double v = 1.0;
    if (p.object_count > 0) {  // exact shadow ray along s_w to the surface through the objects
      kd::real3 n{};
      int mat = 0;
      kd::uw_scene_hit(setup.objects.data(), p.object_count, 0.0, x, s_w, 0.0, &n, &mat);
      if (mat >= 0) continue;
    }
    if (caustics) {
      const double t_up = y / mu_w;
      v = kd::caustic_modulation(x.x + t_up * s_w.x, x.z + t_up * s_w.z, p.time, p.caustic_period, p.caustic_speed);
    }
    sum += e * v;
  }
  return b * phase * sum * u_max / steps / c;
}

std::vector<double> froxelBruteForce(const UnderwaterSetup& setup, int steps) {
  const UwParams& p = setup.params;
  const std::vector<double> S = froxelPixelDistances(setup);
  std::vector<double> out(size_t(3) * p.width * p.height, 0.0);
  const Vec3 o{p.cam_pos[0], p.cam_pos[1], p.cam_pos[2]};
  tbb::parallel_for(tbb::blocked_range<int>(0, p.height), [&](const tbb::blocked_range<int>& r) {
    for (int y = r.begin(); y < r.end(); ++y)
      for (int x = 0; x < p.width; ++x) {
        const kd::real3 dk = kd::uw_screen_dir(&p, (x + 0.5) / p.width, (y + 0.5) / p.height);
        const Vec3 d{dk.x, dk.y, dk.z};
        const size_t pixel = size_t(y) * p.width + x;
        for (size_t i = 0; i < setup.bands.size(); ++i) {
          const double l = froxelBruteForceRay(setup, static_cast<int>(i), o, d, S[pixel], steps);
          out[3 * pixel + 0] += l * setup.bands[i].w_r;
          out[3 * pixel + 1] += l * setup.bands[i].w_g;
          out[3 * pixel + 2] += l * setup.bands[i].w_b;
        }
      }
  });
  return out;
}

}  // namespace seasim
