// caustic_stack.h — the caustic maps the underwater passes read when `[underwater] caustics = "map"`:
// the FFT ocean at the scene's time (004 §3) splatted by flux conservation (004 §5.2.1, caustics.cl)
// onto caustic_layers planes between the surface and caustic_depth_max, each divided by its mean so
// it holds the focusing pattern only (kernels/common/caustic_map.h explains the layout and the read).
#pragma once
#include <CL/opencl.hpp>

#include <vector>

#include "device/device.h"
#include "passes/ocean_pass.h"
#include "render/frame_result.h"
#include "scene/scene.h"
#include "underwater/underwater_setup.h"

namespace seasim {

class CausticStack {
 public:
  // Runs the ocean and the splats; the maps stay on the device. Sun below the horizon: all layers 1.
  CausticStack(Device& device, const Scene& scene, const UnderwaterSetup& setup);
  // The same from an ocean that has already run at scene.surface.time (the renderer's ocean_fft
  // pass); timings() then holds the splats only.
  CausticStack(Device& device, const Scene& scene, const UnderwaterSetup& setup, const OceanMaps* ocean);

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

// The ocean's caustics on the bottom for the sea seen from above (sea.bottom_caustics, the plan's
// SEASIM_BOTTOM_CAUSTICS; read by sea_single.cl through caustic_map_read). A flat bottom: the plane
// splat at its depth, periodic over the patch, divided by its mean. A height field: the floor splat
// (CausticsPass::runFloor) over the floor's square, each texel divided by what a calm sea would put
// there, T(θ) (-t·n̂)/cos θt (so flat water reads 1 up to the splat's few-% lattice ripple). Either
// way a focusing factor with mean about 1: eq. 9's mean beam is the model's. `ocean` has run.
struct SeaBottomCaustics {
  cl::Buffer map;
  std::vector<float> host;
  int map_size = 1;
  double extent = 1.0, origin = 0.0;  // m: the square [origin, origin + extent]² the map covers
  bool periodic = true;
  double ms = 0.0;                    // wall ms of the splat and normalisation
};
SeaBottomCaustics seaBottomCaustics(Device& device, const Scene& scene, const OceanMaps& ocean);

// A one-float buffer for the kernels' caustic-map argument when the scene has no caustic map.
cl::Buffer noCausticMap(Device& device);

}  // namespace seasim
