// effective_coefficients_node.cpp — "effective_coefficients" of effective_coefficients.cl: the formation
// model's β_D and β_B per pixel (outputs.layers beta_d, beta_b) from kd_multiple's layers and the range,
// published as the LayerTarget "coefficient_layers". Its rule also stands for the layers kd_multiple
// writes when the camera is not under water: an entry planned as unavailable, which stops the render.
#include <memory>

#include "device/enqueue.h"
#include "passes/layer_features.h"
#include "passes/nodes/layer_nodes.h"
#include "passes/nodes/underwater_frame.h"
#include "plan/pass_descriptor.h"
#include "plan/scene_facts.h"
#include "render/layer_target.h"
#include "render/pass.h"

namespace seasim {

namespace {

const std::vector<std::string> kCoefficientLayers = {"beta_d", "beta_b"};
// Every layer of the image's split (kd_multiple.cl), for the not-under-water entry.
const std::vector<std::string> kSplitLayers = {"clear",        "direct",         "backscatter",  "forward",
                                               "lamps",        "lamps_single",   "lamps_multiple", "transmission",
                                               "veiling",      "beta_d",         "beta_b"};

const PassKeys kCoefficientKeys = {{"camera.*", "outputs.*"}, {}};

class EffectiveCoefficientsNode : public Pass {
 public:
  explicit EffectiveCoefficientsNode(const PassPlan& entry) : entry_(entry) {}
  PassKeys keys() const override { return kCoefficientKeys; }
  void prepare(FrameContext& ctx, PassResources& res) override {
    const EffectiveCoefficientsFeatures& f = entry_.featuresAs<EffectiveCoefficientsFeatures>();
    const Scene& scene = ctx.scene();
    const size_t pixels = static_cast<size_t>(scene.camera.width) * static_cast<size_t>(scene.camera.height);
    auto target = std::make_shared<LayerTarget>();
    for (const auto& name : askedLayers(scene, kCoefficientLayers)) {
      const OutputLayer& layer = *findOutputLayer(name);
      target->channels.insert(target->channels.end(), layer.channels.begin(), layer.channels.end());
    }
    onDevice("effective_coefficients pass set-up", [&] {
      kernel_ = cl::Kernel(ctx.device().program(entry_.kernel_file, entry_.defines).program, "effective_coefficients");
      target->image = cl::Buffer(ctx.device().context(), CL_MEM_READ_WRITE, sizeof(float) * f.channels * pixels);
    });
    target_ = target;
    res.publish("coefficient_layers", target);
  }
  void execute(FrameContext& ctx, PassResources& res) override {
    const Scene& scene = ctx.scene();
    const UnderwaterGBuffer& g = res.read<UnderwaterGBuffer>("gbuffer");
    onDevice("effective_coefficients pass", [&] {
      int arg = 0;
      kernel_.setArg(arg++, scene.camera.width);
      kernel_.setArg(arg++, scene.camera.height);
      kernel_.setArg(arg++, g.geometry);
      kernel_.setArg(arg++, res.read<LayerTarget>("formation_layers").image);
      if (entry_.featuresAs<EffectiveCoefficientsFeatures>().beta_b >= 0)
        kernel_.setArg(arg++, res.read<LayerTarget>("veiling_layer").image);
      kernel_.setArg(arg++, target_->image);
    });
    ctx.timings.push_back({"effective_coefficients", runKernel2d(ctx.device(), "effective_coefficients", kernel_,
                                                                 scene.camera.width, scene.camera.height)});
  }

 private:
  const PassPlan& entry_;
  cl::Kernel kernel_;
  std::shared_ptr<LayerTarget> target_;
};

}  // namespace

PassDescriptor effectiveCoefficientsDescriptor() {
  PassDescriptor d;
  d.name = "effective_coefficients";
  d.kernel_file = "effective_coefficients.cl";
  d.rule = [](const Scene& scene, const Plan&) -> std::optional<PassPlan> {
    if (!cameraUnderwater(scene)) {
      const std::vector<std::string> split = askedLayers(scene, kSplitLayers);
      if (split.empty()) return std::nullopt;
      return layersUnavailable(split);
    }
    const std::vector<std::string> asked = askedLayers(scene, kCoefficientLayers);
    if (asked.empty()) return std::nullopt;
    auto f = std::make_shared<EffectiveCoefficientsFeatures>();
    int next = 0;
    for (const auto& name : asked) {
      (name == "beta_d" ? f->beta_d : f->beta_b) = next;
      next += 4;
    }
    f->channels = next;
    std::vector<std::string> reads = {"gbuffer", "formation_layers"};
    if (f->beta_b >= 0) reads.push_back("veiling_layer");
    return planEntry(reads, {"coefficient_layers"},
                     "outputs.layers: " + layerList(asked) + " = -ln(ratio)/range per channel, 0 and mask 0 where "
                     "undefined" + layerCostText(scene, 4.0 * f->channels),
                     f);
  };
  d.keys = kCoefficientKeys;
  d.fast_math = false;  // its finiteness tests must not be folded away
  d.buffers = [](const Scene& s, const PassPlan& p) -> std::vector<BufferEstimate> {
    if (!p.features) return {};  // planned as unavailable: nothing allocated
    const double w = s.camera.width, h = s.camera.height;
    const double bytes = 4.0 * p.featuresAs<EffectiveCoefficientsFeatures>().channels * w * h;
    const std::vector<std::string> keys = {"camera.width", "camera.height", "outputs.layers"};
    return {{p.name, "effective coefficients", bytes, keys, {w, h}},
            {p.name, "effective coefficients (read back)", bytes, keys, {w, h}, true}};
  };
  d.cost = [](const Scene&, const PassPlan&) { return 0.05; };
  d.factory = [](const PassPlan& e, const Plan&, const Scene&, const AutoQuality&) -> std::unique_ptr<Pass> {
    return std::make_unique<EffectiveCoefficientsNode>(e);
  };
  return d;
}

}  // namespace seasim
