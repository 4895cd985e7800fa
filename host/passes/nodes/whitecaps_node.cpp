// whitecaps_node.cpp — "whitecaps": sea-surface foam (passes/whitecaps_pass.h, the model in
// kernels/common/whitecaps.h) over the "rgb" the sea passes wrote, where the FFT ocean's Jacobian is
// lowest, covering Monahan & O'Muircheartaigh's whitecap fraction at the scene's wind. Its one scene
// key, surface.whitecaps, is declared here.
#include <memory>

#include "passes/nodes/standard_passes.h"
#include "passes/ocean_pass.h"
#include "passes/whitecaps_features.h"
#include "passes/whitecaps_math.h"
#include "passes/whitecaps_pass.h"
#include "passes/whitecaps_threshold.h"
#include "plan/pass_descriptor.h"
#include "plan/scene_facts.h"
#include "render/pass.h"
#include "render/radiance_target.h"
#include "scene/model_keys.h"
#include "util/error.h"

namespace seasim {

namespace {

// The foam's radiance follows the light and the sensor, its footprints the camera, its coverage the
// wind; a new ocean (its keys) or a new frame of it is a new "ocean_maps", which sets up or reruns it.
// A camera moved at the same image size changes only the parameter block's camera, and an ocean not
// written since the last frame keeps its foam mask (the Jacobian's read-back, its quantile and the
// mask's mips): the preview's orbit recomposites the foam alone.
const PassKeys kWhitecapsKeys = {
    {"camera.width", "camera.height", "sun.*", "sky.*", "spectral.*", "surface.whitecaps", "surface.wind_speed"},
    {"camera.*"}};

class WhitecapsNode : public Pass {
 public:
  explicit WhitecapsNode(const PassPlan& entry) : entry_(entry) {}
  PassKeys keys() const override { return kWhitecapsKeys; }
  void prepare(FrameContext& ctx, PassResources& res) override {
    const OceanMaps& ocean = res.read<OceanMaps>("ocean_maps");
    pass_ = std::make_unique<WhitecapsPass>(ctx.device(), ctx.scene(), entry_, ctx.grid(), ctx.sensor(), ocean.n(),
                                            ocean.patchSize());
    fresh_ = true;
    foam_ocean_version_ = 0;
  }
  void execute(FrameContext& ctx, PassResources& res) override {
    if (!fresh_ && anyKeyMatches("camera.*", ctx.changedKeys())) pass_->moveCamera(ctx.scene().camera);
    fresh_ = false;
    const OceanMaps& ocean = res.read<OceanMaps>("ocean_maps");
    RadianceTarget& target = res.read<RadianceTarget>("rgb");
    if (res.version("ocean_maps") != foam_ocean_version_) {
      const double coverage = whitecaps_d::whitecaps_coverage(ctx.scene().surface.wind_speed);
      const WhitecapsFoamLevels levels = whitecapsFoamLevels(readJacobian(ctx.device(), ocean), coverage);
      ctx.timings.push_back({"whitecaps_mask", pass_->updateFoam(ocean.jacobian, levels)});
      foam_ocean_version_ = res.version("ocean_maps");
    }
    ctx.timings.push_back({"whitecaps", pass_->composite(target.rgb, target.hasSpectral() ? &target.spectral : nullptr)});
  }

 private:
  const PassPlan& entry_;
  std::unique_ptr<WhitecapsPass> pass_;
  bool fresh_ = false;                 // set up for this frame's scene: nothing to move
  uint64_t foam_ocean_version_ = 0;    // the ocean's version the foam mask was made from (0: none yet)
};

}  // namespace

PassDescriptor whitecapsDescriptor() {
  PassDescriptor d;
  d.name = "whitecaps";
  d.kernel_file = "whitecaps.cl";
  // Off unless asked: foam changes every wavy scene's image, and it needs a choppy ocean.
  d.scene_keys = {{"surface", "whitecaps", ModelKey::Type::Boolean, 0.0, 0.0, 0.0, ""}};
  d.rule = [](const Scene& scene, const Plan&) -> std::optional<PassPlan> {
    if (modelKey(scene, "surface.whitecaps") == 0 || !oceanForSea(scene)) return std::nullopt;
    // Without horizontal displacement J = 1 everywhere: there is no low tail to put foam on.
    if (!(scene.surface.choppiness > 0))
      throw InputError(scene.file, 1, "surface.whitecaps",
                       "foam forms where the choppy displacement compresses the surface (its Jacobian, 004 eq. 30), "
                       "which is 1 everywhere with surface.choppiness = 0; set choppiness > 0 (e.g. 1) or "
                       "whitecaps = false");
    auto features = std::make_shared<WhitecapsFeatures>();
    features->spectral_output = scene.spectral.spectral_exr;
    return planEntry({"ocean_maps", "rgb"}, {"rgb"},
                     "surface.whitecaps = true on the FFT ocean: foam where its Jacobian is lowest, covering "
                     "Monahan's W(U10)",
                     features);
  };
  d.keys = kWhitecapsKeys;
  // Built without the plan's relaxed maths: its error under it was not measured.
  d.fast_math = false;
  d.buffers = [](const Scene& s, const PassPlan& p) -> std::vector<BufferEstimate> {
    const int n = s.surface.grid;
    const double N = n;
    return {{p.name, "foam mask's mips", 4.0 * whitecaps_d::whitecaps_level_offset(n, whitecaps_d::whitecaps_levels(n)),
             {"surface.grid", "surface.grid"}, {N, N}},
            {p.name, "parameter block, foam radiance per band, rank table",
             double(sizeof(WhitecapsParams)) + 4.0 * double(s.spectral.count) + 4.0 * WHITECAPS_RANK_NODES, {}, {}},
            // The Jacobian map read back each frame for its quantile (passes/whitecaps_threshold.h).
            {p.name, "host copy of the Jacobian map", 4.0 * N * N, {"surface.grid", "surface.grid"}, {N, N}, true}};
  };
  // Per pixel, not per band: its kernels took 122-129 ms against sea_single's 1173-1530 ms (480 x 270,
  // 16 bands, PoCL on the loaded 2-core machine; scenes/whitecaps.toml at grids 256 and 512).
  d.cost = [](const Scene&, const PassPlan&) { return 0.1; };
  d.factory = [](const PassPlan& e, const Plan&, const Scene&, const AutoQuality&) -> std::unique_ptr<Pass> {
    return std::make_unique<WhitecapsNode>(e);
  };
  return d;
}

}  // namespace seasim
