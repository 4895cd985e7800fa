// pass_descriptor_test.cpp — each model's descriptor (plan/pass_descriptor.h) is complete and is the
// one place the planner, the memory budget and the shard estimate learn about the model; the typed
// features generate the kernel defines.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "jobs/shard_balance.h"
#include "passes/sea_single_features.h"
#include "passes/shafts_features.h"
#include "plan/memory_budget.h"
#include "plan/pass_descriptor.h"
#include "plan/plan.h"
#include "scene/scene_parser.h"
#include "scene/set_option.h"
#include "util/error.h"

namespace {

// The shipped sea seen from above: sun at 40 degrees, a flat sand bottom at 8 m.
seasim::Scene flatSea(const std::vector<seasim::Override>& overrides = {}) {
  return seasim::loadScene(SEASIM_SOURCE_DIR "/scenes/flat_sea.toml", overrides);
}

std::vector<std::string> shippedScenes() {
  std::vector<std::string> files;
  for (const auto& e : std::filesystem::directory_iterator(SEASIM_SOURCE_DIR "/scenes"))
    if (e.path().extension() == ".toml") files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  return files;
}

TEST(PassDescriptor, EveryDescriptorHasARuleBuffersACostAndAFactoryUnderItsOwnName) {
  std::set<std::string> seen;
  for (const seasim::PassDescriptor& d : seasim::passDescriptors()) {
    SCOPED_TRACE(d.name + "@" + d.kernel_file);
    EXPECT_FALSE(d.name.empty());
    // A pass with no kernel (the underwater set-up: host tables and their upload) builds nothing with
    // relaxed maths.
    if (d.kernel_file.empty()) EXPECT_FALSE(d.fast_math);
    EXPECT_TRUE(d.rule);
    EXPECT_TRUE(d.buffers);
    EXPECT_TRUE(d.cost);
    EXPECT_TRUE(d.factory);
    EXPECT_TRUE(seen.insert(d.name + "@" + d.kernel_file).second) << "two descriptors for one plan entry";
  }
  EXPECT_GE(seen.size(), 14u);
}

TEST(PassDescriptor, EveryPlannedEntryOfEveryShippedSceneComesFromItsDescriptor) {
  for (const std::string& file : shippedScenes()) {
    SCOPED_TRACE(file);
    const seasim::Scene scene = seasim::loadScene(file);
    const seasim::Plan plan = seasim::makePlan(scene);
    ASSERT_FALSE(plan.passes.empty());
    for (const seasim::PassPlan& entry : plan.passes) {
      const seasim::PassDescriptor* d = seasim::descriptorOf(entry);
      ASSERT_NE(d, nullptr) << entry.name;
      // The defines are the features' own plus the fast-maths switch the descriptor allows.
      EXPECT_EQ(entry.defines,
                seasim::kernelDefines(entry.features.get(), seasim::fastMathFor(scene) && d->fast_math))
          << entry.name;
      // Per pixel and band: a pass with a kernel costs something; a host-only one's work is per frame.
      if (entry.kernel_file.empty())
        EXPECT_EQ(d->cost(scene, entry), 0.0) << entry.name;
      else
        EXPECT_GT(d->cost(scene, entry), 0.0) << entry.name;
    }
  }
}

TEST(PassDescriptor, KnobsAreReadFromTheDescriptorsOwnListWithItsDefaults) {
  const seasim::PassDescriptor* second = nullptr;
  for (const auto& d : seasim::passDescriptors())
    if (d.name == "sea_second") second = &d;
  ASSERT_NE(second, nullptr);
  seasim::Scene scene = flatSea();
  scene.quality.erase("sea_nz");
  EXPECT_EQ(second->knob(scene, "sea_nz"), 12.0);  // absent: the descriptor's default
  scene.quality["sea_nz"] = seasim::Knob{false, 20.0};
  EXPECT_EQ(second->knob(scene, "sea_nz"), 20.0);
  EXPECT_EQ(second->settledKnob(scene, "sea_nz"), 20.0);
  scene.quality["sea_nz"] = seasim::Knob{true, 8.0};  // "auto": its placeholder, or the default once settled
  EXPECT_EQ(second->knob(scene, "sea_nz"), 8.0);
  EXPECT_EQ(second->settledKnob(scene, "sea_nz"), 12.0);
  // A knob the model does not list is a programming error, not a silent default.
  EXPECT_THROW((void)second->knob(scene, "froxel_x"), seasim::RuntimeError);
}

TEST(PassDescriptor, TheBudgetAndTheShardCostAskTheDescriptors) {
  seasim::Scene scene = flatSea({{"sea.second_order", "true", {}}, {"sea.model", "\"paper\"", {}}});
  const seasim::Plan plan = seasim::makePlan(scene);
  ASSERT_TRUE(plan.hasPass("sea_second"));
  const auto buffers = seasim::estimateBuffers(scene, plan);
  const bool maps = std::any_of(buffers.begin(), buffers.end(), [](const seasim::BufferEstimate& b) {
    return b.pass == "sea_second" && b.what == "scattering maps";
  });
  EXPECT_TRUE(maps);
  // An entry no descriptor made (a plan built by hand) allocates nothing of its own and costs as much
  // as the unit pass.
  seasim::Plan by_hand;
  by_hand.passes.push_back({"fill", "none.cl", {}, {"scene"}, {"rgb"}, "test", true, ""});
  seasim::Plan unit;
  unit.passes.push_back(*plan.find("sea_single"));
  EXPECT_EQ(seasim::estimateItemCost(scene, by_hand), seasim::estimateItemCost(scene, unit));
  EXPECT_EQ(seasim::estimateBuffers(scene, by_hand).size(), seasim::estimateBuffers(scene, seasim::Plan{}).size());
  // The second order at 4x the depth planes costs more, through its descriptor's knobs.
  seasim::Scene finer = scene;
  finer.quality["sea_nz"] = seasim::Knob{false, 48.0};
  EXPECT_GT(seasim::estimateItemCost(finer, plan), seasim::estimateItemCost(scene, plan));
}

TEST(Features, TheDefinesAreGeneratedFromTheTypedFieldsInOrder) {
  seasim::SeaSingleFeatures f;
  f.reflection = true;
  f.bottom = true;
  f.sky_model = 3;
  f.waves = true;
  f.wave_filter = true;
  f.supersample = 1;
  const std::vector<std::string> expected = {
      "SEASIM_HAS_REFLECTION=1", "SEASIM_HAS_SINGLE_SCATTERING=0", "SEASIM_HAS_BOTTOM=1",  "SEASIM_HAS_SUN=0",
      "SEASIM_SPECTRAL_OUTPUT=0", "SEASIM_HAS_WAVES=1",           "SEASIM_SKY_MODEL=3",   "SEASIM_BOTTOM_CAUSTICS=0",
      "SEASIM_SEA_MODEL=0",      "SEASIM_WAVE_FILTER=1"};
  EXPECT_EQ(seasim::kernelDefines(&f, false), expected);
  std::vector<std::string> fast = expected;
  fast.push_back("SEASIM_FAST_MATH=1");
  EXPECT_EQ(seasim::kernelDefines(&f, true), fast);
  EXPECT_EQ(seasim::featuresText(&f).find("reflection=1 single_scattering=0 bottom=1"), 0u);
  // Optional defines appear only when their feature is on.
  f.waves = false;
  f.supersample = 3;
  const auto defines = seasim::kernelDefines(&f, false);
  EXPECT_EQ(std::count(defines.begin(), defines.end(), "SEASIM_SUPERSAMPLE=3"), 1);
  EXPECT_EQ(std::count_if(defines.begin(), defines.end(),
                          [](const std::string& d) { return d.rfind("SEASIM_WAVE_FILTER", 0) == 0; }),
            0);
}

TEST(Features, APassReadsItsOwnStructAndRefusesAnother) {
  const seasim::Plan plan = seasim::makePlan(flatSea());
  const seasim::PassPlan& sea = *plan.find("sea_single");
  EXPECT_TRUE(sea.featuresAs<seasim::SeaSingleFeatures>().bottom);
  EXPECT_THROW((void)sea.featuresAs<seasim::ShaftsFeatures>(), seasim::RuntimeError);
  const seasim::PassPlan& check = *plan.find("nonfinite_check");
  EXPECT_THROW((void)check.featuresAs<seasim::SeaSingleFeatures>(), seasim::RuntimeError);
  // `seasim plan` prints the features beside the defines they made, one pass per line.
  const std::string text = plan.toText();
  EXPECT_NE(text.find("-DSEASIM_HAS_BOTTOM=1"), std::string::npos) << text;
  EXPECT_NE(text.find("  | features: reflection=1 single_scattering=1 bottom=1 sun=1"), std::string::npos) << text;
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 2);
}

