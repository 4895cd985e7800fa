// layer_target.h — a resource of ground-truth layers (scene/output_layers.h) one pass wrote: named
// channels per pixel. The renderer reads back every LayerTarget its plan writes into
// FrameResult::layers, knowing no layer by name.
#pragma once
#include <CL/opencl.hpp>

#include <string>
#include <vector>

namespace seasim {

struct LayerTarget {
  std::vector<std::string> channels;  // image.exr names, e.g. {"range", "normal.X", ...}
  cl::Buffer image;                   // channels.size() floats per pixel, pixel-major
};

}  // namespace seasim
