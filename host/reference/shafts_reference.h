// shafts_reference.h — references for the spotlight shafts of paper 001 (kernels/shafts.cl):
//
//  * renderShaftsReference: a CPU double ray marcher (TBB) on the same scene: per lamp, N midpoint
//    steps over the whole part of the view ray inside the lamp's cone, from the camera to the first
//    surface or to infinity, an exact shadow ray at every step, the exact integrand H I_l g of 001
//    eq. 2–4, and the same surface shading I_o (001 eq. 1). This is the paper's reference method
//    (Nishita et al. 1987; 001 used 180 steps), with the steps taken in the angle the lamp sees
//    (t = a + r tan φ), which maps an unbounded ray to a finite interval and flattens the 1/s²
//    peak; it shares neither the planes, nor their split point, nor the far-field closed form with
//    shafts.cl.
//  * sunAirlight: the closed-form single-scattering airlight of an isotropic point light in a
//    homogeneous medium (Sun, Ramamoorthi, Narasimhan, Nayar 2005), an exact test of the
//    sampling-plane integrator without shadows.
//
// Also the frame set-up the pass and the reference share (table ranges, light frames, light maps),
// so both integrate exactly the same problem.
#pragma once
#include <string>
#include <vector>

#include "io/image.h"
#include "math/vec3.h"
#include "scene/scene.h"

namespace seasim {

// The ranges of the 001 eq. 6 table ĥ(s, t) (table mode): the largest t and s at which any pixel's
// sampling planes evaluate g. shafts.cl integrates each lamp over the part of the view ray inside its
// cone, up to the first surface, with planes up to SHAFTS_TAIL_K r past the closest approach (the far
// field beyond does not read the table); this walks the same geometry in double at every pixel
// centre, plus 1 % for float rounding. At least 1 mm each, so an unlit scene still has a table.
struct ShaftsRange {
  double t_max = 0.0;  // m, longest view-ray distance of any plane
  double s_max = 0.0;  // m, largest lamp distance of any plane
};
ShaftsRange shaftsTableRange(const Scene& scene);

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

// `steps` midpoint steps per ray and lamp, uniform in φ = atan((t - a) / r) over the cone's part of
// the ray (a: the closest approach's ray parameter, r = max(its distance, the lamp radius); t = ∞
// is φ = π/2). Throws RuntimeError for scenes it does not model (height-field objects, no air).
Image renderShaftsReference(const Scene& scene, int steps);

// F(u, v) = ∫_0^v exp(-u tan ξ) dξ (Sun et al. 2005), by adaptive Gauss–Kronrod-free Simpson in double.
double sunF(double u, double v);

// Single-scattering airlight along a ray of length T (may be +infinity) from the eye, for an isotropic point light of
// intensity I0 (W/sr) at distance D from the eye, at angle gamma (0 < gamma < π) between the ray and
// the direction to the light; scattering coefficient sigma_s, extinction sigma_t (1/m), phase 1/(4π):
//   L = sigma_s I0 exp(-sigma_t D cos γ) / (2π D sin γ) · [F(A1, v1) - F(A1, γ/2)],
//   A1 = sigma_t D sin γ,  v1 = π/4 + ½ atan((T - D cos γ) / (D sin γ)).
double sunAirlight(double sigma_s, double sigma_t, double I0, double D, double gamma, double T);

}  // namespace seasim
