// radiance_distribution_test.cpp — L(θ, φ) on the θ–φ grid (host/radiometry/radiance_distribution.*): its
// hemisphere integrals against E_d and E_u of the same photons and of the profile's Monte Carlo, a
// Lambertian bottom's uniform upward radiance R E_d / π, the sun's beam in its one cell, and bad grids.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "math/kernel_math.h"
#include "radiometry/canonical_problems.h"
#include "radiometry/light_profile_mc.h"
#include "radiometry/radiance_distribution.h"

namespace {

using namespace seasim;
constexpr double kPi = 3.14159265358979323846;

TEST(RadianceDistribution, HemisphereIntegralsAreThePlaneIrradiances) {
  const PlaneParallelWater w = canonicalWater(2, 0.9);
  const PhaseFunction p = canonicalPhase(2);
  const std::vector<double> depths = {1.0, 5.0};
  RadianceDistributionSettings s;
  s.n_theta = 30;
  s.n_phi = 36;
  s.photons = 40000;
  const RadianceDistribution r = solveRadianceDistribution(w, p, depths, s);
  MonteCarloSettings m;
  m.photons = 20000;
  const LightProfileMc profile = solveLightProfileMonteCarlo(w, p, depths, m);
  for (size_t k = 0; k < depths.size(); ++k) {
    // The same photons: the grid's bookkeeping (cells, projected solid angles, the beam's cell) exactly.
    EXPECT_NEAR(r.hemisphereIrradiance(k, true), r.e_d[k], 1e-9 * r.e_d[k]);
    EXPECT_NEAR(r.hemisphereIrradiance(k, false), r.e_u[k], 1e-9 * r.e_u[k]);
    // Independent photons and estimator (the profile's next event, which follows μ only).
    const LightAtDepth &q = profile.mean.rows[k], &e = profile.standard_error[k];
    EXPECT_NEAR(r.e_d[k], q.e_d, 4 * std::hypot(r.e_d_se[k], e.e_d)) << depths[k];
    EXPECT_NEAR(r.e_u[k], q.e_u, 4 * std::hypot(r.e_u_se[k], e.e_u)) << depths[k];
    EXPECT_LT(r.e_u_se[k], 0.03 * r.e_u[k]);
  }
}

TEST(RadianceDistribution, LambertianBottomReadsUniform) {
  const PlaneParallelWater w = canonicalWater(6, 0.2);  // R = 0.5 at 5 m
  RadianceDistributionSettings s;
  s.n_theta = 8;
  s.n_phi = 6;
  s.photons = 40000;
  const RadianceDistribution r = solveRadianceDistribution(w, canonicalPhase(6), {5.0}, s);
  const double expected = 0.5 * r.e_d[0] / kPi;
  for (int i = s.n_theta / 2; i < s.n_theta; ++i)
    for (int j = 0; j < s.n_phi; ++j) {
      const size_t q = static_cast<size_t>(i) * s.n_phi + j;
      EXPECT_NEAR(r.radiance[0][q], expected, 5 * r.standard_error[0][q] + 0.02 * expected) << i << " " << j;
    }
}

TEST(RadianceDistribution, SunBeamLandsInItsCell) {
  PlaneParallelWater w;
  w.a = 0.3;  // no scattering, black sky: only the refracted beam
  w.sun_zenith = 50 * kPi / 180;
  w.sun_irradiance = 1;
  RadianceDistributionSettings s;
  s.n_theta = 18;
  s.n_phi = 12;
  s.photons = 4000;
  const RadianceDistribution r = solveRadianceDistribution(w, PhaseFunction::henyeyGreenstein(0.8), {2.0}, s);
  const double mu_w = std::sqrt(1 - std::pow(std::sin(w.sun_zenith) / w.ior, 2));
  const int row = static_cast<int>(std::acos(mu_w) / kPi * s.n_theta);
  const double e = std::cos(w.sun_zenith) * (1 - kmath_d::fresnel_reflectance(std::cos(w.sun_zenith), 1.0, w.ior)) *
                   std::exp(-0.3 * 2 / mu_w);
  for (int i = 0; i < s.n_theta; ++i)
    for (int j = 0; j < s.n_phi; ++j) {
      const double v = r.radiance[0][static_cast<size_t>(i) * s.n_phi + j];
      if (i == row && j == 0)  // the photons that reach the depth unscattered: a binomial count
        EXPECT_NEAR(v, e / r.cellProjectedSolidAngle(i), 4 * r.standard_error[0][static_cast<size_t>(i) * s.n_phi]);
      else EXPECT_EQ(v, 0.0) << i << " " << j;
    }
}

TEST(RadianceDistribution, RejectsBadGrids) {
  const PlaneParallelWater w = canonicalWater(1, 0.9);
  RadianceDistributionSettings s;
  s.photons = 100;
  s.n_theta = 9;  // odd: a row would straddle the horizon
  EXPECT_THROW(solveRadianceDistribution(w, canonicalPhase(1), {1.0}, s), std::invalid_argument);
  s.n_theta = 10;
  s.n_phi = 0;
  EXPECT_THROW(solveRadianceDistribution(w, canonicalPhase(1), {1.0}, s), std::invalid_argument);
  s.n_phi = 4;
  EXPECT_THROW(solveRadianceDistribution(w, canonicalPhase(1), {-1.0}, s), std::invalid_argument);
}

}  // namespace