// The reporting commands (seasim bench, seasim underwater-regions) find passes by role, never by a name
// of their own: each role is held by exactly one descriptor, the band-loop roles say which timing is
// their loop and how many items it runs, and the names the CSV columns are built from are unchanged.
TEST(PassDescriptor, EachReportingRoleIsHeldByExactlyOneDescriptor) {
  using seasim::PassRole;
  for (PassRole role : {PassRole::SeaShading, PassRole::SeaSecondOrder, PassRole::Spotlights, PassRole::ShadowMaps,
                        PassRole::UnderwaterGBuffer, PassRole::UnderwaterSingleScattering,
                        PassRole::UnderwaterShading, PassRole::UnderwaterLamps, PassRole::Check}) {
    const auto& all = seasim::passDescriptors();
    EXPECT_EQ(std::count_if(all.begin(), all.end(), [&](const auto& d) { return d.role == role; }), 1)
        << "role " << static_cast<int>(role);
  }
  const seasim::Scene sea = flatSea();
  const double pixels = static_cast<double>(sea.camera.width) * sea.camera.height;
  for (PassRole role : {PassRole::SeaShading, PassRole::UnderwaterShading}) {
    const seasim::PassDescriptor& d = seasim::descriptorFor(role);
    EXPECT_EQ(d.band_loop_timing, d.name);
    ASSERT_TRUE(d.band_loop_items);
    EXPECT_EQ(d.band_loop_items(sea, 16), pixels * 16);
  }
  const seasim::Scene seabed =
      seasim::loadScene(SEASIM_SOURCE_DIR "/scenes/seabed.toml",
                        {seasim::parseSetOption("quality.froxel_x=8"), seasim::parseSetOption("quality.froxel_y=4"),
                         seasim::parseSetOption("quality.froxel_z=16")});
  const seasim::PassDescriptor& froxel = seasim::descriptorFor(PassRole::UnderwaterSingleScattering);
  ASSERT_TRUE(froxel.band_loop_items);
  EXPECT_EQ(froxel.band_loop_timing.rfind(froxel.name, 0), 0u);  // one of the pass's kernels
  const int injected = seabed.underwater.injection == seasim::UnderwaterDesc::Injection::Spectral ? 16 : 3;
  EXPECT_EQ(froxel.band_loop_items(seabed, 16), 8.0 * 4 * 16 * injected);
  EXPECT_EQ(seasim::descriptorFor(PassRole::UnderwaterShading).name + "_ms", "kd_multiple_ms");
  EXPECT_EQ(seasim::descriptorFor(PassRole::UnderwaterGBuffer).name + "_ms", "raycast_ms");
  EXPECT_EQ(seasim::descriptorFor(PassRole::UnderwaterSingleScattering).name + "_ms", "froxel_ms");
  EXPECT_EQ(seasim::descriptorFor(PassRole::ShadowMaps).name + "_ms", "shadow_maps_ms");
  EXPECT_EQ(seasim::descriptorFor(PassRole::Spotlights).name + "_ms", "shafts_ms");
}

}  // namespace
