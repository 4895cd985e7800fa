// underwater_pass.h — host side of kernels/raycast.cl (the G-buffer) and kernels/kd_multiple.cl (the
// per-band deferred shading of 002 eq. 4.7–4.8): buffers, arguments, profiled times.
#pragma once
#include <CL/opencl.hpp>

#include <vector>

#include "device/device.h"
#include "plan/plan.h"
#include "underwater/underwater_setup.h"

namespace seasim {

class UnderwaterPass {
 public:
  // raycast / kd: the plan's passes of those names (their defines). spectral_output allocates the
  // band_count floats per pixel buffer.
  UnderwaterPass(Device& device, const UnderwaterSetup& setup, const PassPlan& raycast, const PassPlan& kd,
                 bool spectral_output);
  // The G-buffer; returns the kernel's profiled ms. caustic_maps: CausticStack::maps() when the raycast
  // pass was planned with SEASIM_CAUSTICS=2 (else ignored).
  double runRaycast(const cl::Buffer* caustic_maps = nullptr);
  // The shading. froxel_params / froxel_volume: the froxel pass's outputs when the kd pass was planned
  // with SEASIM_HAS_FROXEL=1 (else ignored). Returns ms.
  double runShading(const cl::Buffer* froxel_params, const cl::Buffer* froxel_volume);
  // Rewrites the parameter blocks from a newer setup with the same band and object counts (a change
  // of sun, water or time), keeping kernels and buffers; RuntimeError when a count changed (make a
  // new pass then).
  void update(const UnderwaterSetup& setup);
  cl::Buffer& rgb() { return rgb_; }
  cl::Buffer& spectral() { return spectral_; }
  cl::Buffer& geometry() { return geom_; }  // float4 (S, n) per pixel
  cl::Buffer& sunVisibility() { return vis_; }  // float per pixel: shadow ray × caustic factor
  cl::Buffer& material() { return material_; }  // int per pixel: object index or UW_MAT_*
  cl::Buffer& params() { return params_; }      // UwParams, the frame's
  cl::Buffer& bandTable() { return band_table_; }  // common/underwater_band_table.h, the frame's
  // With the water's point-spread (kd planned with SEASIM_UWI_SPREAD=1, kernels/water_spread.cl): the
  // moments of the forward light kd_multiple kept apart (common/water_spread_params.h), [pixel][2][3] in
  // sensor RGB, [pixel][2] its light-weighted distance and, with spectral output, [pixel][2][band_count];
  // null buffers otherwise.
  bool spread() const { return spread_; }
  cl::Buffer& forwardRgb() { return forward_rgb_; }
  cl::Buffer& forwardSpectral() { return forward_spectral_; }
  cl::Buffer& forwardDepth() { return forward_depth_; }
  // The ground-truth layers (kd planned with formation_layers / veiling_layer; kernels/kd_multiple.cl's
  // header gives their layout); null buffers otherwise.
  cl::Buffer& formationLayers() { return formation_; }  // [pixel][12]: clear, direct, backscatter, transmission
  cl::Buffer& forwardLayer() { return forward_layer_; }  // [pixel][3], water_spread adds into it
  cl::Buffer& lampsLayer() { return lamps_layer_; }      // [pixel][3], underwater_lamps adds into it
  cl::Buffer& veilingLayer() { return veiling_; }        // [pixel][3]
  // The split per band (band_layers): [pixel][5][band] clear, direct, backscatter, lamps, transmission,
  // and the forward light [pixel][band] (water_spread adds into it).
  cl::Buffer& bandLayers() { return band_layers_; }
  cl::Buffer& forwardBands() { return forward_bands_; }
  cl::Buffer& veilingBands() { return veiling_bands_; }  // [pixel][band] (veiling_bands)

 private:
  double enqueue(cl::Kernel& kernel, const char* what);
  Device& device_;
  int width_, height_;
  bool spectral_output_;
  bool spread_ = false;
  cl::Buffer forward_rgb_, forward_spectral_, forward_depth_;
  cl::Buffer formation_, forward_layer_, lamps_layer_, veiling_, band_layers_, forward_bands_, veiling_bands_;
  cl::Kernel raycast_, shade_;
  cl::Buffer params_, bands_, objects_, albedo_, geom_, material_, vis_, rgb_, spectral_, no_caustics_;
  cl::Buffer sky_params_, sky_;  // the [sky] for Snell's window (common/sky_view.h)
  cl::Buffer band_table_;         // per-band values of the band loop (underwater/underwater_band_table.h)
  bool has_improved_ = false;      // underwater.model = "improved": the band table has its rows
  size_t band_count_, object_count_, albedo_count_, sky_count_, band_table_count_ = 0;
};

}  // namespace seasim
