// shafts_node.cpp — "shafts": spotlight shafts in air (paper 001, passes/shafts_pass.h). Sets up the
// pass (and its "auto" (n, m) search), runs it, and reports the shadow-map and shafts kernel times.
// Spotlights over the sea seen from above need the lamp's light through the surface, which is not
// modelled: the entry is planned as not implemented, which stops the render before anything is
// written, naming the lamp's table.
#include <algorithm>
#include <memory>
#include <utility>

#include "common/shafts_params.h"
#include "io/image_io.h"
#include "passes/nodes/shafts_frame.h"
#include "passes/nodes/standard_passes.h"
#include "passes/shafts_pass.h"
#include "plan/scene_facts.h"
#include "plan/shafts_method.h"
#include "render/radiance_target.h"

namespace seasim {

std::shared_ptr<ShaftsFeatures> shaftsFeatures(const Scene& scene) {
  auto f = std::make_shared<ShaftsFeatures>();
  const ShaftsMethod method = shaftsMethod(scene);  // plan/shafts_method.h
  f->intervals = method == ShaftsMethod::Intervals;
  f->march = method == ShaftsMethod::March;
  const auto exact = scene.quality.find("shafts_exact");
  f->exact = exact != scene.quality.end() && exact->second.value != 0;
  f->henyey_greenstein = scene.air.phase == AirDesc::Phase::HenyeyGreenstein;
  f->objects = !scene.objects.empty();
  for (const auto& l : scene.spotlights) f->light_map = f->light_map || !l.light_map.empty();
  return f;
}

namespace {

class ShaftsNode : public Pass {
 public:
  ShaftsNode(const PassPlan& entry, bool shadow_maps, AutoQuality auto_quality)
      : entry_(entry), shadow_maps_(shadow_maps), auto_quality_(std::move(auto_quality)) {}
  PassKeys keys() const override { return kShaftsKeys; }
  void prepare(FrameContext& ctx, PassResources& res) override {
    const ShaftsPass::Config config = auto_quality_.shaftsConfig(ctx.device(), ctx.scene(), entry_);
    pass_ = std::make_unique<ShaftsPass>(ctx.device(), ctx.scene(), entry_, config);
    auto target = std::make_shared<RadianceTarget>();
    target->rgb = pass_->rgb();
    target->pixels = static_cast<size_t>(ctx.scene().camera.width) * static_cast<size_t>(ctx.scene().camera.height);
    res.publish("rgb", target);
  }
  void execute(FrameContext& ctx, PassResources&) override {
    pass_->run();
    if (shadow_maps_) ctx.timings.push_back({"shadow_maps", pass_->shadowMapMs()});
    ctx.timings.push_back({"shafts", pass_->shaftsMs()});
  }

