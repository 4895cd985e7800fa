// render_frame.h — one frame of a scene, start to finish: a Renderer (render/renderer.h) built for
// this frame alone, with the shipped passes and their "auto" quality searched (quality/auto_quality.h). Callers that render more than one frame of a scene (animations, sweeps, bench)
// keep a Renderer instead, so that only what changed runs again.
#pragma once
#include "device/device.h"
#include "plan/plan.h"
#include "render/frame_result.h"
#include "scene/scene.h"

namespace seasim {

// Throws RuntimeError when the plan has a pass that is not implemented yet (naming it and its issue),
// DeviceError on OpenCL failures. Never returns an image with NaN/Inf silently: nonfinite > 0 is
// reported to the caller, which fails the run.
FrameResult renderFrame(Device& device, const Scene& scene, const Plan& plan);

}  // namespace seasim
