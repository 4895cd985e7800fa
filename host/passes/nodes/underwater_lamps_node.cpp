// underwater_lamps_node.cpp — "underwater_lamps": spotlights in the water (divers' torches, ROV
// lamps; passes/underwater_lamps_pass.h), 001's sampling planes in the water's spectral medium,
// added into the "rgb" kd_multiple wrote (it reads "rgb" so that it runs after).
#include <memory>

#include "passes/nodes/underwater_frame.h"
#include "passes/pixel_lattice.h"
#include "passes/underwater_features.h"
#include "passes/underwater_lamps_pass.h"
#include "passes/underwater_setup_buffers.h"
#include "plan/pass_descriptor.h"
#include "scene/model_keys.h"
#include "plan/scene_facts.h"
#include "render/pass.h"
#include "render/layer_target.h"
#include "render/radiance_target.h"
#include "underwater/lamps_ms_weights.h"

namespace seasim {

namespace {

const PassKeys kLampsKeys = {{"camera.*", "spectral.*", "objects.*", "spotlights.*", "quality.shafts_planes",
                              "quality.shafts_subplanes", "quality.lamps_delta_m", "quality.lamps_model",
                              "quality.lamps_orders", "quality.lamps_ms_steps", "quality.lamps_ms_kappa", "quality.lamps_ms_spread",
                              "quality.lamps_ms_cell_deg"},
                             kUnderwaterSetupKeys};

// Where lamps_single and lamps_multiple sit in kd_multiple's split layer (the channels it was given).
LampSplitLayers splitLayers(LayerTarget& t) {
  LampSplitLayers s;
  s.buffer = &t.image;
  s.stride = static_cast<int>(t.channels.size());
  for (size_t i = 0; i < t.channels.size(); ++i) {
    if (t.channels[i] == "lamps_single.R") s.single_at = static_cast<int>(i);
    if (t.channels[i] == "lamps_multiple.R") s.multiple_at = static_cast<int>(i);
  }
  return s;
}

class UnderwaterLampsNode : public Pass {
 public:
  explicit UnderwaterLampsNode(const PassPlan& entry) : entry_(entry) {}
  PassKeys keys() const override { return kLampsKeys; }
  void prepare(FrameContext& ctx, PassResources& res) override {
    pass_ = std::make_unique<UnderwaterLampsPass>(ctx.device(), ctx.scene(),
                                                  res.read<UnderwaterSetupBuffers>("underwater_setup").setup, ctx.grid(),
                                                  entry_, UnderwaterLampsPass::configFromScene(ctx.scene()), &tables_);
    fresh_ = true;
  }
  void execute(FrameContext& ctx, PassResources& res) override {
    if (!fresh_) pass_->update(res.read<UnderwaterSetupBuffers>("underwater_setup").setup);  // sun, water, time
    fresh_ = false;
    UnderwaterGBuffer& gbuffer = res.read<UnderwaterGBuffer>("gbuffer");
    RadianceTarget& target = res.read<RadianceTarget>("rgb");
    cl::Buffer* spectral = ctx.scene().spectral.spectral_exr ? &target.spectral : nullptr;
    const bool lamps_layer_on = entry_.featuresAs<UnderwaterLampsFeatures>().lamps_layer;
    cl::Buffer* lamps_layer = lamps_layer_on ? &res.read<LayerTarget>("lamps_layer").image : nullptr;
    const bool bands_on = entry_.featuresAs<UnderwaterLampsFeatures>().band_layers;
    cl::Buffer* band_layers = bands_on ? &res.read<LayerTarget>("band_layers").image : nullptr;
    LampSplitLayers split;
    if (entry_.featuresAs<UnderwaterLampsFeatures>().lamps_split) split = splitLayers(res.read<LayerTarget>("lamps_split_layer"));
    pass_->run(ctx.timings, gbuffer.geometry, gbuffer.material, target.rgb, spectral, lamps_layer, band_layers, split);
  }

