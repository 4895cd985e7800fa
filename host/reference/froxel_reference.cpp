#include "reference/froxel_reference.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "math/kernel_math.h"
#include "reference/pixel_centre_hits.h"
#include "util/error.h"

namespace seasim {

namespace {

namespace kd = kmath_d;

Vec3 sunWater(const UwParams& p) { return {p.sun_dir_water[0], p.sun_dir_water[1], p.sun_dir_water[2]}; }

kd::real3 toReal3(Vec3 v) { return kd::real3{v.x, v.y, v.z}; }

}  // namespace

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
  const std::vector<PixelCentreHit> hits = pixelCentreHits(setup);
  std::vector<double> out(hits.size());
  for (size_t i = 0; i < hits.size(); ++i) out[i] = hits[i].distance;
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
