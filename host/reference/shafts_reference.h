// shafts_reference.h — references for the spotlight shafts of paper 001 (kernels/shafts.cl):
//
//  * renderShaftsReference: a CPU double ray marcher (TBB) on the same scene: N midpoint steps per
//    pixel along the view ray, an exact shadow ray to every lamp at every step, the exact
//    integrand H I_l g of 001 eq. 2–4, and the same surface shading I_o (001 eq. 1). This is the
//    paper's reference method (Nishita et al. 1987; 001 used 180 steps).
//  * sunAirlight: the closed-form single-scattering airlight of an isotropic point light in a
//    homogeneous medium (Sun, Ramamoorthi, Narasimhan, Nayar 2005), an exact test of the
//    sampling-plane integrator without shadows.
//
// Also the frame set-up the pass and the reference share (depth range of the sampling planes,
// light frames, light maps), so both integrate exactly the same problem.
#pragma once
#include <string>
#include <vector>

#include "io/image.h"
#include "math/vec3.h"
#include "scene/scene.h"

namespace seasim {

// The camera-depth range of the sampling planes (001 eq. 5) and the ranges of the h(s,t) table.
struct ShaftsRange {
  double z_near = 0.01;  // m
  double z_far = 0.0;    // m: the farthest visible surface depth (coarse host ray cast), or twice the
                         // scene's finite extent when some ray sees nothing
  double t_max = 0.0;    // m, longest view-ray length inside [0, z_far] (image corner)
  double s_max = 0.0;    // m, largest lamp distance of any sample
};
ShaftsRange shaftsRange(const Scene& scene);

// `range` with [z_near, z_far] clipped to the camera-depth range of the union of the lights' cones
// (001 eq. 5 places the n planes between near and far; planes where no cone reaches waste work). Each
// cone, cut at the distance beyond which its airlight cannot reach 0.01 of an 8-bit level, is bounded
// by a circumscribed 8-sided pyramid with a cap plane and intersected with the view frustum (near,
// far and the four side planes); the depth extremes of that convex polytope are found at its
// vertices. Conservative: no lit point inside the frustum is cut. A camera inside a cone keeps
// z_near. When no cone reaches the frustum (e.g. all behind the camera) the range is empty
// (z_far = z_near: no plane, zero airlight). t_max and s_max are recomputed for the clipped range.
ShaftsRange shaftsClipToCones(const Scene& scene, const ShaftsRange& range);

// Light frame: +z = direction, right/up across the beam (the light map's u and v).
void shaftsLightBasis(const SpotlightDesc& light, Vec3& right, Vec3& up);

// A lamp's light map as linear RGB (sRGB-decoded from the file), top row first.
struct LightMap {
  int width = 0, height = 0;
  std::vector<float> rgb;  // 3 per texel
};
LightMap loadLightMap(const std::string& path);

// Lambertian albedo of an object as linear R,G,B (its spectrum at 610, 550, 465 nm).
Vec3 objectAlbedoRgb(const ObjectDesc& object);

// The lamp's radius: 1/s² is clamped at this distance (common/shafts.h).
constexpr double kShaftsLampRadius = 1e-3;  // m

// `steps` midpoint steps per ray over [0, min(T, z_far / cos θ)]. The range defaults to
// shaftsRange(scene). Throws RuntimeError for scenes it does not model (height-field objects, no air).
Image renderShaftsReference(const Scene& scene, int steps, const ShaftsRange* range = nullptr);

// F(u, v) = ∫_0^v exp(-u tan ξ) dξ (Sun et al. 2005), by adaptive Gauss–Kronrod-free Simpson in double.
double sunF(double u, double v);

// Single-scattering airlight along a ray of length T from the eye, for an isotropic point light of
// intensity I0 (W/sr) at distance D from the eye, at angle gamma (0 < gamma < π) between the ray and
// the direction to the light; scattering coefficient sigma_s, extinction sigma_t (1/m), phase 1/(4π):
//   L = sigma_s I0 exp(-sigma_t D cos γ) / (2π D sin γ) · [F(A1, v1) - F(A1, γ/2)],
//   A1 = sigma_t D sin γ,  v1 = π/4 + ½ atan((T - D cos γ) / (D sin γ)).
double sunAirlight(double sigma_s, double sigma_t, double I0, double D, double gamma, double T);

}  // namespace seasim
