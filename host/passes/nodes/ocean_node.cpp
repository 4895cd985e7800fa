// ocean_node.cpp — "ocean_fft": the FFT ocean (004 §3, passes/ocean_pass.h) at the scene's
// surface.time. Set up (h̃0, FFT plan, maps) when the wave spectrum's keys change; a new time only
// evolves the spectra and runs the FFTs again into the same maps.
#include <memory>

#include "passes/nodes/standard_passes.h"
#include "passes/ocean_pass.h"

namespace seasim {

namespace {

class OceanNode : public Pass {
 public:
  PassKeys keys() const override {
    return {{"surface.type", "surface.grid", "surface.patch_size", "surface.wind_speed", "surface.wind_direction_deg",
             "surface.choppiness", "surface.directional_exponent", "surface.small_wave", "surface.depth",
             "surface.loop_period", "surface.seed"},
            {"surface.time"}};
  }
  void prepare(FrameContext& ctx, PassResources& res) override {
    res.publish("ocean_maps", std::make_shared<OceanPass>(ctx.device(), oceanConfigFromSurface(ctx.scene().surface)));
  }
  void execute(FrameContext& ctx, PassResources& res) override {
    ctx.timings.push_back({"ocean_fft", res.read<OceanPass>("ocean_maps").run(ctx.scene().surface.time)});
  }
};

}  // namespace

void registerOceanPass(PassRegistry& registry) {
  registry.add("ocean_fft", [](const PassPlan&, const Plan&, const Scene&) { return std::make_unique<OceanNode>(); });
}

}  // namespace seasim
