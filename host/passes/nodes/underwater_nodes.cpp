// underwater_nodes.cpp — the underwater frame (paper 002): "raycast" (the G-buffer, raycast.cl),
// "froxel" (single scattering of the sun beam, froxel.cl) and "kd_multiple" (the per-band shading of
// eq. 4.7–4.8, which writes the frame's "rgb"). All read the scene through ctx.underwaterSetup().
//
// raycast.cl and kd_multiple.cl share one UnderwaterPass (passes/underwater_pass.h), published as
// "gbuffer". A change of sun, water, time or knobs rewrites its parameter blocks in place
// (UnderwaterPass::update) and runs the kernels again; only the camera, the objects or the band
// count set it up again.
#include <memory>
#include <vector>

#include "passes/froxel_pass.h"
#include "passes/nodes/standard_passes.h"
#include "passes/underwater_lamps_pass.h"
#include "passes/underwater_pass.h"
#include "passes/water_spread_pass.h"
#include "underwater/underwater_improved_ordinates.h"  // kOrdinatesSourceMoments
#include "render/radiance_target.h"
#include "device/device.h"
#include "util/error.h"

namespace seasim {

namespace {

struct UnderwaterGBuffer {
  std::unique_ptr<UnderwaterPass> pass;
  uint64_t setup_version = 0;  // FrameContext::setupVersion() its parameter blocks hold
  // Brings the parameter blocks up to the context's setup.
  void sync(FrameContext& ctx) {
    const UnderwaterSetup& setup = ctx.underwaterSetup();
    if (setup_version == ctx.setupVersion()) return;
    pass->update(setup);
    setup_version = ctx.setupVersion();
  }
};

// Everything the underwater setup folds in: a change reruns the kernels with new parameter blocks.
const std::vector<std::string> kSetupKeys = {"sun.*",        "sky.*",     "water.*",
                                             "bottom.*",     "surface.*", "underwater.*",
                                             "objects.*",    "quality.caustic_map_size", "quality.caustic_layers"};

class RaycastNode : public Pass {
 public:
  RaycastNode(const PassPlan& entry, const PassPlan& kd) : entry_(entry), kd_(kd) {}
  // Sizes (image, bands, objects) and the kernels' defines come from these.
  // sky.model and sky.image: kd_multiple's SEASIM_SKY_MODEL and the size of its sky buffer.
  PassKeys keys() const override {
    return {{"camera.*", "spectral.*", "objects.*", "sky.model", "sky.image"}, kSetupKeys};
  }
  void prepare(FrameContext& ctx, PassResources& res) override {
    auto gbuffer = std::make_shared<UnderwaterGBuffer>();
    gbuffer->pass = std::make_unique<UnderwaterPass>(ctx.device(), ctx.underwaterSetup(), entry_, kd_,
                                                     ctx.scene().spectral.spectral_exr);
    gbuffer->setup_version = ctx.setupVersion();
    res.publish("gbuffer", gbuffer);
  }
  void execute(FrameContext& ctx, PassResources& res) override {
    UnderwaterGBuffer& gbuffer = res.read<UnderwaterGBuffer>("gbuffer");
    gbuffer.sync(ctx);
    ctx.timings.push_back({"raycast", gbuffer.pass->runRaycast(underwaterCausticMaps(res))});
  }

 private:
  const PassPlan& entry_;
  const PassPlan& kd_;
};

class FroxelNode : public Pass {
 public:
  explicit FroxelNode(const PassPlan& entry) : entry_(entry) {}
  // FroxelPass folds the whole setup into its tables at set-up.
  PassKeys keys() const override {
    std::vector<std::string> rebuild = kSetupKeys;
    rebuild.push_back("camera.*");
    rebuild.push_back("spectral.*");
    for (const char* knob : {"quality.froxel_x", "quality.froxel_y", "quality.froxel_z", "quality.shadow_map_size"})
      rebuild.push_back(knob);
    return {rebuild, {}};
  }
  void prepare(FrameContext& ctx, PassResources& res) override {
    res.publish("froxel_volume",
                std::make_shared<FroxelPass>(ctx.device(), ctx.scene(), ctx.underwaterSetup(), entry_.defines));
  }
  void execute(FrameContext& ctx, PassResources& res) override {
    FroxelPass& froxels = res.read<FroxelPass>("froxel_volume");
    // With the G-buffer, only the froxels that kd_multiple's reads need are evaluated.
    const cl::Buffer* geom =
        res.declaresRead("gbuffer") ? &res.read<UnderwaterGBuffer>("gbuffer").pass->geometry() : nullptr;
    froxels.run(underwaterCausticMaps(res), geom, ctx.scene().camera.width, ctx.scene().camera.height);
    for (const PassTiming& t : froxels.timings()) ctx.timings.push_back(t);
  }

