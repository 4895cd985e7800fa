// geometry_layers_node.cpp — "geometry_layers" of geometry_layers.cl: range, depth, normal, object_id
// and albedo (outputs.layers) from the underwater G-buffer, published as the LayerTarget
// "geometry_layers". Planned only when the scene asks for one of them.
#include <memory>

#include "device/enqueue.h"
#include "io/spectral_layout.h"
#include "passes/layer_features.h"
#include "passes/nodes/layer_nodes.h"
#include "passes/nodes/underwater_frame.h"
#include "passes/underwater_setup_buffers.h"
#include "plan/pass_descriptor.h"
#include "plan/scene_facts.h"
#include "render/layer_target.h"
#include "render/pass.h"

namespace seasim {

namespace {

const std::vector<std::string> kGeometryLayers = {"range", "depth", "normal", "object_id", "albedo"};

// The geometry reads the camera and the objects; the albedo the spectra and sensor (the band table).
const PassKeys kGeometryLayerKeys = {{"camera.*", "spectral.*", "objects.*", "outputs.*"}, kUnderwaterSetupKeys};

class GeometryLayersNode : public Pass {
 public:
  explicit GeometryLayersNode(const PassPlan& entry) : entry_(entry) {}
  PassKeys keys() const override { return kGeometryLayerKeys; }
  void prepare(FrameContext& ctx, PassResources& res) override {
    const GeometryLayerFeatures& f = entry_.featuresAs<GeometryLayerFeatures>();
    const Scene& scene = ctx.scene();
    const size_t pixels = static_cast<size_t>(scene.camera.width) * static_cast<size_t>(scene.camera.height);
    auto target = std::make_shared<LayerTarget>();
    for (const auto& name : askedLayers(scene, kGeometryLayers)) {
      const OutputLayer& layer = *findOutputLayer(name);
      target->channels.insert(target->channels.end(), layer.channels.begin(), layer.channels.end());
    }
    std::shared_ptr<LayerTarget> bands;
    if (f.albedo_bands) {  // "albedo.S0.<nm>" (output_layers.h)
      bands = std::make_shared<LayerTarget>();
      for (double nm : ctx.grid().centers_nm) bands->channels.push_back(spectralLayerChannelName("albedo", nm));
    }
    onDevice("geometry_layers pass set-up", [&] {
      kernel_ = cl::Kernel(ctx.device().program(entry_.kernel_file, entry_.defines).program, "geometry_layers");
      target->image = cl::Buffer(ctx.device().context(), CL_MEM_READ_WRITE, sizeof(float) * f.channels * pixels);
      if (bands)
        bands->image = cl::Buffer(ctx.device().context(), CL_MEM_READ_WRITE, sizeof(float) * ctx.grid().size() * pixels);
    });
    target_ = target;
    bands_ = bands;
    res.publish("geometry_layers", target);
    if (bands) res.publish("albedo_band_layer", bands);
  }
  void execute(FrameContext& ctx, PassResources& res) override {
    const UnderwaterSetupBuffers& setup = res.read<UnderwaterSetupBuffers>("underwater_setup");
    const UnderwaterGBuffer& g = res.read<UnderwaterGBuffer>("gbuffer");
    onDevice("geometry_layers pass", [&] {
      int arg = 0;
      kernel_.setArg(arg++, setup.params);
      kernel_.setArg(arg++, g.geometry);
      kernel_.setArg(arg++, g.material);
      kernel_.setArg(arg++, setup.band_table);
      kernel_.setArg(arg++, target_->image);
      if (bands_) kernel_.setArg(arg++, bands_->image);
    });
    const Scene& scene = ctx.scene();
    ctx.timings.push_back({"geometry_layers", runKernel2d(ctx.device(), "geometry_layers", kernel_,
                                                          scene.camera.width, scene.camera.height)});
  }

 private:
  const PassPlan& entry_;
  cl::Kernel kernel_;
  std::shared_ptr<LayerTarget> target_, bands_;
};

double bytesPerPixel(const Scene& s, const GeometryLayerFeatures& f) {
  return 4.0 * (f.channels + (f.albedo_bands ? s.spectral.count : 0));
}

}  // namespace

PassDescriptor geometryLayersDescriptor() {
  PassDescriptor d;
  d.name = "geometry_layers";
  d.kernel_file = "geometry_layers.cl";
  d.rule = [](const Scene& scene, const Plan&) -> std::optional<PassPlan> {
    const std::vector<std::string> asked = askedLayers(scene, kGeometryLayers);
    if (asked.empty()) return std::nullopt;
    if (!cameraUnderwater(scene)) return layersUnavailable(asked);
    auto f = std::make_shared<GeometryLayerFeatures>();
    int next = 0;
    for (const auto& name : asked) {
      int* at = name == "range" ? &f->range
                : name == "depth" ? &f->depth
                : name == "normal" ? &f->normal
                : name == "object_id" ? &f->object_id
                                      : &f->albedo;
      *at = next;
      next += static_cast<int>(findOutputLayer(name)->channels.size());
    }
    f->channels = next;
    f->albedo_bands = f->albedo >= 0 && scene.spectral.spectral_exr;
    std::vector<std::string> writes = {"geometry_layers"};
    if (f->albedo_bands) writes.push_back("albedo_band_layer");
    return planEntry({"underwater_setup", "gbuffer"}, writes,
                     "outputs.layers: " + layerList(asked) + " from the G-buffer" +
                         (f->albedo_bands ? ", the albedo per band in spectral.exr" : "") +
                         layerCostText(scene, bytesPerPixel(scene, *f)),
                     f);
  };
  d.keys = kGeometryLayerKeys;
  d.fast_math = false;  // +inf for open water must survive
  d.buffers = [](const Scene& s, const PassPlan& p) -> std::vector<BufferEstimate> {
    if (!p.features) return {};  // planned as unavailable (layersUnavailable): nothing allocated
    const double w = s.camera.width, h = s.camera.height;
    const double bytes = bytesPerPixel(s, p.featuresAs<GeometryLayerFeatures>()) * w * h;
    const std::vector<std::string> keys = {"camera.width", "camera.height", "outputs.layers"};
    return {{p.name, "geometry layers", bytes, keys, {w, h}},
            {p.name, "geometry layers (read back)", bytes, keys, {w, h}, true}};
  };
  d.cost = [](const Scene&, const PassPlan&) { return 0.05; };
  d.factory = [](const PassPlan& e, const Plan&, const Scene&, const AutoQuality&) -> std::unique_ptr<Pass> {
    return std::make_unique<GeometryLayersNode>(e);
  };
  return d;
}

}  // namespace seasim
