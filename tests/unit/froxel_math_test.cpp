// froxel_math_test.cpp — the froxel single scattering math (kernels/common/froxel.h, 002 §5.1 eq. 5.2)
// and the scrolling caustic textures (kernels/common/caustic_texture.h, 002 §5.3) in float and double:
// slice boundaries and look-up of the exponential slicing, the per-slice integral against the exact
// one of a uniform medium (rays level, down and rising to the surface: exact for any slice count), the
// in-slice read, stiff optical depths, the caustic modulation's periodicity, unit mean, range and
// finiteness, and the footprint filter on its integral scale.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "math/kernel_math.h"

namespace {

namespace kd = seasim::kmath_d;
namespace kf = seasim::kmath_f;

// ---- caustics ----

// Spatial mean of the modulation over one tile (period 4 m), midpoint samples n².
template <typename F>
double tileMean(F modulation, double time, int n) {
  double sum = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) sum += modulation(4.0 * (i + 0.5) / n, 4.0 * (j + 0.5) / n, time);
  return sum / (double(n) * n);
}

TEST(CausticTexture, MeanIsOneAtEveryTime) {
  // Measured (caustic_texture.h): mean over 64 times 1.0000, spread -0.4 % … +0.5 %. 512² samples
  // resolve the lines (≈ 5 samples per line width at 32 cells per tile): sampling error < 0.1 %.
  for (double t : {0.0, 1.7, 17.3, 123.4, 1000.0}) {
    const double md = tileMean([](double x, double z, double t) { return kd::caustic_modulation(x, z, t, 4.0, 0.5); },
                               t, 512);
    const double mf = tileMean(
        [](double x, double z, double t) { return double(kf::caustic_modulation(float(x), float(z), float(t), 4.0f, 0.5f)); },
        t, 512);
    EXPECT_NEAR(md, 1.0, 0.01) << "t = " << t;
    EXPECT_NEAR(mf, 1.0, 0.01) << "t = " << t;
    std::printf("caustic tile mean at t = %7.1f s: double %.5f float %.5f\n", t, md, mf);
  }
}

TEST(CausticTexture, PeriodicOnTheTile) {
  for (int k = 0; k < 400; ++k) {
    const double x = -7.3 + 0.731 * k, z = 2.9 - 0.377 * k, t = 0.13 * k;
    const double v = kd::caustic_modulation(x, z, t, 4.0, 0.5);
    EXPECT_NEAR(kd::caustic_modulation(x + 4.0, z, t, 4.0, 0.5), v, 1e-9);
    EXPECT_NEAR(kd::caustic_modulation(x, z - 8.0, t, 4.0, 0.5), v, 1e-9);
    // Float: x/period rounds at ~2e-7 of a tile (6e-6 of a cell), the texture's slope is ~40 per cell.
    const float vf = kf::caustic_modulation(float(x), float(z), float(t), 4.0f, 0.5f);
    EXPECT_NEAR(kf::caustic_modulation(float(x) + 4.0f, float(z), float(t), 4.0f, 0.5f), vf, 2e-3f);
    EXPECT_NEAR(vf, v, 2e-3);  // float against double
  }
  // The tile seam itself (u = 0 and u → 1) joins continuously.
  for (double z : {0.1, 1.3, 2.9}) {
    EXPECT_NEAR(kd::caustic_modulation(4.0 - 1e-9, z, 0.0, 4.0, 0.5), kd::caustic_modulation(0.0, z, 0.0, 4.0, 0.5), 1e-6);
    EXPECT_NEAR(kd::caustic_modulation(z, -1e-9, 0.0, 4.0, 0.5), kd::caustic_modulation(z, 0.0, 0.0, 4.0, 0.5), 1e-6);
  }
}

TEST(CausticTexture, FiniteBoundedAndMoving) {
  double lo = 1e30, hi = -1e30, changed = 0;
  int n = 0;
  for (int k = 0; k < 20000; ++k) {
    const double x = -50 + 0.0173 * k, z = 13 + 0.0091 * k;
    for (double t : {0.0, 3.0, 1e4}) {
      const double v = kd::caustic_modulation(x, z, t, 4.0, 0.5);
      const float vf = kf::caustic_modulation(float(x), float(z), float(t), 4.0f, 0.5f);
      ASSERT_TRUE(std::isfinite(v) && std::isfinite(vf));
      lo = std::min(lo, v);
      hi = std::max(hi, v);
      EXPECT_GE(vf, 0.77f);
    }
    changed += std::fabs(kd::caustic_modulation(x, z, 1.0, 4.0, 0.5) - kd::caustic_modulation(x, z, 0.0, 4.0, 0.5));
    ++n;
  }
  // [FLOOR/MEAN, 1/MEAN] = [0.775, 3.100] (caustic_texture.h).
  EXPECT_GE(lo, 0.25 / 0.32258 - 1e-6);
  EXPECT_LE(hi, 1.0 / 0.32258 + 1e-6);
  EXPECT_GT(hi, 2.5);  // the lines are there
  EXPECT_GT(changed / n, 0.05);  // and they move
  // Large coordinates and times stay finite; no period means no texture.
  EXPECT_TRUE(std::isfinite(kf::caustic_modulation(3e4f, -7e4f, 1e6f, 4.0f, 0.5f)));
  EXPECT_TRUE(std::isfinite(kd::caustic_modulation(1e12, -1e12, 1e9, 4.0, 0.5)));
  EXPECT_EQ(kd::caustic_modulation(1.0, 2.0, 3.0, 0.0, 0.5), 1.0);
  EXPECT_EQ(kf::caustic_modulation(1.0f, 2.0f, 3.0f, -1.0f, 0.5f), 1.0f);
}

