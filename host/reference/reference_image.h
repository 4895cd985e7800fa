// reference_image.h — the brute-force reference image of a scene, the one `seasim reference` writes
// and the Python package's seasim.reference() returns: under water (and the sea seen from above with
// all orders) the spectral path tracer on the device; spotlights in air the shafts ray marcher; else
// the sea's quadrature (plus its second order by direct quadrature when the scene asks for it).
#pragma once
#include <functional>
#include <string>

#include "io/image.h"
#include "scene/scene.h"

namespace seasim {

struct ReferenceOptions {
  std::string device;       // path tracer only: a selector as in --device
  int steps = 0;            // 0: the scene's quality.reference_spp (under water) or quality.reference_steps
  long long seed = -1;      // path tracer: its seed; -1: not given (seed 1)
  bool all_orders = false;  // the sea seen from above: the path tracer refracting in, not 000's quadrature
                            // (the scene's sky, its flat or height-field floor, FFT waves as sea_waves.h)
  int max_bounces = 0;      // path tracer: scattering vertices per path (0: its default, 64)
  bool lamp_mis = true;     // path tracer: UnderwaterReferenceSettings::lamp_mis
  bool pixel_centre = false;  // path tracer: every path through the pixel's centre (no jitter over its area)
  int sun_single_subpixels = 0;  // > 0, under water without multiple scattering: the sun beam's single
                                 // scattering by quadrature (froxelBruteForcePixelArea), this many² rays per
                                 // pixel, instead of the path tracer
  std::function<void(int done, int total)> progress;  // path tracer: samples per pixel done
};

struct ReferenceImage {
  Image rgb;
  Image std_error;         // path tracer: the per-pixel standard error (from independent blocks of
                           // paths, reference/batch_error.h); empty for the deterministic ones
  // Path tracer under water: the part of rgb from paths whose camera ray reached a surface unscattered
  // (UnderwaterReferenceResult::direct: the fast models' direct layer) and its standard error; empty
  // for the others.
  Image direct, direct_std_error;
  std::string method;      // "path tracer", "ray-march" or "quadrature"
  int steps = 0;           // paths per pixel, or ray-march / quadrature steps
  unsigned seed = 0;       // path tracer
  int max_bounces = 0;     // path tracer (1: single scattering)
  double ms = 0.0;
  double mean_std_error = 0.0, image_mean = 0.0;  // path tracer
  double image_mean_std_error = 0.0;              // path tracer: from the blocks' image means
  double effective_samples = 0.0;                 // path tracer: paths per pixel the error is worth
  int blocks = 0;                                 // path tracer: independent blocks of paths
  std::string device_name;                        // path tracer; "" on the CPU
};

// Throws RuntimeError for options the scene's reference cannot honour (all_orders on a scene it does
// not model, "auto" steps) and DeviceError on OpenCL failures.
ReferenceImage renderReference(const Scene& scene, const ReferenceOptions& options);

}  // namespace seasim
