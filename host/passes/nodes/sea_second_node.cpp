// sea_second_node.cpp — "sea_second": the scattering maps of 000 eq. 6-8 (passes/sea_second_pass.h),
// added into the "rgb" sea_single wrote.
#include <memory>
#include <utility>

#include "common/sea_params.h"
#include "common/sea_second_params.h"

#include "passes/nodes/standard_passes.h"
#include "passes/sea_second_features.h"
#include "passes/sea_heightfield.h"
#include "passes/sea_second_pass.h"
#include "plan/pass_descriptor.h"
#include "plan/scene_facts.h"
#include "render/radiance_target.h"

namespace seasim {

namespace {

const PassKeys kSeaSecondKeys = {{"camera.*", "sun.*", "sky.*", "water.*", "bottom.*", "sea.*", "spectral.*",
                                  "quality.sea_nz", "quality.sea_nd", "quality.sea_map_size"},
                                 {}};

class SeaSecondNode : public Pass {
 public:
  SeaSecondNode(const PassPlan& entry, AutoQuality auto_quality) : entry_(entry), auto_quality_(std::move(auto_quality)) {}
  PassKeys keys() const override { return kSeaSecondKeys; }
  void prepare(FrameContext& ctx, PassResources& res) override {
    RadianceTarget& target = res.read<RadianceTarget>("rgb");
    const SeaSecondPass::Config config = auto_quality_.seaSecondConfig(ctx.device(), ctx.scene());
    pass_ = std::make_unique<SeaSecondPass>(ctx.device(), ctx.scene(), entry_, config, ctx.grid(), ctx.sensor(),
                                            target.rgb, ctx.scene().spectral.spectral_exr ? &target.spectral : nullptr);
  }
  void execute(FrameContext& ctx, PassResources&) override { ctx.timings.push_back({"sea_second", pass_->run()}); }

 private:
  const PassPlan& entry_;
  AutoQuality auto_quality_;
  std::unique_ptr<SeaSecondPass> pass_;
};

}  // namespace

PassDescriptor seaSecondDescriptor() {
  PassDescriptor d;
  d.name = "sea_second";
  d.kernel_file = "sea_second.cl";
  d.role = PassRole::SeaSecondOrder;
  d.rule = [](const Scene& scene, const Plan&) -> std::optional<PassPlan> {
    // With "multiple" the second order is inside the closed form: its pass would count it twice.
    if (!seaSeenFromAbove(scene) || scene.shallow.present || !scene.sea.second_order ||
        scene.sea.model == SeaDesc::Model::Multiple)
      return std::nullopt;
    auto features = std::make_shared<SeaSecondFeatures>();
    features->bottom_height_field = scene.bottom.type == BottomDesc::Type::HeightField;
    features->bottom = scene.bottom.type == BottomDesc::Type::Flat || features->bottom_height_field;
    features->spectral_output = scene.spectral.spectral_exr;
    return planEntry({"scene", "rgb"}, {"rgb"}, "sea.second_order = true", features);
  };
  d.keys = kSeaSecondKeys;
  d.knobs = {{"sea_nz", 12}, {"sea_nd", 128}, {"sea_map_size", 32}};
  d.buffers = [d](const Scene& s, const PassPlan& p) -> std::vector<BufferEstimate> {
    const double n_z = d.knob(s, "sea_nz"), n_d = d.knob(s, "sea_nd"), M = d.knob(s, "sea_map_size");
    const double nb = s.spectral.count;
    // Rows of bands and directions padded to the kernels' lanes (sea_second_params.h).
    const double nb_rows = SEA_SECOND_STRIDE(s.spectral.count), n_d_rows = SEA_SECOND_STRIDE(static_cast<int>(n_d));
    std::vector<BufferEstimate> out = {
        {p.name, "scattering maps", 4 * n_z * M * M * nb_rows,
         {"quality.sea_nz", "quality.sea_map_size", "quality.sea_map_size", "spectral.count"}, {n_z, M, M, nb_rows}},
        {p.name, "radiance maps", 4 * n_z * n_d * nb, {"quality.sea_nz", "quality.sea_nd", "spectral.count"},
         {n_z, n_d, nb}}};
    // The parameter block, the bands, the VSF map, the directions, the planes' weights and their per-band values
    // (plane_bands, 4 floats per plane and band).
    const double vsf = SeaSecondPass::Config{}.vsf_size;
    out.push_back({p.name, "parameter block, bands, VSF map, directions, plane weights and values",
                   double(sizeof(SeaSecondParams)) + double(sizeof(SeaBand)) * nb_rows + 4 * vsf + 16 * n_d_rows +
                       (4 + 16) * n_z * nb_rows,
                   {}, {}});
    if (s.bottom.type == BottomDesc::Type::HeightField) {
      const double bytes = heightFieldBytes(loadHeightField(s.bottom, s.files.get()));
      out.push_back({p.name, "bottom height field", bytes, {}, {}});
    }
    if (s.bottom.type == BottomDesc::Type::HeightField)
      out.push_back({p.name, "height-field depth table", 4 * (n_z + 1) * M * M * n_d_rows,
                     {"quality.sea_nz", "quality.sea_map_size", "quality.sea_map_size", "quality.sea_nd"},
                     {n_z + 1, M, M, n_d_rows}});
    return out;
  };
  // 1.6x sea_single per pixel and band, 18x over a height-field floor (results/BENCHMARKS.md "Farm
  // shards"), in proportion to n_z x n_d.
  d.cost = [d](const Scene& s, const PassPlan& p) {
    const double weight = p.featuresAs<SeaSecondFeatures>().bottom_height_field ? 18.0 : 1.6;
    return weight * (d.settledKnob(s, "sea_nz") / 12.0 * (d.settledKnob(s, "sea_nd") / 128.0));
  };
  d.factory = [](const PassPlan& e, const Plan&, const Scene&, const AutoQuality& auto_quality) -> std::unique_ptr<Pass> {
    return std::make_unique<SeaSecondNode>(e, auto_quality);
  };
  return d;
}

}  // namespace seasim
