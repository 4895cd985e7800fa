// froxel_band_term.h — the froxel pass's single scattering per wavelength band, added into per-band
// images on the device, so spectral.exr and its layers hold the whole image (the froxel volume holds
// sensor RGB only). Each band is integrated again from the same injected light (V·C, band-free) as a
// one-band volume with its own c for the in-slice fraction (002 §5, common/froxel.h), then read at
// each target's distances and added into the target's slot of that band (froxel.cl's
// froxel_resolve_add). One integration per band and one resolve per band and target; opt-in
// (spectral.spectral_exr with the froxels).
#pragma once
#include <CL/opencl.hpp>

#include <vector>

#include "device/device.h"
#include "passes/froxel_pass.h"
#include "plan/plan.h"
#include "underwater/underwater_setup.h"

namespace seasim {

class FroxelBandTerm {
 public:
  // Builds froxel.cl with the plan entry's defines (FroxelFeatures, as the froxel pass's); a one-band
  // volume of its own is integrated into.
  FroxelBandTerm(Device& device, const PassPlan& entry, const FroxelVolume& volume);

  // values[pixel * stride + offset + band] += the band's froxel term at geom[pixel].x.
  struct Target {
    const cl::Buffer* geom;  // float4 per pixel, S first (the G-buffer, or UW_INFINITE for the veiling)
    cl::Buffer* values;
    int stride;
    int offset;
  };
  // Every band of `setup` into every target; returns the summed kernel ms.
  double addTo(const UnderwaterSetup& setup, int width, int height, const std::vector<Target>& targets);

 private:
  Device& device_;
  const FroxelVolume& volume_;
  cl::Kernel integrate_, resolve_add_;
  cl::Buffer band_volume_;
};

}  // namespace seasim
