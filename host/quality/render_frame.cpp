#include "quality/render_frame.h"

#include "quality/auto_quality.h"
#include "render/renderer.h"

namespace seasim {

FrameResult renderFrame(Device& device, const Scene& scene, const Plan& plan) {
  Renderer renderer(device, scene, plan, shippedPasses());
  return renderer.render();
}

}  // namespace seasim
