// froxel_pass.h — host side of kernels/froxel.cl (002 §5: single scattering of the refracted sun beam
// by froxels, with the scrolling caustic textures of §5.3): FroxelParams and the integration bands
// from the scene (host/reference/froxel_reference.h shares that set-up with the CPU evaluation), the
// buffers, the three kernels (sun shadow map, injection, front-to-back integration) and their times.
//
// Reads: scene (UnderwaterSetup: camera, sun, bands, objects). Writes: froxel_volume (4 floats per
// froxel: RGB single scattering integrated to the end of each slice, the column's d_y), read per
// pixel by kd_multiple.cl through froxel_lookup with paramsBuffer().
#pragma once
#include <CL/opencl.hpp>

#include <string>
#include <vector>

#include "device/device.h"
#include "render/frame_result.h"
#include "underwater/froxel_setup.h"
#include "scene/scene.h"
#include "underwater/underwater_setup.h"

namespace seasim {

// "froxel_volume": what the froxel pass gives the passes after it (kd_multiple reads the volume, the
// band term integrates the light again per band: passes/froxel_band_term.h).
struct FroxelVolume {
  cl::Buffer params;   // FroxelParams on the device (kd_multiple.cl's fp)
  cl::Buffer column_dy;  // d_y of every column's ray (froxelColumnDy), what froxel_integrate stores
  cl::Buffer volume;   // 4 floats per froxel: RGB single scattering to the end of each slice, the column's d_y
  cl::Buffer light;    // the injected light V·C per froxel
  FroxelParams fp{};   // the host copy of `params`
};

class FroxelPass {
 public:
  // defines: the plan's "froxel" pass defines (SEASIM_HAS_OBJECTS, SEASIM_CAUSTICS,
  // SEASIM_SPECTRAL_INJECTION); any of them missing is added from the setup/config, and one that
  // contradicts them is a RuntimeError (the plan and the scene disagree). Grid, near/far, shadow-map
  // size and injection from froxelConfigFromScene(scene).
  FroxelPass(Device& device, const Scene& scene, const UnderwaterSetup& setup, const std::vector<std::string>& defines);
  FroxelPass(Device& device, const UnderwaterSetup& setup, const FroxelConfig& config,
             const std::vector<std::string>& defines);

  // Enqueues shadow map (when there are spheres or boxes), injection and integration, waits; returns
  // the summed kernel ms. timings() then holds each kernel's ms.
  // caustic_maps: CausticStack::maps() when the pass was built with SEASIM_CAUSTICS=2 (else ignored).
  // geom: the G-buffer (float4 per pixel of width × height, raycast.cl) the volume will be read at: froxels
  // that no pixel's froxel_lookup reads are then left 0 instead of evaluated (froxel_column_extent),
  // which leaves every read, and so the image, unchanged. Without it every froxel is evaluated.
  double run(const cl::Buffer* caustic_maps = nullptr, const cl::Buffer* geom = nullptr, int width = 0,
             int height = 0);
  const std::vector<PassTiming>& timings() const { return timings_; }

  // froxel_resolve: per pixel of a width × height image, the volume read at geom[pixel].x (float4 per
  // pixel, the G-buffer of raycast.cl) into rgb (3 floats per pixel, written). Returns ms.
  double resolve(const cl::Buffer& geom, int width, int height, cl::Buffer& rgb);

  // The sun's shadow map depends on the objects, the sun and the map's own knobs, not on the camera: a
  // pass made anew for a moved camera takes the last one's map (adoptShadowMap) when their keys agree
  // and then does not compute it again. The key: the bytes of everything froxel_shadow_map reads.
  const std::string& shadowMapKey() const { return shadow_key_; }
  cl::Buffer& shadowMap() { return map_; }
  void adoptShadowMap(const cl::Buffer& map);

  cl::Buffer& volume() { return volume_; }
  cl::Buffer& light() { return light_; }  // the injected light V·C per froxel, band-free
  cl::Buffer& paramsBuffer() { return fparams_; }
  cl::Buffer& columnDy() { return column_dy_; }  // froxelColumnDy on the device  // FroxelParams on the device (kd_multiple.cl's fp)
  const FroxelParams& params() const { return fp_; }
  const std::vector<std::string>& defines() const { return defines_; }

  // Read-backs for tests and tools.
  void readVolume(std::vector<float>& out);
  void readLight(std::vector<float>& out);
  void readShadowMap(std::vector<float>& out);  // empty without a map

 private:
  void read(cl::Buffer& buffer, size_t floats, std::vector<float>& out, const char* what);
  Device& device_;
  FroxelParams fp_{};
  std::vector<std::string> defines_;
  cl::Kernel shadow_kernel_, inject_kernel_, extent_kernel_, integrate_kernel_, resolve_kernel_;
  cl::Buffer params_, fparams_, objects_, bands_, map_, light_, volume_, no_caustics_,
      caustic_table_, column_last_, column_dy_;
  std::vector<PassTiming> timings_;
  std::string shadow_key_;
  bool shadow_map_ready_ = false;  // map_ holds this pass's shadow map (computed, or adopted)
};

}  // namespace seasim
