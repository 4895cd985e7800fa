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
          if (caustics) {  // as froxel.cl's froxel_injected: the sample kept by the footprint's rho
            const kd::real3 d = kd::froxel_column_dir(&p, &fp, i, j);
            const double t0 = kd::froxel_slice_start(k, fp.nz, fp.z_near, fp.z_far, fp.log_far_near);
            const double t1 = kd::froxel_slice_end(k, fp.nz, fp.z_near, fp.z_far, fp.log_far_near);
            const double s1 = std::max(t0, std::min(t1, kd::froxel_surface_distance(fp.cam_depth, d.y)));
            const double rho = kd::froxel_caustic_correlation(&p, &fp, d, s_w, t0, s1,
                                                               kd::caustic_integral_scale(p.caustic_period));
            const double t_up = -q.y / std::max(s_w.y, 1e-4);
            if (v > 0 && kd::froxel_caustic_evaluated(rho))
              v *= kd::froxel_kept_caustic(kd::caustic_modulation(q.x + t_up * s_w.x, q.z + t_up * s_w.z, p.time,
                                                                  p.caustic_period, p.caustic_speed),
                                           rho);
          }
          if (maps)
            v *= kd::caustic_map_sample(caustic_maps->data(), p.caustic_map_size, p.caustic_layers, p.caustic_extent,
                                        p.caustic_depth_max, q.x, -q.y, q.z);
          out.light[(size_t(k) * fp.ny + j) * fp.nx + i] = static_cast<float>(v);
        }
  });

  const std::vector<UwBand> bands = froxelIntegrationBands(setup, fp);
  const std::vector<float> column_dy = froxelColumnDy(setup, fp);
  out.volume.assign(4 * froxels, 0.0f);
  tbb::parallel_for(tbb::blocked_range<int>(0, fp.ny), [&](const tbb::blocked_range<int>& r) {
    for (int j = r.begin(); j < r.end(); ++j)
      for (int i = 0; i < fp.nx; ++i)
        kd::froxel_integrate_column(&p, &fp, bands.data(), static_cast<int>(bands.size()), out.light.data(),
                                    out.volume.data(), column_dy[size_t(j) * fp.nx + i], i, j);
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

namespace {

// L_SS of every band along o + z d up to S (sensor RGB added into rgb[0..2], times `weight`), all bands
// on one set of points: the midpoint rule in u = 1 - e^{-c_min z} of the band that decays slowest, so the
// shadow ray and the caustic are evaluated once per point for every band. Band b's integrand in u is
// then e^{-(c_b - c_min) z} E_beam V C / c_min = (1 - u)^{c_b/c_min - 1} (...) / c_min: smooth, no
// truncation in deep water (u reaches 1 exactly at z = ∞).
void bruteForceAllBands(const UnderwaterSetup& setup, kd::real3 o, kd::real3 d, double S, int steps, double weight,
                        double* rgb) {
  const UwParams& p = setup.params;
  double c_min = 1e300;
  for (const UwBand& band : setup.bands)
    if (band.b > 0 && band.c > 0) c_min = std::min(c_min, double(band.c));
  if (c_min == 1e300 || steps < 1 || !(S > 0)) return;
  const kd::real3 s_w = toReal3(sunWater(p));
  const double mu_w = std::max(s_w.y, 1e-4);
  const double cos_theta = kd::dot(s_w, d);
  const bool caustics = p.caustic_mode == UW_CAUSTICS_TEXTURE;
  const double u_max = S >= 1e30 ? 1.0 : -std::expm1(-c_min * S);
  const double du = u_max / steps;
  std::vector<double> sum(setup.bands.size(), 0.0);
  for (int k = 0; k < steps; ++k) {
    const double u = (k + 0.5) * du;
    const double z = -std::log1p(-u) / c_min;
    const kd::real3 x = o + z * d;
    const double depth = -x.y;
    if (depth < 0) continue;
    if (p.object_count > 0) {  // exact shadow ray along s_w to the surface through the objects
      kd::real3 n{};
      int mat = 0;
      kd::uw_scene_hit(setup.objects.data(), p.object_count, 0.0, x, s_w, 0.0, &n, &mat);
      if (mat >= 0) continue;
    }
    double v = 1.0;
    if (caustics) {
      const double t_up = depth / mu_w;
      v = kd::caustic_modulation(x.x + t_up * s_w.x, x.z + t_up * s_w.z, p.time, p.caustic_period, p.caustic_speed);
    }
    for (size_t i = 0; i < setup.bands.size(); ++i) {
      const UwBand& band = setup.bands[i];
      if (!(band.b > 0 && band.c > 0)) continue;
      // e^{-c z} dz = e^{-(c - c_min) z} du / c_min
      sum[i] += std::exp(-(band.c - c_min) * z) * kd::uw_beam_irradiance(band.e_beam0, band.c, mu_w, depth) * v;
    }
  }
  for (size_t i = 0; i < setup.bands.size(); ++i) {
    const UwBand& band = setup.bands[i];
    const double l = weight * band.b * kd::hg_phase(cos_theta, p.g) * sum[i] * du / c_min;
    rgb[0] += l * band.w_r;
    rgb[1] += l * band.w_g;
    rgb[2] += l * band.w_b;
  }
}

}  // namespace

std::vector<double> froxelBruteForcePixelArea(const UnderwaterSetup& setup, int steps, int subpixels) {
  if (subpixels < 1) throw RuntimeError("froxel brute force: subpixels must be at least 1");
  const UwParams& p = setup.params;
  std::vector<double> out(size_t(3) * p.width * p.height, 0.0);
  const kd::real3 o{p.cam_pos[0], p.cam_pos[1], p.cam_pos[2]};
  const double weight = 1.0 / (double(subpixels) * subpixels);
  tbb::parallel_for(tbb::blocked_range<int>(0, p.height), [&](const tbb::blocked_range<int>& r) {
    for (int y = r.begin(); y < r.end(); ++y)
      for (int x = 0; x < p.width; ++x)
        for (int sy = 0; sy < subpixels; ++sy)
          for (int sx = 0; sx < subpixels; ++sx) {
            const kd::real3 d = kd::uw_screen_dir(&p, (x + (sx + 0.5) / subpixels) / p.width,
                                                  (y + (sy + 0.5) / subpixels) / p.height);
            kd::real3 n{};
            int material = 0;
            const double S = kd::uw_scene_hit(setup.objects.data(), p.object_count, p.bottom_depth, o, d, 0.0, &n,
                                              &material);
            bruteForceAllBands(setup, o, d, S, steps, weight, &out[3 * (size_t(y) * p.width + x)]);
          }
  });
  return out;
}

}  // namespace seasim
