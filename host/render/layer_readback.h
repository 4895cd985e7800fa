// layer_readback.h — the frame's ground-truth layers read back from the device: every LayerTarget
// (render/layer_target.h) a pass of the plan writes, in plan order, into FrameResult::layers.
// Knows no layer by name.
#pragma once
#include "device/device.h"
#include "plan/plan.h"
#include "render/frame_result.h"
#include "render/resources.h"

namespace seasim {

void readLayers(Device& device, const Resources& resources, const Plan& plan, int width, int height,
                FrameResult& result);

}  // namespace seasim
