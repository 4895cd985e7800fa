// fourflow_pass.h — host side of kernels/fourflow.cl (paper 003): the four-flow bands from the scene,
// the (l, h) tables of eq. 22–23 (built once by a kernel on the table path), and the frame kernel
// ff_render, which writes linear RGB (3 floats per pixel) and, with spectral.spectral_exr, every band's
// radiance (the exact eq. 20 per band, on either path). Bottom: [bottom] flat or height field, or
// the [shallow] slope, through the sea module's height field (passes/sea_heightfield.h).
#pragma once
#include <CL/opencl.hpp>

#include <array>
#include <vector>

#include "device/device.h"
#include "plan/plan.h"
#include "scene/scene.h"
#include "spectral/sensor.h"
#include "spectral/wavelength_grid.h"
#include "common/fourflow_params.h"
#include "passes/sea_heightfield.h"

namespace seasim {
// Nodes per side of the height field a [shallow] slope becomes.
inline constexpr int kFourFlowSlopeNodes = 65;
}  // namespace seasim
#include "sky/sky_light.h"

namespace seasim {

// What the pass hands the kernels, from the scene alone (tests and the sweep use it too).
struct FourFlowSetup {
  std::vector<FfBand> bands;
  FfParams params{};  // tables: resolution from quality.fourflow_table_size (or table_size), ranges
  FfView view{};
  bool height_field = false;
  HeightField field;  // when height_field
  // The [sky] model for ff_render (host/sky; used when the plan's SEASIM_SKY_MODEL is not 0).
  SkyParams sky_params{};
  std::vector<float> sky_buffer;
  std::array<float, 12> sky_rgb_matrix{};
};
// table_size <= 0: quality.fourflow_table_size.
FourFlowSetup makeFourFlowSetup(const Scene& scene, const WavelengthGrid& grid, const Sensor& sensor,
                                int table_size = 0);

// The mean of ff_bottom_texture over a large area (the "average bottom" of 003 eq. 12).
double fourFlowTextureMean(double scale, double dark_fraction);

class FourFlowPass {
 public:
  FourFlowPass(Device& device, const Scene& scene, const PassPlan& plan, const WavelengthGrid& grid,
               const Sensor& sensor, int table_size = 0);
  double run();  // ff_render; returns its profiled ms
  double tableMs() const { return table_ms_; }  // ff_build_tables, 0 on the exact path
  cl::Buffer& rgb() { return rgb_; }
  cl::Buffer& spectral() { return spectral_; }  // bands per pixel; null unless spectral.spectral_exr

 private:
  Device& device_;
  cl::Kernel render_;
  cl::Buffer view_, bands_, params_, table_, rgb_, spectral_, hf_params_, hf_depth_, sky_params_, sky_, sky_matrix_;
  int width_, height_;
  double table_ms_ = 0;
};

}  // namespace seasim
