#include "passes/render_frame.h"

#include "passes/nodes/standard_passes.h"
#include "render/renderer.h"

namespace seasim {

FrameResult renderFrame(Device& device, const Scene& scene, const Plan& plan) {
  Renderer renderer(device, scene, plan, standardPasses());
  return renderer.render();
}

}  // namespace seasim
