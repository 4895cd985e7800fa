// sea_bottom_test.cpp — kernels/common/sea_bottom.h (000 §5.4) in float and double: the ray–height-field
// intersection against brute-force fine stepping over an independent bilinear evaluation, exact
// answers on a constant and a tilted floor, the stiff cases (start under the floor, floor touching
// the surface, grazing and horizontal rays, rays outside the square), the tilted-floor eq. 9, eq. 7
// with table path lengths against the flat-floor radiance map, the table nodes, and the planes'
// share above a pixel's floor.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <type_traits>
#include <vector>

#include "math/kernel_math.h"

namespace {

namespace kd = seasim::kmath_d;
namespace kf = seasim::kmath_f;

// The same header in both precisions behind one interface, so every check runs twice.
struct Float {
  using real3 = kf::real3;
  static constexpr const char* name = "float";
  static int hit(const SeaHeightField& hf, const std::vector<float>& d, double ox, double oy, double oz, double dx,
                 double dy, double dz, double t_max, double* t, double n[3]) {
    float th;
    kf::real3 nn;
    const int r = kf::sea_hf_intersect(&hf, d.data(), kf::real3{float(ox), float(oy), float(oz)},
                                       kf::real3{float(dx), float(dy), float(dz)}, float(t_max), &th, &nn);
    *t = th;
    n[0] = nn.x, n[1] = nn.y, n[2] = nn.z;
    return r;
  }
};
struct Double {
  static constexpr const char* name = "double";
  static int hit(const SeaHeightField& hf, const std::vector<float>& d, double ox, double oy, double oz, double dx,
                 double dy, double dz, double t_max, double* t, double n[3]) {
    kd::real3 nn;
    const int r = kd::sea_hf_intersect(&hf, d.data(), kd::real3{ox, oy, oz}, kd::real3{dx, dy, dz}, t_max, t, &nn);
    n[0] = nn.x, n[1] = nn.y, n[2] = nn.z;
    return r;
  }
};

SeaHeightField makeField(int nx, int ny, double extent, const std::vector<float>& depth) {
  SeaHeightField hf{};
  hf.nx = nx;
  hf.ny = ny;
  hf.extent = float(extent);
  hf.min_depth = *std::min_element(depth.begin(), depth.end());
  hf.max_depth = *std::max_element(depth.begin(), depth.end());
  hf.max_cells = 8 * (nx + ny) + 64;
  return hf;
}

// Independent bilinear floor depth with the border extended (written from the header's doc, not its code).
double floorDepth(const SeaHeightField& hf, const std::vector<float>& d, double x, double z) {
  const double gx = (x / hf.extent + 0.5) * (hf.nx - 1), gz = (z / hf.extent + 0.5) * (hf.ny - 1);
  const double cx = std::clamp(gx, 0.0, double(hf.nx - 1)), cz = std::clamp(gz, 0.0, double(hf.ny - 1));
  const int i = std::min(int(std::floor(cx)), hf.nx - 2), j = std::min(int(std::floor(cz)), hf.ny - 2);
  const double u = cx - i, v = cz - j;
  auto at = [&](int a, int b) { return double(d[size_t(b) * hf.nx + a]); };
  return (1 - u) * (1 - v) * at(i, j) + u * (1 - v) * at(i + 1, j) + (1 - u) * v * at(i, j + 1) + u * v * at(i + 1, j + 1);
}

// First t in [0, t_max] where the ray is on or under the floor, by steps of `step` m and bisection;
// -1 when none. The ray enters from above (or starts under: 0).
double bruteForceHit(const SeaHeightField& hf, const std::vector<float>& d, const double o[3], const double dir[3],
                     double t_max, double step) {
  auto f = [&](double t) { return floorDepth(hf, d, o[0] + t * dir[0], o[2] + t * dir[2]) + (o[1] + t * dir[1]); };
  if (f(0) <= 0) return 0;
  double prev = 0;
  for (double t = step;; t += step) {
    const double tt = std::min(t, t_max);
    if (f(tt) <= 0) {
      double lo = prev, hi = tt;
      for (int k = 0; k < 80; ++k) {
        const double mid = 0.5 * (lo + hi);
        (f(mid) > 0 ? lo : hi) = mid;
      }
      return hi;
    }
    if (tt >= t_max) return -1;
    prev = tt;
  }
}

// A smooth random floor from 1 to 20 m over 40 m: a shelf plus bumps.
std::vector<float> randomFloor(int nx, int ny, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<float> d(size_t(nx) * ny);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      d[size_t(j) * nx + i] = float(std::clamp(10.0 + 6.0 * double(j) / (ny - 1) - 3.0 + 3.0 * std::sin(0.9 * i) *
                                                   std::cos(0.7 * j) + 2.0 * u(rng),
                                               1.0, 20.0));
  return d;
}

struct Case {
  double o[3], dir[3], t_max, expect;
};

// 600 random rays in and around the square, up and down, with their brute-force answers (computed
// once for both precisions). Upwards the surface ends the ray (as for the depth tables); downwards
// the deepest node does.
const std::vector<Case>& bruteForceCases(const SeaHeightField& hf, const std::vector<float>& d) {
  static const std::vector<Case> cases = [&] {
    std::vector<Case> out;
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1, 1), u01(0, 1);
    while (out.size() < 600) {
      Case c{{30 * u(rng), -6.0 * u01(rng), 30 * u(rng)}, {u(rng), u(rng), u(rng)}, 0, 0};
      const double len = std::sqrt(c.dir[0] * c.dir[0] + c.dir[1] * c.dir[1] + c.dir[2] * c.dir[2]);
      if (len < 0.1 || std::fabs(c.dir[1]) < 0.02 * len) continue;  // near-horizontal: stiffCases
      for (double& x : c.dir) x /= len;
      c.t_max = c.dir[1] > 0 ? -c.o[1] / c.dir[1] : 1e6;
      const double t_deep = c.dir[1] < 0 ? (hf.max_depth + c.o[1]) / -c.dir[1] + 1e-3 : c.t_max;
      c.expect = bruteForceHit(hf, d, c.o, c.dir, std::min(c.t_max, t_deep), 2e-3);
      out.push_back(c);
    }
    return out;
  }();
  return cases;
}

