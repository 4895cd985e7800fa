// memory_estimate_test.cpp — the memory budget's estimate (plan/memory_budget.h) against the device
// bytes a render really allocates (device/allocation_count.h counts every clCreateBuffer): for every
// shipped scene the estimate must cover what was allocated (else a render the budget let through can
// still run out of memory) and must not exceed it by more than half (else the budget refuses renders
// that fit).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "device/allocation_count.h"
#include "passes/nodes/standard_passes.h"
#include "plan/memory_budget.h"
#include "render/renderer.h"
#include "scene/scene_parser.h"
#include "test_device.h"

namespace {

using seasim::Override;

struct SceneCase {
  std::string file;                // scenes/<file>
  std::vector<Override> settings;  // on top of the scene's own
  std::string name;                // the case's name: the file's, and what the settings add
};
void PrintTo(const SceneCase& c, std::ostream* os) { *os << c.name; }

std::vector<SceneCase> shippedScenes() {
  std::vector<SceneCase> out;
  for (const auto& e : std::filesystem::directory_iterator(SEASIM_SOURCE_DIR "/scenes"))
    if (e.path().extension() == ".toml")
      out.push_back({e.path().filename().string(), {}, e.path().stem().string()});
  std::sort(out.begin(), out.end(), [](const SceneCase& a, const SceneCase& b) { return a.file < b.file; });
  // Outputs no shipped scene asks for, whose passes allocate their own buffers: spectral.exr with the
  // layers per band (the froxels' term per band, its one-band volume and distances at infinity).
  out.push_back({"seabed.toml",
                 {{"spectral.spectral_exr", "true", {}},
                  {"outputs.layers", "[\"clear\", \"direct\", \"backscatter\", \"veiling\"]", {}}},
                 "seabed_spectral_layers"});
  return out;
}

TEST(DeviceAllocations, CountsABuffersBytesWhileItLives) {
  seasim::Device& device = seasim::test::testDevice();
  const uint64_t before = seasim::DeviceAllocations::live();
  const uint64_t made = seasim::DeviceAllocations::count();
  seasim::DeviceAllocations::resetPeak();
  {
    cl::Buffer a(device.context(), CL_MEM_READ_WRITE, 1000);
    cl::Buffer b(device.context(), CL_MEM_READ_WRITE, 24);
    cl::Buffer copy = a;  // one buffer, held twice
    EXPECT_EQ(seasim::DeviceAllocations::live() - before, 1024u);
    EXPECT_EQ(seasim::DeviceAllocations::count() - made, 2u);
  }
  // Freed by the driver when the last handle goes.
  EXPECT_EQ(seasim::DeviceAllocations::live(), before);
  EXPECT_EQ(seasim::DeviceAllocations::peak() - before, 1024u);
}

class MemoryEstimate : public ::testing::TestWithParam<SceneCase> {};

TEST_P(MemoryEstimate, CoversTheDeviceBytesARenderAllocatesAndAtMostHalfAgainAsMany) {
  const std::string file = std::string(SEASIM_SOURCE_DIR) + "/scenes/" + GetParam().file;
  // A size at which the per-pixel images are the bulk, as in production renders.
  std::vector<Override> overrides = {{"camera.width", "640", {}}, {"camera.height", "360", {}}};
  overrides.insert(overrides.end(), GetParam().settings.begin(), GetParam().settings.end());
  const seasim::Scene scene = seasim::loadScene(file, overrides);
  seasim::Device& device = seasim::test::testDevice();
  const uint64_t before = seasim::DeviceAllocations::live();
  seasim::DeviceAllocations::resetPeak();
  double estimate = 0;
  {
    // standardPasses(): the "auto" knobs' placeholders, no quality search (its own buffers are not the frame's).
    seasim::Renderer renderer(device, scene, seasim::standardPasses());
    for (const seasim::BufferEstimate& b : seasim::estimateBuffers(scene, renderer.plan()))
      if (!b.host) estimate += b.bytes;
    (void)renderer.render();
  }
  const double allocated = double(seasim::DeviceAllocations::peak() - before);
  std::printf("%s: estimate %.0f bytes, allocated %.0f bytes, ratio %.3f\n", GetParam().name.c_str(), estimate,
              allocated, estimate / allocated);
  EXPECT_GE(estimate, allocated);
  EXPECT_LE(estimate, 1.5 * allocated);
}

INSTANTIATE_TEST_SUITE_P(ShippedScenes, MemoryEstimate, ::testing::ValuesIn(shippedScenes()),
                         [](const ::testing::TestParamInfo<SceneCase>& info) {
                           std::string name = info.param.name;
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

}  // namespace
