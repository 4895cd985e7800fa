// frame_result.h — what one rendered frame hands back: the sensor image, optional per-band values,
// per-pass kernel times, the NaN/Inf count and the build/wall times.
#pragma once
#include <string>
#include <vector>

#include "io/image.h"

namespace seasim {

struct PassTiming {
  std::string name;
  double ms = 0.0;  // OpenCL profiling time of the pass's kernels
};

struct FrameResult {
  Image rgb;                          // linear sensor RGB, 3 channels
  std::vector<double> wavelengths_nm; // band centres
  std::vector<float> spectral;        // band_count values per pixel, when the scene asks for it
  // The ground-truth layers the plan wrote (render/layer_target.h), each target's channels as it named
  // them, in plan order (jobs/layer_image.h orders the asked ones for image.exr); 0 channels: none.
  Image layers;
  std::vector<PassTiming> timings;    // the passes that ran for this frame, in plan order
  long long nonfinite = 0;            // NaN/Inf counted on the device by check.cl
  double build_ms = 0.0;              // kernel build (or cache load) time for this frame
  double wall_ms = 0.0;               // set-up + run + read back
};

}  // namespace seasim