template <class K>
void matchesBruteForce() {
  const int nx = 17, ny = 13;
  const std::vector<float> d = randomFloor(nx, ny, 7);
  const SeaHeightField hf = makeField(nx, ny, 40.0, d);
  int hits = 0, misses = 0;
  double worst = 0;
  const std::vector<Case>& cases = bruteForceCases(hf, d);
  for (size_t r = 0; r < cases.size(); ++r) {
    const double *o = cases[r].o, *dir = cases[r].dir;
    const double t_max = cases[r].t_max, expect = cases[r].expect;
    double t, n[3];
    const int got = K::hit(hf, d, o[0], o[1], o[2], dir[0], dir[1], dir[2], t_max, &t, n);
    ASSERT_EQ(got == 1, expect >= 0) << K::name << " ray " << r << " brute " << expect << " dda " << t;
    ASSERT_TRUE(std::isfinite(t) && std::isfinite(n[0]) && std::isfinite(n[1]) && std::isfinite(n[2]));
    if (got) {
      ++hits;
      worst = std::max(worst, std::fabs(t - expect));
      // The normal is the bilinear patch's: (dh/dx, 1, dh/dz) normalised, by central differences.
      const double x = o[0] + t * dir[0], z = o[2] + t * dir[2], e = 1e-4;
      const double hx = (floorDepth(hf, d, x + e, z) - floorDepth(hf, d, x - e, z)) / (2 * e);
      const double hz = (floorDepth(hf, d, x, z + e) - floorDepth(hf, d, x, z - e)) / (2 * e);
      const double nl = std::sqrt(hx * hx + 1 + hz * hz);
      // Away from cell walls (where the one-sided slopes differ) the normal matches to 1e-3.
      const double fx = (x / 40.0 + 0.5) * (nx - 1), fz = (z / 40.0 + 0.5) * (ny - 1);
      const bool interior = std::fabs(fx - std::round(fx)) > 1e-2 && std::fabs(fz - std::round(fz)) > 1e-2;
      if (interior && t > 0) {
        EXPECT_NEAR(n[0], hx / nl, 2e-3) << K::name << " ray " << r;
        EXPECT_NEAR(n[1], 1 / nl, 2e-3) << K::name << " ray " << r;
        EXPECT_NEAR(n[2], hz / nl, 2e-3) << K::name << " ray " << r;
      }
    } else {
      ++misses;
      EXPECT_NEAR(t, t_max, 1e-6 * t_max) << K::name;
    }
  }
  std::printf("%s: %d hits, %d misses, max |t - brute force| = %.3g m\n", K::name, hits, misses, worst);
  EXPECT_GT(hits, 300);
  EXPECT_GT(misses, 20);
  // Brute force brackets to 2 mm then bisects to rounding; float t carries ~1e-5 relative.
  const double tolerance = std::is_same_v<K, Float> ? 2e-3 : 1e-6;
  EXPECT_LT(worst, tolerance);
}

