// layer_image.h — image.exr's channels with the ground-truth layers (scene/output_layers.h): the sensor
// RGB first (R, G, B), then each layer's channels in the catalogue's order, whatever order the passes
// wrote them in.
#pragma once
#include <string>
#include <vector>

#include "render/frame_result.h"
#include "scene/scene.h"

namespace seasim {

// frame.rgb with the channels of the layers `outputs` asks for after it (a pass may write more than
// were asked: kd_multiple writes the whole split); frame.rgb alone when none is asked. RuntimeError
// when an asked layer's channel was not written (a plan that promised it: a bug), or when a layer holds
// NaN or Inf (but +inf in range and depth: open water).
Image imageWithLayers(const FrameResult& frame, const OutputsDesc& outputs);

// The asked layers that have bands (OutputLayer::per_band), per band, for spectral.exr after its bands:
// "<layer>.S0.<nm>" for each of frame.wavelengths_nm, in the catalogue's order. No channels when the frame
// has no spectral image or no such layer is asked. RuntimeError as imageWithLayers.
Image bandLayersImage(const FrameResult& frame, const OutputsDesc& outputs);

// Throws RuntimeError, before anything renders, when the scene asks for layers the outputs cannot
// hold: layers are channels of image.exr, so `formats` must include "exr" (and sensor = "identity",
// whose image.exr holds the bands, has no RGB layers).
void checkLayerOutputs(const Scene& scene, const std::vector<std::string>& formats);

}  // namespace seasim