// The edge distance of caustic_edge's 3×3 search with the branching F1/F2 update it replaced, as the
// reference for the branch-free one (min/max are exact: the same two values, bit for bit).
template <typename K, typename Real>
Real edgeBranching(Real u, Real v, int n, unsigned seed) {
  const Real x = u * Real(n), y = v * Real(n);
  int cx = std::clamp(int(std::floor(x)), 0, n - 1), cy = std::clamp(int(std::floor(y)), 0, n - 1);
  const Real fx = x - Real(cx), fy = y - Real(cy);
  Real f1 = Real(1e9), f2 = Real(1e9);
  for (int j = -1; j <= 1; ++j) {
    for (int i = -1; i <= 1; ++i) {
      const int wx = (cx + i + n) % n, wy = (cy + j + n) % n;
      const unsigned h = K::caustic_hash(unsigned(wx + n * wy) + seed);
      const Real px = Real(i) + Real(0.5) + Real(0.8) * (Real(h & 0xffffU) * Real(1.0 / 65536.0) - Real(0.5));
      const Real py = Real(j) + Real(0.5) + Real(0.8) * (Real(h >> 16) * Real(1.0 / 65536.0) - Real(0.5));
      const Real d2 = (px - fx) * (px - fx) + (py - fy) * (py - fy);
      if (d2 < f1) {
        f2 = f1;
        f1 = d2;
      } else if (d2 < f2) {
        f2 = d2;
      }
    }
  }
  return (std::sqrt(f2) - std::sqrt(f1)) / Real(0.15);
}

struct KfNs {
  static unsigned caustic_hash(unsigned x) { return kf::caustic_hash(x); }
};
struct KdNs {
  static unsigned caustic_hash(unsigned x) { return kd::caustic_hash(x); }
};

TEST(CausticTexture, BranchFreeSearchAndOneExpAreTheOldTexture) {
  // The branch-free F1/F2 update finds the same two distances; min(h_a, h_b) = h(max(e_a, e_b)).
  for (int k = 0; k < 20000; ++k) {
    const double u = std::fmod(0.000731 * k * k + 0.1 * k, 1.0), v = std::fmod(0.37 + 0.0137 * k, 1.0);
    for (int n : {27, 32}) {
      const unsigned seed = n == 32 ? 0U : 0x68bc21ebU;
      ASSERT_EQ(kd::caustic_edge(u, v, n, seed), (edgeBranching<KdNs, double>(u, v, n, seed))) << u << " " << v;
      EXPECT_NEAR(kf::caustic_edge(float(u), float(v), n, seed), (edgeBranching<KfNs, float>(float(u), float(v), n, seed)),
                  1e-5f);
    }
    const double x = -13 + 0.0031 * k, z = 7 - 0.0017 * k, t = 0.001 * k;
    double ua, va, ub, vb;
    kd::caustic_tile_coords(x, z, t, 4.0, 0.5, &ua, &va, &ub, &vb);
    const double two_exp = std::min(kd::caustic_texture(ua, va, 32, 0U), kd::caustic_texture(ub, vb, 27, 0x68bc21ebU));
    EXPECT_EQ(kd::caustic_modulation(x, z, t, 4.0, 0.5), two_exp / 0.32258);
  }
}

