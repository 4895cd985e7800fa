// underwater_improved_setup.h — the per-band coefficients of underwater.model = "improved"
// (kernels/common/underwater_improved.h, whose comment gives the model): delta-M scaled IOPs and the
// two-stream solution for the diffuse plane irradiances E_d(y), E_u(y) in a layer over a Lambertian
// bottom, solved in double on the host once per frame.
#pragma once
#include <vector>

extern "C" {
#include "common/underwater_params.h"
#include "common/underwater_improved_params.h"
}

namespace seasim {

// The surface's reflectance, from below, of upwelling light of uniform radiance: 2 ∫_0^1 F(μ) μ dμ
// (total internal reflection outside Snell's window included); about 0.47 for ior 1.34.
double internalDiffuseReflectance(double ior);

// The mean cosines μ̄ (plane irradiance over scalar irradiance) of the diffuse down and up streams
// with which the in-scatter source weighs them (scalar irradiance E_d/μ̄_down + E_u/μ̄_up), as a
// function of the HG asymmetry g: a small table fitted to the path tracer (see the .cpp). down, up:
// the two-stream's own modes e^{-k y}, e^{-k (H - y)}; beam_down, beam_up: the sun beam's diffuse
// offspring e^{-m y}, whose light lies nearer the beam's direction.
struct DiffuseMeanCosines {
  double down, up, beam_down, beam_up;
};
DiffuseMeanCosines diffuseMeanCosines(double g);

// How the two-stream closes its equations (its α1, α2; Meador & Weaver 1980's γ1, γ2 in metres):
// Quadrature: streams at ±1/√3, k = √3 √(a (a + b' (1 - g'))); Asymptotic: streams at the cosine μ1 for
// which k is the exact asymptotic diffuse attenuation K∞ of the similarity-scaled medium (isotropic
// scattering b' (1 - g'), absorption a; asymptoticStreamCosine), k = √(a (a + b' (1 - g'))) / μ1.
enum class TwoStreamClosure { Quadrature, Asymptotic };
// The improved model's closure (fitted with diffuseMeanCosines; see the .cpp).
TwoStreamClosure twoStreamClosure();

// κ = K∞ / c of an isotropically scattering medium of single-scattering albedo omega in [0, 1]: the
// root in (0, 1] of omega atanh(κ) = κ (the asymptotic radiance's eigenvalue; 1 at omega = 0).
double isotropicAsymptoticKappa(double omega);
// μ1 = √(1 - omega) / κ(omega): the two streams' cosine at which a two-stream of that medium decays at
// K∞ (1/√3 as omega -> 1, the diffusion limit; 1 at omega = 0, where only the unscattered light remains).
double asymptoticStreamCosine(double omega);

// One band's coefficients. mu_w: the refracted sun's cosine (any value in (0, 1] when the sun is off:
// e_beam0 = e_sun0 = 0 then); bottom_depth <= 0: no bottom; g the water's HG asymmetry; mean: the
// streams' mean cosines (the first form: the fitted table at g).
UwiBand makeUwiBand(const UwBand& band, double g, double mu_w, double bottom_depth, double ior);
UwiBand makeUwiBand(const UwBand& band, double g, double mu_w, double bottom_depth, double ior,
                    DiffuseMeanCosines mean, TwoStreamClosure closure = twoStreamClosure());

// All bands of a set-up (params.g, params.bottom_depth, params.ior, params.sun_dir_water[1]).
std::vector<UwiBand> makeUwiBands(const UwParams& params, const std::vector<UwBand>& bands, DiffuseMeanCosines mean,
                                  TwoStreamClosure closure = twoStreamClosure());

}  // namespace seasim
