#include "passes/nodes/layer_nodes.h"

#include <cstdio>

#include "plan/pass_descriptor.h"

namespace seasim {

std::vector<std::string> askedLayers(const Scene& scene, const std::vector<std::string>& names) {
  std::vector<std::string> out;
  for (const auto& l : scene.outputs.layers)
    for (const auto& n : names)
      if (l == n) out.push_back(l);
  return out;
}

std::string layerList(const std::vector<std::string>& layers) {
  std::string text;
  for (const auto& l : layers) text += (text.empty() ? "" : ", ") + l;
  return text;
}

std::string layerCostText(const Scene& scene, double bytes_per_pixel) {
  const double mb = bytes_per_pixel * scene.camera.width * scene.camera.height / 1e6;
  char text[128];
  std::snprintf(text, sizeof text, " (%.0f B/pixel on the device and as much on the host: %.1f MB each at %dx%d)",
                bytes_per_pixel, mb, scene.camera.width, scene.camera.height);
  return text;
}

PassPlan layersUnavailable(const std::vector<std::string>& layers) {
  PassPlan p = planEntry({}, {}, "outputs.layers: " + layerList(layers));
  p.implemented = false;
  p.missing = "these layers come from the underwater models (paper 002): put the camera below the surface "
              "(camera.position y < 0 with [water]), or drop them from outputs.layers / --output";
  return p;
}

}  // namespace seasim
