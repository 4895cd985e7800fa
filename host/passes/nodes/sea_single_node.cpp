// sea_single_node.cpp — "sea_single": the sea seen from above (paper 000: reflection, single
// scattering, bottom; passes/sea_single_pass.h), which owns the frame's "rgb" target.
#include <algorithm>
#include <memory>

extern "C" {
#include "common/sea_band_table.h"
#include "common/sea_params.h"
}

#include "passes/nodes/standard_passes.h"
#include "passes/sea_single_features.h"
#include "passes/sea_single_pass.h"
#include "plan/pass_descriptor.h"
#include "plan/scene_facts.h"
#include "math/kernel_math.h"
#include "passes/sea_heightfield.h"
#include "render/pass.h"
#include "render/radiance_target.h"

namespace seasim {

namespace {

// The ocean and the caustic map come in as resources: a new one sets this pass up again. A camera
// moved at the same image size (the preview's orbit) changes only the parameter block's camera: the
// sky's shape and level, the bands and the LUT do not depend on it, and remaking them (the sky's
// cosine means above all) cost more than the kernel's own time per frame.
const PassKeys kSeaSingleKeys = {{"camera.width", "camera.height", "sun.*", "sky.*", "water.*", "bottom.*", "sea.*",
                                  "spectral.*", "quality.sea_lut_size", "quality.sea_supersample",
                                  "quality.wave_filter", "quality.sea_sky_table"},
                                 {"camera.*"}};

class SeaSingleNode : public Pass {
 public:
  explicit SeaSingleNode(const PassPlan& entry) : entry_(entry) {}
  PassKeys keys() const override { return kSeaSingleKeys; }
  void prepare(FrameContext& ctx, PassResources& res) override {
    const OceanMaps* ocean = res.declaresRead("ocean_maps") ? &res.read<OceanMaps>("ocean_maps") : nullptr;
    const SeaBottomCaustics* caustics =
        res.declaresRead("caustic_map") ? &res.read<SeaBottomCaustics>("caustic_map") : nullptr;
    pass_ = std::make_unique<SeaSinglePass>(ctx.device(), ctx.scene(), entry_, ctx.grid(), ctx.sensor(), ocean, caustics);
    auto target = std::make_shared<RadianceTarget>();
    target->rgb = pass_->rgb();
    target->spectral = pass_->spectral();
    target->pixels = static_cast<size_t>(ctx.scene().camera.width) * static_cast<size_t>(ctx.scene().camera.height);
    target->bands = ctx.grid().size();
    res.publish("rgb", target);
    fresh_ = true;
  }
  void execute(FrameContext& ctx, PassResources&) override {
    if (!fresh_ && anyKeyMatches("camera.*", ctx.changedKeys())) pass_->moveCamera(ctx.scene().camera);
    fresh_ = false;
    ctx.timings.push_back({"sea_single", pass_->run()});
  }

