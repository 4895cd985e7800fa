#include "passes/underwater_setup_buffers.h"

#include <utility>
#include <vector>

#include "device/enqueue.h"
#include "underwater/underwater_band_table.h"

namespace seasim {

UnderwaterSetupBuffers::UnderwaterSetupBuffers(Device& device, UnderwaterSetup made) : setup(std::move(made)) {
  const cl_mem_flags in = CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR;
  onDevice("underwater set-up", [&] {
    params = cl::Buffer(device.context(), in, sizeof(UwParams), &setup.params);
    bands = cl::Buffer(device.context(), in, sizeof(UwBand) * setup.bands.size(), setup.bands.data());
    objects = cl::Buffer(device.context(), in, sizeof(UwObject) * setup.objects.size(), setup.objects.data());
    albedo = cl::Buffer(device.context(), in, sizeof(float) * setup.albedo.size(), setup.albedo.data());
    std::vector<float> table = underwaterBandTable(setup);
    band_table_floats = table.size();
    band_table = cl::Buffer(device.context(), in, sizeof(float) * table.size(), table.data());
    sky_params = cl::Buffer(device.context(), in, sizeof(SkyParams), &setup.sky_params);
    sky = cl::Buffer(device.context(), in, sizeof(float) * setup.sky_buffer.size(), setup.sky_buffer.data());
  });
}

bool UnderwaterSetupBuffers::update(Device& device, UnderwaterSetup&& newer) {
  if (newer.bands.size() != setup.bands.size() || newer.objects.size() != setup.objects.size() ||
      newer.albedo.size() != setup.albedo.size() || newer.sky_buffer.size() != setup.sky_buffer.size() ||
      newer.params.width != setup.params.width || newer.params.height != setup.params.height ||
      newer.ordinates.empty() != setup.ordinates.empty())
    return false;
  setup = std::move(newer);
  const std::vector<float> table = underwaterBandTable(setup);  // same size: same bands and rows
  onDevice("underwater set-up update", [&] {
    cl::CommandQueue& q = device.queue();
    q.enqueueWriteBuffer(params, CL_FALSE, 0, sizeof(UwParams), &setup.params);
    q.enqueueWriteBuffer(bands, CL_FALSE, 0, sizeof(UwBand) * setup.bands.size(), setup.bands.data());
    q.enqueueWriteBuffer(objects, CL_FALSE, 0, sizeof(UwObject) * setup.objects.size(), setup.objects.data());
    q.enqueueWriteBuffer(albedo, CL_FALSE, 0, sizeof(float) * setup.albedo.size(), setup.albedo.data());
    q.enqueueWriteBuffer(band_table, CL_FALSE, 0, sizeof(float) * band_table_floats, table.data());
    q.enqueueWriteBuffer(sky_params, CL_FALSE, 0, sizeof(SkyParams), &setup.sky_params);
    q.enqueueWriteBuffer(sky, CL_FALSE, 0, sizeof(float) * setup.sky_buffer.size(), setup.sky_buffer.data());
    q.finish();  // `table` goes away after this call
  });
  return true;
}

}  // namespace seasim