TEST(SeaBottom, IntersectionMatchesBruteForceStepping) {
  matchesBruteForce<Double>();
  matchesBruteForce<Float>();
}

template <class K>
void exactFloors() {
  // Constant floor at 8 m: every ray going down meets it at t = (8 - d0) / -dir.y, normal +y.
  const std::vector<float> flat(5 * 4, 8.0f);
  const SeaHeightField hf = makeField(5, 4, 20.0, flat);
  for (double dy : {-1.0, -0.7, -0.2, -0.01}) {
    const double dx = std::sqrt(1 - dy * dy);
    double t, n[3];
    ASSERT_EQ(K::hit(hf, flat, 1.0, -0.5, -2.0, dx * 0.6, dy, dx * 0.8, 1e30, &t, n), 1);
    EXPECT_NEAR(t, 7.5 / -dy, 2e-6 * 7.5 / -dy) << K::name << " dy " << dy;
    EXPECT_EQ(n[0], 0.0);
    EXPECT_EQ(n[1], 1.0);
    EXPECT_EQ(n[2], 0.0);
  }
  // Tilted plane h = 10 + 0.25 x (nodes exactly on it): hit of o + t dir solves d0 + dd t = 10 + 0.25 x(t).
  const int nx = 9, ny = 3;
  std::vector<float> tilt(nx * ny);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) tilt[j * nx + i] = float(10.0 + 0.25 * (-16.0 + 32.0 * i / (nx - 1)));
  const SeaHeightField ht = makeField(nx, ny, 32.0, tilt);
  for (double dx : {-0.8, -0.3, 0.0, 0.4, 0.6}) {  // hits inside the square (beyond it the floor is flat)
    const double dy = -std::sqrt(1 - dx * dx);
    double t, n[3];
    ASSERT_EQ(K::hit(ht, tilt, 2.0, -1.0, 3.0, dx, dy, 0.0, 1e30, &t, n), 1);
    const double expect = (10.0 + 0.25 * 2.0 - 1.0) / (-dy - 0.25 * dx);
    EXPECT_NEAR(t, expect, 1e-5 * expect) << K::name << " dx " << dx;
    const double nl = std::sqrt(1 + 0.0625);
    EXPECT_NEAR(n[0], 0.25 / nl, 1e-6) << K::name;
    EXPECT_NEAR(n[1], 1 / nl, 1e-6) << K::name;
  }
}

TEST(SeaBottom, ConstantAndTiltedFloorsAreExact) {
  exactFloors<Double>();
  exactFloors<Float>();
}

