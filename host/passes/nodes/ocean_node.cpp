// ocean_node.cpp — "ocean_fft": the FFT ocean (004 §3, passes/ocean_pass.h) at the scene's
// surface.time. Set up (h̃0, FFT plan, maps) when the wave spectrum's keys change; a new time only
// evolves the spectra and runs the FFTs again into the same maps.
#include <memory>

#include "passes/nodes/standard_passes.h"
#include "passes/ocean_features.h"
#include "passes/ocean_pass.h"
#include "plan/pass_descriptor.h"
#include "plan/scene_facts.h"

namespace seasim {

namespace {

const PassKeys kOceanKeys = {{"surface.type", "surface.grid", "surface.patch_size", "surface.wind_speed",
                              "surface.wind_direction_deg", "surface.choppiness", "surface.directional_exponent",
                              "surface.small_wave", "surface.depth", "surface.loop_period", "surface.seed"},
                             {"surface.time"}};

class OceanNode : public Pass {
 public:
  PassKeys keys() const override { return kOceanKeys; }
  void prepare(FrameContext& ctx, PassResources& res) override {
    ocean_ = std::make_unique<OceanPass>(ctx.device(), oceanConfigFromSurface(ctx.scene().surface));
    res.publish("ocean_maps", std::make_shared<OceanMaps>(ocean_->maps()));
  }
  void execute(FrameContext& ctx, PassResources&) override {
    ctx.timings.push_back({"ocean_fft", ocean_->run(ctx.scene().surface.time)});
  }

 private:
  std::unique_ptr<OceanPass> ocean_;
};

}  // namespace

PassDescriptor oceanDescriptor() {
  PassDescriptor d;
  d.name = "ocean_fft";
  d.kernel_file = "ocean.cl";
  // The sea view's wave normals, and the caustic maps under water.
  d.rule = [](const Scene& scene, const Plan&) -> std::optional<PassPlan> {
    if (!oceanForSea(scene) && !oceanForUnderwaterCaustics(scene)) return std::nullopt;
    auto features = std::make_shared<OceanFeatures>();
    features->choppy = scene.surface.choppiness > 0;
    return planEntry({"scene"}, {"ocean_maps"}, "surface.type = \"fft\"", features);
  };
  d.keys = kOceanKeys;
  // Built without the plan's relaxed maths: its error was not measured under it.
  d.fast_math = false;
  d.buffers = [](const Scene& s, const PassPlan& p) -> std::vector<BufferEstimate> {
    const double N = s.surface.grid;
    // h0, spectra, height, slope, displacement, normal, Jacobian, folding, FFT scratch (ocean_pass).
    return {{p.name, "ocean maps", 4 * 28 * N * N, {"surface.grid", "surface.grid"}, {N, N}}};
  };
  d.cost = [](const Scene&, const PassPlan&) { return 0.4; };
  d.factory = [](const PassPlan&, const Plan&, const Scene&, const AutoQuality&) -> std::unique_ptr<Pass> {
    return std::make_unique<OceanNode>();
  };
  return d;
}

}  // namespace seasim
