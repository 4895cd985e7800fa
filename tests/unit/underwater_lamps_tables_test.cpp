// underwater_lamps_tables_test.cpp — the orders model's host tables kept across passes
// (host/passes/underwater_lamps_tables.h): each is built again only when its own inputs change, and
// what it holds is what the builders make from those inputs.
#include <gtest/gtest.h>

#include <vector>

#include "passes/underwater_lamps_tables.h"
#include "underwater/lamps_bottom_glow.h"
#include "underwater/lamps_ms_table.h"
#include "underwater/lamps_ms_weights.h"

namespace {

UwLamp lamp(float y) {
  UwLamp l{};
  l.position[1] = y;
  l.direction[1] = -1.0f;
  l.cos_cone = 0.94f;
  l.cos_inner = 0.96f;
  return l;
}

UwBand band(float a, float b) {
  UwBand w{};
  w.a = a;
  w.b = b;
  w.c = a + b;
  w.bottom_albedo = 0.5f;
  return w;
}

TEST(UnderwaterLampsTables, EachTableIsBuiltAgainOnlyWhenItsInputsChange) {
  seasim::LampsOrdersTables t;
  const std::vector<UwLamp> lamps = {lamp(-4.0f)};
  std::vector<UwBand> bands = {band(0.1f, 0.3f), band(0.2f, 0.3f)};
  UwParams p{};
  p.bottom_depth = 7.0f;
  const auto build = [&](double g) {
    const int a = t.profiles(lamps, g, 0.8, 4).generation;
    const int b = t.glow(lamps, p, bands, 0.01).generation;
    const int c = t.weights(bands, g, 0.75, 4).generation;
    return std::vector<int>{a, b, c};
  };
  EXPECT_EQ(build(0.9), (std::vector<int>{1, 1, 1}));
  // The same inputs (a moved camera changes none of them): nothing is built.
  p.cam_pos[0] = 3.0f;
  EXPECT_EQ(build(0.9), (std::vector<int>{1, 1, 1}));
  // Another bottom depth: the glow alone.
  p.bottom_depth = 9.0f;
  EXPECT_EQ(build(0.9), (std::vector<int>{1, 2, 1}));
  // Other water: the glow and the weights, not the profiles (they depend on g only).
  bands[1].b = 0.5f;
  bands[1].c = 0.7f;
  EXPECT_EQ(build(0.9), (std::vector<int>{1, 3, 2}));
  // Another g: the profiles and the weights (the glow is the direct light alone: g does not enter it).
  EXPECT_EQ(build(0.8), (std::vector<int>{2, 3, 3}));
  // What they hold is what the builders make.
  EXPECT_EQ(t.profiles(lamps, 0.8, 0.8, 4).values, seasim::lampMsTable(lamps, 0.8, 0.8, 4));
  EXPECT_EQ(t.weights(bands, 0.8, 0.75, 4).values, seasim::lampMsWeights(bands, 0.8, 0.75, 4));
  EXPECT_EQ(t.glow(lamps, p, bands, 0.01).values, seasim::lampBottomGlowTable(lamps, p, bands, 0.01));
}

}  // namespace
