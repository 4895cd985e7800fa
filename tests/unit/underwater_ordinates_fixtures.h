// underwater_ordinates_fixtures.h — what the discrete-ordinates underwater model's unit tests share
// (underwater_ordinates_test, _depth_test, _flux_test, _surface_test, _tilt_test, underwater_model_option_test,
// forward_peak_test):
// one band's block as the set-up would fill it, and a small discrete-ordinates-model scene whose [underwater]
// table a test may extend, with its file:line:key rejection check.
#ifndef SEASIM_TESTS_UNDERWATER_ORDINATES_FIXTURES_H
#define SEASIM_TESTS_UNDERWATER_ORDINATES_FIXTURES_H

#include <gtest/gtest.h>

#include <string>

#include "common/underwater_params.h"
#include "scene/scene_parser.h"
#include "underwater/discrete_ordinates.h"
#include "util/error.h"

namespace seasim::testing {

// a, b in 1/m; the sky's and the sun's irradiance just below the surface; μ_w the refracted sun's
// cosine (the beam is e_sun0 / μ_w per unit area across it); rho the bottom's albedo.
inline UwBand uwTestBand(double a, double b, double e_sky0, double e_sun0, double mu_w, double rho) {
  UwBand o{};
  o.a = float(a);
  o.b = float(b);
  o.c = float(a + b);
  o.e_sky0 = float(e_sky0);
  o.e_sun0 = float(e_sun0);
  o.e_beam0 = float(e_sun0 / mu_w);
  o.bottom_albedo = float(rho);
  return o;
}

// The sun 30° from the zenith, refracted (n = 1.34): its cosine under water.
inline constexpr double kUwTestMuW = 0.9273;

// An axis-aligned box from (x0, y0, z0) to (x1, y1, z1) and a sphere, as the scene's objects (m).
inline UwObject uwTestBox(float x0, float y0, float z0, float x1, float y1, float z1) {
  UwObject o{};
  o.type = UW_BOX;
  o.a[0] = x0, o.a[1] = y0, o.a[2] = z0;
  o.b[0] = x1, o.b[1] = y1, o.b[2] = z1;
  return o;
}
inline UwObject uwTestSphere(float x, float y, float z, float r) {
  UwObject o{};
  o.type = UW_SPHERE;
  o.a[0] = x, o.a[1] = y, o.a[2] = z, o.a[3] = r;
  return o;
}

// The discrete ordinates' layer of the band (its a, b, irradiances, bottom albedo) at asymmetry g over a
// bottom at H (<= 0: none), ior 1.34, the sun at kUwTestMuW.
inline DiscreteOrdinatesLayer uwTestLayer(const UwBand& b, double g, double H) {
  DiscreteOrdinatesLayer l;
  l.a = b.a;
  l.b = b.b;
  l.g = g;
  l.bottom_depth = H;
  l.bottom_albedo = b.bottom_albedo;
  l.ior = 1.34;
  l.mu_sun = kUwTestMuW;
  l.e_sun0 = b.e_sun0;
  l.e_sky0 = b.e_sky0;
  return l;
}

// Jerlov IB over a 25 m bottom, the camera at 3 m; ends inside [underwater], so keys may be appended.
inline constexpr const char* kOrdinatesScene = R"([scene]
name = "uw"
[camera]
position = [0, -3, 0]
look_at = [0, -3, -5]
width = 8
height = 6
[water]
jerlov = "IB"
[bottom]
type = "flat"
depth = 25
[underwater]
caustics = "none"
model = "discrete_ordinates"
)";

// The discrete-ordinates model with the two-stream's diffuse field (its fitted tables), keys may be appended.
inline std::string twoStreamScene() { return std::string(kOrdinatesScene) + "diffuse = \"two_stream\"\n"; }

// kOrdinatesScene with `line` appended (its line 16) must be rejected with an error naming that file:line
// and `key` (underwater.…).
inline void expectOrdinatesSceneRejects(const std::string& line, const std::string& key) {
  try {
    parseScene(std::string(kOrdinatesScene) + line + "\n", "uw.toml");
    ADD_FAILURE() << "accepted " << line;
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("uw.toml:16"), std::string::npos) << m;
    EXPECT_NE(m.find(key), std::string::npos) << m;
  }
}

}  // namespace seasim::testing

#endif  // SEASIM_TESTS_UNDERWATER_ORDINATES_FIXTURES_H
