// sky_table_test.cpp — the reflected sky's table (kernels/common/sky_table.h, host/passes/sea_sky.h)
// against the analytic skies it tabulates, exactly evaluated:
//  - over 20,000 random upper-hemisphere views for Preetham's sky at turbidities 1.7-10 and suns from
//    the zenith to below the horizon, and for the CIE clear sky: the largest error of each of the
//    shape's three components, relative to the largest component of the exact shape, at the default
//    256 x 256 (measured 1.4e-4 - 4.9e-4 for Preetham, 1.4e-4 - 1.5e-4 for CIE; 128 x 128: up to 2e-3);
//  - at its nodes the read is the node's value; float reads of the same table agree with double;
//  - stiff views: the zenith, the horizon, below the horizon (the horizon's value), the sun itself
//    and the anti-sun.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "math/kernel_math.h"
#include "passes/sea_sky.h"
#include "spectral/wavelength_grid.h"
#include "util/error.h"

namespace {

namespace kd = seasim::kmath_d;
namespace kf = seasim::kmath_f;

struct Sky {
  seasim::SeaSky sky;
  kd::real3 sun{0, 1, 0};
};

Sky makeSky(seasim::SkyDesc::Model model, double sun_zenith_deg, double turbidity) {
  seasim::SkyDesc desc;
  desc.model = model;
  desc.turbidity = turbidity;
  desc.chromaticity_on_daylight_locus = true;
  const double z = sun_zenith_deg * M_PI / 180, a = 0.7;
  const double sun[3] = {std::sin(z) * std::cos(a), std::cos(z), std::sin(z) * std::sin(a)};
  Sky s;
  s.sky = seasim::makeSeaSky(desc, sun, seasim::makeGrid(4, 400, 700));
  s.sun = {sun[0], sun[1], sun[2]};
  return s;
}

// The exact scaled shape towards unit d (sea_sky_shape of common/sea_view.h, in double).
kd::real3 exact(const Sky& s, kd::real3 d) {
  if (s.sky.model == 1) {
    const double v = s.sky.scale * kd::sky_cie_clear_shape(d, s.sun);
    return {v, v, v};
  }
  return kd::sky_preetham_daylight(s.sky.texels.data(), d, s.sun) * s.sky.scale;
}

// The table's read towards d, with the sun as sea_reflected_sky_shape takes it.
kd::real3 tabled(const Sky& s, const std::vector<double>& table, int n, kd::real3 d) {
  const kd::real3 sun = s.sky.model == 3 ? kd::sky_preetham_sun(s.sun) : s.sun;
  return kd::sky_table_shape(s.sky.model, s.sky.texels.data(), table.data(), n, s.sky.scale, d.y, kd::dot(d, sun));
}

double worstRelative(const Sky& s, const std::vector<double>& table, int n, int count) {
  std::mt19937 rng(7);
  std::normal_distribution<double> g;
  double worst = 0;
  for (int k = 0; k < count; ++k) {
    kd::real3 d{g(rng), std::fabs(g(rng)), g(rng)};
    d = d * (1.0 / std::sqrt(kd::dot(d, d)));
    const kd::real3 e = exact(s, d), t = tabled(s, table, n, d);
    const double scale = std::max({std::fabs(e.x), std::fabs(e.y), std::fabs(e.z), 1e-30});
    const double w = std::max({std::fabs(t.x - e.x) / scale, std::fabs(t.y - e.y) / scale, std::fabs(t.z - e.z) / scale});
    worst = std::max(worst, w);
  }
  return worst;
}

TEST(SkyTable, PreethamWithinItsBoundOverSunsAndTurbidities) {
  for (double t : {1.7, 2.5, 6.0, 10.0})
    for (double zenith : {0.0, 35.0, 70.0, 88.0, 95.0}) {
      const Sky s = makeSky(seasim::SkyDesc::Model::Preetham, zenith, t);
      const std::vector<double> table = seasim::seaSkyTable(s.sky, 256);
      const double err = worstRelative(s, table, 256, 20000);
      std::printf("[ measured ] Preetham T %.1f, sun zenith %.0f deg: 256 x 256 table within %.2e of the exact shape\n",
                  t, zenith, err);
      EXPECT_LT(err, 1e-3) << "T " << t << ", sun zenith " << zenith;
    }
}

TEST(SkyTable, CieClearSkyWithinItsBound) {
  for (double zenith : {0.0, 35.0, 70.0, 95.0}) {
    const Sky s = makeSky(seasim::SkyDesc::Model::Analytic, zenith, 3.0);
    const std::vector<double> table = seasim::seaSkyTable(s.sky, 256);
    const double err = worstRelative(s, table, 256, 20000);
    std::printf("[ measured ] CIE clear sky, sun zenith %.0f deg: 256 x 256 table within %.2e of the exact shape\n",
                zenith, err);
    EXPECT_LT(err, 1e-3) << "sun zenith " << zenith;
  }
}

// A finer table is closer: the bilinear error falls about fourfold per doubling.
TEST(SkyTable, ErrorFallsWithTheTableSize) {
  const Sky s = makeSky(seasim::SkyDesc::Model::Preetham, 35.0, 2.5);
  double previous = 1e30;
  for (int n : {32, 64, 128, 256}) {
    const double err = worstRelative(s, seasim::seaSkyTable(s.sky, n), n, 20000);
    std::printf("[ measured ] Preetham T 2.5, sun zenith 35 deg: %d x %d table within %.2e\n", n, n, err);
    EXPECT_LT(err, previous / 2.5) << n;
    previous = err;
  }
}

TEST(SkyTable, NodesReadExactlyAndFloatAgreesWithDouble) {
  const Sky s = makeSky(seasim::SkyDesc::Model::Preetham, 40.0, 3.0);
  const int n = 16;
  const std::vector<double> table = seasim::seaSkyTable(s.sky, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      double ct, cg;
      kd::sky_table_node(i, j, n, &ct, &cg);
      const kd::real3 r = kd::sky_table_read(table.data(), n, ct, cg);
      const double* t = table.data() + SKY_TABLE_STRIDE * (i * n + j);
      EXPECT_NEAR(r.x, t[0], 1e-12 * std::fabs(t[0]) + 1e-15) << i << ", " << j;
      EXPECT_NEAR(r.y, t[1], 1e-12 * std::fabs(t[1]) + 1e-15) << i << ", " << j;
    }
  const std::vector<float> table_f(table.begin(), table.end());
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0, 1), c(-1, 1);
  for (int k = 0; k < 1000; ++k) {
    const double ct = u(rng), cg = c(rng);
    const kd::real3 rd = kd::sky_table_read(table.data(), n, ct, cg);
    const kf::real3 rf = kf::sky_table_read(table_f.data(), n, float(ct), float(cg));
    const double scale = std::max({std::fabs(rd.x), std::fabs(rd.y), std::fabs(rd.z)});
    EXPECT_NEAR(rf.x, rd.x, 1e-5 * scale);
    EXPECT_NEAR(rf.y, rd.y, 1e-5 * scale);
    EXPECT_NEAR(rf.z, rd.z, 1e-5 * scale);
  }
}

