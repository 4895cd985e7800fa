// kd_multiple_node.cpp — "kd_multiple": the underwater frame's per-band shading (002 eq. 4.7-4.8,
// or the discrete-ordinates model of common/underwater_ordinates.h; passes/underwater_shading.h). It
// reads the set-up's and the G-buffer's buffers and publishes the frame's "rgb", the forward light for
// the point-spread and the ground-truth layers it writes.
#include <memory>
#include <vector>

#include "device/device.h"
#include "passes/froxel_pass.h"
#include "passes/nodes/underwater_frame.h"
#include "passes/underwater_features.h"
#include "passes/underwater_shading.h"
#include "plan/pass_descriptor.h"
#include "plan/scene_facts.h"
#include "render/pass.h"
#include "passes/nodes/layer_nodes.h"
#include "io/spectral_layout.h"
#include "render/layer_target.h"
#include "render/radiance_target.h"

namespace seasim {

namespace {

// The layers kd_multiple.cl's SEASIM_LAYER_FORMATION and SEASIM_LAYER_VEILING give (the effective
// coefficients are derived from them: nodes/effective_coefficients_node.cpp).
const std::vector<std::string> kFormationLayers = {"clear",  "direct",       "backscatter", "forward",
                                                   "lamps",  "transmission", "beta_d",      "beta_b"};
const std::vector<std::string> kVeilingLayers = {"veiling", "beta_b"};
// The lamps' light split by scattering order: zeroed here, written by underwater_lamps.
const std::vector<std::string> kLampSplitLayers = {"lamps_single", "lamps_multiple"};

// kd_multiple.cl's band layers, slot by slot (its header gives the layout).
const char* const kBandLayerSlots[] = {"clear", "direct", "backscatter", "lamps", "transmission"};

class KdNode : public Pass {
 public:
  explicit KdNode(const PassPlan& entry) : entry_(entry) {}
  PassKeys keys() const override { return {{}, kUnderwaterSetupKeys}; }
  void prepare(FrameContext& ctx, PassResources& res) override {
    const UnderwaterSetupBuffers& setup = res.read<UnderwaterSetupBuffers>("underwater_setup");
    const UnderwaterGBuffer& gbuffer = res.read<UnderwaterGBuffer>("gbuffer");
    if (shading_ && &setup == setup_ && &gbuffer == gbuffer_) return;  // a new froxel volume only
    setup_ = &setup;
    gbuffer_ = &gbuffer;
    shading_ = std::make_unique<UnderwaterShading>(ctx.device(), entry_, setup, gbuffer);
    UnderwaterShading& s = *shading_;
    auto target = std::make_shared<RadianceTarget>();
    target->rgb = s.rgb();
    target->spectral = s.spectral();
    target->pixels = static_cast<size_t>(ctx.scene().camera.width) * static_cast<size_t>(ctx.scene().camera.height);
    target->bands = ctx.grid().size();
    res.publish("rgb", target);
    if (entry_.featuresAs<KdFeatures>().point_spread)
      res.publish("forward_light", std::make_shared<UnderwaterForwardLight>(s.forwardLight()));
    // The ground-truth layers it writes (outputs.layers; kd_multiple.cl's header gives the layout).
    auto layer = [&](const char* name, std::vector<std::string> channels, cl::Buffer& buffer) {
      auto t = std::make_shared<LayerTarget>();
      t->channels = std::move(channels);
      t->image = buffer;
      res.publish(name, t);
    };
    if (s.formationLayers()() != nullptr) {
      std::vector<std::string> channels;
      for (const char* l : {"clear", "direct", "backscatter", "transmission"})
        for (const char* c : {".R", ".G", ".B"}) channels.push_back(std::string(l) + c);
      layer("formation_layers", channels, s.formationLayers());
      layer("forward_layer", {"forward.R", "forward.G", "forward.B"}, s.forwardLayer());
      layer("lamps_layer", {"lamps.R", "lamps.G", "lamps.B"}, s.lampsLayer());
    }
    if (s.veilingLayer()() != nullptr) layer("veiling_layer", {"veiling.R", "veiling.G", "veiling.B"}, s.veilingLayer());
    if (s.lampsSplitLayer()() != nullptr) {
      std::vector<std::string> channels;
      for (const auto& name : askedLayers(ctx.scene(), kLampSplitLayers))
        for (const char* c : {".R", ".G", ".B"}) channels.push_back(name + c);
      layer("lamps_split_layer", channels, s.lampsSplitLayer());
    }
    if (s.bandLayers()() != nullptr) {  // the split per band: "<layer>.S0.<nm>" (output_layers.h)
      std::vector<std::string> channels, forward;
      for (const char* l : kBandLayerSlots)
        for (double nm : ctx.grid().centers_nm) channels.push_back(spectralLayerChannelName(l, nm));
      for (double nm : ctx.grid().centers_nm) forward.push_back(spectralLayerChannelName("forward", nm));
      layer("band_layers", channels, s.bandLayers());
      layer("forward_band_layer", forward, s.forwardBands());
    }
    if (s.veilingBands()() != nullptr) {
      std::vector<std::string> veiling;
      for (double nm : ctx.grid().centers_nm) veiling.push_back(spectralLayerChannelName("veiling", nm));
      layer("veiling_band_layer", veiling, s.veilingBands());
    }
  }
  void execute(FrameContext& ctx, PassResources& res) override {
    FroxelVolume* froxels = res.declaresRead("froxel_volume") ? &res.read<FroxelVolume>("froxel_volume") : nullptr;
    const UnderwaterSandShare* sand =
        res.declaresRead("sand_share") ? &res.read<UnderwaterSandShare>("sand_share") : nullptr;
    ctx.timings.push_back({"kd_multiple", shading_->run(froxels ? &froxels->params : nullptr,
                                                        froxels ? &froxels->volume : nullptr, sand)});
  }