 private:
  const PassPlan& entry_;
  std::unique_ptr<SeaSinglePass> pass_;
  bool fresh_ = false;  // set up for this frame's scene: nothing to move
};

std::shared_ptr<SeaSingleFeatures> seaSingleFeatures(const PassDescriptor& d, const Scene& scene) {
  auto f = std::make_shared<SeaSingleFeatures>();
  const bool sun = scene.sun.enabled && scene.sun.irradiance > 0;
  const bool multiple = scene.sea.model == SeaDesc::Model::Multiple;
  f->reflection = scene.sea.reflection;
  // "multiple"'s column also holds the skylight scattered in the water, which a sun that is off does
  // not remove; paper 000's single scattering is the sun's alone.
  f->single_scattering = scene.sea.single_scattering && (sun || multiple);
  f->bottom_height_field = scene.bottom.type == BottomDesc::Type::HeightField;
  f->bottom = scene.bottom.type == BottomDesc::Type::Flat || f->bottom_height_field;
  f->sun = sun;
  f->spectral_output = scene.spectral.spectral_exr;
  f->waves = fftWaves(scene);
  f->sky_model = skyModelOf(scene.sky);
  f->bottom_caustics = seaBottomCausticsPlanned(scene);
  f->sea_model = multiple ? 1 : 0;
  // Wave normals filtered over the pixel's footprint (common/sea_lean.h), unless turned off or
  // replaced by its reference, n x n rays per pixel over the unfiltered normals.
  f->supersample = static_cast<int>(d.knob(scene, "sea_supersample"));
  f->wave_filter = d.knob(scene, "wave_filter") != 0 && f->supersample == 1;
  // The reflected sky of an analytic model (CIE clear, Preetham) from a table over sqrt(cos theta) and
  // gamma (common/sky_table.h); quality.sea_sky_table = 1 evaluates the model at every reflected
  // direction.
  const bool analytic_sky = f->sky_model == SEASIM_SKY_ANALYTIC || f->sky_model == SEASIM_SKY_PREETHAM;
  const int table = static_cast<int>(d.knob(scene, "sea_sky_table"));
  f->sky_table = f->reflection && analytic_sky && table > 1 ? table : 0;
  return f;
}

}  // namespace

PassDescriptor seaSingleDescriptor() {
  PassDescriptor d;
  d.name = "sea_single";
  d.kernel_file = "sea_single.cl";
  d.role = PassRole::SeaShading;
  d.band_loop_timing = d.name;
  d.band_loop_items = [](const Scene& s, int bands) { return double(s.camera.width) * s.camera.height * bands; };
  d.keys = kSeaSingleKeys;
  d.knobs = {{"sea_supersample", 1}, {"wave_filter", 1, true}, {"sea_sky_table", 256}};
  // [shallow] takes the sea model's place for the view from above (fourflow_node.cpp).
  d.rule = [d](const Scene& scene, const Plan&) -> std::optional<PassPlan> {
    if (!seaSeenFromAbove(scene) || scene.shallow.present) return std::nullopt;
    const auto features = seaSingleFeatures(d, scene);
    std::vector<std::string> reads = {"scene"};
    if (features->waves) reads.push_back("ocean_maps");
    if (features->bottom_caustics) reads.push_back("caustic_map");
    return planEntry(reads, {"rgb"},
                     features->sea_model == 1
                         ? "camera above water (reflection; sea.model = \"multiple\": all orders of the water and the "
                           "bottom in closed form)"
                         : "camera above water (reflection, single scattering, bottom)",
                     features);
  };
  d.knobs.push_back({"sea_lut_size", 64});
  d.buffers = [d](const Scene& s, const PassPlan& p) -> std::vector<BufferEstimate> {
    const SeaSingleFeatures& f = p.featuresAs<SeaSingleFeatures>();
    const double nb = s.spectral.count;
    // The LUT's rows (SeaSinglePass): "multiple" has κ's rows in their place (common/sea_ordinates.h: a
    // depth grid over a height field, else one layer), none over a height field (one placeholder row), 16 to
    // start an "auto" search from, else the knob.
    const auto lut_knob = s.quality.find("sea_lut_size");
    const double ordinates = f.bottom_height_field ? SEA_ORD_NODES : SEA_ORD_LAYER;
    const double lut = f.sea_model == 1                                              ? ordinates
                       : f.bottom_height_field                                       ? 1.0
                       : lut_knob != s.quality.end() && lut_knob->second.automatic ? 16.0
                                                                                   : d.knob(s, "sea_lut_size");
    // The parameter block, the bands, their lanes' table with the LUT (common/sea_band_table.h),
    // the sky's texels and the one-float4 stand-ins for maps the defines do not read.
    std::vector<BufferEstimate> out = {
        {p.name, "parameter block, bands, band table and LUT",
         double(sizeof(SeaParams)) + double(sizeof(SeaBand)) * nb +
             4.0 * (SEA_ROWS + std::max(1.0, lut)) * SEA_BAND_STRIDE(static_cast<int>(nb)) + 4 * 16.0,
         {}, {}}};
    if (f.bottom_height_field) {
      const double bytes = heightFieldBytes(loadHeightField(s.bottom, s.files.get()));
      out.push_back({p.name, "bottom height field", bytes, {}, {}});
    }
    if (f.waves && f.wave_filter) {
      // The wave filter's slope-moment mip chain over the ocean's normal map (common/sea_lean.h).
      const int n = s.surface.grid;
      const double N = n;
      out.push_back({p.name, "wave filter's slope-moment mips",
                     4.0 * kmath_d::sea_lean_level_offset(n, kmath_d::sea_lean_levels(n)),
                     {"surface.grid", "surface.grid"}, {N, N}});
    }
    if (f.sky_table > 0) {
      const double n = f.sky_table;
      out.push_back({p.name, "reflected sky's table", 4.0 * SKY_TABLE_STRIDE * n * n,
                     {"quality.sea_sky_table", "quality.sea_sky_table"}, {n, n}});
    }
    return out;
  };
  // The unit of the shard cost: 24 ms per million pixel-bands on PoCL (results/BENCHMARKS.md "Farm shards").
  d.cost = [](const Scene&, const PassPlan&) { return 1.0; };
  d.factory = [](const PassPlan& e, const Plan&, const Scene&, const AutoQuality&) -> std::unique_ptr<Pass> {
    return std::make_unique<SeaSingleNode>(e);
  };
  return d;
}

}  // namespace seasim