TEST(SkyTable, StiffViews) {
  const Sky s = makeSky(seasim::SkyDesc::Model::Preetham, 60.0, 2.5);
  const int n = 256;
  const std::vector<double> table = seasim::seaSkyTable(s.sky, n);
  const auto close = [&](kd::real3 d, const char* what) {
    const kd::real3 e = exact(s, d), t = tabled(s, table, n, d);
    const double scale = std::max({std::fabs(e.x), std::fabs(e.y), std::fabs(e.z)});
    EXPECT_TRUE(std::isfinite(t.x) && std::isfinite(t.y) && std::isfinite(t.z)) << what;
    EXPECT_NEAR(t.x, e.x, 1e-3 * scale) << what;
    EXPECT_NEAR(t.y, e.y, 1e-3 * scale) << what;
    EXPECT_NEAR(t.z, e.z, 1e-3 * scale) << what;
  };
  close({0, 1, 0}, "zenith");
  close({1, 0, 0}, "horizon");
  close(s.sun, "the sun");
  const double h = std::sqrt(s.sun.x * s.sun.x + s.sun.z * s.sun.z);
  close({-s.sun.x / h, 0, -s.sun.z / h}, "the horizon opposite the sun");
  // Below the horizon the table reads the horizon's cos theta = 0 with the view's own cos gamma, as the
  // exact model does (its cos theta is clamped).
  const kd::real3 below{0.6, -0.8, 0.0};
  const kd::real3 t = tabled(s, table, n, below), e = exact(s, below);
  EXPECT_NEAR(t.x, e.x, 1e-3 * std::fabs(e.x));
}

TEST(SkyTable, RefusesTooSmallATableAndSkiesThatAreNotAnalytic) {
  const Sky s = makeSky(seasim::SkyDesc::Model::Preetham, 30.0, 2.5);
  EXPECT_THROW(seasim::seaSkyTable(s.sky, 1), seasim::RuntimeError);
  seasim::SeaSky uniform;
  EXPECT_THROW(seasim::seaSkyTable(uniform, 64), seasim::RuntimeError);
}

}  // namespace