TEST(CausticTexture, TableWrapsTheTile) {
  std::vector<double> table(CAUSTIC_TABLE_REALS);
  kd::caustic_fill_table(table.data());
  EXPECT_EQ(table.size(), 2u * (34 * 34 + 29 * 29));
  for (int n : {32, 27}) {
    const double* t = table.data() + (n == 32 ? 0 : CAUSTIC_TABLE_SIZE(32));
    const int w = n + 2;
    for (int c = 0; c < w; ++c) {
      for (int q = 0; q < 2; ++q) {
        EXPECT_EQ(t[2 * (0 + w * c) + q], t[2 * (n + w * c) + q]);      // column -1 is column n - 1
        EXPECT_EQ(t[2 * (n + 1 + w * c) + q], t[2 * (1 + w * c) + q]);  // column n is column 0
        EXPECT_EQ(t[2 * (c + w * 0) + q], t[2 * (c + w * n) + q]);
        EXPECT_EQ(t[2 * (c + w * (n + 1)) + q], t[2 * (c + w * 1) + q]);
      }
    }
    for (int i = 0; i < 2 * w * w; ++i) ASSERT_LE(std::fabs(t[i]), 0.4);  // jitter within the central 80 %
  }
}

TEST(CausticTexture, TableGivesTheHashedTexture) {
  // froxel.cl reads the feature points from caustic_fill_table: double the same to rounding; float the
  // same but for the jitter product's rounding (at most an ulp of a point's position, against the
  // texture's steepest slope of ~40 per cell), and within the float-vs-double budget of PeriodicOnTheTile.
  std::vector<double> td(CAUSTIC_TABLE_REALS);
  std::vector<float> tf(CAUSTIC_TABLE_REALS);
  kd::caustic_fill_table(td.data());
  kf::caustic_fill_table(tf.data());
  double worst_d = 0, worst_f = 0, worst_fd = 0;
  for (int k = 0; k < 200000; ++k) {
    const double x = -31 + 0.000619 * k, z = 11 - 0.000233 * k + 0.05 * std::sin(0.01 * k), t = 0.00037 * k;
    const double hd = kd::caustic_modulation(x, z, t, 4.0, 0.5);
    const double ht = kd::caustic_modulation_table(x, z, t, 4.0, 0.5, td.data());
    const float hf = kf::caustic_modulation(float(x), float(z), float(t), 4.0f, 0.5f);
    const float htf = kf::caustic_modulation_table(float(x), float(z), float(t), 4.0f, 0.5f, tf.data());
    worst_d = std::max(worst_d, std::fabs(ht - hd));
    worst_f = std::max(worst_f, double(std::fabs(htf - hf)));
    worst_fd = std::max(worst_fd, std::fabs(double(htf) - hd));
  }
  std::printf("caustic table vs hash: double %.2e, float %.2e, float table vs double %.2e\n", worst_d, worst_f,
              worst_fd);
  EXPECT_LT(worst_d, 1e-12);
  EXPECT_LT(worst_f, 1e-4);
  EXPECT_LT(worst_fd, 2e-3);
  // The seam, large inputs and no period, as for the hashed texture.
  for (double z : {0.1, 1.3, 2.9})
    EXPECT_NEAR(kd::caustic_modulation_table(4.0 - 1e-9, z, 0.0, 4.0, 0.5, td.data()),
                kd::caustic_modulation_table(0.0, z, 0.0, 4.0, 0.5, td.data()), 1e-6);
  EXPECT_TRUE(std::isfinite(kf::caustic_modulation_table(3e4f, -7e4f, 1e6f, 4.0f, 0.5f, tf.data())));
  EXPECT_TRUE(std::isfinite(kd::caustic_modulation_table(1e12, -1e12, 1e9, 4.0, 0.5, td.data())));
  EXPECT_EQ(kf::caustic_modulation_table(1.0f, 2.0f, 3.0f, 0.0f, 0.5f, tf.data()), 1.0f);
  EXPECT_EQ(kd::caustic_modulation_table(1.0, 2.0, 3.0, -1.0, 0.5, td.data()), 1.0);
}

