// light_profile_node.cpp — "light_profile": the plane-parallel light profile of the scene's water, sun,
// sky, surface and bottom (radiometry/scene_profile.h, `seasim profile`'s), at outputs.profile_depths, per
// band and through the sensor, by the discrete ordinates on the CPU; written beside the image as
// profile.csv (a TextOutput resource). No kernel: its kernel file names that. Planned only when the scene
// asks for the depths; planned as unavailable (stopping the render, shown by `seasim plan`) when the
// scene cannot have a plane-parallel profile.
#include <chrono>
#include <cstdio>
#include <memory>

#include "plan/pass_descriptor.h"
#include "radiometry/scene_profile.h"
#include "render/pass.h"
#include "render/text_output.h"

namespace seasim {

namespace {

const PassKeys kProfileKeys = {
    {"outputs.*", "water.*", "sun.*", "sky.*", "bottom.*", "spectral.*", "quality.profile_streams"}, {}};

class LightProfileNode : public Pass {
 public:
  explicit LightProfileNode(int streams) : streams_(streams) {}
  PassKeys keys() const override { return kProfileKeys; }
  void prepare(FrameContext&, PassResources& res) override {
    output_ = std::make_shared<TextOutput>();
    output_->file_name = "profile.csv";
    res.publish("light_profile", output_);
  }
  void execute(FrameContext& ctx, PassResources&) override {
    const auto t0 = std::chrono::steady_clock::now();
    SceneProfileOptions options;
    options.streams = streams_;
    output_->text = sceneProfileCsv(sceneLightProfile(ctx.scene(), ctx.scene().outputs.profile_depths, options)).str();
    ctx.timings.push_back(
        {"light_profile", std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count()});
  }

 private:
  int streams_;
  std::shared_ptr<TextOutput> output_;
};

}  // namespace

PassDescriptor lightProfileDescriptor() {
  PassDescriptor d;
  d.name = "light_profile";
  d.kernel_file = "(none: CPU)";
  d.knobs = {{"profile_streams", 16}};
  d.rule = [d_knobs = d](const Scene& scene, const Plan&) -> std::optional<PassPlan> {
    const std::vector<double>& depths = scene.outputs.profile_depths;
    if (depths.empty()) return std::nullopt;
    if (const std::string problem = sceneProfileProblem(scene, depths); !problem.empty()) {
      PassPlan p = planEntry({}, {}, "outputs.profile_depths");
      p.implemented = false;
      p.missing = problem + ": drop outputs.profile_depths, or give the scene [water] with a flat bottom (or none) "
                  "below the deepest depth";
      return p;
    }
    char why[200];
    std::snprintf(why, sizeof why,
                  "outputs.profile_depths: E_d, E_u, E_0d, E_0u, L_u, K_d, R, L_w, R_rs at %zu depths, %d bands and "
                  "the sensor, discrete ordinates (%g streams), on the CPU -> profile.csv",
                  depths.size(), scene.spectral.count, d_knobs.settledKnob(scene, "profile_streams"));
    return planEntry({}, {"light_profile"}, why);
  };
  d.keys = kProfileKeys;
  d.fast_math = false;  // no kernel to build
  d.buffers = [](const Scene&, const PassPlan&) { return std::vector<BufferEstimate>{}; };  // host only
  d.cost = [](const Scene&, const PassPlan&) { return 0.0; };  // once per frame, not per pixel
  d.factory = [](const PassPlan&, const Plan&, const Scene& scene, const AutoQuality&) -> std::unique_ptr<Pass> {
    return std::make_unique<LightProfileNode>(static_cast<int>(lightProfileDescriptor().settledKnob(scene, "profile_streams")));
  };
  return d;
}

}  // namespace seasim
