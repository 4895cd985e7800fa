// scene_profile_test.cpp — the light profile as a render output (radiometry/scene_profile.h,
// host/passes/nodes/light_profile_node.cpp): outputs.profile_depths parsed with file:line:key errors; the
// planner adds the light_profile entry only when the depths are asked, shows it as unavailable where the
// scene cannot have a plane-parallel profile, and leaves it out of every shipped scene; the CSV it
// writes has every band and sensor channel at every depth.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "plan/plan.h"
#include "radiometry/scene_profile.h"
#include "scene/scene_parser.h"
#include "util/error.h"
#include "small_underwater_scene.h"

namespace seasim {
namespace {

const char* kUnderwater = kSmallUnderwaterScene;

std::string errorOf(const std::string& text) { return parseErrorOf(text, "profile.toml"); }

TEST(LightProfilePass, AbsentUnlessAsked) {
  const Plan plan = makePlan(parseScene(kUnderwater, "profile.toml"));
  EXPECT_FALSE(plan.hasPass("light_profile"));
  EXPECT_FALSE(plan.produces("light_profile"));
  EXPECT_EQ(plan.toText().find("profile"), std::string::npos) << plan.toText();
}

TEST(LightProfilePass, PlannedWhenTheSceneAsksForDepths) {
  const Scene scene = parseScene(std::string(kUnderwater) + "[outputs]\nprofile_depths = [0, 1, 5]\n", "profile.toml");
  EXPECT_EQ(scene.outputs.profile_depths, (std::vector<double>{0, 1, 5}));
  const Plan plan = makePlan(scene);
  const PassPlan* p = plan.find("light_profile");
  ASSERT_NE(p, nullptr) << plan.toText();
  EXPECT_TRUE(p->implemented);
  EXPECT_TRUE(plan.produces("light_profile"));
  EXPECT_NE(p->why.find("3 depths"), std::string::npos) << p->why;
  EXPECT_NE(p->why.find("16 streams"), std::string::npos) << p->why;
  EXPECT_NE(plan.toText().find("profile.csv"), std::string::npos);
  // The quality knob reaches the entry.
  const Plan eight = makePlan(parseScene(
      std::string(kUnderwater) + "[outputs]\nprofile_depths = [1]\n[quality]\nprofile_streams = 8\n", "profile.toml"));
  ASSERT_TRUE(eight.hasPass("light_profile"));
  EXPECT_NE(eight.find("light_profile")->why.find("8 streams"), std::string::npos);
}

TEST(LightProfilePass, UnavailableWhereNoPlaneParallelProfileExists) {
  // No water: planned, not implemented, saying why (render refuses it, plan shows it).
  const Plan dry = makePlan(parseScene("[outputs]\nprofile_depths = [1]\n", "profile.toml"));
  const PassPlan* p = dry.find("light_profile");
  ASSERT_NE(p, nullptr);
  EXPECT_FALSE(p->implemented);
  EXPECT_NE(p->missing.find("[water]"), std::string::npos) << p->missing;
  // A depth below the bottom.
  const Plan deep = makePlan(parseScene(std::string(kUnderwater) + "[outputs]\nprofile_depths = [1, 10]\n", "profile.toml"));
  ASSERT_TRUE(deep.hasPass("light_profile"));
  EXPECT_FALSE(deep.find("light_profile")->implemented);
  EXPECT_NE(deep.find("light_profile")->missing.find("below the bottom"), std::string::npos);
}

TEST(LightProfilePass, BadDepthsFailAtTheirKey) {
  const std::string negative = errorOf(std::string(kUnderwater) + "[outputs]\nprofile_depths = [1, -2]\n");
  EXPECT_NE(negative.find("outputs.profile_depths"), std::string::npos) << negative;
  EXPECT_NE(negative.find(">= 0"), std::string::npos) << negative;
  EXPECT_NE(negative.find("profile.toml:"), std::string::npos) << negative;
  const std::string order = errorOf(std::string(kUnderwater) + "[outputs]\nprofile_depths = [5, 1]\n");
  EXPECT_NE(order.find("ascending"), std::string::npos) << order;
  EXPECT_NE(errorOf(std::string(kUnderwater) + "[outputs]\nprofile_depths = \"1\"\n").find("array of numbers"),
            std::string::npos);
}

TEST(LightProfilePass, CsvHasEveryBandAndSensorChannelAtEveryDepth) {
  const Scene scene = parseScene(std::string(kUnderwater) + "[spectral]\ncount = 4\n", "profile.toml");
  const SceneProfile profile = sceneLightProfile(scene, {0, 1, 5}, SceneProfileOptions{});
  ASSERT_EQ(profile.channels.size(), 4u + 3u);
  EXPECT_EQ(profile.channels.back().name, "sensor_b");
  const std::string csv = sceneProfileCsv(profile).str();
  std::istringstream in(csv);
  std::string line;
  int rows = 0;
  std::getline(in, line);
  EXPECT_EQ(line.rfind("channel,wavelength_nm,depth_m,E_d,E_u", 0), 0u) << line;
  while (std::getline(in, line)) rows += !line.empty();
  EXPECT_EQ(rows, 7 * 3);
  // E_d falls with depth in every band.
  for (size_t c = 0; c < 4; ++c)
    EXPECT_GT(profile.channels[c].p.rows[0].e_d, profile.channels[c].p.rows[2].e_d) << profile.channels[c].name;
  EXPECT_THROW(sceneLightProfile(scene, {7}, SceneProfileOptions{}), RuntimeError);  // below the bottom
}

}  // namespace
}  // namespace seasim