TEST(CausticTexture, LanesGiveTheScalarTexture) {
  // raycast.cl reads the texture for its 16 hits in lanes (caustic_texture_lanes.h, one lane here): the same
  // cells, hashes and arithmetic as caustic_modulation, so the same value in double and in float, across the
  // tiles' seams, at large coordinates and times, and without a period.
  double worst_d = 0, worst_f = 0;
  for (int k = 0; k < 200000; ++k) {
    const double x = -31 + 0.000619 * k, z = 11 - 0.000233 * k + 0.05 * std::sin(0.01 * k), t = 0.00037 * k;
    worst_d = std::max(worst_d, std::fabs(kd::caustic_modulation_b(x, z, t, 4.0, 0.5) -
                                          kd::caustic_modulation(x, z, t, 4.0, 0.5)));
    worst_f = std::max(worst_f, double(std::fabs(kf::caustic_modulation_b(float(x), float(z), float(t), 4.0f, 0.5f) -
                                                 kf::caustic_modulation(float(x), float(z), float(t), 4.0f, 0.5f))));
  }
  std::printf("caustic lanes vs scalar: double %.2e, float %.2e\n", worst_d, worst_f);
  EXPECT_LT(worst_d, 1e-12);
  EXPECT_LT(worst_f, 1e-5);
  for (const double x : {0.0, 4.0 - 1e-9, 4.0, -1e-9, 3e4, -7e4, 1e12})
    for (const double z : {0.1, 2.9, -1e12}) {
      EXPECT_NEAR(kd::caustic_modulation_b(x, z, 1e3, 4.0, 0.5), kd::caustic_modulation(x, z, 1e3, 4.0, 0.5), 1e-12)
          << x << " " << z;
      const float vf = kf::caustic_modulation_b(float(x), float(z), 1e3f, 4.0f, 0.5f);
      EXPECT_TRUE(std::isfinite(vf) && vf > 0.0f) << x << " " << z;
      EXPECT_NEAR(vf, kf::caustic_modulation(float(x), float(z), 1e3f, 4.0f, 0.5f), 1e-5) << x << " " << z;
    }
  EXPECT_EQ(kd::caustic_modulation_b(1.0, 2.0, 3.0, 0.0, 0.5), 1.0);
  EXPECT_EQ(kf::caustic_modulation_b(1.0f, 2.0f, 3.0f, -1.0f, 0.5f), 1.0f);
}

// ---- which froxels a read needs ----

template <typename K, typename Real>
void checkReadSliceAndColumns() {
  FroxelParams fp{};
  fp.nx = 160, fp.ny = 90, fp.nz = 64;
  fp.z_near = 0.1f, fp.z_far = 60.0f, fp.log_far_near = float(std::log(600.0));
  // No read at S <= 0; the last slice at and beyond z_far (deep water, UW_INFINITE).
  EXPECT_EQ(K::froxel_read_slice(&fp, Real(-1)), -1);
  EXPECT_EQ(K::froxel_read_slice(&fp, Real(0)), -1);
  EXPECT_EQ(K::froxel_read_slice(&fp, Real(NAN)), 63);  // fmin(NaN, z_far) = z_far, as froxel_lookup reads
  EXPECT_EQ(K::froxel_read_slice(&fp, Real(1e-30)), 0);
  EXPECT_EQ(K::froxel_read_slice(&fp, Real(60)), 63);
  EXPECT_EQ(K::froxel_read_slice(&fp, Real(1e30)), 63);
  for (int k = 1; k < 63; ++k) {  // just past a slice's end: the next slice
    const Real end = K::froxel_slice_end(k - 1, fp.nz, Real(fp.z_near), Real(fp.z_far), Real(fp.log_far_near));
    EXPECT_EQ(K::froxel_read_slice(&fp, end * Real(1.0001)), k);
  }
  // Pixel centres over columns: clamped to [0, n − 1] at the border, two pixels per column at 2×.
  EXPECT_EQ(K::froxel_pixel_column(0, 320, 160), Real(0));
  EXPECT_EQ(K::froxel_pixel_column(319, 320, 160), Real(159));
  EXPECT_NEAR(K::froxel_pixel_column(100, 320, 160), Real(49.75), 1e-5);
  EXPECT_EQ(K::froxel_pixel_column(0, 1, 1), Real(0));
}

TEST(FroxelMath, ReadSliceAndPixelColumns) {
  struct F {
    static int froxel_read_slice(const FroxelParams* fp, float s) { return kf::froxel_read_slice(fp, s); }
    static float froxel_pixel_column(int x, int w, int n) { return kf::froxel_pixel_column(x, w, n); }
    static float froxel_slice_end(int k, int nz, float a, float b, float c) { return kf::froxel_slice_end(k, nz, a, b, c); }
  };
  struct D {
    static int froxel_read_slice(const FroxelParams* fp, double s) { return kd::froxel_read_slice(fp, s); }
    static double froxel_pixel_column(int x, int w, int n) { return kd::froxel_pixel_column(x, w, n); }
    static double froxel_slice_end(int k, int nz, double a, double b, double c) { return kd::froxel_slice_end(k, nz, a, b, c); }
  };
  checkReadSliceAndColumns<F, float>();
  checkReadSliceAndColumns<D, double>();
}

// ---- froxel grid ----

