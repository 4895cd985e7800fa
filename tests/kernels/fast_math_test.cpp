// fast_math_test.cpp — quality.fast_math (kernels built with -cl-fast-relaxed-math) keeps every
// shipped scene where it is on by default (fastMathFor: all but those with FFT waves seen from
// above; the four-flow pass is never built with it), and the non-default models a scene may pick
// (sea.model = "multiple", the shafts' sampling planes), within the budget that made it the default: < 0.05 of an 8-bit level (max |Δ| after the
// tone map, at the scene's exposure) from the exact-maths image, and finite. The scenes render at a
// reduced size (the kernels and their maths are the same at any size); the full-size figures are in
// results/BENCHMARKS.md (tests/perf/fast_math_scenes.sh).
#include <gtest/gtest.h>

#include <ostream>

#include <cmath>
#include <string>
#include <vector>

#include "quality/render_frame.h"
#include "plan/plan.h"
#include "reference/compare.h"
#include "scene/scene_parser.h"
#include "test_device.h"

namespace {

seasim::Override set(const char* key, const std::string& value) { return {key, value, {"test", 1}}; }

struct Case {
  const char* scene;   // scenes/<scene>.toml
  int width, height;   // reduced size
  double budget;       // max |Δ| in 8-bit levels
  const char* key = "";    // an extra override (e.g. a non-default model), or ""
  const char* value = "";
  const char* name = "";   // the test's name when it differs from the scene's
};
// The case as gtest prints it (its name, not the struct's bytes).
void PrintTo(const Case& c, std::ostream* os) { *os << (*c.name ? c.name : c.scene) << " at " << c.width << "x" << c.height; }

class FastMath : public ::testing::TestWithParam<Case> {};

TEST_P(FastMath, ImageStaysWithinBudgetOfExactMaths) {
  const Case& c = GetParam();
  const std::string file = std::string(SEASIM_SOURCE_DIR) + "/scenes/" + c.scene + ".toml";
  auto load = [&](bool fast) {
    std::vector<seasim::Override> o = {set("camera.width", std::to_string(c.width)),
                                       set("camera.height", std::to_string(c.height)),
                                       set("quality.fast_math", fast ? "true" : "false")};
    if (*c.key) o.push_back(set(c.key, c.value));
    return seasim::loadScene(file, o);
  };
  const seasim::Scene exact_scene = load(false), fast_scene = load(true);
  const seasim::Plan fast_plan = seasim::makePlan(fast_scene);
  bool marked = false;
  for (const auto& p : fast_plan.passes)
    for (const auto& d : p.defines) marked = marked || d == "SEASIM_FAST_MATH=1";
  ASSERT_TRUE(marked) << "the plan does not build any pass with fast maths";
  auto& device = seasim::test::testDevice();
  const seasim::FrameResult exact = seasim::renderFrame(device, exact_scene, seasim::makePlan(exact_scene));
  const seasim::FrameResult fast = seasim::renderFrame(device, fast_scene, fast_plan);
  ASSERT_EQ(fast.nonfinite, 0);
  ASSERT_EQ(exact.nonfinite, 0);
  const seasim::CompareResult d = seasim::compareImages(fast.rgb, exact.rgb, exact_scene.camera.exposure_ev);
  std::printf("[ measured ] %s fast vs exact maths: max %.4f levels, RMSE %.4f, rel. L2 %.3g\n", c.scene,
              d.max_abs_8bit, d.rmse_8bit, d.rel_l2);
  EXPECT_LT(d.max_abs_8bit, c.budget) << c.scene;
  // Where the driver gets -cl-fast-relaxed-math (PoCL: seasim::fastMathOptions), the fast image is a
  // different computation: at least one value moved. (If it did not, the build option never reached
  // the compiler and this test would guard nothing.) Other drivers get only -cl-mad-enable and
  // -cl-no-signed-zeros, which may leave the image as it was.
  double moved = 0;
  for (size_t i = 0; i < fast.rgb.pixels.size(); ++i)
    moved = std::fmax(moved, std::fabs(double(fast.rgb.pixels[i]) - exact.rgb.pixels[i]));
  if (seasim::fastMathOptions(device.info()).find("-cl-fast-relaxed-math") != std::string::npos)
    EXPECT_GT(moved, 0.0) << c.scene;
}

INSTANTIATE_TEST_SUITE_P(ShippedScenes, FastMath,
                         ::testing::Values(Case{"deep_ocean", 96, 54, 0.05}, Case{"flat_sea", 96, 54, 0.05},
                                           Case{"open_ocean", 96, 54, 0.05}, Case{"seabed", 96, 54, 0.05},
                                           Case{"seashore", 96, 54, 0.05}, Case{"spot_sphere", 96, 64, 0.05},
                                           Case{"stage", 96, 64, 0.05}, Case{"tropical", 96, 54, 0.05},
                                           Case{"rov_lights", 96, 54, 0.05},
                                           Case{"flat_sea", 96, 54, 0.05, "sea.model", "\"multiple\"", "flat_sea_multiple"},
                                           Case{"spot_sphere", 96, 64, 0.05, "quality.shafts_method", "\"planes\"",
                                                "spot_sphere_planes"}),
                         [](const ::testing::TestParamInfo<Case>& info) {
                           return std::string(*info.param.name ? info.param.name : info.param.scene);
                         });

}  // namespace