 private:
  const PassPlan& entry_;
  const UnderwaterSetupBuffers* setup_ = nullptr;
  const UnderwaterGBuffer* gbuffer_ = nullptr;
  std::unique_ptr<UnderwaterShading> shading_;
};

std::shared_ptr<KdFeatures> kdFeatures(const Scene& scene, bool froxels, bool sand_map) {
  auto f = std::make_shared<KdFeatures>();
  f->multiple = scene.underwater.multiple_scattering;
  f->froxel = froxels;
  f->spectral_output = scene.spectral.spectral_exr;
  f->sky_model = skyModelOf(scene.sky);
  f->underwater_model = scene.underwater.model == UnderwaterDesc::Model::DiscreteOrdinates ? 1 : 0;
  f->point_spread = underwaterPointSpread(scene);
  f->formation_layers = scene.outputs.wantsAny(kFormationLayers);
  f->veiling_layer = scene.outputs.wantsAny(kVeilingLayers);
  f->band_layers = f->formation_layers && f->spectral_output;
  f->veiling_bands = f->veiling_layer && f->spectral_output;
  f->lamps_split_layers = static_cast<int>(askedLayers(scene, kLampSplitLayers).size());
  f->sand_map = sand_map;
  return f;
}

// The resources it publishes: the image, the forward light for the point-spread, the layers asked.
std::vector<std::string> kdWrites(const KdFeatures& f) {
  std::vector<std::string> writes = {"rgb"};
  if (f.point_spread) writes.push_back("forward_light");
  if (f.formation_layers) writes.insert(writes.end(), {"formation_layers", "forward_layer", "lamps_layer"});
  if (f.veiling_layer) writes.push_back("veiling_layer");
  if (f.lamps_split_layers > 0) writes.push_back("lamps_split_layer");
  if (f.band_layers) writes.insert(writes.end(), {"band_layers", "forward_band_layer"});
  if (f.veiling_bands) writes.push_back("veiling_band_layer");
  return writes;
}

// The plan's "why": the model, and the layers with their cost.
std::string kdWhy(const Scene& scene, const KdFeatures& f) {
  std::string layers;
  std::vector<std::string> asked = askedLayers(scene, kFormationLayers);
  for (const auto& l : askedLayers(scene, kLampSplitLayers)) asked.push_back(l);
  if (f.formation_layers || f.veiling_layer || f.lamps_split_layers > 0)
    layers = "; outputs.layers: " + layerList(asked) +
             (f.veiling_layer && !scene.outputs.wants("veiling") ? ", veiling (for beta_b)" : "") +
             (f.band_layers || f.veiling_bands ? ", per band in spectral.exr" : "") +
             layerCostText(scene, 4.0 * ((f.formation_layers ? 18 : 0) + (f.veiling_layer ? 3 : 0) + 3 * f.lamps_split_layers +
                                         (f.band_layers ? 6 * scene.spectral.count : 0) +
                                         (f.veiling_bands ? scene.spectral.count : 0)));
  if (f.underwater_model == 1)
    return "camera below the surface: T L_s + L_MS per band, model \"discrete_ordinates\" (delta-M, the diffuse "
           "field over the bottom by discrete ordinates or a two-stream, its in-scatter by direction)" +
           layers;
  return "camera below the surface: T L_s + L_MS per band (002 eq. 4.7)" + layers;
}

std::optional<PassPlan> kdRule(const Scene& scene, const Plan& so_far) {
  if (!cameraUnderwater(scene)) return std::nullopt;
  const bool froxels = so_far.produces("froxel_volume");
  const bool sand_map = so_far.produces("sand_share");
  std::vector<std::string> reads = {"underwater_setup", "gbuffer"};
  if (froxels) reads.push_back("froxel_volume");
  if (sand_map) reads.push_back("sand_share");
  const std::shared_ptr<KdFeatures> features = kdFeatures(scene, froxels, sand_map);
  return planEntry(reads, kdWrites(*features), kdWhy(scene, *features), features);
}

std::vector<BufferEstimate> kdBuffers(const Scene& s, const PassPlan& p) {
  const KdFeatures& f = p.featuresAs<KdFeatures>();
  const double w = s.camera.width, h = s.camera.height, nb = s.spectral.count;
  std::vector<BufferEstimate> out;
  // The ground-truth layers (underwater_shading.cpp) and their copies read back on the host.
  const double layer_floats = (f.formation_layers ? 18 : 0) + (f.veiling_layer ? 3 : 0) + 3 * f.lamps_split_layers;
  if (layer_floats > 0) {
    const std::vector<std::string> keys = {"camera.width", "camera.height", "outputs.layers"};
    out.push_back({p.name, "formation layers", 4 * layer_floats * w * h, keys, {w, h}});
    out.push_back({p.name, "formation layers (read back)", 4 * layer_floats * w * h, keys, {w, h}, true});
  }
  // Per band (kd_multiple.cl): five slots and the forward light; the veiling.
  const double band_floats = (f.band_layers ? 6 : 0) + (f.veiling_bands ? 1 : 0);
  if (band_floats > 0) {
    const std::vector<std::string> keys = {"camera.width", "camera.height", "spectral.count", "outputs.layers"};
    out.push_back({p.name, "layers per band", 4 * band_floats * nb * w * h, keys, {w, h, nb}});
    out.push_back({p.name, "layers per band (read back)", 4 * band_floats * nb * w * h, keys, {w, h, nb}, true});
  }
  if (!f.point_spread) return out;
  // The forward light's moments the point spread blurs (underwater_shading.cpp): F and F E per
  // channel, F D and F per pixel, and per band with spectral output.
  out.push_back({p.name, "forward light moments (underwater.point_spread)", 4 * 8 * w * h,
                 {"camera.width", "camera.height"}, {w, h}});
  if (s.spectral.spectral_exr)
    out.push_back({p.name, "forward light moments per band", 4 * 2 * nb * w * h,
                   {"camera.width", "camera.height", "spectral.count"}, {w, h, nb}});
  return out;
}

}  // namespace

PassDescriptor kdMultipleDescriptor() {
  PassDescriptor d;
  d.name = "kd_multiple";
  d.kernel_file = "kd_multiple.cl";
  d.role = PassRole::UnderwaterShading;
  d.band_loop_timing = d.name;
  d.band_loop_items = [](const Scene& s, int bands) { return double(s.camera.width) * s.camera.height * bands; };
  d.rule = kdRule;
  d.keys = {{}, kUnderwaterSetupKeys};
  d.buffers = kdBuffers;
  // Per pixel and band, in units of sea_single: the thesis model 1.5x (seabed against flat_sea;
  // results/BENCHMARKS.md "Farm shards"); the discrete-ordinates model 4.2x the thesis's kd_multiple, the split
  // layers' second evaluation of the hit +0.7 and the veiling's in-scatter to infinity +0.8 of those
  // units for either model (kd_multiple's own ms at 320x180, 3 bands, three rounds:
  // BENCHMARKS "Ground-truth layers").
  d.cost = [](const Scene&, const PassPlan& p) {
    const KdFeatures& f = p.featuresAs<KdFeatures>();
    return (f.underwater_model == 1 ? 6.3 : 1.5) + (f.formation_layers ? 0.7 : 0.0) + (f.veiling_layer ? 0.8 : 0.0);
  };
  d.factory = [](const PassPlan& e, const Plan&, const Scene&, const AutoQuality&) -> std::unique_ptr<Pass> {
    return std::make_unique<KdNode>(e);
  };
  return d;
}

}  // namespace seasim