TEST(FroxelMath, ExponentialSlices) {
  const double near = 0.1, far = 60.0, lg = std::log(far / near);
  const float lgf = float(lg);
  for (int nz : {1, 2, 8, 64, 256}) {
    EXPECT_EQ(kd::froxel_slice_start(0, nz, near, far, lg), 0.0);
    EXPECT_EQ(kd::froxel_slice_end(nz - 1, nz, near, far, lg), far);
    EXPECT_EQ(kf::froxel_slice_end(nz - 1, nz, float(near), float(far), lgf), float(far));
    if (nz > 1) EXPECT_NEAR(kd::froxel_slice_end(0, nz, near, far, lg), near * std::pow(far / near, 1.0 / nz), 1e-12);
    for (int k = 1; k < nz; ++k) {
      const double a = kd::froxel_slice_end(k - 1, nz, near, far, lg), b = kd::froxel_slice_end(k, nz, near, far, lg);
      EXPECT_GT(b, a);
      EXPECT_EQ(kd::froxel_slice_start(k, nz, near, far, lg), a);
      EXPECT_NEAR(b / a, std::pow(far / near, 1.0 / nz), 1e-12);  // equal ratios: z_k = near (far/near)^{k/nz}
    }
    // Look-up: every t lands in the slice (start, end] that holds it, boundaries included, float too.
    for (int q = 0; q <= 5000; ++q) {
      const double t = 1e-4 * std::pow(far * 2 / 1e-4, q / 5000.0);
      const int k = kd::froxel_slice_index(t, nz, near, far, lg);
      ASSERT_GE(k, 0);
      ASSERT_LT(k, nz);
      if (t < far) {
        EXPECT_LE(t, kd::froxel_slice_end(k, nz, near, far, lg) * (1 + 1e-15)) << nz << " " << t;
        if (k > 0) EXPECT_GT(t, kd::froxel_slice_start(k, nz, near, far, lg)) << nz << " " << t;
      } else {
        EXPECT_EQ(k, nz - 1);
      }
      const float tf = float(t);
      const int kf_ = kf::froxel_slice_index(tf, nz, float(near), float(far), lgf);
      if (tf < float(far)) {
        EXPECT_LE(tf, kf::froxel_slice_end(kf_, nz, float(near), float(far), lgf));
        if (kf_ > 0) EXPECT_GT(tf, kf::froxel_slice_start(kf_, nz, float(near), float(far), lgf));
      }
    }
    for (int k = 0; k < nz; ++k) {
      const double e = kd::froxel_slice_end(k, nz, near, far, lg);
      EXPECT_EQ(kd::froxel_slice_index(e, nz, near, far, lg), k);
      const float ef = kf::froxel_slice_end(k, nz, float(near), float(far), lgf);
      EXPECT_EQ(kf::froxel_slice_index(ef, nz, float(near), float(far), lgf), k);
    }
  }
}

// froxel_read_slice_bounds (the lookup's slice and its ends, computed once) against froxel_read_slice
// and the slice's own start and end: the same slice at and next to every boundary, below z_near, at and
// beyond z_far, for S <= 0 and NaN, in both precisions.
template <typename Real, typename ReadSlice, typename Bounds, typename Start, typename End>
void checkReadSliceBounds(ReadSlice read_slice, Bounds bounds, Start start, End end) {
  for (int nz : {1, 2, 8, 32, 64, 256}) {
    FroxelParams fp{};
    fp.nx = 80, fp.ny = 45, fp.nz = nz;
    fp.z_near = 0.1f, fp.z_far = 60.0f, fp.log_far_near = float(std::log(600.0));
    const Real zn = Real(fp.z_near), zf = Real(fp.z_far), lg = Real(fp.log_far_near);
    std::vector<Real> ts = {Real(-1), Real(0), Real(NAN), Real(1e-30), Real(1e-3), zf, Real(1e30)};
    for (int k = 0; k < nz; ++k) {
      const Real e = end(k, nz, zn, zf, lg);
      ts.insert(ts.end(), {e, std::nextafter(e, Real(0)), std::nextafter(e, Real(1e30)), e * Real(0.999)});
    }
    for (Real t : ts) {
      Real t0 = Real(-7), t1 = Real(-7);
      const int k = bounds(&fp, t, &t0, &t1);
      ASSERT_EQ(k, read_slice(&fp, t)) << nz << " " << t;
      if (k < 0) continue;
      EXPECT_EQ(t0, start(k, nz, zn, zf, lg)) << nz << " " << t;
      EXPECT_EQ(t1, end(k, nz, zn, zf, lg)) << nz << " " << t;
    }
  }
}

TEST(FroxelMath, ReadSliceBoundsIsTheReadSliceAndItsEnds) {
  checkReadSliceBounds<float>([](const FroxelParams* fp, float t) { return kf::froxel_read_slice(fp, t); },
                              [](const FroxelParams* fp, float t, float* a, float* b) {
                                return kf::froxel_read_slice_bounds(fp, t, a, b);
                              },
                              kf::froxel_slice_start, kf::froxel_slice_end);
  checkReadSliceBounds<double>([](const FroxelParams* fp, double t) { return kd::froxel_read_slice(fp, t); },
                               [](const FroxelParams* fp, double t, double* a, double* b) {
                                 return kd::froxel_read_slice_bounds(fp, t, a, b);
                               },
                               kd::froxel_slice_start, kd::froxel_slice_end);
}

