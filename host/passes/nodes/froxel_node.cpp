// froxel_node.cpp — "froxel": single scattering of the sun beam in the underwater frame (002 §5,
// froxel.cl, passes/froxel_pass.h); its buffers are published as "froxel_volume" for kd_multiple and
// the band term (nodes/froxel_bands_node.cpp).
#include <algorithm>
#include <memory>

#include "passes/froxel_pass.h"
#include "passes/nodes/underwater_frame.h"
#include "passes/underwater_features.h"
#include "passes/underwater_setup_buffers.h"
#include "plan/pass_descriptor.h"
#include "plan/scene_facts.h"
#include "render/pass.h"

namespace seasim {

namespace {

// The froxels per pixel from which the pass skips the froxels no pixel reads.
constexpr double kFroxelCullingPerPixel = 8.0;

// FroxelPass folds the whole setup into its tables at set-up.
PassKeys froxelKeys() {
  std::vector<std::string> rebuild = kUnderwaterSetupKeys;
  for (const char* key : {"camera.*", "spectral.*", "quality.froxel_x", "quality.froxel_y", "quality.froxel_z",
                          "quality.froxel_columns", "quality.shadow_map_size"})
    rebuild.push_back(key);
  return {rebuild, {}};
}

class FroxelNode : public Pass {
 public:
  explicit FroxelNode(const PassPlan& entry) : entry_(entry) {}
  PassKeys keys() const override { return froxelKeys(); }
  void prepare(FrameContext& ctx, PassResources& res) override {
    froxels_ = std::make_unique<FroxelPass>(ctx.device(), ctx.scene(),
                                            res.read<UnderwaterSetupBuffers>("underwater_setup").setup, entry_.defines);
    // A moved camera (or a new time: caustics) leaves the sun's shadow map as it was.
    if (kept_map_() && kept_key_ == froxels_->shadowMapKey()) froxels_->adoptShadowMap(kept_map_);
    auto volume = std::make_shared<FroxelVolume>();
    volume->params = froxels_->paramsBuffer();
    volume->volume = froxels_->volume();
    volume->light = froxels_->light();
    volume->column_dy = froxels_->columnDy();
    volume->fp = froxels_->params();
    res.publish("froxel_volume", volume);
  }
  void execute(FrameContext& ctx, PassResources& res) override {
    // With the G-buffer, only the froxels that kd_multiple's reads need are evaluated.
    const cl::Buffer* geom = res.declaresRead("gbuffer") ? &res.read<UnderwaterGBuffer>("gbuffer").geometry : nullptr;
    froxels_->run(underwaterCausticMaps(res), geom, ctx.scene().camera.width, ctx.scene().camera.height);
    kept_key_ = froxels_->shadowMapKey();  // computed (or adopted) by now
    kept_map_ = froxels_->shadowMap();
    for (const PassTiming& t : froxels_->timings()) ctx.timings.push_back(t);
  }