template <class K>
void stiffCases() {
  const int nx = 17, ny = 13;
  std::vector<float> d = randomFloor(nx, ny, 3);
  d[6 * nx + 8] = 0.0f;  // a rock reaching the surface: the floor touches y = 0
  const SeaHeightField hf = makeField(nx, ny, 40.0, d);
  ASSERT_EQ(hf.min_depth, 0.0f);
  double t, n[3];
  // Start on the rock's top (depth 0 at x = z = 0): a hit at t = 0 in every direction.
  for (double dy : {-1.0, -0.3, 0.0, 0.5}) {
    const double dx = std::sqrt(1 - dy * dy);
    ASSERT_EQ(K::hit(hf, d, 0.0, 0.0, 0.0, dx, dy, 0.0, 10.0, &t, n), 1) << K::name;
    EXPECT_EQ(t, 0.0);
  }
  // Start under the floor (25 m, deeper than every node): a hit at t = 0.
  ASSERT_EQ(K::hit(hf, d, 3.0, -25.0, 1.0, 0.0, -1.0, 0.0, 1e30, &t, n), 1);
  EXPECT_EQ(t, 0.0);
  // Horizontal and grazing rays at 0.5 m: finite answers, bounded walks, whichever way they go.
  for (double dy : {0.0, -1e-6, -1e-3, 1e-3}) {
    for (double az = 0; az < 6.28; az += 0.7) {
      const double h = std::sqrt(1 - dy * dy);
      const double t_max = dy > 0 ? 0.5 / dy : 1e30;
      const int r = K::hit(hf, d, -10.0, -0.5, 5.0, h * std::cos(az), dy, h * std::sin(az), t_max, &t, n);
      EXPECT_TRUE(std::isfinite(t) && t >= 0) << K::name << " dy " << dy << " az " << az;
      EXPECT_TRUE(std::isfinite(n[0] + n[1] + n[2]));
      if (r) EXPECT_LE(floorDepth(hf, d, -10.0 + t * h * std::cos(az), 5.0 + t * h * std::sin(az)) - (0.5 - dy * t), 1e-3);
    }
  }
  // A vertical ray crosses no cell walls; straight down onto the rock's flank.
  ASSERT_EQ(K::hit(hf, d, 1.0, 0.0, 0.5, 0.0, -1.0, 0.0, 1e30, &t, n), 1);
  EXPECT_NEAR(t, floorDepth(hf, d, 1.0, 0.5), 1e-5 * 20);
  // Far outside the square the border extends: a ray at x = 500 m meets the clamped edge depth.
  ASSERT_EQ(K::hit(hf, d, 500.0, 0.0, 0.0, 0.0, -1.0, 0.0, 1e30, &t, n), 1);
  EXPECT_NEAR(t, floorDepth(hf, d, 20.0, 0.0), 1e-4);
  // Upwards from above every node: never a hit, t = t_max.
  EXPECT_EQ(K::hit(makeField(nx, ny, 40.0, randomFloor(nx, ny, 3)), randomFloor(nx, ny, 3), 0.0, -0.5, 0.0, 0.6, 0.8,
                   0.0, 0.625, &t, n),
            0);
  EXPECT_NEAR(t, 0.625, 1e-7);
}

TEST(SeaBottom, StiffCasesGiveFiniteAnswers) {
  stiffCases<Double>();
  stiffCases<Float>();
}

TEST(SeaBottom, TiltedBottomReflectionIsEquation9WithTheLocalCosine) {
  // cos(gamma) = cos(theta_io) is the flat floor exactly; the tilted floor scales by cos_gamma/cos_io.
  for (double z : {0.0, 1.0, 40.0}) {
    const double flat = kd::sea_bottom_reflection(1.2, 0.97, 0.98, 0.3, 0.4, z, 0.8, 0.9);
    EXPECT_DOUBLE_EQ(kd::sea_bottom_reflection_tilted(1.2, 0.97, 0.98, 0.3, 0.4, z, 0.8, 0.9, 0.8), flat);
    EXPECT_NEAR(kd::sea_bottom_reflection_tilted(1.2, 0.97, 0.98, 0.3, 0.4, z, 0.8, 0.9, 0.4), 0.5 * flat, 1e-15);
    EXPECT_NEAR(kf::sea_bottom_reflection_tilted(1.2f, 0.97f, 0.98f, 0.3f, 0.4f, float(z), 0.8f, 0.9f, 0.8f), flat,
                1e-6 * flat + 1e-30);
    EXPECT_EQ(kd::sea_bottom_reflection_tilted(1.2, 0.97, 0.98, 0.3, 0.4, z, 0.8, 0.9, 0.0), 0.0);
  }
}

TEST(SeaBottom, TablePathRadianceIsTheFlatRadianceMap) {
  // With l = tau_k / cos(theta) upwards and (tau_d - tau_k)/|cos(theta)| downwards, eq. 7 by path
  // length is sea_radiance_map exactly, including the 0/0 at cos(theta) = cos(theta_io).
  const double e = 1.5, albedo = 0.7, phase = 0.25, tau_d = 4.0;
  for (double cos_io : {1.0, 0.8, 0.66}) {
    for (double cos_theta : {0.99, 0.8, 0.3, 0.02, -0.02, -0.5, -1.0}) {
      for (double tau_k : {0.0, 0.3, 2.0, 3.99}) {
        const double l = cos_theta > 0 ? tau_k / cos_theta : (tau_d - tau_k) / -cos_theta;
        const double flat = kd::sea_radiance_map(e, albedo, phase, cos_io, cos_theta, tau_k, tau_d);
        EXPECT_NEAR(kd::sea_radiance_map_path(e, albedo, phase, cos_io, cos_theta, tau_k, l), flat, 1e-13 * flat + 1e-300);
        const float ff = kf::sea_radiance_map_path(float(e), float(albedo), float(phase), float(cos_io),
                                                   float(cos_theta), float(tau_k), float(l));
        EXPECT_NEAR(ff, flat, 2e-5 * flat + 1e-30);
        EXPECT_TRUE(std::isfinite(ff));
      }
    }
  }
  // A sampling ray that ends at once (the floor right there) carries nothing; negative l is clamped.
  EXPECT_EQ(kd::sea_radiance_map_path(e, albedo, phase, 0.8, -0.5, 1.0, 0.0), 0.0);
  EXPECT_EQ(kf::sea_radiance_map_path(1.5f, 0.7f, 0.25f, 0.8f, -0.5f, 1.0f, -1e-3f), 0.0f);
}

