// underwater_shading.h — host side of kernels/kd_multiple.cl, the underwater frame's per-band deferred
// shading (002 eq. 4.7–4.8, or the discrete-ordinates model of common/underwater_ordinates.h): its
// kernel, the buffers it writes (the image, spectral image, forward light and ground-truth layers) and
// their arguments. It reads the "underwater_setup" and "gbuffer" resources' buffers.
#pragma once
#include <CL/opencl.hpp>

#include "device/device.h"
#include "passes/nodes/underwater_frame.h"
#include "passes/underwater_features.h"
#include "passes/underwater_setup_buffers.h"
#include "plan/plan.h"

namespace seasim {

class UnderwaterShading {
 public:
  // kd: the plan's kd_multiple entry (defines, KdFeatures): which buffers it writes. The kernel's
  // inputs are bound here and stay bound: a new setup or G-buffer needs a new UnderwaterShading.
  UnderwaterShading(Device& device, const PassPlan& kd, const UnderwaterSetupBuffers& setup,
                    const UnderwaterGBuffer& gbuffer);
  // Runs kd_multiple; returns its profiled ms. froxel_params / froxel_volume: the froxel pass's
  // volume when kd was planned with its froxel feature (else null); sand: sand_share.cl's lattice when
  // planned with its sand_map feature (else null).
  double run(const cl::Buffer* froxel_params, const cl::Buffer* froxel_volume,
             const UnderwaterSandShare* sand = nullptr);

  cl::Buffer& rgb() { return rgb_; }
  cl::Buffer& spectral() { return spectral_; }  // band_count floats per pixel; null without spectral output
  // With the point-spread feature (else null buffers).
  UnderwaterForwardLight& forwardLight() { return forward_; }
  // The ground-truth layers (features formation_layers / veiling_layer; kernels/kd_multiple.cl's
  // header gives their layout); null buffers otherwise.
  cl::Buffer& formationLayers() { return formation_; }  // [pixel][12]: clear, direct, backscatter, transmission
  cl::Buffer& forwardLayer() { return forward_layer_; }  // [pixel][3], water_spread adds into it
  cl::Buffer& lampsLayer() { return lamps_layer_; }      // [pixel][3], underwater_lamps adds into it
  cl::Buffer& veilingLayer() { return veiling_; }        // [pixel][3]
  // lamps_single and/or lamps_multiple, 3 floats each per pixel (lamps_split_layers): zeroed by run(),
  // underwater_lamps adds into it.
  cl::Buffer& lampsSplitLayer() { return lamps_split_; }
  // The split per band (band_layers): [pixel][5][band] clear, direct, backscatter, lamps, transmission,
  // and the forward light [pixel][band] (water_spread adds into it).
  cl::Buffer& bandLayers() { return band_layers_; }
  cl::Buffer& forwardBands() { return forward_bands_; }
  cl::Buffer& veilingBands() { return veiling_bands_; }  // [pixel][band] (veiling_bands)

 private:
  Device& device_;
  int width_, height_;
  KdFeatures features_;
  const UnderwaterSetupBuffers& setup_;
  const UnderwaterGBuffer& gbuffer_;
  cl::Kernel kernel_;
  cl::Buffer rgb_, spectral_;
  UnderwaterForwardLight forward_;
  cl::Buffer formation_, forward_layer_, lamps_layer_, veiling_, band_layers_, forward_bands_, veiling_bands_;
  cl::Buffer lamps_split_;
  size_t lamps_split_floats_ = 0;
};

}  // namespace seasim
