// fourflow_waves_test.cpp — the wave-averaged air–water coefficients of 003 eq. 10
// (kernels/common/fourflow_waves.h, host/underwater/fourflow_waves.h): a calm sea gives the flat
// Fresnel values; eq. 6 (R + T = 1 per direction class) holds; the per-facet hemisphere integral
// matches a brute-force Monte Carlo average over random directions and many random facets, in double,
// from above and from below (total internal reflection); the quadrature converges; waves change the
// coefficients in the expected direction.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>

#include "math/kernel_math.h"
#include "underwater/fourflow_waves.h"

namespace kd = seasim::kmath_d;
using seasim::FourFlowSurface;

namespace {

constexpr double kIor = 1.333;

// Brute force: F(max(ω·n, 0)) averaged over directions ω drawn cosine-weighted on the upper hemisphere
// (the uniform sky's irradiance on a horizontal plane), for each of `facets` facets. Returns mean and
// its standard error.
struct McResult {
  double mean, stderr_;
};
McResult monteCarlo(const std::vector<std::array<double, 3>>& facets, double n1, double n2, int per_facet,
                    unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  double sum = 0, sum2 = 0;
  long long count = 0;
  for (const auto& n : facets)
    for (int k = 0; k < per_facet; ++k) {
      const double u = u01(rng), phi = 2 * M_PI * u01(rng);
      const double mu = std::sqrt(u), s = std::sqrt(1 - u);
      const double c = s * std::cos(phi) * n[0] + mu * n[1] + s * std::sin(phi) * n[2];
      const double f = kd::fresnel_reflectance(std::max(c, 0.0), n1, n2);
      sum += f;
      sum2 += f * f;
      ++count;
    }
  const double mean = sum / count;
  return {mean, std::sqrt(std::max(sum2 / count - mean * mean, 0.0) / count)};
}

std::array<double, 3> facetNormal(double sx, double sz) {
  const double len = std::sqrt(sx * sx + 1 + sz * sz);
  return {-sx / len, 1 / len, -sz / len};
}

}  // namespace

TEST(FourFlowWaves, CalmSeaGivesTheFlatFresnelValues) {
  for (double zenith_deg : {0.0, 30.0, 60.0, 85.0}) {
    const double z = zenith_deg * M_PI / 180;
    const FourFlowSurface flat = seasim::flatFourFlowSurface(std::cos(z), kIor);
    const FourFlowSurface calm = seasim::waveAveragedSurface({{0.0, 1.0, 0.0}, {0.0, 1.0, 0.0}}, z, 0.7, kIor);
    EXPECT_NEAR(calm.T_dd, flat.T_dd, 1e-12) << zenith_deg;
    EXPECT_NEAR(calm.Rw_dd, flat.Rw_dd, 1e-12) << zenith_deg;
    EXPECT_NEAR(calm.T_ff, flat.T_ff, 1e-7) << zenith_deg;
    EXPECT_NEAR(calm.Rw_ff, flat.Rw_ff, 1e-7) << zenith_deg;
    EXPECT_EQ(calm.T_df, 0.0);
    EXPECT_EQ(calm.Rw_df, 0.0);
  }
  // A wind of 0 makes the FFT patch flat: the scene path gives the same numbers.
  seasim::SurfaceDesc still;
  still.type = seasim::SurfaceDesc::Type::Fft;
  still.wind_speed = 0.0;
  still.grid = 32;
  const auto normals = seasim::oceanFacetNormals(still);
  ASSERT_FALSE(normals.empty());
  const FourFlowSurface calm = seasim::waveAveragedSurface(normals, 0.5, 0.0, kIor);
  const FourFlowSurface flat = seasim::flatFourFlowSurface(std::cos(0.5), kIor);
  EXPECT_NEAR(calm.T_dd, flat.T_dd, 1e-12);
  EXPECT_NEAR(calm.T_ff, flat.T_ff, 1e-7);
  EXPECT_NEAR(calm.Rw_ff, flat.Rw_ff, 1e-7);
}

TEST(FourFlowWaves, EnergyPerDirectionClass) {
  // 003 eq. 6: R_ff + T_ff = 1 and R_df + R_dd + T_df + T_dd = 1, each coefficient in [0, 1].
  std::mt19937_64 rng(3);
  std::normal_distribution<double> slope(0.0, 0.25);
  std::vector<std::array<double, 3>> facets;
  for (int i = 0; i < 500; ++i) facets.push_back(facetNormal(slope(rng), slope(rng)));
  for (double zenith_deg : {0.0, 40.0, 80.0}) {
    const FourFlowSurface s = seasim::waveAveragedSurface(facets, zenith_deg * M_PI / 180, 0.3, kIor);
    const double r_ff = 1 - s.T_ff, r_dd = 1 - s.T_dd, r_df = 0;
    EXPECT_DOUBLE_EQ(r_ff + s.T_ff, 1.0);
    EXPECT_DOUBLE_EQ(r_df + r_dd + s.T_df + s.T_dd, 1.0);
    for (double v : {s.T_dd, s.T_ff, s.Rw_dd, s.Rw_ff, r_ff, r_dd}) {
      EXPECT_GE(v, 0.0) << zenith_deg;
      EXPECT_LE(v, 1.0) << zenith_deg;
    }
  }
}

