// layer_nodes.h — what the ground-truth layer nodes (scene/output_layers.h) share: the plan entry of a
// layer pass a scene asked for but whose model cannot give it, and the memory text `seasim plan` shows.
#pragma once
#include <string>
#include <vector>

#include "plan/plan.h"
#include "scene/scene.h"

namespace seasim {

// The layers of `names` the scene asks for, in catalogue order.
std::vector<std::string> askedLayers(const Scene& scene, const std::vector<std::string>& names);

// "range, object_id"
std::string layerList(const std::vector<std::string>& layers);

// " (8 B/pixel: 1.8 MB at 640x360)": the device buffers and the host copy the layers cost.
std::string layerCostText(const Scene& scene, double bytes_per_pixel);

// A planned-but-not-implemented entry: the layers need the camera under water (the models that
// split the image are paper 002's); render and run refuse it with this text, `plan` shows it.
PassPlan layersUnavailable(const std::vector<std::string>& layers);

}  // namespace seasim
