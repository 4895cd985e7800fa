// water_spread_node.cpp — "water_spread": the water's point-spread (passes/water_spread_pass.h):
// adds the forward light kd_multiple kept apart, blurred by the phase's small angles, into the "rgb"
// it wrote.
#include <cmath>
#include <memory>

#include "passes/nodes/underwater_frame.h"
#include "passes/underwater_setup_buffers.h"
#include "passes/water_spread_pass.h"
#include "plan/pass_descriptor.h"
#include "plan/scene_facts.h"
#include "render/pass.h"
#include "render/layer_target.h"
#include "render/radiance_target.h"
#include "underwater/underwater_ordinates_solver.h"  // kOrdinatesSourceMoments
#include "util/error.h"

namespace seasim {

namespace {

// The blur follows the image's size and field of view and the phase's g (and the model's delta-M order).
WaterSpread spreadOf(const Scene& scene, double g, double tan_half_fov_y) {
  const int order = scene.underwater.diffuse == UnderwaterDesc::Diffuse::DiscreteOrdinates
                        ? kOrdinatesSourceMoments
                        : 2;  // the two-stream's f = g² (ordinatesDeltaM)
  return makeWaterSpread(g, order, tan_half_fov_y, scene.camera.width, scene.camera.height);
}

const PassKeys kWaterSpreadKeys = {{"camera.*", "spectral.*", "water.*", "underwater.*"}, kUnderwaterSetupKeys};

class WaterSpreadNode : public Pass {
 public:
  explicit WaterSpreadNode(const PassPlan& entry) : entry_(entry) {}
  PassKeys keys() const override { return kWaterSpreadKeys; }
  void prepare(FrameContext& ctx, PassResources& res) override {
    const Scene& scene = ctx.scene();
    const UwParams& p = res.read<UnderwaterSetupBuffers>("underwater_setup").setup.params;
    pass_ = std::make_unique<WaterSpreadPass>(ctx.device(), entry_, spreadOf(scene, p.g, p.tan_half_fov_y),
                                              scene.spectral.spectral_exr ? p.band_count : 0);
  }
  void execute(FrameContext& ctx, PassResources& res) override {
    UnderwaterGBuffer& gbuffer = res.read<UnderwaterGBuffer>("gbuffer");
    UnderwaterForwardLight& forward = res.read<UnderwaterForwardLight>("forward_light");
    RadianceTarget& target = res.read<RadianceTarget>("rgb");
    const bool spectral = ctx.scene().spectral.spectral_exr;
    ctx.timings.push_back({"water_spread", pass_->run(gbuffer.geometry, forward.depth, forward.rgb, target.rgb,
                                                      spectral ? &forward.spectral : nullptr,
                                                      spectral ? &target.spectral : nullptr)});
    if (res.declaresRead("forward_layer"))  // the blurred light is the forward layer's too
      ctx.timings.push_back({"water_spread_forward_layer", pass_->addRgbInto(res.read<LayerTarget>("forward_layer").image)});
    if (res.declaresRead("forward_band_layer"))  // and, per band, spectral.exr's
      ctx.timings.push_back(
          {"water_spread_forward_layer", pass_->addBandsInto(res.read<LayerTarget>("forward_band_layer").image)});
  }

 private:
  const PassPlan& entry_;
  std::unique_ptr<WaterSpreadPass> pass_;
};

}  // namespace

PassDescriptor waterSpreadDescriptor() {
  PassDescriptor d;
  d.name = "water_spread";
  d.kernel_file = "water_spread.cl";
  d.rule = [](const Scene& scene, const Plan& so_far) -> std::optional<PassPlan> {
    if (!cameraUnderwater(scene) || !underwaterPointSpread(scene)) return std::nullopt;
    // The blurred light also goes into the forward layer, and its per-band blur into the layer per band.
    std::vector<std::string> targets = {"rgb"};
    for (const char* layer : {"forward_layer", "forward_band_layer"})
      if (so_far.produces(layer)) targets.push_back(layer);
    std::vector<std::string> reads = {"underwater_setup", "gbuffer", "forward_light"};
    reads.insert(reads.end(), targets.begin(), targets.end());
    return planEntry(reads, targets,
                     std::string("underwater.model \"discrete_ordinates\", water.g > 0, underwater.point_spread: the light "
                                 "delta-M counts as unscattered, blurred by the phase's small angles "
                                 "(common/water_spread.h)") +
                         (targets.size() > 1 ? "; also into outputs.layers' forward" : "") +
                         (targets.size() > 2 ? ", per band too" : ""));
  };
  d.keys = kWaterSpreadKeys;
  // The blur's grid (water_spread_pass.cpp): per channel its layers, their rows and the blurred
  // result, 2 UWS_LAYERS + 1 floats per cell, for RGB and, with spectral.exr, every band; the grid's
  // distances, 2 floats per cell. The grid is the image's at the factor makeWaterSpread picks from g
  // and the field of view (with the set-up's float g and tan, as the pass gets them).
  d.buffers = [](const Scene& s, const PassPlan& p) -> std::vector<BufferEstimate> {
    const WaterSpread spread =
        spreadOf(s, static_cast<float>(s.water.g), static_cast<float>(std::tan(s.camera.fov_y / 2)));
    const double cells = double(spread.params.low_width) * spread.params.low_height;
    const double channels = 3 + (s.spectral.spectral_exr ? s.spectral.count : 0);
    return {{p.name, "point-spread grid (layers, rows, blurred)", 4 * (2 * UWS_LAYERS + 1) * channels * cells,
             {"channels (RGB and spectral.count)", "grid cells (camera, water.g)"}, {channels, cells}},
            {p.name, "point-spread grid distances", 4 * 2 * cells, {"grid cells (camera, water.g)"}, {cells}}};
  };
  d.cost = [](const Scene&, const PassPlan&) { return 1.0; };
  d.factory = [](const PassPlan& e, const Plan&, const Scene&, const AutoQuality&) -> std::unique_ptr<Pass> {
    return std::make_unique<WaterSpreadNode>(e);
  };
  return d;
}

}  // namespace seasim
