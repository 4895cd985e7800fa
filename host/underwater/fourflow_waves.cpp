// fourflow_waves.cpp — 003 eq. 10 over the FFT patch (see the header and kernels/common/fourflow_waves.h).
#include "underwater/fourflow_waves.h"

#include <algorithm>
#include <cmath>

#include "math/kernel_math.h"
#include "ocean/ocean_cpu.h"
#include "passes/ocean_pass.h"

namespace seasim {

namespace kd = kmath_d;

namespace {

FourFlowSurface fromKernel(const kd::FfSurface& s) {
  FourFlowSurface o;
  o.T_dd = s.T_dd, o.T_df = s.T_df, o.T_ff = s.T_ff;
  o.Rw_dd = s.Rw_dd, o.Rw_df = s.Rw_df, o.Rw_ff = s.Rw_ff;
  return o;
}

double dot(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

}  // namespace

FourFlowSurface flatFourFlowSurface(double mu_sun, double n_water) {
  return fromKernel(kd::ff_flat_surface(mu_sun, n_water));
}

FourFlowSurface waveAveragedSurface(const std::vector<std::array<double, 3>>& normals, double sun_zenith,
                                    double sun_azimuth, double n_water, int intervals) {
  // Towards the sun, and the upward beam in the water: the flat surface's refracted sun, mirrored up.
  const double st = std::sin(sun_zenith), ct = std::cos(sun_zenith);
  const std::array<double, 3> to_sun = {st * std::cos(sun_azimuth), ct, st * std::sin(sun_azimuth)};
  const double sw = st / n_water, cw = std::sqrt(std::max(0.0, (1 - sw) * (1 + sw)));
  const std::array<double, 3> beam_up = {-sw * std::cos(sun_azimuth), cw, -sw * std::sin(sun_azimuth)};
  if (intervals <= 0) intervals = FF_WAVE_INTERVALS;
  double sky = 0, sky_w = 0, sun = 0, sun_w = 0, beam = 0, beam_w = 0;
  size_t facets = 0;
  for (const auto& n : normals) {
    if (!(n[1] > 0)) continue;
    ++facets;
    sky += kd::ff_facet_diffuse_reflectance(n[1], 1.0, n_water, intervals);
    sky_w += kd::ff_facet_diffuse_reflectance(n[1], n_water, 1.0, intervals);
    // The sun: weight = sunlight a facet intercepts per unit horizontal area.
    const double cs = dot(to_sun, n), ws = std::max(cs, 0.0) / n[1];
    sun += ws * kd::fresnel_reflectance(std::max(cs, 0.0), 1.0, n_water);
    sun_w += ws;
    const double cb = dot(beam_up, n), wb = std::max(cb, 0.0) / n[1];
    beam += wb * kd::fresnel_reflectance(std::max(cb, 0.0), n_water, 1.0);
    beam_w += wb;
  }
  if (facets == 0) return flatFourFlowSurface(std::max(ct, 0.0), n_water);
  const double nf = double(facets);
  // A sun at or below the horizon meets no facet: its coefficients do not matter (e_sun = 0), keep flat ones.
  const kd::FfSurface flat = kd::ff_flat_surface(std::max(ct, 0.0), n_water);
  const double r_sun = sun_w > 0 ? sun / sun_w : 1.0 - flat.T_dd;
  const double r_beam = beam_w > 0 ? beam / beam_w : flat.Rw_dd;
  return fromKernel(kd::ff_wave_surface(sky / nf, r_sun, sky_w / nf, r_beam));
}

std::vector<std::array<double, 3>> oceanFacetNormals(const SurfaceDesc& surface, int max_side) {
  OceanCpu ocean(oceanConfigFromSurface(surface), OceanCpu::Precision::Double);
  ocean.run(surface.time);
  const std::vector<double> normal = ocean.normal();  // float4 layout: (nx, ny, nz, 0) per texel
  const int n = ocean.n();
  const int stride = std::max(1, n / std::max(1, max_side));
  std::vector<std::array<double, 3>> out;
  for (int j = 0; j < n; j += stride)
    for (int i = 0; i < n; i += stride) {
      const size_t t = (size_t(j) * n + i) * 4;
      out.push_back({normal[t], normal[t + 1], normal[t + 2]});
    }
  return out;
}

}  // namespace seasim
