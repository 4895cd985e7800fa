#include "passes/froxel_band_term.h"

#include <string>

#include "device/enqueue.h"

namespace seasim {

FroxelBandTerm::FroxelBandTerm(Device& device, const PassPlan& entry, const FroxelVolume& volume)
    : device_(device), volume_(volume) {
  const size_t froxels = size_t(volume.fp.nx) * volume.fp.ny * volume.fp.nz;
  onDevice("froxel band term set-up", [&] {
    const BuiltProgram& built = device.program(entry.kernel_file, entry.defines);
    integrate_ = cl::Kernel(built.program, "froxel_integrate");
    resolve_add_ = cl::Kernel(built.program, "froxel_resolve_add");
    band_volume_ = cl::Buffer(device.context(), CL_MEM_READ_WRITE, sizeof(float) * 4 * froxels);
  });
}

double FroxelBandTerm::addTo(const UnderwaterSetup& setup, int width, int height, const std::vector<Target>& targets) {
  const cl_mem_flags in = CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR;
  double ms = 0;
  onDevice("froxel band term", [&] {
    for (size_t b = 0; b < setup.bands.size(); ++b) {
      // One band, weight 1 into R (and two zero-weight copies for the RGB-injection kernel, which
      // always reads three pseudo-bands); band_count 1 for the spectral-injection kernel.
      UwParams p = setup.params;
      p.band_count = 1;
      UwBand one[3] = {setup.bands[b], setup.bands[b], setup.bands[b]};
      one[0].w_r = 1, one[0].w_g = 0, one[0].w_b = 0;
      for (int k = 1; k < 3; ++k) one[k].w_r = one[k].w_g = one[k].w_b = 0;
      FroxelParams fp = volume_.fp;
      for (int k = 0; k < 3; ++k) fp.sigma_t_rgb[k] = setup.bands[b].c;  // in-slice fraction of this band
      cl::Buffer params(device_.context(), in, sizeof p, &p), band_buffer(device_.context(), in, sizeof one, one);
      cl::Buffer fparams(device_.context(), in, sizeof fp, &fp);
      integrate_.setArg(0, params);
      integrate_.setArg(1, fparams);
      integrate_.setArg(2, band_buffer);
      integrate_.setArg(3, volume_.light);
      integrate_.setArg(4, band_volume_);
      integrate_.setArg(5, volume_.column_dy);
      ms += runKernel2d(device_, "froxel", integrate_, size_t(fp.nx), size_t(fp.ny));
      resolve_add_.setArg(0, fparams);
      resolve_add_.setArg(1, band_volume_);
      resolve_add_.setArg(3, width);
      resolve_add_.setArg(4, height);
      for (const Target& t : targets) {
        resolve_add_.setArg(2, *t.geom);
        resolve_add_.setArg(5, t.stride);
        resolve_add_.setArg(6, t.offset + static_cast<int>(b));
        resolve_add_.setArg(7, *t.values);
        ms += runKernel2d(device_, "froxel", resolve_add_, size_t(width), size_t(height));
      }
    }
  });
  return ms;
}

}  // namespace seasim