TEST(FroxelMath, BeamSegmentIsTheExactIntegralAndStable) {
  // scale e0 ∫_0^len e^{-c P(t)} dt with P linear from p0 to p1, against the difference of the two ends'
  // exponentials over the slope in long double, (e^{-c p0} - e^{-c p1}) len / (c (p1 - p0)), for P
  // rising (a view down or level) and falling (a view rising more steeply than the sun).
  for (double c : {1e-4, 0.05, 0.4, 3.0, 11.0}) {
    for (double p0 : {0.0, 0.7, 12.0}) {
      for (double rate : {-0.5, 0.0, 0.3, 1.0, 2.4}) {
        for (double len : {1e-3, 0.2, 1.0, 8.0}) {
          const double p1 = std::max(0.0, p0 + rate * len);
          const long double e0 = std::exp(-(long double)c * p0), e1 = std::exp(-(long double)c * p1);
          const long double mean = p1 == p0 ? e0 : (e0 - e1) / ((long double)c * (p1 - p0));
          const double exact = static_cast<double>(0.9L * 1.7L * len * mean);
          const double got = kd::froxel_beam_segment(0.9, 1.7, c, p0, p1, len);
          EXPECT_NEAR(got, exact, 1e-9 * exact + 1e-300) << c << " " << p0 << " " << rate << " " << len;
          const float gotf = kf::froxel_beam_segment(0.9f, 1.7f, float(c), float(p0), float(p1), float(len));
          EXPECT_NEAR(gotf, exact, 3e-6 * exact + 1e-37) << c << " " << p0 << " " << rate << " " << len;
        }
      }
    }
  }
  // Stiff: 1 km of 9C water underflows to 0; a steep rise over 1 km (P falling by 500 m) stays finite and
  // below scale e0 len; never NaN.
  EXPECT_EQ(kf::froxel_beam_segment(1.0f, 1.0f, 11.0f, 1e3f, 2e3f, 1e3f), 0.0f);
  const float rise = kf::froxel_beam_segment(1.0f, 1.0f, 11.0f, 600.0f, 100.0f, 1e3f);
  EXPECT_TRUE(std::isfinite(rise));
  EXPECT_LE(rise, 1e3f);
  EXPECT_EQ(kf::froxel_beam_segment(1.0f, 1.0f, 11.0f, 0.0f, 0.0f, 0.0f), 0.0f);
}

TEST(FroxelMath, PartialIsStableForBothSignsOfTau) {
  // (1 - e^{-τx})/(1 - e^{-τ}): x at τ = 0, → 1 as τ → ∞ and → 0 (x < 1) as τ → -∞ (a rising view
  // gathers its slice's light at the far end); never NaN.
  for (double x : {0.0, 1e-6, 0.3, 0.5, 1.0}) {
    EXPECT_NEAR(kd::froxel_partial(x, 0.0), x, 1e-15);
    for (double tau : {-40.0, -3.0, -0.5, -1e-3, -1e-8, 1e-8, 1e-3, 0.5, 3.0, 40.0}) {
      const double exact = -std::expm1(-tau * x) / -std::expm1(-tau);
      EXPECT_NEAR(kd::froxel_partial(x, tau), exact, 1e-12) << x << " " << tau;
      EXPECT_NEAR(kf::froxel_partial(float(x), float(tau)), exact, 2e-6) << x << " " << tau;
    }
  }
  EXPECT_NEAR(kf::froxel_partial(0.5f, 1e6f), 1.0f, 1e-6f);
  EXPECT_EQ(kf::froxel_partial(0.5f, -1e6f), 0.0f);
  EXPECT_EQ(kf::froxel_partial(1.0f, -1e6f), 1.0f);
  EXPECT_TRUE(std::isfinite(kf::froxel_partial(0.0f, 1e30f)));
  EXPECT_TRUE(std::isfinite(kf::froxel_partial(0.3f, -1e30f)));
}

