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
// The geometry the pass and the reference share is in geometry/shafts_geometry.h.
#pragma once
#include <string>
#include <vector>

#include "geometry/shafts_geometry.h"
#include "io/image.h"
#include "math/vec3.h"
#include "scene/scene.h"

namespace seasim {

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