// The scattering map's vector lanes (sea_bottom_lanes.h, one lane per direction on the host) against the
// scalar sea_path_integral's finite path: across the switch at |κ l| = 1/2, at κ l = 0 (cos θ = cos θ_io),
// deep planes where e^{-a} underflows, and long paths towards the surface (κ < 0).
TEST(SeaBottom, PathIntegralLanesAreTheScalarFinitePath) {
  double worst_d = 0, worst_f = 0;
  for (double a : {0.0, 0.01, 0.7, 5.0, 40.0, 95.0}) {
    for (double kappa : {-2.5, -0.5, -0.02, 0.0, 1e-7, 0.3, 0.5, 1.0, 2.0}) {
      for (double l : {0.0, 1e-6, 0.2, 0.999, 1.0, 1.001, 3.0, 30.0}) {
        if (a + kappa * l < 0) continue;  // the path's far end above the surface: not a sampling ray
        const double ref = kd::sea_path_integral(a, kappa, l);
        const double d = kd::sea_path_integral_finite_b(std::exp(-a), a, kappa, kappa != 0 ? 1 / kappa : 0.0, l);
        const float f = kf::sea_path_integral_finite_b(std::exp(-float(a)), float(a), float(kappa),
                                                       kappa != 0 ? 1 / float(kappa) : 0.0f, float(l));
        ASSERT_TRUE(std::isfinite(d) && std::isfinite(f) && f >= 0) << a << " " << kappa << " " << l;
        worst_d = std::max(worst_d, std::fabs(d - ref) / (ref + 1e-300));
        if (ref > 1e-30) worst_f = std::max(worst_f, std::fabs(f - ref) / ref);
        else EXPECT_LE(f, 1e-30);
      }
    }
  }
  std::printf("[ measured ] path integral, lanes vs scalar: max rel %.2e (double), %.2e (float)\n", worst_d, worst_f);
  EXPECT_LE(worst_d, 1e-13);
  EXPECT_LE(worst_f, 2e-5);
}

// The accumulation's vector lanes (sea_bottom_lanes.h, one lane per band on the host) against the scalar
// sea_plane_share_above: floors above, inside and below each plane's cell, at the surface, and no water.
TEST(SeaBottom, PlaneShareLanesAreTheScalarShare) {
  for (int n_z : {1, 5, 12}) {
    for (int k = 0; k < n_z; ++k) {
      for (double cos_io : {1.0, 0.8, 0.66}) {
        for (double tau_d : {0.0, 1e-6, 0.3, 4.0, 60.0}) {
          for (double frac : {0.0, 1e-4, 0.2, 0.5, 0.93, 1.0, 3.0}) {
            const double tau_q = frac * tau_d;
            const double ref = kd::sea_plane_share_above(k, n_z, cos_io, tau_d, tau_q);
            EXPECT_NEAR(kd::sea_plane_share_above_b(k, n_z, cos_io, tau_d, tau_q), ref, 1e-12);
            const float f = kf::sea_plane_share_above_b(k, n_z, float(cos_io), float(tau_d), float(tau_q));
            EXPECT_NEAR(f, kf::sea_plane_share_above(k, n_z, float(cos_io), float(tau_d), float(tau_q)), 1e-6);
            EXPECT_TRUE(f >= 0.0f && f <= 1.0f);
          }
        }
      }
    }
  }
  EXPECT_EQ(kd::sea_plane_share_above_b(3, 12, 0.8, 0.0, 0.0), 0.0);  // no water: the planes weigh nothing
}

