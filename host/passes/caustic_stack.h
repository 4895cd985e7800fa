// caustic_stack.h — the caustic maps the underwater passes read when `[underwater] caustics = "map"`:
// the FFT ocean at the scene's time (004 §3) splatted by flux conservation (004 §5.2.1, caustics.cl)
// onto caustic_layers planes between the surface and caustic_depth_max, each divided by its mean so
// it holds the focusing pattern only (kernels/common/caustic_map.h explains the layout and the read).
#pragma once
#include <CL/opencl.hpp>

#include <vector>

#include "device/device.h"
#include "passes/ocean_pass.h"
#include "passes/render_frame.h"
#include "scene/scene.h"
#include "underwater/underwater_setup.h"

namespace seasim {

class CausticStack {
 public:
  // Runs the ocean and the splats; the maps stay on the device. Sun below the horizon: all layers 1.
  CausticStack(Device& device, const Scene& scene, const UnderwaterSetup& setup);

  cl::Buffer& maps() { return maps_; }                 // layers × m² floats, normalised to mean 1
  const std::vector<float>& hostMaps() const { return host_; }
  int mapSize() const { return map_size_; }
  int layers() const { return layers_; }
  const std::vector<PassTiming>& timings() const { return timings_; }  // ocean_fft, caustics

 private:
  int map_size_ = 0;
  int layers_ = 0;
  std::vector<float> host_;
  cl::Buffer maps_;
  std::vector<PassTiming> timings_;
};

// A one-float buffer for the kernels' caustic-map argument when the scene has no caustic map.
cl::Buffer noCausticMap(Device& device);

}  // namespace seasim
