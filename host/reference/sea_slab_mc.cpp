#include "reference/sea_slab_mc.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "math/kernel_math.h"
#include "reference/batch_error.h"
#include "spectral/jerlov.h"
#include "spectral/sensor.h"
#include "spectral/wavelength_grid.h"
#include "util/error.h"

namespace seasim {

namespace {

namespace k = kmath_d;

constexpr int kOrders = 8;  // orders tallied one by one
// Tallies per path: orders 1..8, orders >= 3, all orders, bottom direct, bottom other.
enum Tally { kOrders3Plus = kOrders, kAll, kBottomDirect, kBottomOther, kTallies };
constexpr int64_t kChunks = 256;
constexpr double kSunLobe = 0.5;  // share of scattering directions drawn from the sun NEE's lobe
constexpr int kMisOrders = 1;     // ... at the first kMisOrders vertices (later: phase sampling only)  // fixed summation blocks: the result does not depend on threads

// The water-side quantities every estimator and closed form shares (as sea_single.cl computes them).
struct Geometry {
  bool sees_water = false;
  double t_out = 0;      // T_o (1 - R) / n²: radiance / n² crosses the surface (docs/radiometry.md)
  k::real3 view{};       // refracted view ray, travelling down into the water
  double cos_ji = 1;
  bool sun_up = false;
  double e_h = 0;        // sun irradiance on the horizontal surface, E cos(zenith)
  double t_in = 0;       // T_i
  k::real3 sun{};        // travel direction of the refracted sunlight (y < 0)
  double cos_io = 1;
  double e_beam = 0;     // beam irradiance just below the surface, E_h T_i / cos_io
};

Geometry geometry(const SlabMcSetup& s) {
  Geometry g;
  const k::real3 n{0, 1, 0};
  const Vec3 d0 = normalize(s.view);
  const k::real3 d{d0.x, d0.y, d0.z};
  if (d.y < 0) {
    g.sees_water = true;
    g.t_out = (1 - k::fresnel_reflectance(-d.y, 1.0, s.ior)) / (s.ior * s.ior);  // T_o and the n² law
    k::refract_dir(d, n, 1.0 / s.ior, &g.view);
    g.cos_ji = std::max(-g.view.y, 1e-4);  // the clamp of sea_single.cl / the references
  }
  const k::real3 sun{std::sin(s.sun_zenith) * std::cos(s.sun_azimuth), std::cos(s.sun_zenith),
                     std::sin(s.sun_zenith) * std::sin(s.sun_azimuth)};
  if (sun.y > 0 && s.sun_irradiance > 0) {
    g.sun_up = true;
    g.e_h = s.sun_irradiance * sun.y;
    g.t_in = 1 - k::fresnel_reflectance(sun.y, 1.0, s.ior);
    k::refract_dir(-sun, n, 1.0 / s.ior, &g.sun);
    g.cos_io = std::max(-g.sun.y, 1e-4);
    g.e_beam = g.e_h * g.t_in / g.cos_io;
  }
  return g;
}

void validate(const SlabMcSetup& s) {
  if (!(s.a >= 0) || !(s.b >= 0) || !std::isfinite(s.a + s.b)) {
    throw RuntimeError("slab Monte Carlo: a and b must be finite and >= 0 (1/m)");
  }
  if (!(std::fabs(s.g) < 1)) throw RuntimeError("slab Monte Carlo: the HG parameter g must satisfy |g| < 1");
  if (!(s.ior > 0)) throw RuntimeError("slab Monte Carlo: ior must be > 0");
  if (!(s.bottom_albedo >= 0 && s.bottom_albedo <= 1)) {
    throw RuntimeError("slab Monte Carlo: bottom_albedo must be in [0, 1]");
  }
  if (!(length(s.view) > 0)) throw RuntimeError("slab Monte Carlo: the view direction must be non-zero");
}

// Philox4x32-10 stream of one path: counter (path low, path high, block, "slab"), key (seed, const).
struct PathRng {
  uint32_t seed;
  uint64_t path;
  uint32_t block = 0;
  unsigned int words[4] = {0, 0, 0, 0};
  int used = 4;
  double uniform() {  // in (0, 1), 32-bit resolution
    if (used == 4) {
      words[0] = static_cast<unsigned int>(path);
      words[1] = static_cast<unsigned int>(path >> 32);
      words[2] = block++;
      words[3] = 0x736C6162u;  // "slab": separates this stream from other Philox users
      k::philox4x32_10(words, seed, 0x5EA51AB0u);
      used = 0;
    }
    return (double(words[used++]) + 0.5) * 0x1p-32;
  }
};

// Direction at polar cosine mu and azimuth phi about the unit axis a.
k::real3 aroundAxis(k::real3 a, double mu, double phi) {
  const k::real3 helper = std::fabs(a.x) < 0.9 ? k::real3{1, 0, 0} : k::real3{0, 1, 0};
  const k::real3 t1 = k::normalize(k::cross(a, helper));
  const k::real3 t2 = k::cross(a, t1);
  const double st = std::sqrt(std::max(0.0, 1 - mu * mu));
  return k::normalize(a * mu + t1 * (st * std::cos(phi)) + t2 * (st * std::sin(phi)));
}

// Inverse CDF of Henyey–Greenstein in the cosine to its axis, u in (0, 1) -> mu in (-1, 1).
double hgInverseCdf(double u, double g) {
  if (std::fabs(g) < 1e-6) return 1 - 2 * u;
  const double q = (1 - g * g) / (1 - g + 2 * g * u);
  return std::clamp((1 + g * g - q * q) / (2 * g), -1.0, 1.0);
}

// One backward path from P; adds its score per tally to `score`.
void tracePath(const SlabMcSetup& s, const Geometry& geo, const SlabMcSettings& settings, PathRng& rng,
               double* score) {
  const double c = s.a + s.b, albedo = c > 0 ? s.b / c : 0.0;
  const bool bottom = s.bottom_depth >= 0;
  const double z_d = s.bottom_depth;
  const double w_floor = 0.1 * geo.t_out;  // Russian roulette below this weight
  k::real3 v = geo.view;                   // backward direction: light arrives travelling -v
  double depth = 0, w = geo.t_out;
  int order = 0;
  bool bounced = false;
  for (int event = 0; event < settings.max_order && w > 0; ++event) {
    enum { kNone, kSurface, kBottom } boundary = kNone;
    double t_b = std::numeric_limits<double>::infinity();
    if (v.y > 0) {
      t_b = depth / v.y;
      boundary = kSurface;
    } else if (v.y < 0 && bottom) {
      t_b = std::max(z_d - depth, 0.0) / -v.y;
      boundary = kBottom;
    }
    const double t = c > 0 ? -std::log(rng.uniform()) / c : std::numeric_limits<double>::infinity();
    if (t < t_b) {  // a scattering vertex
      depth = std::max(depth - t * v.y, 0.0);
      ++order;
      if (geo.sun_up) {
        // NEE of the sun beam: weight 1/c of the free flight times b p(s . -v) E_beam(depth).
        const double contrib =
            w * albedo * k::hg_phase(k::dot(geo.sun, -v), s.g) * geo.e_beam * std::exp(-c * depth / geo.cos_io);
        if (bounced) {
          score[kBottomOther] += contrib;
        } else {
          if (order <= kOrders) score[order - 1] += contrib;
          if (order >= 3) score[kOrders3Plus] += contrib;
          score[kAll] += contrib;
        }
      }
      // Next backward direction v' from the mixture of the phase lobe about v (p1 = p(v' . v)) and
      // the lobe the next vertex's sun NEE has about -s (p2 = p(s . -v')), weight albedo p1 / pdf:
      // one-sample MIS (balance heuristic), so the next order's score is bounded by 2 min(p1, p2)
      // instead of carrying the spike of p2 with a direction sampled from p1 alone.
      const double u = rng.uniform(), mu = hgInverseCdf(rng.uniform(), s.g), phi = 2 * M_PI * rng.uniform();
      if (!geo.sun_up || order > kMisOrders) {
        w *= albedo;  // phase sampling: b/c x p/p
        v = aroundAxis(v, mu, phi);
      } else {
        const k::real3 next = aroundAxis(u < kSunLobe ? -geo.sun : v, mu, phi);
        const double p1 = k::hg_phase(k::dot(next, v), s.g), p2 = k::hg_phase(k::dot(geo.sun, -next), s.g);
        w *= albedo * p1 / ((1 - kSunLobe) * p1 + kSunLobe * p2);
        v = next;
      }
    } else if (boundary == kSurface) {
      depth = 0;
      if (!s.internal_reflection) break;  // leaves the water (the model's transparent surface)
      w *= k::fresnel_reflectance(v.y, s.ior, 1.0);
      v.y = -v.y;
    } else if (boundary == kBottom) {
      depth = z_d;
      if (s.bottom_albedo <= 0) break;
      if (geo.sun_up) {  // the sun's direct irradiance on the flat bottom, Lambertian BRDF albedo/pi
        const double contrib =
            w * (s.bottom_albedo / M_PI) * geo.e_beam * geo.cos_io * std::exp(-c * z_d / geo.cos_io);
        score[(order == 0 && !bounced) ? kBottomDirect : kBottomOther] += contrib;
      }
      bounced = true;
      w *= s.bottom_albedo;  // cosine sampling: (albedo/pi) cos / (cos/pi)
      const double u1 = rng.uniform(), u2 = rng.uniform();
      const double r = std::sqrt(u1), phi = 2 * M_PI * u2;
      v = k::real3{r * std::cos(phi), std::sqrt(std::max(0.0, 1 - u1)), r * std::sin(phi)};
    } else {
      break;  // no interaction and no boundary ahead (c = 0, or level/downward into bottomless water)
    }
    if (w < w_floor) {
      if (rng.uniform() < 0.5) break;
      w *= 2;
    }
  }
}

}  // namespace

SlabMcResult runSlabMc(const SlabMcSetup& setup, const SlabMcSettings& settings) {
  validate(setup);
  if (settings.paths < 2) throw RuntimeError("slab Monte Carlo: paths must be at least 2");
  if (settings.max_order < 1) throw RuntimeError("slab Monte Carlo: max_order must be at least 1");
  const Geometry geo = geometry(setup);
  SlabMcResult result;
  result.paths = settings.paths;
  result.order.assign(kOrders, {});
  if (!geo.sees_water) return result;  // the camera ray sees the sky: nothing from the water

  const int64_t n = settings.paths;
  std::vector<std::array<double, 2 * kTallies>> chunk(kChunks);
  tbb::parallel_for(int64_t(0), kChunks, [&](int64_t ci) {
    std::array<double, 2 * kTallies> acc{};
    const int64_t begin = n * ci / kChunks, end = n * (ci + 1) / kChunks;
    for (int64_t p = begin; p < end; ++p) {
      PathRng rng{settings.seed, static_cast<uint64_t>(p)};
      double score[kTallies] = {};
      tracePath(setup, geo, settings, rng, score);
      for (int t = 0; t < kTallies; ++t) {
        acc[t] += score[t];
        acc[kTallies + t] += score[t] * score[t];
      }
    }
    chunk[ci] = acc;
  });
  // The chunks are contiguous ranges of independent paths: the standard errors come from the spread of
  // their means (reference/batch_error.h), honest where a few rare paths carry the tally.
  BatchMeans blocks(kTallies);
  for (int64_t ci = 0; ci < kChunks; ++ci) {
    const int64_t m = n * (ci + 1) / kChunks - n * ci / kChunks;
    if (m < 1) continue;
    double mean[kTallies], m2[kTallies];
    for (int t = 0; t < kTallies; ++t) {
      mean[t] = chunk[ci][t] / double(m);
      m2[t] = std::max(0.0, chunk[ci][kTallies + t] - chunk[ci][t] * mean[t]);
    }
    blocks.addBlock(mean, m2, m);
  }
  auto estimateOf = [&](int t) {
    const BatchEstimate b = blocks.estimate(static_cast<size_t>(t));
    SlabMcEstimate e;
    e.mean = b.mean;
    e.std_error = b.blocks > 1 ? b.std_error : b.sample_std_error;
    e.sample_std_error = b.sample_std_error;
    return e;
  };
  for (int o = 0; o < kOrders; ++o) result.order[o] = estimateOf(o);
  result.orders_3plus = estimateOf(kOrders3Plus);
  result.all_orders = estimateOf(kAll);
  result.bottom_direct = estimateOf(kBottomDirect);
  result.bottom_other = estimateOf(kBottomOther);
  return result;
}

namespace {

double singleScattering(const SlabMcSetup& s, bool with_c_f) {
  validate(s);
  const Geometry geo = geometry(s);
  if (!geo.sees_water || !geo.sun_up) return 0;
  const double c = s.a + s.b, albedo = c > 0 ? s.b / c : 0.0;
  const double phase = k::hg_phase(k::dot(geo.sun, -geo.view), s.g);
  const double c_f = with_c_f ? k::hg_forward_fraction(s.g) : 0.0;
  return k::sea_single_scattering(geo.e_h, geo.t_in, geo.t_out, s.b * phase, c, albedo, c_f, geo.cos_io, geo.cos_ji,
                                  s.bottom_depth);
}

}  // namespace

double slabExactSingle(const SlabMcSetup& setup) { return singleScattering(setup, false); }

double slabPaperSingle(const SlabMcSetup& setup) { return singleScattering(setup, true); }

double slabBottomDirect(const SlabMcSetup& setup) {
  validate(setup);
  const Geometry geo = geometry(setup);
  if (!geo.sees_water || !geo.sun_up || setup.bottom_depth < 0) return 0;
  return k::sea_bottom_reflection(geo.e_h, geo.t_in, geo.t_out, setup.bottom_albedo, setup.a + setup.b,
                                  setup.bottom_depth, geo.cos_io, geo.cos_ji);
}

SlabMcSetup slabSetupFromScene(const Scene& scene, int px, int py, int band) {
  if (!scene.water.present || scene.camera.position.y <= 0) {
    throw RuntimeError("slab Monte Carlo: scenes seen from above the water only");
  }
  if (scene.surface.type != SurfaceDesc::Type::Flat || scene.bottom.type == BottomDesc::Type::HeightField) {
    throw RuntimeError("slab Monte Carlo: a flat surface and a flat or no bottom only");
  }
  const CameraDesc& cam = scene.camera;
  if (px < 0 || py < 0 || px >= cam.width || py >= cam.height) {
    throw RuntimeError("slab Monte Carlo: pixel outside the image");
  }
  const WavelengthGrid grid = makeGrid(scene.spectral.count, scene.spectral.min_nm, scene.spectral.max_nm);
  if (band < 0 || band >= static_cast<int>(grid.centers_nm.size())) {
    throw RuntimeError("slab Monte Carlo: band outside the scene's wavelength grid");
  }
  const BandOptics water = resolveWater(scene.water, grid);
  const std::vector<double> sun_e = sunIrradianceBands(grid, scene.sun.irradiance);

  SlabMcSetup s;
  s.sun_zenith = scene.sun.enabled ? scene.sun.zenith : M_PI;  // disabled: below the horizon
  s.sun_azimuth = scene.sun.azimuth;
  s.sun_irradiance = sun_e[band];
  const Vec3 fwd = normalize(cam.look_at - cam.position);
  const Vec3 right = normalize(cross(fwd, cam.up));
  const Vec3 up = cross(right, fwd);
  const double tan_half = std::tan(cam.fov_y / 2), aspect = double(cam.width) / cam.height;
  const double u = (2.0 * (px + 0.5) / cam.width - 1.0) * tan_half * aspect;
  const double v = (1.0 - 2.0 * (py + 0.5) / cam.height) * tan_half;
  s.view = normalize(fwd + right * u + up * v);
  s.ior = scene.water.ior;
  s.a = water.a[band];
  s.b = water.b[band];
  s.g = scene.water.g;
  if (scene.bottom.type == BottomDesc::Type::Flat) {
    s.bottom_depth = scene.bottom.depth;
    s.bottom_albedo = scene.bottom.albedo.at(grid.centers_nm[band]);
  }
  return s;
}

}  // namespace seasim