 private:
  const PassPlan& entry_;
};

class KdNode : public Pass {
 public:
  PassKeys keys() const override { return {{}, kSetupKeys}; }
  void prepare(FrameContext& ctx, PassResources& res) override {
    UnderwaterPass& pass = *res.read<UnderwaterGBuffer>("gbuffer").pass;
    if (&pass == published_for_) return;  // a new froxel volume only: the same image buffers
    published_for_ = &pass;
    auto target = std::make_shared<RadianceTarget>();
    target->rgb = pass.rgb();
    target->spectral = pass.spectral();
    target->pixels = static_cast<size_t>(ctx.scene().camera.width) * static_cast<size_t>(ctx.scene().camera.height);
    target->bands = ctx.grid().size();
    res.publish("rgb", target);
  }
  void execute(FrameContext& ctx, PassResources& res) override {
    UnderwaterGBuffer& gbuffer = res.read<UnderwaterGBuffer>("gbuffer");
    gbuffer.sync(ctx);
    FroxelPass* froxels = res.declaresRead("froxel_volume") ? &res.read<FroxelPass>("froxel_volume") : nullptr;
    ctx.timings.push_back({"kd_multiple", gbuffer.pass->runShading(froxels ? &froxels->paramsBuffer() : nullptr,
                                                                   froxels ? &froxels->volume() : nullptr)});
    // spectral.exr holds the whole image: kd_multiple wrote T L_s + L_MS per band; the froxel term per
    // band is added from the same injected light (issue 13), into the buffer the renderer reads back.
    if (froxels && ctx.scene().spectral.spectral_exr) {
      const Scene& scene = ctx.scene();
      const size_t pixels = static_cast<size_t>(scene.camera.width) * static_cast<size_t>(scene.camera.height);
      std::vector<float> spectral(pixels * ctx.grid().size());
      cl::CommandQueue& queue = ctx.device().queue();
      try {
        queue.enqueueReadBuffer(gbuffer.pass->spectral(), CL_TRUE, 0, sizeof(float) * spectral.size(), spectral.data());
        const double ms = froxels->addBandsToSpectral(ctx.underwaterSetup(), gbuffer.pass->geometry(), scene.camera.width,
                                                      scene.camera.height, spectral);
        queue.enqueueWriteBuffer(gbuffer.pass->spectral(), CL_TRUE, 0, sizeof(float) * spectral.size(), spectral.data());
        ctx.timings.push_back({"froxel_spectral_bands", ms});
      } catch (const cl::Error& e) {
        throw DeviceError(std::string("froxel spectral bands: ") + e.what() + " " + clErrorName(e.err()));
      }
    }
  }

