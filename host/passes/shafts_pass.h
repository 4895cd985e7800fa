// shafts_pass.h — host side of kernels/shafts.cl (paper 001): builds ShaftsParams, the lights
// (frames, light maps), the objects and the F and h tables of 001 eq. 6 from the scene; enqueues the
// shadow-map kernel (one depth map per light, when there are objects) and the per-pixel
// sampling-plane kernel; reports each kernel's profiled time. With the intervals method
// (plan/shafts_method.h, define SEASIM_SHAFTS_INTERVALS) it builds each object's shadow volume per
// light instead of shadow maps (kernels/common/shafts_intervals.h).
//
// Reads: scene. Writes: shadow_maps (internal), rgb (3 floats per pixel, linear RGB radiance).
#pragma once
#include <CL/opencl.hpp>

#include <string>
#include <vector>

#include "device/device.h"
#include "plan/plan.h"
#include "geometry/shafts_geometry.h"
#include "scene/scene.h"

namespace seasim {

class ShaftsPass {
 public:
  struct Config {
    int planes = 30;            // n sampling planes (001 eq. 5)
    int subplanes = 6;          // m sub-sample planes per interval (001 eq. 7–9)
    int shadow_map_size = 512;  // texels per side, per light
    int table_size = 256;       // F table entries; h table is table_size² (table mode)
    double panel_deg = 4.0;     // intervals: widest quadrature panel, degrees of the lamp's angle
    double panel_texels = 2.0;  // intervals: widest panel over a light map, its texels
    int march_steps = 20;       // march: midpoint steps per ray and lamp
  };
  // The quality knobs of the scene ([quality] shafts_planes, shafts_subplanes, shadow_map_size,
  // shafts_table_size); "auto" takes the paper's setting n = 30, m = 6 here. The per-scene search
  // of "auto" (host/quality/shafts_auto.h) comes in through passes/auto_quality.h.
  static Config configFromScene(const Scene& scene);
  // The ranges of the h(s, t) table (table mode) the pass uses: shaftsTableRange(scene).
  static ShaftsRange rangeFor(const Scene& scene);

  // `plan` is the "shafts" pass of makePlan(scene): its kernel file and defines.
  ShaftsPass(Device& device, const Scene& scene, const PassPlan& plan, const Config& config);

  // Enqueues the shadow maps (if any objects) and the shafts kernel, waits; returns total kernel ms.
  double run();
  double shadowMapMs() const { return shadow_ms_; }
  double shaftsMs() const { return shafts_ms_; }
  cl::Buffer& rgb() { return rgb_; }
  // Reads the rgb buffer back (3 floats per pixel).
  void readRgb(std::vector<float>& out);
  const ShaftsRange& range() const { return range_; }

 private:
  Device& device_;
  cl::Kernel shadow_kernel_, render_kernel_;
  cl::Buffer params_, lights_, objects_, shadow_, light_maps_, f_table_, h_table_, occluders_, rgb_;
  int width_, height_, light_count_, shadow_size_;
  bool has_objects_;
  bool planes_ = false;  // paper 001's planes: shadow maps and the eq. 6 tables (the intervals and march use neither)
  double shadow_ms_ = 0, shafts_ms_ = 0;
  ShaftsRange range_;
};

}  // namespace seasim
