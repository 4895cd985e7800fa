#include "underwater/froxel_setup.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "geometry/kernel_camera.h"
#include "math/kernel_math.h"
#include "util/error.h"

namespace seasim {

namespace {

int knob(const Scene& scene, const char* name, int fallback) {
  const auto it = scene.quality.find(name);
  if (it == scene.quality.end() || it->second.automatic) return fallback;
  return static_cast<int>(it->second.value);
}

Vec3 sunWater(const UwParams& p) { return {p.sun_dir_water[0], p.sun_dir_water[1], p.sun_dir_water[2]}; }

}  // namespace

FroxelConfig froxelConfigFromScene(const Scene& scene) {
  FroxelConfig c;
  // froxel_columns across the image's wider side (at most one per pixel), the other side in proportion:
  // the error is the columns' angular spacing, not pixels per column (seabed with caustics: 2.16 % at
  // 320×180 and 2.37 % at 640×360 with 80×45 columns; results/BENCHMARKS.md), so the grid does not grow
  // with the image.
  const int w = std::max(scene.camera.width, 1), h = std::max(scene.camera.height, 1);
  const int across = std::min(std::max(w, h), std::max(1, knob(scene, "froxel_columns", 80)));
  const double per_column = double(std::max(w, h)) / across;  // pixels per column side, >= 1
  c.nx = knob(scene, "froxel_x", std::max(1, static_cast<int>(std::lround(w / per_column))));
  c.ny = knob(scene, "froxel_y", std::max(1, static_cast<int>(std::lround(h / per_column))));
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
  fp.mu_w = std::max(setup.params.sun_dir_water[1], 1e-4f);
  fp.cam_depth = -setup.params.cam_pos[1];
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

std::vector<float> froxelColumnDy(const UnderwaterSetup& setup, const FroxelParams& params) {
  std::vector<float> out(size_t(params.nx) * params.ny);
  for (int j = 0; j < params.ny; ++j)
    for (int i = 0; i < params.nx; ++i)
      out[size_t(j) * params.nx + i] = kmath_f::froxel_column_dir(&setup.params, &params, i, j).y;
  return out;
}

std::vector<UwBand> froxelIntegrationBands(const UnderwaterSetup& setup, const FroxelParams& params) {
  return params.injection == FROXEL_INJECTION_RGB ? froxelRgbPseudoBands(setup) : setup.bands;
}

}  // namespace seasim
