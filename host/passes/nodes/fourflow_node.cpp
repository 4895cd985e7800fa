// fourflow_node.cpp — shallow water with a visible bottom (paper 003): "fourflow"
// (passes/fourflow_pass.h), which owns the frame's "rgb" target. The (l, h) tables are built in
// prepare (the paper's preprocessing stage) and timed there; execute runs the frame kernel.
#include <algorithm>
#include <memory>

#include "passes/fourflow_features.h"
#include "passes/fourflow_pass.h"
#include "passes/nodes/standard_passes.h"
#include "plan/pass_descriptor.h"
#include "plan/scene_facts.h"
#include "render/radiance_target.h"

namespace seasim {

namespace {

// surface.*: with waves, R and T are averaged over the FFT patch (003 eq. 10) when the pass is set up.
const PassKeys kFourFlowKeys = {{"camera.*", "sun.*", "sky.*", "water.*", "surface.*", "bottom.*", "shallow.*",
                                 "spectral.*", "quality.fourflow_table_size"},
                                {}};

class FourFlowNode : public Pass {
 public:
  explicit FourFlowNode(const PassPlan& entry) : entry_(entry) {}
  PassKeys keys() const override { return kFourFlowKeys; }
  void prepare(FrameContext& ctx, PassResources& res) override {
    pass_ = std::make_unique<FourFlowPass>(ctx.device(), ctx.scene(), entry_, ctx.grid(), ctx.sensor());
    if (pass_->tableMs() > 0) ctx.timings.push_back({"fourflow_tables", pass_->tableMs()});
    auto target = std::make_shared<RadianceTarget>();
    target->rgb = pass_->rgb();
    target->pixels = static_cast<size_t>(ctx.scene().camera.width) * static_cast<size_t>(ctx.scene().camera.height);
    target->spectral = pass_->spectral();  // null unless spectral.spectral_exr
    target->bands = ctx.grid().size();
    res.publish("rgb", target);
  }
  void execute(FrameContext& ctx, PassResources&) override { ctx.timings.push_back({"fourflow", pass_->run()}); }

 private:
  const PassPlan& entry_;
  std::unique_ptr<FourFlowPass> pass_;
};

}  // namespace

PassDescriptor fourFlowDescriptor() {
  PassDescriptor d;
  d.name = "fourflow";
  d.kernel_file = "fourflow.cl";
  // Shallow water with a visible bottom: the four-flow pass takes the place of the sea model for the
  // view from above; its tables are built only on the table path.
  d.rule = [](const Scene& scene, const Plan&) -> std::optional<PassPlan> {
    if (!seaSeenFromAbove(scene) || !scene.shallow.present) return std::nullopt;
    const ShallowDesc::Path path = scene.shallow.path;
    auto features = std::make_shared<FourFlowFeatures>();
    features->tables = path == ShallowDesc::Path::TableEq24 ? 2 : path != ShallowDesc::Path::Exact ? 1 : 0;
    features->height_field = scene.shallow.slope || scene.bottom.type == BottomDesc::Type::HeightField;
    features->spectral_output = scene.spectral.spectral_exr;
    features->sky_model = skyModelOf(scene.sky);
    const char* method = features->tables == 2   ? "(l, h) tables + pre-converted blend (eq. 24)"
                         : features->tables == 1 ? "(l, h) tables + blend (eq. 22-23)"
                                                 : "exact spectral path (eq. 20)";
    return planEntry({"scene"}, {"rgb"},
                     std::string("[shallow]: four-flow light field over a visible bottom (003 eq. 4-20), ") + method,
                     features);
  };
  d.keys = kFourFlowKeys;
  // Built without the plan's relaxed maths: its error was not measured under it.
  d.fast_math = false;
  d.knobs = {{"fourflow_table_size", 32}};
  d.buffers = [d](const Scene& s, const PassPlan& p) -> std::vector<BufferEstimate> {
    const FourFlowFeatures& f = p.featuresAs<FourFlowFeatures>();
    const double nb = s.spectral.count;
    std::vector<BufferEstimate> out = {{p.name, "view, bands and parameter block",
                                        double(sizeof(FfView)) + double(sizeof(FfBand)) * nb + double(sizeof(FfParams)),
                                        {}, {}}};
    // The (l, h) tables, FF_TABLE_STRIDE floats per cell ("auto" sizes are not known before the search).
    const double n = f.tables == 0 ? 1.0 : std::max(2.0, d.knob(s, "fourflow_table_size"));
    out.push_back({p.name, "(l, h) tables", 4.0 * FF_TABLE_STRIDE * n * n,
                   {"quality.fourflow_table_size", "quality.fourflow_table_size"}, {n, n}});
    if (s.shallow.slope) {
      const double side = kFourFlowSlopeNodes;
      out.push_back({p.name, "bottom slope's height field", double(sizeof(SeaHeightField)) + 4 * side * side, {}, {}});
    } else if (f.height_field) {
      const double bytes = heightFieldBytes(loadHeightField(s.bottom, s.files.get()));
      out.push_back({p.name, "bottom height field", bytes, {}, {}});
    }
    return out;
  };
  d.cost = [](const Scene&, const PassPlan&) { return 1.0; };
  d.factory = [](const PassPlan& e, const Plan&, const Scene&, const AutoQuality&) -> std::unique_ptr<Pass> {
    return std::make_unique<FourFlowNode>(e);
  };
  return d;
}

}  // namespace seasim
