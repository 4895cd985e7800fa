// radiance_target.h — the "rgb" resource: the frame's linear sensor RGB (3 floats per pixel) and, when
// the scene asks for spectral output, its per-band values (band_count floats per pixel). The pass
// that writes it first owns the buffers; later passes add into them (sea_second) and the renderer
// reads them back.
#pragma once
#include <CL/opencl.hpp>

#include <cstddef>

namespace seasim {

struct RadianceTarget {
  cl::Buffer rgb;
  cl::Buffer spectral;  // null without spectral output
  size_t pixels = 0;
  size_t bands = 0;
  bool hasSpectral() const { return spectral() != nullptr; }
};

}  // namespace seasim
