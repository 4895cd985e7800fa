// underwater_reference.h — references for the underwater model of paper 002 (kernels/reference.cl):
//
//  * renderUnderwaterReference: the spectral Monte Carlo volumetric path tracer on the device, full
//    multiple scattering (the reference 002 §6.1 validates against), progressive in batches, with the
//    standard error of every pixel so error numbers can be quoted beside the reference's own noise.
//    The errors come from independent blocks of paths (reference/batch_error.h), honest under the heavy
//    tails of dim, absorbing, forward-scattering water where the per-sample variance is too small.
//    max_bounces = 1 is its single-scattering mode (the sun beam scattered once, what the froxel pass
//    integrates).
//  * underwaterSingleScatteringRay / renderUnderwaterSingleScatteringQuadrature: that single
//    scattering integral by deterministic quadrature in double on the CPU with exact shadow rays,
//      L_SS = ∫_0^S e^{-c z} b p(θ) E_beam(y(z)) V(x_z) dz,  E_beam(y) = e_beam0 e^{-c y/μ_w},
//    the check of both the path tracer's single-scattering mode and the froxel integrator.
//
// Both read the scene as the underwater passes do (UnderwaterSetup: common/underwater_params.h,
// common/underwater.h): flat surface, no caustics. The path tracer also lights the scene's spotlights
// (settings.lamps, as the underwater_lamps pass does), to all orders of scattering.
#pragma once
#include <functional>
#include <vector>

#include "device/device.h"
#include "io/image.h"
#include "math/vec3.h"
#include "passes/sea_heightfield.h"
#include "underwater/lamps_setup.h"
#include "underwater/underwater_setup.h"

