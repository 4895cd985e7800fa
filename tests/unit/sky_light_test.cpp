// sky_light_test.cpp — the one sky interface (host/sky/sky_light.*, common/sky_view.h):
//  - the uniform sky gives exactly what the underwater and shallow models always used: π L_sky on a
//    horizontal plane, π L_sky (1 - r̄) just below the surface, radiance L_sky in every direction;
//  - for the CIE clear, Preetham and image skies, the irradiance integrals against a brute-force
//    quadrature in double over (θ, φ) (a different rule from the module's (cos²θ, φ) midpoints), per
//    band, through radiance() alone;
//  - a Preetham sky moves E_D0 the expected way: bluer than the uniform sky of the same luminance;
//  - Snell's window: the air direction is unit, obeys n sin θ_w = sin θ_a, and at and past the
//    critical angle stays finite (the horizon);
//  - the sun: its disk's solid angle (6.8e-5 sr at the default radius) and radiance E_sun / Ω;
//  - the planner builds kd_multiple.cl and fourflow.cl for the scene's sky model;
//  - the sweep: the integral's rule at several sizes, error against the brute force and time.
#include <gtest/gtest.h>

#include <ostream>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "math/kernel_math.h"
#include "plan/plan.h"
#include "scene/scene_parser.h"
#include "sky/sky_light.h"
#include "spectral/sensor.h"
#include "spectral/wavelength_grid.h"