// A one-column grid along `forward` (the column's ray is the screen centre: exactly `forward`), one
// band (b, c, e_beam0, sensor weight 1 in every channel), no shadows, no caustics.
struct Column {
  UwParams p{};
  FroxelParams fp{};
  UwBand band{};
  std::vector<float> light, volume;
  Column(double cam_depth, kd::real3 forward, kd::real3 sun_water, int nz, double near, double far, double b,
         double c, double e0) {
    const kd::real3 up0 = std::fabs(forward.y) > 0.9 ? kd::real3{0, 0, 1} : kd::real3{0, 1, 0};
    const kd::real3 right = kd::normalize(kd::cross(forward, up0));
    const kd::real3 up = kd::cross(right, forward);
    auto set = [](float out[4], kd::real3 v) {
      out[0] = float(v.x);
      out[1] = float(v.y);
      out[2] = float(v.z);
    };
    p.cam_pos[1] = float(-cam_depth);
    set(p.cam_forward, forward);
    set(p.cam_right, right);
    set(p.cam_up, up);
    set(p.sun_dir_water, sun_water);
    p.tan_half_fov_y = 0.1f;
    p.aspect = 1.0f;
    p.g = 0.8f;
    p.width = p.height = 1;
    p.band_count = 1;
    fp.nx = fp.ny = 1;
    fp.nz = nz;
    fp.z_near = float(near);
    fp.z_far = float(far);
    fp.log_far_near = float(std::log(far / near));
    fp.mu_w = float(std::max(sun_water.y, 1e-4));
    fp.cam_depth = float(cam_depth);
    for (int k = 0; k < 3; ++k) fp.sigma_t_rgb[k] = float(c);
    band.b = float(b);
    band.c = float(c);
    band.a = float(c - b);
    band.e_beam0 = float(e0);
    band.w_r = band.w_g = band.w_b = 1.0f;
    light.assign(nz, 1.0f);
    volume.assign(4 * nz, 0.0f);
  }
  // Integrated L_SS to distance S, by the double or float code.
  double run(double S, bool use_float) {
    if (use_float) {
      kf::froxel_integrate_column(&p, &fp, &band, 1, light.data(), volume.data(), kf::froxel_column_dir(&p, &fp, 0, 0).y, 0, 0);
      return kf::froxel_lookup(&fp, volume.data(), 0, 0, 1, 1, float(S)).y;
    }
    kd::froxel_integrate_column(&p, &fp, &band, 1, light.data(), volume.data(), float(kd::froxel_column_dir(&p, &fp, 0, 0).y), 0, 0);
    return kd::froxel_lookup(&fp, volume.data(), 0, 0, 1, 1, S).y;
  }
};

TEST(FroxelMath, HorizontalRayIsExactForAnySliceCount) {
  // Horizontal ray at depth y0: E_beam(y0) is constant along it, L_SS = b p E_beam(y0) (1 - e^{-cS})/c
  // exactly, for one slice or 256 and for S inside a slice (the read's fraction is exact here).
  const double y0 = 4.0, b = 0.3, c = 0.45, e0 = 1.7, g = 0.8;
  const kd::real3 sun = kd::normalize(kd::real3{0.3, 0.9, 0.2});
  const kd::real3 fwd{0, 0, -1};
  const double phase = kd::hg_phase(kd::dot(sun, fwd), g);
  const double li = b * phase * e0 * std::exp(-c * y0 / sun.y);
  for (int nz : {1, 256}) {
    for (double S : {0.013, 0.7, 3.33, 20.0, 60.0, 1e30}) {
      Column col(y0, fwd, sun, nz, 0.1, 60.0, b, c, e0);
      const double exact = li * -std::expm1(-c * std::min(S, 60.0)) / c;
      // Double: volume stored as float (rounding 6e-8 relative), float: 1e-5 relative.
      EXPECT_NEAR(col.run(S, false) / exact, 1.0, 1e-6) << nz << " " << S;
      EXPECT_NEAR(col.run(S, true) / exact, 1.0, 2e-5) << nz << " " << S;
    }
  }
}

TEST(FroxelMath, PhaseScattersTheBeamTowardsTheSunwardView) {
  // The beam travels along -s_w and is scattered towards the camera along -d: cos θ = s_w·d, so with
  // g > 0 a view towards the sun (d ~ s_w) sees the forward lobe. Horizontal views towards and away
  // from the sun's azimuth differ by exactly the ratio of the phase function (normalised over 4π sr:
  // optics_test integrates it to 1).
  const kd::real3 sun = kd::normalize(kd::real3{0.4, 0.85, 0.1});
  const kd::real3 towards = kd::normalize(kd::real3{sun.x, 0, sun.z});
  const kd::real3 away{-towards.x, 0, -towards.z};
  Column a(3.0, towards, sun, 16, 0.1, 40.0, 0.2, 0.3, 1.0), b(3.0, away, sun, 16, 0.1, 40.0, 0.2, 0.3, 1.0);
  const double ratio = a.run(40.0, false) / b.run(40.0, false);
  EXPECT_NEAR(ratio, kd::hg_phase(kd::dot(sun, towards), 0.8) / kd::hg_phase(kd::dot(sun, away), 0.8), 1e-5);
  EXPECT_GT(ratio, 3.0);  // g = 0.8, the views 58° and 122° from the sun direction: 3.9
}