TEST(SeaBottom, TableNodesSpanTheWaterAndInvert) {
  for (double c_ref : {1e-6, 0.05, 0.5, 5.0}) {
    for (int n_z : {1, 4, 12}) {
      const double cos_io = 0.75, z_max = 40.0;
      EXPECT_EQ(kd::sea_table_node_depth(0, n_z, cos_io, c_ref, z_max), 0.0);
      EXPECT_EQ(kd::sea_table_node_depth(n_z, n_z, cos_io, c_ref, z_max), z_max);
      double prev = -1;
      for (int t = 0; t <= n_z; ++t) {
        const double z = kd::sea_table_node_depth(t, n_z, cos_io, c_ref, z_max);
        EXPECT_GT(z, prev);
        prev = z;
        double w;
        const int at = kd::sea_table_node_interval(z, n_z, cos_io, c_ref, z_max, &w);
        EXPECT_NEAR(at + w, double(t), 1e-6) << "c_ref " << c_ref << " n_z " << n_z << " t " << t;
        float wf;
        const int atf = kf::sea_table_node_interval(float(z), n_z, float(cos_io), float(c_ref), float(z_max), &wf);
        EXPECT_NEAR(atf + wf, double(t), 2e-3);
      }
      // A depth between nodes is read linearly in depth; beyond the deepest node, clamped.
      double w;
      const int at = kd::sea_table_node_interval(1e3, n_z, cos_io, c_ref, z_max, &w);
      EXPECT_EQ(at, n_z - 1);
      EXPECT_EQ(w, 1.0);
    }
  }
  // The planes of a band with c = c_ref lie half-way (in transmittance) between nodes.
  const double cos_io = 0.8, c = 0.3, z_max = 25.0;
  for (int k = 0; k < 12; ++k) {
    double w;
    const double z_k = kd::sea_plane_depth(k, 12, cos_io, c * z_max, &w) / c;
    EXPECT_GT(z_k, kd::sea_table_node_depth(k, 12, cos_io, c, z_max));
    EXPECT_LT(z_k, kd::sea_table_node_depth(k + 1, 12, cos_io, c, z_max));
  }
}

// The patch root's closed form against a long double bisection of the same (rounded) quadratic: random
// brackets as sea_hf_intersect makes them (f(0) > 0 >= f(ts), monotone on [0, ts]), with f2 = 0, both signs of
// f2, roots at either end of the bracket and a near-double root just past it (a grazing ray). The answer must be on
// or just under the floor (f <= 0) and as close to the root as the precision's own 48-step bisection comes, or
// within `step` of the bracket (near a double root, where neither method is well-conditioned, by their worst
// cases); -1 (the caller bisects) must be rare.
template <class Real, class Root>
void patchRootMatchesBisection(const char* name, Root root, double step) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int fallbacks = 0, n = 0;
  double worst = 0, worst_bisect = 0, worst_near = 0, worst_near_bisect = 0;
  for (int c = 0; c < 20000; ++c) {
    const double ts = 0.01 + 2.0 * u(rng), r = ts * (c % 50 == 0 ? 1.0 : c % 50 == 1 ? 1e-6 : u(rng));
    // f(tau) = k (tau - r)(tau - s) with s outside [0, ts] (monotone on it), or f2 = 0 (every eighth).
    const int kind = c % 8;
    const double k = 0.1 + 5 * u(rng);
    double f0, f1, f2;
    if (kind == 0) {
      f2 = 0, f1 = -k, f0 = k * r;
    } else {
      const double s = kind == 1 ? -1e6 : kind == 2 ? ts * (1 + 1e-3) : kind % 2 ? -ts * (0.01 + 3 * u(rng))
                                                                               : ts * (1.01 + 3 * u(rng));
      const double sign = s > ts ? 1.0 : -1.0;  // f(0) = k r s > 0 needs k of the sign of s
      f2 = sign * k, f1 = -sign * k * (r + s), f0 = sign * k * r * s;
    }
    const Real F0 = Real(f0), F1 = Real(f1), F2 = Real(f2), TS = Real(ts);
    auto f = [&](long double t) { return (long double)F0 + t * ((long double)F1 + t * (long double)F2); };
    if (!(F0 > 0) || f(TS) > 0) continue;  // rounding of the coefficients left the bracket open
    long double lo = 0, hi = TS;
    for (int it = 0; it < 200; ++it) {
      const long double mid = (lo + hi) / 2;
      (f(mid) > 0 ? lo : hi) = mid;
    }
    Real b_lo = 0, b_hi = TS;  // the working precision's own bisection, as sea_hf_intersect did it
    for (int it = 0; it < 48; ++it) {
      const Real mid = Real(0.5) * (b_lo + b_hi);
      (F0 + mid * (F1 + mid * F2) > 0 ? b_lo : b_hi) = mid;
    }
    ++n;
    const double e_bisect = std::fabs(double(b_hi) - double(hi)) / ts;
    worst_bisect = std::max(worst_bisect, e_bisect);
    const Real tau = root(F0, F1, F2, TS);
    if (tau < 0) {
      ++fallbacks;
      continue;
    }
    EXPECT_LE(double(F0 + tau * (F1 + tau * F2)), 0.0) << name << " case " << c;
    const double e = std::fabs(double(tau) - double(hi)) / ts;
    if (kind == 2) {  // a near-double root: ill-conditioned, for either method; compared by the worst case below
      worst_near = std::max(worst_near, e);
      worst_near_bisect = std::max(worst_near_bisect, e_bisect);
    } else {
      EXPECT_LE(e, std::max(step, 2 * e_bisect)) << name << " case " << c << " kind " << kind;
    }
    worst = std::max(worst, e);
  }
  EXPECT_LE(worst_near, 1.5 * worst_near_bisect) << name;
  std::printf("%s: %d brackets, %d to bisect, max |tau - root| = %.3g of the bracket (the 48-step bisection's %.3g)\n",
              name, n, fallbacks, worst, worst_bisect);
  EXPECT_GT(n, 15000);
  EXPECT_LT(fallbacks, n / 100);
}

