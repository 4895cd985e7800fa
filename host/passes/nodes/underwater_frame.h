// underwater_frame.h — what the underwater frame's nodes share (paper 002): the "gbuffer" resource
// that raycast.cl and kd_multiple.cl's UnderwaterPass publishes, the scene keys the underwater set-up
// folds in, and the "caustic_map" buffer the caustics node writes under water.
#pragma once
#include <CL/opencl.hpp>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "passes/underwater_pass.h"
#include "render/frame_context.h"
#include "render/resources.h"

namespace seasim {

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
inline const std::vector<std::string> kUnderwaterSetupKeys = {
    "sun.*",     "sky.*",     "water.*",  "bottom.*", "surface.*", "underwater.*",
    "objects.*", "quality.caustic_map_size", "quality.caustic_layers"};

// The "caustic_map" buffer of the caustics pass when `res` declares reading it, else null.
const cl::Buffer* underwaterCausticMaps(PassResources& res);

}  // namespace seasim
