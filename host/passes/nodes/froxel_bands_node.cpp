// froxel_bands_node.cpp — "froxel_bands": the froxel pass's single scattering per wavelength band
// (passes/froxel_band_term.h), added on the device into the spectral image kd_multiple wrote, the
// backscatter slot of the band layers and, read at infinity, the veiling per band, so spectral.exr and
// its layers hold the whole image. Planned with the froxels and spectral.spectral_exr only.
#include <algorithm>
#include <memory>
#include <vector>

#include "device/enqueue.h"
#include "passes/froxel_band_term.h"
#include "passes/froxel_pass.h"
#include "passes/nodes/underwater_frame.h"
#include "passes/underwater_setup_buffers.h"
#include "plan/pass_descriptor.h"
#include "plan/scene_facts.h"
#include "render/layer_target.h"
#include "render/pass.h"
#include "render/radiance_target.h"

namespace seasim {

namespace {

// kd_multiple.cl's band layers: [pixel][5][band], the backscatter third (nodes/kd_multiple_node.cpp).
constexpr int kBandLayerSlots = 5;
constexpr int kBackscatterSlot = 2;

class FroxelBandsNode : public Pass {
 public:
  explicit FroxelBandsNode(const PassPlan& entry) : entry_(entry) {}
  PassKeys keys() const override { return {{"camera.*", "spectral.*"}, {}}; }
  void prepare(FrameContext& ctx, PassResources& res) override {
    term_ = std::make_unique<FroxelBandTerm>(ctx.device(), entry_, res.read<FroxelVolume>("froxel_volume"));
    at_infinity_ = cl::Buffer();
    if (res.declaresRead("veiling_band_layer")) {
      // Every pixel's distance UW_INFINITE (1e30): the whole column, as kd_multiple's ss_inf.
      std::vector<cl_float4> far(size_t(ctx.scene().camera.width) * size_t(ctx.scene().camera.height),
                                 cl_float4{{1e30f, 0.0f, 0.0f, 0.0f}});
      onDevice("froxel_bands set-up", [&] {
        at_infinity_ = cl::Buffer(ctx.device().context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                                  sizeof(cl_float4) * far.size(), far.data());
      });
    }
  }
  void execute(FrameContext& ctx, PassResources& res) override {
    const Scene& scene = ctx.scene();
    const int bands = static_cast<int>(ctx.grid().size());
    const cl::Buffer& geom = res.read<UnderwaterGBuffer>("gbuffer").geometry;
    std::vector<FroxelBandTerm::Target> targets = {{&geom, &res.read<RadianceTarget>("rgb").spectral, bands, 0}};
    if (res.declaresRead("band_layers"))
      targets.push_back({&geom, &res.read<LayerTarget>("band_layers").image, kBandLayerSlots * bands,
                         kBackscatterSlot * bands});
    if (res.declaresRead("veiling_band_layer"))
      targets.push_back({&at_infinity_, &res.read<LayerTarget>("veiling_band_layer").image, bands, 0});
    const UnderwaterSetup& setup = res.read<UnderwaterSetupBuffers>("underwater_setup").setup;
    ctx.timings.push_back(
        {"froxel_spectral_bands", term_->addTo(setup, scene.camera.width, scene.camera.height, targets)});
  }

 private:
  const PassPlan& entry_;
  std::unique_ptr<FroxelBandTerm> term_;
  cl::Buffer at_infinity_;
};

}  // namespace

PassDescriptor froxelBandsDescriptor() {
  PassDescriptor d;
  d.name = "froxel_bands";
  d.kernel_file = "froxel.cl";
  d.rule = [](const Scene& scene, const Plan& so_far) -> std::optional<PassPlan> {
    const PassPlan* froxel = so_far.writerOf("froxel_volume");
    if (!froxel || !scene.spectral.spectral_exr) return std::nullopt;
    std::vector<std::string> targets = {"rgb"};
    for (const char* layer : {"band_layers", "veiling_band_layer"})
      if (so_far.produces(layer)) targets.push_back(layer);
    std::vector<std::string> reads = {"underwater_setup", "froxel_volume", "gbuffer"};
    reads.insert(reads.end(), targets.begin(), targets.end());
    return planEntry(reads, targets,
                     std::string("the froxels' single scattering per band into spectral.exr (spectral.spectral_exr)") +
                         (targets.size() > 1 ? ", and into its layers per band" : ""),
                     froxel->features);  // froxel.cl built as the froxel pass builds it
  };
  d.keys = {{"camera.*", "spectral.*"}, {}};
  d.buffers = [](const Scene& s, const PassPlan& p) -> std::vector<BufferEstimate> {
    const FroxelConfig c = froxelConfigFromScene(s);
    const double fx = c.nx, fy = c.ny, fz = c.nz;
    std::vector<BufferEstimate> out = {{p.name, "one-band froxel volume", 16 * fx * fy * fz,
                                        {"quality.froxel_x", "quality.froxel_y", "quality.froxel_z"}, {fx, fy, fz}}};
    if (std::find(p.reads.begin(), p.reads.end(), "veiling_band_layer") != p.reads.end()) {
      const double w = s.camera.width, h = s.camera.height;
      out.push_back({p.name, "distances at infinity (veiling per band)", 16 * w * h,
                     {"camera.width", "camera.height"}, {w, h}});
    }
    return out;
  };
  // Per pixel and band: one resolve per target, and the volume integrated again per band.
  d.cost = [](const Scene&, const PassPlan& p) { return 0.5 * static_cast<double>(p.writes.size()); };
  d.factory = [](const PassPlan& e, const Plan&, const Scene&, const AutoQuality&) -> std::unique_ptr<Pass> {
    return std::make_unique<FroxelBandsNode>(e);
  };
  return d;
}

}  // namespace seasim
