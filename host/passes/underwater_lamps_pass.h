// underwater_lamps_pass.h — host side of kernels/underwater_lamps.cl: spotlights in the water's
// spectral medium (paper 001's sampling planes with the water's per-band σ_s, σ_t and HG phase,
// common/underwater_lamps.h), added into the underwater frame's rgb (and spectral) after kd_multiple.
//
// Reads: the underwater set-up (camera, bands with IOPs and sensor weights, objects, albedo), the
// G-buffer (hit distance, normal, material), the lamps with their spectra (spectral/lamp_spectrum.h).
// Writes: += rgb, += spectral. Quality: quality.shafts_planes (n), quality.shafts_subplanes (m), the
// knobs of the shafts in air; their defaults here, and what "auto" takes, are n = 30, m = 2 (the pass
// descriptor's; the auto search is for air).
// quality.lamps_model: "single" (001's single scattering in the water as it is), "delta_m" (the water
// delta-M scaled, so the light forward scattering keeps in the beam is not lost; also the older
// quality.lamps_delta_m = true) or "orders" (single scattering plus the orders of multiple scattering of
// common/underwater_lamps_ms.h, from a table of the lamps' blurred profiles built here:
// underwater/lamps_ms_table.h). Measured against the path tracer: results/BENCHMARKS.md.
#pragma once
#include <CL/opencl.hpp>

#include <vector>

#include <memory>

#include "device/device.h"
#include "passes/underwater_lamps_tables.h"
#include "plan/plan.h"
#include "render/frame_result.h"
#include "scene/scene.h"
#include "spectral/wavelength_grid.h"
#include "underwater/lamps_setup.h"
#include "underwater/underwater_setup.h"

namespace seasim {

// The lamps_single / lamps_multiple layers (SEASIM_LAYER_LAMPS_SPLIT): stride floats per pixel, each
// layer's R at its offset (-1: not asked).
struct LampSplitLayers {
  cl::Buffer* buffer = nullptr;
  int stride = 0, single_at = -1, multiple_at = -1;
};

// The "orders" model's lattice step in pixels: as many pixels as fit in quality.lamps_ms_cell_deg along
// the image's height (at least 1: every pixel), so that the lattice's error, which follows the cell's
// angle, is the same at every image size.
int lampsMsLatticeStep(const Scene& scene);

// Floats per lattice pixel (kernels/underwater_lamps.cl, LAMP_LATTICE_ENTRY): the surface's part and the view
// ray's, each per band, and each again for the part scattered at most once when the lamps' layers are split.
size_t lampsMsLatticeFloats(int band_count, bool lamps_split);

class UnderwaterLampsPass {
 public:
  enum class Model { Single = 0, DeltaM = 1, Orders = 2 };
  // The scene's settings (configFromScene; their defaults are the pass descriptor's,
  // passes/nodes/underwater_lamps_node.cpp).
  struct Config {
    int planes = 0;                // n sampling planes per lamp (001 eq. 5): quality.shafts_planes
    int subplanes = 0;             // m sub-samples per interval (001 eq. 7–9): quality.shafts_subplanes
    Model model = Model::DeltaM;   // quality.lamps_model
    int orders = 0;                // quality.lamps_orders ("orders" model)
    int ms_steps = 0;              // quality.lamps_ms_steps: quadrature steps per view ray and lamp
    double kappa = 0.0;            // quality.lamps_ms_kappa: path-stretch exponent
    double beta = 0.0;             // quality.lamps_ms_spread: β of the landing spread h_n = 1 - β (1 - g^n)
    int ms_step = 1;               // the smooth part on every ms_step-th pixel (1: all): lampsMsLatticeStep
  };
  static Config configFromScene(const Scene& scene);
  // m where quality.shafts_subplanes is absent or "auto": 2, not the paper's 6 (the shafts in air keep 6).
  // In the water the planes span the cone's exact interval, so the sub-samples only follow a soft edge's
  // ramp and the objects' shadows: on rov_lights at 640x360 m = 2 is within 1e-5 (rel. L2) of m = 6,
  // both measured against planes converged at n = 240, m = 24, for 0.8x the pass (results/BENCHMARKS.md).
  static constexpr int kSubplanesInWater = 2;

  // `plan`: the "underwater_lamps" entry (its defines). RuntimeError for n or m < 1. `tables`: the orders
  // model's host tables kept by the caller across passes (none: the pass keeps its own).
  UnderwaterLampsPass(Device& device, const Scene& scene, const UnderwaterSetup& setup, const WavelengthGrid& grid,
                      const PassPlan& plan, const Config& config, LampsOrdersTables* tables = nullptr);
  // Adds the lamps into rgb (and spectral when given) for the G-buffer (geom, material); appends the
  // kernels' ms to `timings` (the lattice's, with ms_step > 1, then the pixels').
  // lamps_layer: the "lamps" ground-truth layer (3 floats per pixel) when planned with SEASIM_LAYER_LAMPS;
  // band_layers: kd_multiple's split per band ([pixel][5][band], slot 3 the lamps) with SEASIM_LAYER_BANDS.
  void run(std::vector<PassTiming>& timings, cl::Buffer& geom, cl::Buffer& material, cl::Buffer& rgb,
           cl::Buffer* spectral, cl::Buffer* lamps_layer = nullptr, cl::Buffer* band_layers = nullptr,
           const LampSplitLayers& split = {});
  // Rewrites the underwater parameter blocks (sun, water or time changed; same sizes).
  void update(const UnderwaterSetup& setup);

 private:
  Device& device_;
  Config config_;
  std::vector<UwLamp> lamp_list_;
  float lamp_s_min_ = 0.0f;
  std::unique_ptr<LampsOrdersTables> own_tables_;
  LampsOrdersTables* tables_ = nullptr;
  // The generations of the orders' tables on the device (LampsOrdersTables::Table::generation).
  int profiles_on_device_ = 0, glow_on_device_ = 0, weights_on_device_ = 0;
  // Builds (where their inputs changed) the orders' tables for this water and writes what is new to the
  // device (buffers made when `create`).
  void orderTables(const UwParams& params, const std::vector<UwBand>& bands, bool create);
  int width_, height_;
  size_t band_count_, object_count_, albedo_count_;
  cl::Kernel kernel_;
  // The orders model's smooth part on a lattice (ms_step > 1; kernels/underwater_lamps.cl).
  cl::Kernel lattice_kernel_;
  cl::Buffer lattice_;
  int lattice_w_ = 0, lattice_h_ = 0;
  cl::Buffer params_, bands_, albedo_, objects_, lamp_params_, lamps_, spectra_, ms_table_, ms_glow_, ms_weights_;
  // The delta-M model with the lamps' split layers: its single-scattering part is evaluated apart, in
  // the water as it is (plain_bands_; otherwise plain_bands_ is bands_ and the kernel does not read it).
  bool single_apart_ = false;
  cl::Buffer plain_bands_;
  float plain_g_ = 0.0f;
};

}  // namespace seasim
