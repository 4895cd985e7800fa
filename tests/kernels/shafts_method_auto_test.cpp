// shafts_method_auto_test.cpp — quality.shafts_method = "auto" (host/quality/shafts_method_auto.h) on
// the test device, on spot_sphere at 64x40 (the search runs at the scene's own size there):
//  * the chosen method and setting meets the budget against a reference rendered here with more steps,
//    and every candidate predicted cheaper missed the budget;
//  * the search tries each method, keeps a knob the scene gives fixed, and stops the march at its
//    first setting within budget;
//  * the decision is cached per scene and budget but not per camera pose;
//  * the Renderer plans the measured method for "auto" as written and the rule's for the key absent.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <unistd.h>

#include "passes/shafts_pass.h"
#include "plan/plan.h"
#include "quality/auto_quality.h"
#include "quality/quality_search.h"
#include "quality/shafts_method_auto.h"
#include "reference/compare.h"
#include "reference/shafts_reference.h"
#include "render/renderer.h"
#include "scene/scene_parser.h"
#include "test_device.h"

namespace {

namespace fs = std::filesystem;
using seasim::Override;
using seasim::ShaftsMethod;

seasim::Device& device() { return seasim::test::testDevice(); }

Override set(const std::string& key, const std::string& value) { return {key, value, {"test", 1}}; }

// spot_sphere gives n = 30, m = 6 in its file; the tests that search the planes' ladder set them "auto".
seasim::Scene autoScene(std::vector<Override> more = {}) {
  std::vector<Override> o = {set("camera.width", "64"), set("camera.height", "40"),
                             set("quality.shafts_method", "\"auto\""), set("quality.shadow_map_size", "256")};
  o.insert(o.end(), more.begin(), more.end());
  return seasim::loadScene(std::string(SEASIM_SOURCE_DIR) + "/scenes/spot_sphere.toml", o);
}

// A short ladder keeps each search to about a second.
seasim::ShaftsMethodOptions shortLadder(double budget) {
  seasim::ShaftsMethodOptions o;
  o.budget_levels = budget;
  o.march_steps = {5, 10, 20, 40};
  o.planes = {10, 30};
  o.subplanes = {1, 6};
  o.use_cache = false;
  return o;
}

std::string tempCacheDir(const char* name) {
  const fs::path dir =
      fs::temp_directory_path() / ("seasim_shafts_method_" + std::string(name) + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  return dir.string();
}

// Renders `scene` with its method fixed as `c` through the shafts pass alone.
seasim::Image renderSetting(const seasim::Scene& scene, const seasim::ShaftsMethodCandidate& c) {
  const seasim::Scene s = seasim::withShaftsMethod(scene, c);
  const seasim::Plan plan = seasim::makePlan(s);
  seasim::ShaftsPass pass(device(), s, *plan.find("shafts"), seasim::ShaftsPass::configFromScene(s));
  pass.run();
  seasim::Image img;
  img.resize(s.camera.width, s.camera.height, 3);
  pass.readRgb(img.pixels);
  return img;
}

TEST(ShaftsMethodAuto, ChoiceMeetsTheBudgetAndEveryCheaperCandidateMissesIt) {
  const seasim::Scene scene =
      autoScene({set("quality.shafts_planes", "\"auto\""), set("quality.shafts_subplanes", "\"auto\"")});
  ASSERT_TRUE(seasim::shaftsMethodMeasured(scene));
  for (double budget : {1.0, 0.3}) {
    const auto r = seasim::chooseShaftsMethod(device(), scene, shortLadder(budget));
    ASSERT_TRUE(r.has_value());
    EXPECT_EQ(r->search_width, 64);
    EXPECT_EQ(r->search_height, 40);
    for (const auto& c : r->candidates)
      std::printf("[ measured ] budget %g: %-22s RMS %.3f levels, predicted %.2f ms\n", budget,
                  seasim::describeShaftsSetting(c).c_str(), c.rmse_8bit, c.predicted_ms);
    std::printf("[ measured ] budget %g: chosen %s\n", budget, seasim::describeShaftsSetting(r->chosen).c_str());
    EXPECT_TRUE(r->met_budget);
    EXPECT_LE(r->chosen.rmse_8bit, budget);
    for (const auto& c : r->candidates)
      if (c.predicted_ms < r->chosen.predicted_ms) EXPECT_GT(c.rmse_8bit, budget) << seasim::describeShaftsSetting(c);

    // Each method was tried; the march stopped at its first setting within budget.
    bool tried[3] = {false, false, false};
    int march_in_budget = 0;
    for (const auto& c : r->candidates) {
      tried[static_cast<int>(c.method)] = true;
      if (c.method == ShaftsMethod::March && c.rmse_8bit <= budget) ++march_in_budget;
    }
    EXPECT_TRUE(tried[0] && tried[1] && tried[2]);
    EXPECT_LE(march_in_budget, 1);

    // The choice rendered again against a reference with more steps than the search's.
    const seasim::Image ref = seasim::renderShaftsReference(scene, 8000);
    const seasim::CompareResult cmp = seasim::compareImages(renderSetting(scene, r->chosen), ref, scene.camera.exposure_ev);
    EXPECT_EQ(cmp.nonfinite, 0);
    EXPECT_LE(cmp.rmse_8bit, budget + 0.02);  // 4000 against 8000 steps: 0.004 levels here
    EXPECT_NEAR(cmp.rmse_8bit, r->chosen.rmse_8bit, 0.02);
  }
}

TEST(ShaftsMethodAuto, AnUnreachableBudgetTakesTheCheapestAtTheErrorFloor) {
  const seasim::Scene scene =
      autoScene({set("quality.shafts_planes", "\"auto\""), set("quality.shafts_subplanes", "\"auto\"")});
  const auto r = seasim::chooseShaftsMethod(device(), scene, shortLadder(1e-6));
  ASSERT_TRUE(r.has_value());
  EXPECT_FALSE(r->met_budget);
  double least = r->candidates.front().rmse_8bit;
  for (const auto& c : r->candidates) least = std::min(least, c.rmse_8bit);
  EXPECT_LE(r->chosen.rmse_8bit, least * (1 + seasim::kErrorFloorTolerance));
  for (const auto& c : r->candidates)
    if (c.rmse_8bit <= least * (1 + seasim::kErrorFloorTolerance))
      EXPECT_GE(c.predicted_ms, r->chosen.predicted_ms) << seasim::describeShaftsSetting(c);
}

TEST(ShaftsMethodAuto, KnobsTheSceneGivesAreNotSearched) {
  // spot_sphere's file gives n = 30, m = 6; the march's steps given as 40.
  const seasim::Scene scene = autoScene({set("quality.shafts_march_steps", "40")});
  seasim::ShaftsMethodOptions o = shortLadder(1.0);
  const auto r = seasim::chooseShaftsMethod(device(), scene, o);
  ASSERT_TRUE(r.has_value());
  for (const auto& c : r->candidates) {
    if (c.method == ShaftsMethod::March) EXPECT_EQ(c.march_steps, 40);
    if (c.method == ShaftsMethod::Planes) {
      EXPECT_EQ(c.planes, 30);
      EXPECT_EQ(c.subplanes, 6);
    }
  }
  // withShaftsMethod writes the choice in as given numbers: no "auto" left for the pass to search.
  const seasim::Scene chosen = seasim::withShaftsMethod(scene, r->chosen);
  EXPECT_FALSE(chosen.quality.at("shafts_method").automatic);
  EXPECT_FALSE(seasim::shaftsMethodMeasured(chosen));
}

TEST(ShaftsMethodAuto, PickRuleOnAHandMadeTable) {
  using C = seasim::ShaftsMethodCandidate;
  auto cand = [](ShaftsMethod m, double rmse, double ms) {
    C c;
    c.method = m;
    c.rmse_8bit = rmse;
    c.predicted_ms = ms;
    return c;
  };
  const std::vector<C> t = {cand(ShaftsMethod::Intervals, 0.2, 60), cand(ShaftsMethod::March, 0.7, 26),
                            cand(ShaftsMethod::March, 0.27, 56), cand(ShaftsMethod::Planes, 0.22, 54)};
  EXPECT_EQ(seasim::pickShaftsMethod(t, 1.0), 1);   // the march at few steps
  EXPECT_EQ(seasim::pickShaftsMethod(t, 0.25), 3);  // the planes
  EXPECT_EQ(seasim::pickShaftsMethod(t, 0.21), 0);  // only the intervals
  EXPECT_EQ(seasim::pickShaftsMethod(t, 0.1), 0);   // none: the most accurate
  // Nothing meets the budget: the cheapest at the floor (within 2 % of the least error), not the planes'
  // last 0.0002 levels for 13x the time (stage at 0.25 levels, at the search size).
  const std::vector<C> floor = {cand(ShaftsMethod::Intervals, 0.38456, 164), cand(ShaftsMethod::March, 0.3932, 361),
                                cand(ShaftsMethod::Planes, 0.38439, 2069), cand(ShaftsMethod::Planes, 0.4160, 201)};
  EXPECT_EQ(seasim::pickShaftsMethod(floor, 0.25), 0);
  EXPECT_EQ(seasim::pickShaftsMethod(floor, 0.3844), 2);  // within budget: the budget decides
  const std::vector<C> tie = {cand(ShaftsMethod::March, 0.5, 30), cand(ShaftsMethod::Planes, 0.4, 30)};
  EXPECT_EQ(seasim::pickShaftsMethod(tie, 1.0), 1);  // equal time: the lower error
  EXPECT_EQ(seasim::pickShaftsMethod({}, 1.0), -1);
}

TEST(ShaftsMethodAuto, CachedPerSceneAndBudgetNotPerCameraPose) {
  const seasim::Scene scene = autoScene();
  seasim::ShaftsMethodOptions o = shortLadder(1.0);
  o.use_cache = true;
  o.cache_dir = tempCacheDir("cache");
  seasim::ShaftsMethodOptions lookup = o;
  lookup.search = false;
  EXPECT_FALSE(seasim::chooseShaftsMethod(device(), scene, lookup).has_value());  // nothing cached yet

  const auto first = seasim::chooseShaftsMethod(device(), scene, o);
  ASSERT_TRUE(first.has_value());
  EXPECT_FALSE(first->from_cache);
  EXPECT_EQ(fs::path(first->cache_file).stem().string(), "method_" + seasim::shaftsMethodKey(device(), scene, o));
  const auto second = seasim::chooseShaftsMethod(device(), scene, lookup);
  ASSERT_TRUE(second.has_value());
  EXPECT_TRUE(second->from_cache);
  EXPECT_TRUE(second->candidates.empty());
  EXPECT_EQ(second->chosen.method, first->chosen.method);
  EXPECT_EQ(second->chosen.march_steps, first->chosen.march_steps);
  EXPECT_EQ(second->chosen.planes, first->chosen.planes);
  EXPECT_DOUBLE_EQ(second->chosen.rmse_8bit, first->chosen.rmse_8bit);

  // The camera moved: the same decision (a moving camera does not search per frame).
  seasim::Scene moved = scene;
  moved.camera.position.x += 0.5;
  moved.camera.look_at.y += 0.2;
  const auto after_move = seasim::chooseShaftsMethod(device(), moved, lookup);
  ASSERT_TRUE(after_move.has_value());
  EXPECT_EQ(after_move->chosen.method, first->chosen.method);
  // Another budget, image size or lamp is another entry.
  seasim::ShaftsMethodOptions tighter = o;
  tighter.budget_levels = 0.5;
  EXPECT_NE(seasim::shaftsMethodKey(device(), scene, tighter), seasim::shaftsMethodKey(device(), scene, o));
  seasim::Scene wider = scene;
  wider.camera.width = 128;
  EXPECT_NE(seasim::shaftsMethodKey(device(), wider, o), seasim::shaftsMethodKey(device(), scene, o));
  seasim::Scene lamp = scene;
  lamp.spotlights[0].cone *= 0.9;
  EXPECT_NE(seasim::shaftsMethodKey(device(), lamp, o), seasim::shaftsMethodKey(device(), scene, o));
  fs::remove_all(o.cache_dir);
}

const std::string& shaftsDefines(const seasim::Plan& plan, std::string& out) {
  out.clear();
  for (const auto& d : plan.find("shafts")->defines) out += d + " ";
  return out;
}

TEST(ShaftsMethodAuto, TheRendererPlansTheMeasuredMethodOnlyWhenAutoIsWritten) {
  const std::string dir = tempCacheDir("renderer");
  const char* old = std::getenv("SEASIM_CACHE_DIR");
  const std::string saved = old ? old : "";
  setenv("SEASIM_CACHE_DIR", dir.c_str(), 1);
  std::string defines;

  const seasim::Scene scene = autoScene();
  seasim::Renderer renderer(device(), scene, seasim::shippedPasses());
  const seasim::Knob& method = renderer.scene().quality.at("shafts_method");
  EXPECT_FALSE(method.automatic);  // measured and written in before planning
  const auto cached = [&] {
    seasim::ShaftsMethodOptions lookup;
    lookup.search = false;
    return seasim::chooseShaftsMethod(device(), scene, lookup);
  }();
  ASSERT_TRUE(cached.has_value());  // the renderer's search filled the default folder
  EXPECT_EQ(static_cast<int>(method.value), static_cast<int>(cached->chosen.method));
  shaftsDefines(renderer.plan(), defines);
  const bool march = cached->chosen.method == ShaftsMethod::March;
  const bool intervals = cached->chosen.method == ShaftsMethod::Intervals;
  EXPECT_NE(defines.find(std::string("SEASIM_SHAFTS_MARCH=") + (march ? "1" : "0")), std::string::npos) << defines;
  EXPECT_NE(defines.find(std::string("SEASIM_SHAFTS_INTERVALS=") + (intervals ? "1" : "0")), std::string::npos) << defines;
  EXPECT_EQ(renderer.plan().find("shadow_maps") != nullptr, cached->chosen.method == ShaftsMethod::Planes);
  const seasim::FrameResult frame = renderer.render();
  EXPECT_EQ(frame.nonfinite, 0);
  EXPECT_GT(frame.rgb.pixels.size(), 0u);

  // The camera moves: the renderer keeps the method (read from the cache, no new search).
  seasim::Scene moved = scene;
  moved.camera.position.x += 0.3;
  renderer.update(moved, {"camera.position"});
  EXPECT_EQ(static_cast<int>(renderer.scene().quality.at("shafts_method").value), static_cast<int>(cached->chosen.method));
  EXPECT_FALSE(renderer.scene().quality.at("shafts_method").automatic);
  size_t entries = 0;
  for (const auto& e : fs::directory_iterator(dir + "/shafts_auto")) entries += e.path().filename().string().rfind("method_", 0) == 0;
  EXPECT_EQ(entries, 1u);

  // The key absent: the planner's rule, nothing measured (spot_sphere has 3 objects: the intervals).
  const seasim::Scene plain = seasim::loadScene(std::string(SEASIM_SOURCE_DIR) + "/scenes/spot_sphere.toml",
                                                {set("camera.width", "64"), set("camera.height", "40")});
  EXPECT_FALSE(seasim::shaftsMethodMeasured(plain));
  seasim::Renderer rule(device(), plain, seasim::shippedPasses());
  EXPECT_TRUE(rule.scene().quality.at("shafts_method").automatic);
  EXPECT_NE(shaftsDefines(rule.plan(), defines).find("SEASIM_SHAFTS_INTERVALS=1"), std::string::npos);

  if (saved.empty()) unsetenv("SEASIM_CACHE_DIR"); else setenv("SEASIM_CACHE_DIR", saved.c_str(), 1);
  fs::remove_all(dir);
}

}  // namespace