 private:
  const PassPlan& entry_;
  std::unique_ptr<FroxelPass> froxels_;
  // The last sun shadow map a pass ran with, outliving the passes a moved camera makes anew, and what it
  // was made from.
  std::string kept_key_;
  cl::Buffer kept_map_;  // none (null) before the first frame
};

}  // namespace

PassDescriptor froxelDescriptor() {
  PassDescriptor d;
  d.name = "froxel";
  d.kernel_file = "froxel.cl";
  d.role = PassRole::UnderwaterSingleScattering;
  d.band_loop_timing = "froxel_integrate";  // the band loop; RGB injection integrates 3 bands
  d.band_loop_items = [](const Scene& s, int bands) {
    const FroxelConfig c = froxelConfigFromScene(s);
    const double froxels = double(c.nx) * c.ny * c.nz;
    return froxels * (s.underwater.injection == UnderwaterDesc::Injection::Spectral ? bands : 3);
  };
  d.rule = [](const Scene& scene, const Plan& so_far) -> std::optional<PassPlan> {
    const UnderwaterDesc& uw = scene.underwater;
    if (!cameraUnderwater(scene) || !uw.single_scattering || !sunUp(scene)) return std::nullopt;
    std::vector<std::string> reads = {"underwater_setup"};
    // The G-buffer says which froxels the pixels read (froxel_column_extent), so that the others are not
    // evaluated. That pays only for a grid much finer than the image: at 2 froxels per pixel (seabed's
    // defaults) finding them costs more than evaluating them all, at 8 and 16 as much (results/BENCHMARKS.md).
    const FroxelConfig grid = froxelConfigFromScene(scene);
    const double froxels = double(grid.nx) * grid.ny * grid.nz;
    const double pixels = double(scene.camera.width) * scene.camera.height;
    const bool culled = froxels >= kFroxelCullingPerPixel * pixels;
    if (culled) reads.push_back("gbuffer");
    if (so_far.produces("caustic_map")) reads.push_back("caustic_map");
    auto features = std::make_shared<FroxelFeatures>();
    features->objects = !scene.objects.empty();
    features->caustics = underwaterCausticsMode(scene);
    features->spectral_injection = uw.injection == UnderwaterDesc::Injection::Spectral;
    return planEntry(reads, {"froxel_volume"},
                     std::string("camera below the surface, sun up, underwater.single_scattering") +
                         (culled ? "; only the froxels the pixels read (the grid >= 8 froxels per pixel)" : ""),
                     features);
  };
  d.keys = froxelKeys();
  // froxel_x, froxel_y: "auto", from froxel_columns and the image's aspect (froxelConfigFromScene).
  d.knobs = {{"froxel_x", 0, false, true},  {"froxel_y", 0, false, true}, {"froxel_z", 32},
             {"froxel_columns", 80},        {"caustic_map_size", 256},    {"caustic_layers", 8},
             {"shadow_map_size", 512}};
  d.buffers = [d](const Scene& s, const PassPlan& p) -> std::vector<BufferEstimate> {
    const FroxelConfig c = froxelConfigFromScene(s);
    const double fx = c.nx, fy = c.ny, fz = c.nz;
    std::vector<BufferEstimate> out = {{p.name, "froxel volume", 20 * fx * fy * fz,
                                        {"quality.froxel_x", "quality.froxel_y", "quality.froxel_z"}, {fx, fy, fz}}};
    // The sun's shadow map over the spheres and boxes (froxel_setup.cpp), one float per texel.
    const bool bounded = std::any_of(s.objects.begin(), s.objects.end(), [](const ObjectDesc& o) {
      return o.type == ObjectDesc::Type::Sphere || o.type == ObjectDesc::Type::Box;
    });
    if (bounded) {
      const double S = d.knob(s, "shadow_map_size");
      out.push_back({p.name, "sun shadow map over the objects", 4 * S * S,
                     {"quality.shadow_map_size", "quality.shadow_map_size"}, {S, S}});
    }
    const double C = d.knob(s, "caustic_map_size"), L = d.knob(s, "caustic_layers");
    out.push_back({p.name, "caustic maps", 4 * L * C * C,
                   {"quality.caustic_layers", "quality.caustic_map_size", "quality.caustic_map_size"}, {L, C, C}});
    return out;
  };
  // 16x sea_single per pixel and band at the grid of 160×90×64 froxels for 320×180 pixels (seabed
  // against flat_sea, 3 rounds; results/BENCHMARKS.md "Farm shards"), in proportion to the froxels per
  // pixel.
  d.cost = [](const Scene& s, const PassPlan&) {
    const FroxelConfig c = froxelConfigFromScene(s);
    const double per_pixel = double(c.nx) * c.ny * c.nz / std::max(1.0, double(s.camera.width) * s.camera.height);
    return 16.0 * per_pixel / (160.0 * 90 * 64 / (320.0 * 180));
  };
  d.factory = [](const PassPlan& e, const Plan&, const Scene&, const AutoQuality&) -> std::unique_ptr<Pass> {
    return std::make_unique<FroxelNode>(e);
  };
  return d;
}

}  // namespace seasim