TEST(SeaBottom, PatchRootIsTheBracketsRootOnOrUnderTheFloor) {
  patchRootMatchesBisection<double>("double", [](double a, double b, double c, double t) {
    return kd::sea_hf_patch_root(a, b, c, t);
  }, 2e-13);
  patchRootMatchesBisection<float>("float", [](float a, float b, float c, float t) {
    return kf::sea_hf_patch_root(a, b, c, t);
  }, 2e-6);
}

TEST(SeaBottom, PlaneSharesAboveTheFloor) {
  const int n_z = 12;
  const double cos_io = 0.8, tau_d = 6.0;
  for (int k = 0; k < n_z; ++k) {
    EXPECT_EQ(kd::sea_plane_share_above(k, n_z, cos_io, tau_d, tau_d), 1.0);  // the flat floor
    EXPECT_EQ(kd::sea_plane_share_above(k, n_z, cos_io, tau_d, 100.0), 1.0);
    EXPECT_EQ(kd::sea_plane_share_above(k, n_z, cos_io, tau_d, 0.0), 0.0);   // floor at the surface
    EXPECT_EQ(kf::sea_plane_share_above(k, n_z, 0.8f, 6.0f, 6.0f), 1.0f);
  }
  // Empty cells (tau_d = 0: c = 0, or the floor at the surface everywhere): 0, never 0/0.
  EXPECT_EQ(kd::sea_plane_share_above(3, n_z, cos_io, 0.0, 0.0), 0.0);
  EXPECT_EQ(kf::sea_plane_share_above(3, n_z, 0.8f, 0.0f, 1.0f), 0.0f);
  double w = -1;
  EXPECT_EQ(kd::sea_table_node_interval(0.5, n_z, cos_io, 0.3, 0.0, &w), 0);
  EXPECT_EQ(w, 0.0);
  EXPECT_EQ(kd::sea_table_node_depth(4, n_z, cos_io, 0.3, 0.0), 0.0);
  // The shares weight the planes' quadrature into int_0^{tau_q} of a smooth integrand.
  const double s = 1 + 1 / cos_io;
  for (double tau_q : {0.05, 0.4, 1.3, 3.0}) {
    double sum = 0;
    for (int k = 0; k < 96; ++k) {
      double w;
      const double tau = kd::sea_plane_depth(k, 96, cos_io, tau_d, &w);
      sum += w * kd::sea_plane_share_above(k, 96, cos_io, tau_d, tau_q) * std::exp(-s * tau);
    }
    const double exact = (1 - std::exp(-s * tau_q)) / s;
    EXPECT_NEAR(sum, exact, 2e-3 * exact) << "tau_q " << tau_q;
  }
}

}  // namespace