 private:
  const UnderwaterPass* published_for_ = nullptr;
};

// The water's point-spread (passes/water_spread_pass.h, issue 13 s11): adds the forward light kd_multiple
// kept apart, blurred, into the "rgb" it wrote.
class WaterSpreadNode : public Pass {
 public:
  explicit WaterSpreadNode(const PassPlan& entry) : entry_(entry) {}
  // The blur follows the image's size and field of view and the phase's g (and the model's delta-M order).
  PassKeys keys() const override { return {{"camera.*", "spectral.*", "water.*", "underwater.*"}, kSetupKeys}; }
  void prepare(FrameContext& ctx, PassResources&) override {
    const Scene& scene = ctx.scene();
    const UwParams& p = ctx.underwaterSetup().params;
    const int order = scene.underwater.improved_diffuse == UnderwaterDesc::Diffuse::DiscreteOrdinates
                          ? kOrdinatesSourceMoments
                          : 2;  // the two-stream's f = g² (improvedDeltaM)
    pass_ = std::make_unique<WaterSpreadPass>(ctx.device(), entry_,
                                              makeWaterSpread(p.g, order, p.tan_half_fov_y, p.width, p.height),
                                              scene.spectral.spectral_exr ? p.band_count : 0);
  }
  void execute(FrameContext& ctx, PassResources& res) override {
    UnderwaterPass& gbuffer = *res.read<UnderwaterGBuffer>("gbuffer").pass;
    if (!gbuffer.spread())
      throw RuntimeError("plan: the water_spread pass needs kd_multiple planned with SEASIM_UWI_SPREAD=1");
    RadianceTarget& target = res.read<RadianceTarget>("rgb");
    const bool spectral = ctx.scene().spectral.spectral_exr;
    ctx.timings.push_back({"water_spread", pass_->run(gbuffer.geometry(), gbuffer.forwardDepth(), gbuffer.forwardRgb(),
                                                      target.rgb, spectral ? &gbuffer.forwardSpectral() : nullptr,
                                                      spectral ? &target.spectral : nullptr)});
  }

 private:
  const PassPlan& entry_;
  std::unique_ptr<WaterSpreadPass> pass_;
};

// Spotlights in the water (passes/underwater_lamps_pass.h): adds into the "rgb" kd_multiple wrote.
class UnderwaterLampsNode : public Pass {
 public:
  explicit UnderwaterLampsNode(const PassPlan& entry) : entry_(entry) {}
  PassKeys keys() const override {
    return {{"camera.*", "spectral.*", "objects.*", "spotlights.*", "quality.shafts_planes", "quality.shafts_subplanes",
             "quality.lamps_delta_m"},
            kSetupKeys};
  }
  void prepare(FrameContext& ctx, PassResources&) override {
    pass_ = std::make_unique<UnderwaterLampsPass>(ctx.device(), ctx.scene(), ctx.underwaterSetup(), ctx.grid(), entry_,
                                                  UnderwaterLampsPass::configFromScene(ctx.scene()));
    setup_version_ = ctx.setupVersion();
  }
  void execute(FrameContext& ctx, PassResources& res) override {
    if (setup_version_ != ctx.setupVersion()) {
      pass_->update(ctx.underwaterSetup());
      setup_version_ = ctx.setupVersion();
    }
    UnderwaterPass& gbuffer = *res.read<UnderwaterGBuffer>("gbuffer").pass;
    RadianceTarget& target = res.read<RadianceTarget>("rgb");
    cl::Buffer* spectral = ctx.scene().spectral.spectral_exr ? &target.spectral : nullptr;
    ctx.timings.push_back({"underwater_lamps", pass_->run(gbuffer.geometry(), gbuffer.material(), target.rgb, spectral)});
  }

 private:
  const PassPlan& entry_;
  std::unique_ptr<UnderwaterLampsPass> pass_;
  uint64_t setup_version_ = 0;
};

}  // namespace

void registerUnderwaterPasses(PassRegistry& registry) {
  registry.add("raycast", "raycast.cl", [](const PassPlan& e, const Plan& plan, const Scene&) -> std::unique_ptr<Pass> {
    const PassPlan* kd = plan.find("kd_multiple");
    if (!kd) throw RuntimeError("plan: the underwater raycast pass needs a kd_multiple pass in the same plan");
    return std::make_unique<RaycastNode>(e, *kd);
  });
  registry.add("froxel", [](const PassPlan& e, const Plan&, const Scene&) { return std::make_unique<FroxelNode>(e); });
  registry.add("kd_multiple", [](const PassPlan&, const Plan&, const Scene&) { return std::make_unique<KdNode>(); });
  registry.add("water_spread",
               [](const PassPlan& e, const Plan&, const Scene&) { return std::make_unique<WaterSpreadNode>(e); });
  registry.add("underwater_lamps",
               [](const PassPlan& e, const Plan&, const Scene&) { return std::make_unique<UnderwaterLampsNode>(e); });
}

}  // namespace seasim