 private:
  const PassPlan& entry_;
  bool shadow_maps_;
  AutoQuality auto_quality_;
  std::unique_ptr<ShaftsPass> pass_;
};

bool automatic(const Scene& scene, const char* knob) {
  const auto it = scene.quality.find(knob);
  return it != scene.quality.end() && it->second.automatic;
}

std::optional<PassPlan> shaftsInAir(const Scene& scene, const Plan& so_far) {
  const auto features = shaftsFeatures(scene);
  const auto method = scene.quality.find("shafts_method");
  // "auto" as written: the Renderer measures the method before it plans (host/quality/shafts_method_auto.h);
  // a plan made before that shows the rule's method.
  const std::string measured = method != scene.quality.end() && method->second.automatic && method->second.given
                                   ? "; method \"auto\": measured on the device at quality.shafts_error_budget "
                                     "before the first render (until then the rule's choice)"
                                   : "";
  std::vector<std::string> reads = {"scene"};
  if (so_far.produces("shadow_maps")) reads.push_back("shadow_maps");
  const std::string why =
      features->intervals
          ? std::string("spotlights in air; method intervals: exact lit stretches, analytic shadow volumes, no "
                        "shadow maps (quality.shafts_method)")
      : features->march
          ? std::string("spotlights in air; method march: steps in the lamp's angle with exact shadow rays, no "
                        "shadow maps (quality.shafts_method, quality.shafts_march_steps)")
          : std::string("spotlights in air; method planes (001's sampling planes)") +
                (automatic(scene, "shafts_planes") || automatic(scene, "shafts_subplanes")
                     ? "; n, m \"auto\": the cheapest under quality.shafts_error_budget (searched once, cached)"
                     : "");
  return planEntry(reads, {"rgb"}, why + measured, features);
}

PassPlan shaftsOverTheSea(const Scene& scene) {
  const SourceLoc& at = scene.spotlights.front().loc;
  PassPlan entry = planEntry({"scene"}, {"rgb"},
                             "[[spotlights]] at " + at.file + ":" + std::to_string(at.line) +
                                 " with the camera above [water]");
  entry.implemented = false;
  entry.missing = "spotlights are composed with the underwater view (camera below y = 0), not with the sea seen "
                  "from above; move the camera below the surface or remove the [[spotlights]] tables";
  return entry;
}

// Per lamp, from stage (5 lamps) and spot_sphere (1) at 720x480 against flat_sea, interleaved
// (results/BENCHMARKS.md "Farm shards"): intervals 8-10x sea_single per pixel and band, planes at
// n = 30, m = 6 19-26x. The planes scale with n x m; the intervals' panel width moves them little
// (stage: -22 % from 4 to 32 degrees), so it is left out.
double shaftsCost(const PassDescriptor& d, const Scene& scene) {
  const double lamps = std::max<double>(1.0, static_cast<double>(scene.spotlights.size()));
  const ShaftsMethod method = shaftsMethod(scene);
  if (method == ShaftsMethod::Intervals) return lamps * 9.0;
  // The march: per step one emission and one shadow ray (stage and spot_sphere at 20 steps measured about
  // the intervals' cost: results/BENCHMARKS.md "Spotlight shafts in air").
  if (method == ShaftsMethod::March) return lamps * 9.0 * d.settledKnob(scene, "shafts_march_steps") / 20.0;
  return lamps * 22.0 * (d.settledKnob(scene, "shafts_planes") / 30.0) *
         (d.settledKnob(scene, "shafts_subplanes") / 6.0);
}

}  // namespace

PassDescriptor shaftsDescriptor() {
  PassDescriptor d;
  d.name = "shafts";
  d.kernel_file = "shafts.cl";
  d.role = PassRole::Spotlights;
  d.rule = [](const Scene& scene, const Plan& so_far) -> std::optional<PassPlan> {
    if (spotlightsInAir(scene)) return shaftsInAir(scene, so_far);
    if (seaSeenFromAbove(scene) && !scene.spotlights.empty()) return shaftsOverTheSea(scene);
    return std::nullopt;
  };
  d.keys = kShaftsKeys;
  d.knobs = {{"shafts_table_size", 256}, {"shafts_planes", 30}, {"shafts_subplanes", 6},
             {"shafts_march_steps", kShaftsMarchStepsDefault}};
  d.buffers = [d](const Scene& s, const PassPlan& p) -> std::vector<BufferEstimate> {
    std::vector<BufferEstimate> out;
    // The lamps, the objects, the light maps (RGB floats; their size from the image's header, not a decode)
    // and, for the intervals, each lamp's shadow volume of each object (ShaftsPass).
    const double lamps = static_cast<double>(s.spotlights.size());
    const double objects = std::max<double>(1.0, static_cast<double>(s.objects.size()));
    double texels = 0;
    for (const SpotlightDesc& l : s.spotlights)
      if (!l.light_map.empty()) {
        const ImageHeader map = readImageHeader(l.light_map);
        texels += static_cast<double>(map.width) * map.height;
      }
    const ShaftsFeatures& f = p.featuresAs<ShaftsFeatures>();
    const double occluders = f.intervals ? lamps * objects : 1.0;
    out.push_back({p.name, "lamps, objects, light maps and shadow volumes",
                   sizeof(ShaftsParams) + sizeof(ShaftsLight) * lamps + sizeof(ShaftsObject) * objects +
                       12 * texels + sizeof(ShaftsOccluder) * occluders + 4 * 4,
                   {"spotlights (count)", "objects (count)", "light-map texels"}, {lamps, objects, texels}});
    // Only the planes read 001 eq. 6's tables, and only without shafts_exact (ShaftsPass: the intervals
    // and the march evaluate g exactly).
    if (!f.planes() || f.exact) return out;
    const double n = d.knob(s, "shafts_table_size");
    // Built on the host in float and uploaded (an oversized one threw bad_alloc on the host).
    out.push_back({p.name, "shafts integral table", 4 * n * n + 4 * n,
                   {"quality.shafts_table_size", "quality.shafts_table_size"}, {n, n}});
    return out;
  };
  d.cost = [d](const Scene& s, const PassPlan&) { return shaftsCost(d, s); };
  d.factory = [](const PassPlan& e, const Plan& plan, const Scene&, const AutoQuality& auto_quality)
      -> std::unique_ptr<Pass> { return std::make_unique<ShaftsNode>(e, plan.produces("shadow_maps"), auto_quality); };
  return d;
}

}  // namespace seasim
