// shafts_exact_test.cpp — the spotlight shafts (paper 001) through the real CLI against the exact
// single-scattering integral, in an open medium (no objects): a point lamp with a wide hard-edged
// cone and an isotropic phase function. Along each view ray the airlight is
//   L = ∫_{cone part of [0, ∞)} ρ I /(4π) exp(-ρκ (s + t)) / s² dt,
// which the closed form of Sun et al. 2005 (sunAirlight, itself checked against quadrature in
// tests/unit/shafts_math_test.cpp) gives over any [0, T]; the cone part [t0, t1] of each ray is found
// here by bisection on the point-in-cone test, independently of the code under test. `seasim render`
// with the planes (exact g, n = 4000 planes, m = 1) and with the intervals method (default
// panels), and `seasim reference` must match within 1e-3
// relative at every pixel. The cameras are placed where the former fixed cuts lost airlight: 5 cm
// from the lamp (a 1 cm near cut), behind the lamp looking down the beam and looking back at it
// from inside, and in nearly clear air (a far cut at twice the scene's extent).
#include <gtest/gtest.h>

#include <ostream>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "io/image_io.h"
#include "math/vec3.h"
#include "reference/shafts_reference.h"

namespace fs = std::filesystem;

namespace {

const std::string kBinary = SEASIM_BINARY;

int runCli(const std::string& args, std::string* output) {
  FILE* pipe = popen((kBinary + " " + args + " 2>&1").c_str(), "r");
  char buf[4096];
  while (size_t n = fread(buf, 1, sizeof buf, pipe)) output->append(buf, n);
  const int status = pclose(pipe);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

struct OpenCase {
  const char* name;
  seasim::Vec3 camera, look_at;
  double density, extinction;  // ρ (1/m) and κ: ρκ is the extinction coefficient
};
// The case as gtest prints it (its name, not the struct's bytes).
void PrintTo(const OpenCase& c, std::ostream* os) { *os << c.name; }

constexpr double kCone = 80.0 * M_PI / 180, kIntensity = 10.0;
constexpr int kWidth = 24, kHeight = 16;
constexpr double kFovDeg = 40;
const seasim::Vec3 kLamp{0, 0, 0}, kAxis{0, 0, -1};

bool insideCone(seasim::Vec3 p) {
  const seasim::Vec3 q = p - kLamp;
  const double qa = seasim::dot(q, kAxis);
  return qa > 0 && qa > std::cos(kCone) * seasim::length(q);
}

// The exact airlight along the ray eye + t d: the cone's part of the ray, found by scanning t on a
// geometric grid to 1e7 m and refining each in/out flip by bisection, integrated by Sun's closed form.
double exactAirlight(const OpenCase& c, seasim::Vec3 d) {
  const double rho = c.density, sigma_t = c.density * c.extinction;
  const seasim::Vec3 q = kLamp - c.camera;
  const double D = seasim::length(q);
  const double gamma = std::acos(std::clamp(seasim::dot(q, d) / D, -1.0, 1.0));
  auto airlight = [&](double T) { return T <= 0 ? 0.0 : seasim::sunAirlight(rho, sigma_t, kIntensity, D, gamma, T); };
  auto flip = [&](double lo, double hi) {
    const bool in_lo = insideCone(c.camera + d * lo);
    for (int i = 0; i < 200; ++i) {
      const double mid = 0.5 * (lo + hi);
      (insideCone(c.camera + d * mid) == in_lo ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
  };
  double total = 0, start = insideCone(c.camera) ? 0.0 : -1.0;
  double t_prev = 0;
  bool in_prev = insideCone(c.camera);
  for (int i = 0; i <= 4000; ++i) {
    const double t = 1e-4 * std::pow(1e11, i / 4000.0);  // 1e-4 ... 1e7 m
    const bool in = insideCone(c.camera + d * t);
    if (in != in_prev) {
      const double tf = flip(t_prev, t);
      if (in) start = tf;
      else total += airlight(tf) - airlight(start);
    }
    t_prev = t;
    in_prev = in;
  }
  if (in_prev) total += airlight(INFINITY) - airlight(start);
  return total;
}

std::string sceneText(const OpenCase& c) {
  char text[1024];
  std::snprintf(text, sizeof text, R"([scene]
name = "open_lamp"
[camera]
position = [%.17g, %.17g, %.17g]
look_at = [%.17g, %.17g, %.17g]
fov_deg = %g
width = %d
height = %d
[air]
density = %.17g
extinction = %.17g
phase = "hg"
g = 0
[[spotlights]]
position = [0, 0, 0]
direction = [0, 0, -1]
cone_deg = 80
falloff_deg = 0
intensity = %g
color = [1, 1, 1]
)",
                c.camera.x, c.camera.y, c.camera.z, c.look_at.x, c.look_at.y, c.look_at.z, kFovDeg, kWidth, kHeight,
                c.density, c.extinction, kIntensity);
  return text;
}

class ShaftsOpenMedium : public ::testing::TestWithParam<OpenCase> {};

TEST_P(ShaftsOpenMedium, RenderAndReferenceMatchTheExactIntegral) {
  const OpenCase c = GetParam();
  const fs::path dir = fs::temp_directory_path() / (std::string("seasim_open_lamp_") + c.name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string scene = (dir / "scene.toml").string();
  std::ofstream(scene) << sceneText(c);

  std::string out;
  ASSERT_EQ(runCli("render " + scene + " -o " + (dir / "r").string() +
                       " --set quality.shafts_method=planes --set quality.shafts_planes=4000"
                       " --set quality.shafts_subplanes=1 --set quality.shafts_exact=true --device pocl",
                   &out),
            0)
      << out;
  // The intervals method at its default panels.
  ASSERT_EQ(runCli("render " + scene + " -o " + (dir / "i").string() + " --set quality.shafts_method=intervals --device pocl",
                   &out),
            0)
      << out;
  const seasim::Image intervals = seasim::readImage((dir / "i" / "image.exr").string());
  ASSERT_EQ(runCli("reference " + scene + " -o " + (dir / "ref.exr").string() + " --steps 4000", &out), 0) << out;
  const seasim::Image render = seasim::readImage((dir / "r" / "image.exr").string());
  const seasim::Image ref = seasim::readImage((dir / "ref.exr").string());
  ASSERT_EQ(render.width, kWidth);
  ASSERT_EQ(ref.width, kWidth);

  const seasim::Vec3 fwd = seasim::normalize(c.look_at - c.camera);
  const seasim::Vec3 right = seasim::normalize(seasim::cross(fwd, seasim::Vec3{0, 1, 0}));
  const seasim::Vec3 up = seasim::cross(right, fwd);
  const double tan_half = std::tan(kFovDeg * M_PI / 360), aspect = double(kWidth) / kHeight;
  double worst_render = 0, worst_ref = 0, worst_intervals = 0, lit = 0;
  char worst_at[200] = "";
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const double u = (2.0 * (x + 0.5) / kWidth - 1.0) * tan_half * aspect;
      const double v = (1.0 - 2.0 * (y + 0.5) / kHeight) * tan_half;
      const seasim::Vec3 d = seasim::normalize(fwd + right * u + up * v);
      const double exact = exactAirlight(c, d);
      ASSERT_GT(exact, 0) << "every pixel of these cases sees the beam";
      ++lit;
      for (int ch = 0; ch < 3; ++ch) {
        const double e = std::fabs(render.at(x, y, ch) - exact) / exact;
        if (e > worst_render) std::snprintf(worst_at, sizeof worst_at, "(%d, %d): render %.7g, exact %.7g", x, y, render.at(x, y, ch), exact);
        worst_render = std::max(worst_render, e);
        worst_ref = std::max(worst_ref, std::fabs(ref.at(x, y, ch) - exact) / exact);
        worst_intervals = std::max(worst_intervals, std::fabs(intervals.at(x, y, ch) - exact) / exact);
      }
    }
  std::printf("[ measured ] %s: max relative error vs the exact integral: render (planes) %.2e, intervals %.2e, "
              "reference %.2e (%g pixels); render's worst pixel %s\n",
              c.name, worst_render, worst_intervals, worst_ref, lit, worst_at);
  EXPECT_LT(worst_render, 1e-3);
  EXPECT_LT(worst_intervals, 1e-3);
  EXPECT_LT(worst_ref, 1e-3);
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(
    Cameras, ShaftsOpenMedium,
    ::testing::Values(
        // 5 cm in front of the lamp, inside the cone, looking down the beam: the 1 cm near cut mattered.
        OpenCase{"near_lamp", {0.02, 0.01, -0.05}, {0.3, 0.1, -1.0}, 0.05, 2.0},
        // Behind the lamp and beside it, looking down the beam: every ray enters the cone and stays.
        OpenCase{"behind_lamp", {0.4, 0.3, 1.0}, {0.0, 0.0, -6.0}, 0.05, 2.0},
        // Far down the beam looking back at the lamp: rays leave the cone near its apex.
        OpenCase{"looking_back", {0.3, -0.2, -6.0}, {0.0, 0.0, 0.0}, 0.05, 2.0},
        // Nearly clear air (ρκ = 0.002/m): the far field carries most of the light.
        OpenCase{"clear_air", {0.1, 0.0, -0.5}, {0.5, 0.2, -3.0}, 0.01, 0.2}),
    [](const ::testing::TestParamInfo<OpenCase>& info) { return std::string(info.param.name); });

}  // namespace