TEST(FourFlowWaves, FacetIntegralConvergesAndMatchesFlatAtZeroTilt) {
  double worst = 0;
  for (double beta_deg : {0.0, 5.0, 20.0, 45.0, 70.0, 89.0})
    for (int side = 0; side < 2; ++side) {
      const double n1 = side ? kIor : 1.0, n2 = side ? 1.0 : kIor;
      const double cb = std::cos(beta_deg * M_PI / 180);
      const double coarse = kd::ff_facet_diffuse_reflectance(cb, n1, n2, FF_WAVE_INTERVALS);
      const double fine = kd::ff_facet_diffuse_reflectance(cb, n1, n2, 1024);
      worst = std::max(worst, std::fabs(coarse - fine));
      EXPECT_NEAR(coarse, fine, 1e-7) << beta_deg << " side " << side;
    }
  std::printf("[ measured ] facet R_ff, %d vs 1024 Simpson intervals per piece: max |diff| %.2e\n", FF_WAVE_INTERVALS,
              worst);
  EXPECT_NEAR(kd::ff_facet_diffuse_reflectance(1.0, 1.0, kIor, 1024),
              kd::ff_diffuse_reflectance(1.0, kIor, 4096), 1e-9);
  EXPECT_NEAR(kd::ff_facet_diffuse_reflectance(1.0, kIor, 1.0, 1024),
              kd::ff_diffuse_reflectance(kIor, 1.0, 4096), 1e-9);
}

TEST(FourFlowWaves, FacetIntegralMatchesBruteForceForSingleTilts) {
  for (double beta_deg : {10.0, 35.0, 60.0})
    for (int side = 0; side < 2; ++side) {
      const double n1 = side ? kIor : 1.0, n2 = side ? 1.0 : kIor;
      const double b = beta_deg * M_PI / 180;
      const std::vector<std::array<double, 3>> facet = {{std::sin(b), std::cos(b), 0.0}};
      const McResult mc = monteCarlo(facet, n1, n2, 2000000, 11 + side);
      const double quad = kd::ff_facet_diffuse_reflectance(std::cos(b), n1, n2, FF_WAVE_INTERVALS);
      std::printf("[ measured ] tilt %.0f° %s: quadrature %.6f, Monte Carlo %.6f ± %.6f\n", beta_deg,
                  side ? "from below" : "from above", quad, mc.mean, mc.stderr_);
      EXPECT_NEAR(quad, mc.mean, 5 * mc.stderr_ + 1e-6) << beta_deg << " side " << side;
    }
}

TEST(FourFlowWaves, PatchAverageMatchesBruteForceOverManyRandomFacets) {
  // Many random facets (Gaussian slopes, σ = 0.3 per axis: a rough sea), eq. 10 by the facet quadrature
  // against plain Monte Carlo over facets and directions together.
  std::mt19937_64 rng(7);
  std::normal_distribution<double> slope(0.0, 0.3);
  std::vector<std::array<double, 3>> facets;
  for (int i = 0; i < 4000; ++i) facets.push_back(facetNormal(slope(rng), slope(rng)));
  const FourFlowSurface s = seasim::waveAveragedSurface(facets, 0.4, 0.0, kIor);
  const McResult above = monteCarlo(facets, 1.0, kIor, 1000, 21);
  const McResult below = monteCarlo(facets, kIor, 1.0, 1000, 22);
  std::printf("[ measured ] 4000 random facets: R_ff %.6f vs MC %.6f ± %.6f; R~_ff %.6f vs MC %.6f ± %.6f\n",
              1 - s.T_ff, above.mean, above.stderr_, s.Rw_ff, below.mean, below.stderr_);
  EXPECT_NEAR(1 - s.T_ff, above.mean, 5 * above.stderr_);
  EXPECT_NEAR(s.Rw_ff, below.mean, 5 * below.stderr_);
  // Waves make the sky's reflectance larger than the flat mirror's (tilted facets see grazing sky), and
  // a low sun's reflectance smaller (facets tilted towards it see it more steeply).
  const FourFlowSurface flat = seasim::flatFourFlowSurface(std::cos(80 * M_PI / 180), kIor);
  const FourFlowSurface low_sun = seasim::waveAveragedSurface(facets, 80 * M_PI / 180, 0.0, kIor);
  EXPECT_GT(1 - s.T_ff, 1 - flat.T_ff);
  EXPECT_LT(1 - low_sun.T_dd, 1 - flat.T_dd);
}

TEST(FourFlowWaves, CoefficientsOverTheFftPatchByWindSpeed) {
  // The FFT patch of [surface] (100 m, N = 256, every 4th texel: 64 x 64 facets) at several winds,
  // the sun at 35° (the mountain lake's). Printed for results/shallow/wave_coefficients.md.
  seasim::SurfaceDesc surface;
  surface.type = seasim::SurfaceDesc::Type::Fft;
  std::printf("[ measured ] wind_mps  R_ff      T_dd      R~_ff     R~_dd     ms\n");
  double prev_rff = 0;
  for (double wind : {0.0, 2.0, 5.0, 10.0, 15.0}) {
    surface.wind_speed = wind;
    const auto t0 = std::chrono::steady_clock::now();
    const FourFlowSurface s =
        seasim::waveAveragedSurface(seasim::oceanFacetNormals(surface), 35 * M_PI / 180, 0.0, kIor);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    std::printf("[ measured ] %8.1f  %.6f  %.6f  %.6f  %.6f  %.1f\n", wind, 1 - s.T_ff, s.T_dd, s.Rw_ff, s.Rw_dd, ms);
    EXPECT_GE(1 - s.T_ff, prev_rff - 1e-9) << wind;  // rougher water reflects more of the sky
    prev_rff = 1 - s.T_ff;
  }
}