namespace {

namespace kd = seasim::kmath_d;
namespace kf = seasim::kmath_f;

seasim::Scene sceneWithSky(const std::string& sky) {
  return seasim::parseScene("[sun]\nzenith_deg = 50\nazimuth_deg = 30\n[sky]\nradiance = 0.05\n" + sky, "sky.toml");
}

// ∫_{upper hemisphere} radiance(band, d) · weight(cos θ) cos θ dω by the midpoint rule in θ and φ.
template <class Weight>
double bruteForce(const seasim::SkyLight& sky, std::size_t band, Weight weight, int n_theta, int n_phi) {
  double sum = 0;
  for (int i = 0; i < n_theta; ++i) {
    const double th = (i + 0.5) * (M_PI / 2) / n_theta;
    const double ct = std::cos(th), st = std::sin(th);
    double row = 0;
    for (int k = 0; k < n_phi; ++k) {
      const double ph = (k + 0.5) * 2 * M_PI / n_phi;
      row += sky.radiance(band, {st * std::cos(ph), ct, st * std::sin(ph)});
    }
    sum += row * weight(ct) * ct * st;
  }
  return sum * (M_PI / 2 / n_theta) * (2 * M_PI / n_phi);
}

TEST(SkyLight, UniformSkyIsWhatTheModelsAlwaysUsed) {
  const seasim::WavelengthGrid grid = seasim::makeGrid(8, 400, 700);
  const seasim::SkyLight sky = seasim::makeSkyLight(sceneWithSky(""), grid);
  const std::vector<double> level = seasim::sunIrradianceBands(grid, 0.05);
  const std::vector<double> e = sky.horizontalIrradiance();
  const std::vector<double> e0 = sky.transmittedIrradiance(1.333);
  const double r_mean = seasim::skyFresnelMean(1.333);
  EXPECT_NEAR(r_mean, 0.066, 0.001);
  for (std::size_t i = 0; i < grid.size(); ++i) {
    EXPECT_EQ(sky.level[i], level[i]);
    EXPECT_EQ(e[i], M_PI * level[i]);
    EXPECT_EQ(e0[i], M_PI * level[i] * (1.0 - r_mean));
    EXPECT_EQ(sky.radiance(i, {0.6, 0.8, 0.0}), level[i]);
  }
  EXPECT_EQ(sky.params.model, 0);
  EXPECT_EQ(sky.params.scale, 1.0f);
}

struct ModelCase {
  const char* name;
  std::string sky;
  double tolerance;  // relative, module's 256 x 512 rule against the brute force
};
// The case as gtest prints it (its name, not the struct's bytes).
void PrintTo(const ModelCase& c, std::ostream* os) { *os << c.name; }

class SkyLightModels : public ::testing::TestWithParam<ModelCase> {};

TEST_P(SkyLightModels, IrradianceIntegralsMatchBruteForceQuadrature) {
  const seasim::WavelengthGrid grid = seasim::makeGrid(4, 400, 700);
  const seasim::SkyLight sky = seasim::makeSkyLight(sceneWithSky(GetParam().sky), grid);
  const std::vector<double> e = sky.horizontalIrradiance();
  const std::vector<double> e0 = sky.transmittedIrradiance(1.333);
  for (std::size_t i = 0; i < grid.size(); ++i) {
    const double want = bruteForce(sky, i, [](double) { return 1.0; }, 600, 1200);
    const double want0 =
        bruteForce(sky, i, [](double ct) { return 1.0 - kd::fresnel_reflectance(ct, 1.0, 1.333); }, 600, 1200);
    EXPECT_NEAR(e[i], want, GetParam().tolerance * want) << GetParam().name << " band " << i;
    EXPECT_NEAR(e0[i], want0, GetParam().tolerance * want0) << GetParam().name << " band " << i;
    EXPECT_LT(e0[i], e[i]);
    EXPECT_GT(e0[i], 0.9 * e[i]);  // the surface reflects 5–10 % of a sky
  }
}

INSTANTIATE_TEST_SUITE_P(Skies, SkyLightModels,
                         ::testing::Values(ModelCase{"cie_clear", "model = \"analytic\"\n", 1e-3},
                                           ModelCase{"preetham_t3", "model = \"preetham\"\nturbidity = 3\n", 1e-3},
                                           ModelCase{"preetham_t9", "model = \"preetham\"\nturbidity = 9\n", 1e-3}),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(SkyLight, PreethamSkyMakesTheLightBelowTheSurfaceBluer) {
  const seasim::WavelengthGrid grid = seasim::makeGrid(8, 400, 700);
  const seasim::SkyLight uniform = seasim::makeSkyLight(sceneWithSky(""), grid);
  const seasim::SkyLight clear = seasim::makeSkyLight(sceneWithSky("model = \"preetham\"\nturbidity = 2.5\n"), grid);
  const std::vector<double> u = uniform.transmittedIrradiance(1.333), p = clear.transmittedIrradiance(1.333);
  // A clear sky is bluer than D65 (its colour temperature is well above 6500 K away from the sun):
  // the blue band's E_D0 rises against the uniform sky's, the red band's falls.
  EXPECT_GT(p.front() / u.front(), 1.05);
  EXPECT_LT(p.back() / u.back(), 0.97);
  for (std::size_t i = 1; i < grid.size(); ++i) EXPECT_LE(p[i] / u[i], p[i - 1] / u[i - 1] + 1e-9) << i;
}

TEST(SkyLight, SunDiskHasItsSolidAngleAndRadiance) {
  const seasim::WavelengthGrid grid = seasim::makeGrid(4, 400, 700);
  const seasim::SkyLight sky = seasim::makeSkyLight(sceneWithSky(""), grid);
  EXPECT_NEAR(sky.sun_solid_angle, 6.8e-5, 0.05e-5);
  const std::vector<double> sun = seasim::sunIrradianceBands(grid, 1.0);
  for (std::size_t i = 0; i < grid.size(); ++i) {
    EXPECT_EQ(sky.sun_irradiance[i], sun[i]);
    EXPECT_NEAR(sky.sunDiskRadiance(i) * sky.sun_solid_angle, sun[i], 1e-12 * sun[i]);
  }
  // A sun below the horizon lights nothing.
  const seasim::SkyLight night =
      seasim::makeSkyLight(seasim::parseScene("[sun]\nzenith_deg = 100\n", "night.toml"), grid);
  for (double v : night.sun_irradiance) EXPECT_EQ(v, 0.0);
}

template <class T>
class SnellWindow : public ::testing::Test {};
using Precisions = ::testing::Types<float, double>;
TYPED_TEST_SUITE(SnellWindow, Precisions);

TYPED_TEST(SnellWindow, AirDirectionFollowsSnellAndStaysFiniteOutside) {
  using T = TypeParam;
  const T n = T(1.333);
  const double tol = sizeof(T) == 4 ? 2e-6 : 1e-14;
  const double critical = std::asin(1.0 / 1.333);
  for (double th : {0.0, 0.1, 0.5, critical - 1e-3, critical, critical + 1e-6, 1.2, M_PI / 2}) {
    for (double ph : {0.0, 1.0, 4.0}) {
      const double dx = std::sin(th) * std::cos(ph), dy = std::cos(th), dz = std::sin(th) * std::sin(ph);
      double ax, ay, az;
      if constexpr (sizeof(T) == 4) {
        const kf::real3 a = kf::sky_window_air_dir(kf::real3{float(dx), float(dy), float(dz)}, n);
        ax = a.x, ay = a.y, az = a.z;
      } else {
        const kd::real3 a = kd::sky_window_air_dir(kd::real3{dx, dy, dz}, n);
        ax = a.x, ay = a.y, az = a.z;
      }
      ASSERT_TRUE(std::isfinite(ax) && std::isfinite(ay) && std::isfinite(az)) << th;
      EXPECT_NEAR(ax * ax + ay * ay + az * az, 1.0, 4 * tol) << th;
      EXPECT_GE(ay, 0.0);
      if (th < critical - 1e-4) {
        EXPECT_NEAR(std::sqrt(ax * ax + az * az), 1.333 * std::sin(th), 4 * tol) << th;  // n sin θ_w = sin θ_a
        if (th > 0) EXPECT_NEAR(std::atan2(az, ax), std::atan2(dz, dx), 1e-5) << th;       // same azimuth
      } else if (th > critical + 1e-4) {
        EXPECT_EQ(ay, 0.0) << th;  // outside the window: the horizon (1 - F = 0 there)
      }
    }
  }
}

}  // namespace

namespace {

// The sweep (house rule: error and time side by side): the module's midpoint rule in (cos²θ, φ) at a
// few sizes against the brute-force (θ, φ) quadrature at 1200 × 2400, for the spectral Preetham sky
// (its circumsolar peak is the sharpest shape) at T = 3 and the sun 50° from the zenith, per band.
// Printed for docs/models.md and results/BENCHMARKS.md; asserts the shipped 256 × 512 is within 1e-4.
TEST(SkyLightSweep, IrradianceRuleErrorAndTime) {
  const seasim::WavelengthGrid grid = seasim::makeGrid(4, 400, 700);
  const seasim::SkyLight sky = seasim::makeSkyLight(sceneWithSky("model = \"preetham\"\nturbidity = 3\n"), grid);
  std::vector<double> want(grid.size());
  for (std::size_t i = 0; i < grid.size(); ++i) want[i] = bruteForce(sky, i, [](double) { return 1.0; }, 1200, 2400);
  std::printf("n_s x n_phi   max rel. error   ms (all bands)\n");
  for (int n : {32, 64, 128, 256, 512}) {
    const auto t0 = std::chrono::steady_clock::now();
    const std::vector<double> e = sky.horizontalIrradiance(n, 2 * n);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    double worst = 0;
    for (std::size_t i = 0; i < grid.size(); ++i) worst = std::max(worst, std::fabs(e[i] - want[i]) / want[i]);
    std::printf("%4d x %-5d   %.2e         %.1f\n", n, 2 * n, worst, ms);
    if (n == 256) EXPECT_LT(worst, 1e-4);
  }
}

}  // namespace

namespace {

// The planner builds the underwater and shallow kernels for the scene's sky model (the define their
// sky_view.h branch folds on); the uniform sky keeps 0.
TEST(SkyLightPlan, UnderwaterAndShallowKernelsAreBuiltForTheSkyModel) {
  auto define = [](const seasim::Plan& plan, const char* pass) {
    const seasim::PassPlan* p = plan.find(pass);
    EXPECT_NE(p, nullptr) << pass;
    if (!p) return std::string();
    for (const std::string& d : p->defines)
      if (d.rfind("SEASIM_SKY_MODEL=", 0) == 0) return d;
    return std::string();
  };
  const std::string under = "[camera]\nposition = [0, -3, 0]\nlook_at = [0, 0, -5]\n[water]\njerlov = \"IB\"\n";
  const std::string shallow = "[camera]\nposition = [0, 3, 0]\nlook_at = [0, 0, -10]\n[water]\njerlov = \"IB\"\n"
                              "[bottom]\ntype = \"flat\"\ndepth = 4\n[shallow]\n";
  EXPECT_EQ(define(seasim::makePlan(seasim::parseScene(under, "u.toml")), "kd_multiple"), "SEASIM_SKY_MODEL=0");
  EXPECT_EQ(define(seasim::makePlan(seasim::parseScene(under + "[sky]\nmodel = \"preetham\"\n", "u.toml")), "kd_multiple"),
            "SEASIM_SKY_MODEL=3");
  EXPECT_EQ(define(seasim::makePlan(seasim::parseScene(shallow, "s.toml")), "fourflow"), "SEASIM_SKY_MODEL=0");
  EXPECT_EQ(define(seasim::makePlan(seasim::parseScene(shallow + "[sky]\nmodel = \"analytic\"\n", "s.toml")), "fourflow"),
            "SEASIM_SKY_MODEL=1");
}

}  // namespace
