#include "render/layer_readback.h"

#include <algorithm>

#include "device/enqueue.h"
#include "render/layer_target.h"

namespace seasim {

void readLayers(Device& device, const Resources& resources, const Plan& plan, int width, int height,
                FrameResult& result) {
  std::vector<const LayerTarget*> targets;
  for (const PassPlan& p : plan.passes)
    for (const auto& w : p.writes)
      if (resources.holds<LayerTarget>(w)) {
        const LayerTarget* t = &resources.get<LayerTarget>(w);
        if (std::find(targets.begin(), targets.end(), t) == targets.end()) targets.push_back(t);
      }
  result.layers = Image{};
  if (targets.empty()) return;
  const size_t pixels = static_cast<size_t>(width) * static_cast<size_t>(height);
  size_t channels = 0;
  for (const LayerTarget* t : targets) {
    channels += t->channels.size();
    result.layers.channel_names.insert(result.layers.channel_names.end(), t->channels.begin(), t->channels.end());
  }
  result.layers.resize(width, height, static_cast<int>(channels));
  size_t at = 0;
  std::vector<float> part;
  for (const LayerTarget* t : targets) {
    const size_t n = t->channels.size();
    part.resize(pixels * n);
    onDevice("reading the layers back", [&] {
      device.queue().enqueueReadBuffer(t->image, CL_TRUE, 0, sizeof(float) * part.size(), part.data());
    });
    for (size_t i = 0; i < pixels; ++i)
      std::copy_n(part.data() + i * n, n, result.layers.pixels.data() + i * channels + at);
    at += n;
  }
}

}  // namespace seasim
