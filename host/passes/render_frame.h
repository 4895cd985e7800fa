// render_frame.h — runs a plan's passes on a device for one frame and reads the image back.
#pragma once
#include <string>
#include <vector>

#include "device/device.h"
#include "io/image.h"
#include "plan/plan.h"
#include "scene/scene.h"

namespace seasim {

struct PassTiming {
  std::string name;
  double ms = 0.0;  // OpenCL profiling time of the pass's kernels
};

struct FrameResult {
  Image rgb;                          // linear sensor RGB, 3 channels
  std::vector<double> wavelengths_nm; // band centres
  std::vector<float> spectral;        // band_count values per pixel, when the scene asks for it
  std::vector<PassTiming> timings;
  long long nonfinite = 0;            // NaN/Inf counted on the device by check.cl
  double build_ms = 0.0;              // kernel build (or cache load) time for this frame
  double wall_ms = 0.0;               // set-up + run + read back
};

// Throws RuntimeError when the plan has a pass that is not implemented yet (naming it and its issue),
// DeviceError on OpenCL failures. Never returns an image with NaN/Inf silently: nonfinite > 0 is
// reported to the caller, which fails the run.
FrameResult renderFrame(Device& device, const Scene& scene, const Plan& plan);

}  // namespace seasim