namespace seasim {

// The ocean's normal map the sea seen from above is traced through (kernels/reference.cl,
// common/sea_waves.h): 4 floats per texel (nx, ny, nz, unused), grid x grid texels over patch metres,
// row j along z, x fastest.
struct WaveNormalMap {
  std::vector<float> normals;
  int grid = 0;
  double patch = 0.0;
};

struct UnderwaterReferenceSettings {
  int samples_per_pixel = 64;  // paths per pixel in all (the last launch may trace fewer than `batch`)
  int batch = 8;               // paths per pixel per kernel launch
  int max_bounces = 1000;      // scattering vertices per path (medium, Lambertian, surface reflection);
                               // Russian roulette ends nearly every path long before; 1000 as the
                               // Mitsuba validation's volpath max_depth. A cap of 64 took up to 40 % off
                               // deep, clear, strongly forward water (docs/journal/sea_all_orders.md);
                               // 1 = single scattering of the sun beam only (no surface, sky or objects'
                               // own shading)
  bool isotropic = false;      // phase 1/(4π) instead of Henyey–Greenstein with UwParams.g
  // The water's phase for next-event weights and sampling (PhaseFunction::pathTracerTables: PHASE_PT_VALUES
  // values then PHASE_PT_SAMPLES inverse-CDF entries, common/phase.h); empty: HG of UwParams.g.
  std::vector<float> phase_tables;
  bool jitter = true;          // false: every path through the pixel centre (tests against quadrature)
  unsigned seed = 1;           // the same seed traces the same paths, whatever `batch` or `blocks` is
  int blocks = 32;             // independent blocks of paths (contiguous sample ranges) whose spread
                               // gives the standard errors (reference/batch_error.h); clamped to
                               // samples_per_pixel (1 path per block: the per-sample estimate)
  bool camera_above = false;   // the camera is above the surface (y > 0): the sea seen from above,
                               // R L_sky + (1 - R)/n² × the water's paths (reference.cl); else y < 0
  // The scene's spotlights (underwater/lamps_setup.h: makeUnderwaterLamps), seen by next-event
  // estimation at every vertex; null: no lamps. Must outlive the call.
  const UnderwaterLamps* lamps = nullptr;
  // How a path segment sees the lamps (common/path_tracer_lamps.h): true, an equiangular sample inside
  // each lamp's cone and next-event estimation at the free-flight vertex, combined by the balance
  // heuristic; false, one equiangular sample on the whole segment alone (the plain estimator, kept to
  // measure the combination's variance against; both are unbiased).
  bool lamp_mis = true;
  // A height-field floor (the sea's [bottom] type = "heightfield": passes/sea_heightfield.h) in place of
  // the flat bottom (UwParams.bottom_depth must be 0); null: none. Must outlive the call.
  const HeightField* height_field = nullptr;
  // FFT waves seen from above (camera_above only): the surface's normal map; null: the flat surface.
  // Must outlive the call.
  const WaveNormalMap* waves = nullptr;
  double sun_angular_radius = 0.004654;  // radians: the sun's disk in the waves' mirror (with waves only)
  std::function<void(int done, int total)> progress;  // after each launch: samples done, samples asked
};

struct UnderwaterReferenceResult {
  Image rgb;                          // mean linear sensor RGB, Σ_bands L(λ_i) w(λ_i) (002 eq. 4.8)
  Image std_error;                    // standard error of that mean, per pixel and channel, from the
                                      // spread of the blocks' means (blocks - 1 degrees of freedom)
  // The part of rgb from paths whose camera ray reached a surface (the water surface, an object, the
  // bottom) without scattering: all the light they gather from there on (reference.cl). It is the
  // fast models' direct layer; rgb - direct is their backscatter + forward + lamps (docs/layers.md).
  // Camera above the surface: 0.
  Image direct;
  Image direct_std_error;             // its standard error, from the blocks as std_error
  double mean_std_error = 0.0;        // mean of std_error over pixels and channels ("reference noise")
  double rms_std_error = 0.0;         // sqrt(mean std_error²): the RMSE the reference's noise alone adds
  double image_mean = 0.0;            // mean of rgb over pixels and channels
  double image_mean_std_error = 0.0;  // standard error of image_mean from the spread of the blocks'
                                      // image means (any correlation between pixels included)
  double image_mean_sample_std_error = 0.0;  // the same from the per-sample variances, pixels taken
                                             // as independent (the estimate before blocks)
  double effective_samples = 0.0;     // paths per pixel whose per-sample variance would give
                                      // image_mean_std_error: samples when that estimate is honest,
                                      // fewer when a heavy tail makes it too small (batch_error.h)
  double ms = 0.0;                    // kernel time, summed over launches (profiling events)
  int samples = 0;                    // paths per pixel traced
  int blocks = 0;                     // independent blocks of paths the errors come from
};

// Throws RuntimeError for settings or scenes it cannot trace (no samples, camera above the surface,
// |g| >= 1, non-finite output) and DeviceError on OpenCL failures.
UnderwaterReferenceResult renderUnderwaterReference(Device& device, const UnderwaterSetup& setup,
                                                    const UnderwaterReferenceSettings& settings);

// L_SS of one band along the ray origin + z dir (dir unit, origin below the surface), in double, with
// an exact shadow ray along sun_dir_water through the objects at every step; S the first hit of
// uw_scene_hit. Midpoint rule with `steps` steps in u = 1 - e^{-κ z}, κ = c (1 - d_y/μ_w), the
// unshadowed integrand's own decay: exact without objects (it is 002 eq. 4.7's kd_exp_integral then),
// error O(1/steps) across shadow edges; deep water needs no truncation. 0 when c = 0 or b = 0.
double underwaterSingleScatteringRay(const UnderwaterSetup& setup, int band, Vec3 origin, Vec3 dir, bool isotropic,
                                     int steps);

// That integral through every pixel centre (the pinhole camera of sea_single.cl), as sensor RGB.
Image renderUnderwaterSingleScatteringQuadrature(const UnderwaterSetup& setup, bool isotropic, int steps);

// The view direction through image point (x, y) (pixel units; + 0.5 for a pixel centre): uw_screen_dir
// in double, the same pinhole the kernels evaluate in float.
Vec3 underwaterPixelDirection(const UwParams& params, double x, double y);

}  // namespace seasim