 private:
  const PassPlan& entry_;
  // The orders model's host tables outlive the passes a moved camera makes anew (prepare): only what
  // the camera does not change is in them, so the preview does not rebuild them per frame.
  LampsOrdersTables tables_;
  std::unique_ptr<UnderwaterLampsPass> pass_;
  bool fresh_ = false;
};

}  // namespace

PassDescriptor underwaterLampsDescriptor() {
  PassDescriptor d;
  d.name = "underwater_lamps";
  d.kernel_file = "underwater_lamps.cl";
  d.role = PassRole::UnderwaterLamps;
  // The lamps' interval integral takes the shafts' sampling planes (001 eq. 5, 7-9); their sub-samples
  // default otherwise here (UnderwaterLampsPass::kSubplanesInWater), so the knob is the air's.
  d.knobs = {{"shafts_planes", 30}};
  // The "orders" model's orders of scattering kept (the last takes all higher ones), its quadrature steps
  // per view ray, its path-stretch exponent κ and the spread β of its landing (common/underwater_lamps_ms.h).
  d.scene_keys = {{"quality", "lamps_orders", ModelKey::Type::Integer, 4.0, 1.0, 12.0, ""},
                  {"quality", "lamps_ms_steps", ModelKey::Type::Integer, 12.0, 1.0, 64.0, ""},
                  {"quality", "lamps_ms_kappa", ModelKey::Type::Number, 0.6, 0.0, 2.0, ""},
                  {"quality", "lamps_ms_spread", ModelKey::Type::Number, 0.6, 0.0, 1.0, "", true},
                  {"quality", "lamps_ms_cell_deg", ModelKey::Type::Number, 1.0, 0.0, 10.0, ""}};
  d.rule = [](const Scene& scene, const Plan& so_far) -> std::optional<PassPlan> {
    if (!cameraUnderwater(scene) || scene.spotlights.empty()) return std::nullopt;
    auto features = std::make_shared<UnderwaterLampsFeatures>();
    features->objects = !scene.objects.empty();
    features->spectral_output = scene.spectral.spectral_exr;
    const UnderwaterLampsPass::Config config = UnderwaterLampsPass::configFromScene(scene);
    features->orders = config.model == UnderwaterLampsPass::Model::Orders;
    // The orders' smooth part (its multiple scattering along the view ray and on the bottom) on a lattice
    // of every ms_step-th pixel, interpolated where the lattice sees the same surface.
    features->ms_lattice = features->orders && config.ms_step > 1;
    // The lamps' own layer: kd_multiple zeroed it, this pass adds into it as into "rgb".
    features->lamps_layer = so_far.produces("lamps_layer");
    features->band_layers = so_far.produces("band_layers");
    features->lamps_split = so_far.produces("lamps_split_layer");
    std::vector<std::string> targets = {"rgb"};
    if (features->lamps_layer) targets.push_back("lamps_layer");
    if (features->band_layers) targets.push_back("band_layers");
    if (features->lamps_split) targets.push_back("lamps_split_layer");
    std::vector<std::string> reads = {"underwater_setup", "gbuffer"};
    reads.insert(reads.end(), targets.begin(), targets.end());
    return planEntry(reads, targets,
                     std::string("[[spotlights]] under water: 001's sampling planes with the water's sigma_s, sigma_t, HG") +
                         (features->orders ? " + orders of multiple scattering" : "") +
                         (features->ms_lattice ? " (its smooth part on a lattice of every " +
                                                     std::to_string(config.ms_step) + " pixels, quality.lamps_ms_cell_deg)"
                                               : "") +
                         (features->lamps_layer ? "; also into outputs.layers' lamps" : "") +
                         (features->band_layers ? ", per band too" : "") +
                         (features->lamps_split ? "; split into lamps_single and lamps_multiple" : ""),
                     features);
  };
  d.keys = kLampsKeys;
  d.buffers = [](const Scene& s, const PassPlan& p) -> std::vector<BufferEstimate> {
    const double lights = static_cast<double>(s.spotlights.size()), nb = s.spectral.count;
    // Its own copies of the underwater parameter blocks are per band, not per pixel: only the spectra.
    std::vector<BufferEstimate> out = {{p.name, "lamp spectra (one per spotlight and band)", 4 * lights * nb,
                                        {"spotlights (count)", "spectral.count"}, {lights, nb}}};
    if (p.featuresAs<UnderwaterLampsFeatures>().orders) {
      const double orders = modelKey(s, "quality.lamps_orders");
      out.push_back({p.name,
                     "the orders' weights per band, order and distance, and the bottom halo's light per band, height "
                     "and direction (underwater/lamps_ms_weights.h)",
                     4.0 * lampMsWeightsSize(s.spectral.count, static_cast<int>(orders)),
                     {"spectral.count", "quality.lamps_orders"}, {nb, orders}});
    }
    if (p.featuresAs<UnderwaterLampsFeatures>().ms_lattice) {
      const int step = lampsMsLatticeStep(s);
      const double w = pixelLatticeSize(s.camera.width, step), h = pixelLatticeSize(s.camera.height, step);
      const double per = static_cast<double>(
          lampsMsLatticeFloats(static_cast<int>(nb), p.featuresAs<UnderwaterLampsFeatures>().lamps_split));
      out.push_back({p.name, "the orders' smooth part on the lattice, the surface's and the view ray's per band",
                     4.0 * per * w * h,
                     {"camera.width", "camera.height", "quality.lamps_ms_cell_deg", "spectral.count"},
                     {static_cast<double>(s.camera.width), static_cast<double>(s.camera.height),
                      modelKey(s, "quality.lamps_ms_cell_deg"), nb}});
    }
    return out;
  };
  d.cost = [](const Scene&, const PassPlan&) { return 1.0; };
  d.factory = [](const PassPlan& e, const Plan&, const Scene&, const AutoQuality&) -> std::unique_ptr<Pass> {
    return std::make_unique<UnderwaterLampsNode>(e);
  };
  return d;
}

}  // namespace seasim
