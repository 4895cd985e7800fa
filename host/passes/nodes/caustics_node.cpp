// caustics_node.cpp — "caustics": the FFT ocean's caustics (004 §5.2.1) from the ocean_fft pass's
// surface, written into one persistent "caustic_map" buffer (copied into, so the passes that bound it
// as a kernel argument keep it; a new buffer only when its size changes):
//   - seen from above, on the sea bottom (passes/caustic_stack.h seaBottomCaustics, read by sea_single);
//   - under water, the stack of depth layers (CausticStack, read by raycast and froxel).
#include <cmath>
#include <memory>

#include "device/enqueue.h"
#include "passes/caustic_stack.h"
#include "passes/nodes/standard_passes.h"
#include "passes/nodes/underwater_frame.h"
#include "passes/underwater_setup_buffers.h"
#include "plan/pass_descriptor.h"
#include "plan/scene_facts.h"
#include "util/error.h"

namespace seasim {

namespace {

// Copies `fresh` into `kept` when both hold `bytes`; returns false when `kept` must be replaced.
bool copyInto(Device& device, const cl::Buffer& fresh, cl::Buffer& kept, size_t bytes) {
  if (!kept() || kept.getInfo<CL_MEM_SIZE>() != bytes) return false;
  onDevice("caustics pass: copying the caustic map", [&] {
    device.queue().enqueueCopyBuffer(fresh, kept, 0, 0, bytes);
    device.queue().finish();
  });
  return true;
}

const std::vector<std::string> kCausticKeys = {"sun.*", "water.*", "bottom.*", "underwater.*",
                                               "quality.caustic_map_size", "quality.caustic_layers"};

class SeaBottomCausticsNode : public Pass {
 public:
  PassKeys keys() const override { return {{}, kCausticKeys}; }
  void prepare(FrameContext&, PassResources&) override {}
  void execute(FrameContext& ctx, PassResources& res) override {
    SeaBottomCaustics fresh = seaBottomCaustics(ctx.device(), ctx.scene(), res.read<OceanMaps>("ocean_maps"));
    ctx.timings.push_back({"caustics", fresh.ms});
    if (kept_ && kept_->map_size == fresh.map_size &&
        copyInto(ctx.device(), fresh.map, kept_->map, sizeof(float) * fresh.host.size())) {
      cl::Buffer map = kept_->map;
      *kept_ = std::move(fresh);
      kept_->map = map;
      return;
    }
    kept_ = std::make_shared<SeaBottomCaustics>(std::move(fresh));
    res.publish("caustic_map", kept_);
  }

 private:
  std::shared_ptr<SeaBottomCaustics> kept_;
};

// Under water: the maps of CausticStack, kept in one buffer.
struct UnderwaterCausticMaps {
  cl::Buffer maps;
};

class UnderwaterCausticsNode : public Pass {
 public:
  PassKeys keys() const override { return {{}, kCausticKeys}; }
  void prepare(FrameContext&, PassResources&) override {}
  void execute(FrameContext& ctx, PassResources& res) override {
    CausticStack stack(ctx.device(), ctx.scene(), res.read<UnderwaterSetupBuffers>("underwater_setup").setup,
                       &res.read<OceanMaps>("ocean_maps"));
    for (const PassTiming& t : stack.timings()) ctx.timings.push_back(t);
    if (kept_ && copyInto(ctx.device(), stack.maps(), kept_->maps, sizeof(float) * stack.hostMaps().size())) return;
    kept_ = std::make_shared<UnderwaterCausticMaps>(UnderwaterCausticMaps{stack.maps()});
    res.publish("caustic_map", kept_);
  }

 private:
  std::shared_ptr<UnderwaterCausticMaps> kept_;
};

}  // namespace

// The underwater readers (underwater_nodes.cpp) read the buffer through this.
const cl::Buffer* underwaterCausticMaps(PassResources& res) {
  if (!res.declaresRead("caustic_map")) return nullptr;
  return &res.read<UnderwaterCausticMaps>("caustic_map").maps;
}

PassDescriptor causticsDescriptor() {
  PassDescriptor d;
  d.name = "caustics";
  d.kernel_file = "caustics.cl";
  d.rule = [](const Scene& scene, const Plan&) -> std::optional<PassPlan> {
    if (oceanForUnderwaterCaustics(scene))
      return planEntry({"underwater_setup", "ocean_maps"}, {"caustic_map"},
                       "camera below an FFT surface, underwater.caustics = \"map\" (004 §5.2.1)");
    if (seaBottomCausticsPlanned(scene))
      return planEntry({"ocean_maps"}, {"caustic_map"},
                       "FFT surface over a bottom, sea.bottom_caustics = true (004 §5.2.1)");
    return std::nullopt;
  };
  d.keys = {{}, kCausticKeys};
  d.knobs = {{"caustic_map_size", 256}, {"caustic_layers", 8}};
  // Built without the plan's relaxed maths: its error was not measured under it.
  d.fast_math = false;
  d.buffers = [d](const Scene& s, const PassPlan& p) -> std::vector<BufferEstimate> {
    const double C = d.knob(s, "caustic_map_size");
    return {{p.name, "caustic maps", 2 * 4 * C * C, {"quality.caustic_map_size", "quality.caustic_map_size"}, {C, C}}};
  };
  // 70x sea_single per pixel and band on a height-field floor (results/BENCHMARKS.md "Farm shards").
  d.cost = [d](const Scene& s, const PassPlan&) {
    return 70.0 * std::pow(d.settledKnob(s, "caustic_map_size") / 256.0, 2);
  };
  d.factory = [](const PassPlan&, const Plan&, const Scene& scene, const AutoQuality&) -> std::unique_ptr<Pass> {
    // Under water the caustics are the layered stack the G-buffer and the froxels read.
    if (cameraUnderwater(scene)) return std::make_unique<UnderwaterCausticsNode>();
    return std::make_unique<SeaBottomCausticsNode>();
  };
  return d;
}

}  // namespace seasim