TEST(FroxelMath, SlopedRaysAreExactForAnySliceCount) {
  // The beam's exponential is integrated exactly in each slice, so with V·C = 1 a ray at any slope is
  // exact for one slice or 256, and so is a read inside a slice (one band: the in-slice fraction is
  // exact). With P(t) = t + (y0 - t d_y)/μ of slope r = 1 - d_y/μ:
  //   L_SS(S) = b p e0 e^{-c y0/μ} (1 - e^{-c r S})/(c r),
  // S up to where a rising ray leaves the water, y0/d_y (beyond it: no water, no light).
  const double y0 = 2.0, b = 0.5, c = 0.6, e0 = 1.0, far = 30.0, mu = 0.8;
  const kd::real3 sun{0.6, mu, 0.0};
  const kd::real3 views[] = {{0, -1, 0}, kd::normalize(kd::real3{0.3, -0.4, -1}), kd::normalize(kd::real3{-0.2, 0.25, -1}),
                             kd::normalize(kd::real3{0.6, 0.95, 0.1})};  // down, down-ahead, rising, rising steeply (r < 0)
  for (const kd::real3& fwd : views) {
    const double phase = kd::hg_phase(kd::dot(sun, fwd), 0.8);
    const double r = 1 - fwd.y / mu;
    const double t_surface = fwd.y > 0 ? y0 / fwd.y : 1e300;
    auto exact = [&](double S) {
      const double s = std::min({S, far, t_surface});
      const double k = c * r;
      const double integral = std::fabs(k) < 1e-12 ? s : -std::expm1(-k * s) / k;
      return b * phase * e0 * std::exp(-c * y0 / mu) * integral;
    };
    for (int nz : {1, 4, 64, 256}) {
      for (double S : {0.3, 1.7, 4.0, 29.0, 1e30}) {
        if (S < 1e29 && S > t_surface) continue;  // a pixel's surface lies at t_surface
        Column col(y0, fwd, sun, nz, 0.05, far, b, c, e0);
        const double want = exact(S);
        EXPECT_NEAR(col.run(S, false) / want, 1.0, 2e-6) << "d_y " << fwd.y << " nz " << nz << " S " << S;
        EXPECT_NEAR(col.run(S, true) / want, 1.0, 3e-5) << "d_y " << fwd.y << " nz " << nz << " S " << S;
      }
    }
  }
}

// The caustic texture's integral scale (caustic_texture.h) and the footprint filter built on it
// (froxel.h froxel_footprint_correlation): the regression of a segment's mean on its centre value is
// about λ/L once the segment is a few λ long, and 1 for a point.
TEST(FroxelMath, CausticShrinkFollowsItsIntegralScale) {
  const double period = 4.0, time = 0.7, lambda = kd::caustic_integral_scale(period);
  EXPECT_NEAR(lambda, 0.032, 1e-3);
  auto c = [&](double x, double z) { return kd::caustic_modulation(x, z, time, period, 0.5); };
  unsigned state = 12345u;
  auto uniform = [&] {  // a fixed LCG: the test draws the same lines everywhere
    state = state * 1664525u + 1013904223u;
    return (state >> 8) * (1.0 / 16777216.0);
  };
  for (double L : {4 * lambda, 12 * lambda}) {
    double sxy = 0, sxx = 0;
    for (int k = 0; k < 3000; ++k) {
      const double x0 = 100 * uniform(), z0 = 100 * uniform(), a = 6.283185307179586 * uniform();
      double mean = 0;
      const int steps = 120;
      for (int i = 0; i < steps; ++i) {
        const double s = ((i + 0.5) / steps - 0.5) * L;
        mean += c(x0 + s * std::cos(a), z0 + s * std::sin(a)) / steps;
      }
      const double c0 = c(x0, z0);
      sxy += (c0 - 1) * (mean - 1);
      sxx += (c0 - 1) * (c0 - 1);
    }
    const double rho = sxy / sxx;
    std::printf("segment %.3f m (%.0f lambda): regression of its mean on the centre %.4f, the filter's %.4f\n", L,
                L / lambda, rho, kd::froxel_footprint_correlation(lambda, L, 0.0));
    EXPECT_NEAR(rho / kd::froxel_footprint_correlation(lambda, L, 0.0), 1.0, 0.2) << L;
  }
  EXPECT_EQ(kd::froxel_footprint_correlation(lambda, 0.0, 0.0), 1.0);
  EXPECT_NEAR(kd::froxel_footprint_correlation(lambda, 10 * lambda, 10 * lambda), 0.01, 1e-12);
  EXPECT_EQ(kf::froxel_footprint_correlation(0.032f, 0.0f, 0.0f), 1.0f);
}

}  // namespace
