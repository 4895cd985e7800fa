#include "jobs/layer_image.h"

#include <algorithm>
#include <cmath>

#include "io/spectral_layout.h"
#include "scene/output_layers.h"
#include "util/error.h"

namespace seasim {

namespace {

// The index in frame.layers of the channel `channel` of layer `layer`; a channel the plan promised and
// the render did not write is an error (`where`: "" for image.exr, " for spectral.exr").
int layerChannelIndex(const FrameResult& frame, const char* layer, const std::string& channel, const char* where) {
  const auto& have = frame.layers.channel_names;
  const auto it = std::find(have.begin(), have.end(), channel);
  if (it == have.end())
    throw RuntimeError(std::string("layer '") + layer + "': the render wrote no channel '" + channel + "'" + where +
                       " (the plan promised it); nothing written");
  return static_cast<int>(it - have.begin());
}

}  // namespace

Image imageWithLayers(const FrameResult& frame, const OutputsDesc& outputs) {
  if (outputs.layers.empty()) return frame.rgb;
  // Each written channel's index in frame.layers, in the catalogue's order.
  std::vector<int> order;
  std::vector<std::string> names = {"R", "G", "B"};
  for (const OutputLayer& layer : outputLayers()) {
    if (!outputs.wants(layer.name)) continue;
    for (const auto& channel : layer.channels) {
      order.push_back(layerChannelIndex(frame, layer.name, channel, ""));
      names.push_back(channel);
    }
  }
  Image out;
  out.resize(frame.rgb.width, frame.rgb.height, static_cast<int>(names.size()));
  out.channel_names = names;
  const size_t pixels = out.pixelCount();
  // The check pass counts NaN/Inf in the image only: the layers are checked here, where they are
  // written. +inf is the range and depth of open water; anything else non-finite is a bug.
  long long nonfinite = 0;
  std::string first;
  for (size_t i = 0; i < pixels; ++i) {
    float* o = out.pixels.data() + i * names.size();
    std::copy_n(frame.rgb.pixels.data() + i * 3, 3, o);
    for (size_t c = 0; c < order.size(); ++c) {
      const float v = frame.layers.pixels[i * frame.layers.channels + order[c]];
      const std::string& name = names[3 + c];
      if (std::isnan(v) || (std::isinf(v) && !(v > 0 && (name == "range" || name == "depth")))) {
        if (nonfinite++ == 0) first = name;
      }
      o[3 + c] = v;
    }
  }
  if (nonfinite != 0)
    throw RuntimeError("the layers hold " + std::to_string(nonfinite) + " NaN/Inf values (first in '" + first +
                       "'); nothing written; please report it with the scene");
  return out;
}

Image bandLayersImage(const FrameResult& frame, const OutputsDesc& outputs) {
  Image out;
  if (frame.spectral.empty()) return out;
  std::vector<int> order;
  std::vector<std::string> names;
  for (const OutputLayer& layer : outputLayers()) {
    if (!layer.per_band || !outputs.wants(layer.name)) continue;
    for (double nm : frame.wavelengths_nm) {
      const std::string channel = spectralLayerChannelName(layer.name, nm);
      order.push_back(layerChannelIndex(frame, layer.name, channel, " for spectral.exr"));
      names.push_back(channel);
    }
  }
  if (names.empty()) return out;
  out.resize(frame.rgb.width, frame.rgb.height, static_cast<int>(names.size()));
  out.channel_names = names;
  long long nonfinite = 0;
  for (size_t i = 0; i < out.pixelCount(); ++i)
    for (size_t c = 0; c < order.size(); ++c) {
      const float v = frame.layers.pixels[i * frame.layers.channels + order[c]];
      if (!std::isfinite(v)) ++nonfinite;
      out.pixels[i * names.size() + c] = v;
    }
  if (nonfinite != 0)
    throw RuntimeError("the layers per band hold " + std::to_string(nonfinite) +
                       " NaN/Inf values; nothing written; please report it with the scene");
  return out;
}

void checkLayerOutputs(const Scene& scene, const std::vector<std::string>& formats) {
  if (scene.outputs.layers.empty()) return;
  std::string names;
  for (const auto& l : scene.outputs.layers) names += (names.empty() ? "" : ", ") + l;
  if (std::find(formats.begin(), formats.end(), "exr") == formats.end())
    throw RuntimeError("outputs.layers (" + names + ") are channels of image.exr: add exr to the outputs "
                       "(--output exr), or drop the layers; nothing written");
  if (scene.spectral.sensor == "identity")
    throw RuntimeError("outputs.layers (" + names + "): with spectral.sensor = \"identity\" image.exr holds the raw "
                       "bands, not RGB; use a camera or cie1931 sensor for layers; nothing written");
}

}  // namespace seasim
