// underwater_ordinates_setup.h — the per-band coefficients of underwater.model = "discrete_ordinates"
// (kernels/common/underwater_ordinates.h, whose comment gives the model): delta-M scaled IOPs and the
// two-stream solution for the diffuse plane irradiances E_d(y), E_u(y) in a layer over a Lambertian
// bottom, solved in double on the host once per frame.
#pragma once
#include <vector>

extern "C" {
#include "common/underwater_params.h"
#include "common/underwater_ordinates_params.h"
}

namespace seasim {

struct ForwardPeak;  // forward_peak.h

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
// The discrete-ordinates model's closure (fitted with diffuseMeanCosines; see the .cpp).
TwoStreamClosure twoStreamClosure();

// κ = K∞ / c of an isotropically scattering medium of single-scattering albedo omega in [0, 1]: the
// root in (0, 1] of omega atanh(κ) = κ (the asymptotic radiance's eigenvalue; 1 at omega = 0).
double isotropicAsymptoticKappa(double omega);
// μ1 = √(1 - omega) / κ(omega): the two streams' cosine at which a two-stream of that medium decays at
// K∞ (1/√3 as omega -> 1, the diffusion limit; 1 at omega = 0, where only the unscattered light remains).
double asymptoticStreamCosine(double omega);

// K∞ of the similarity-scaled medium (absorption a, isotropic scattering 2 b_back, b_back = b'(1 - g')/2
// per stream as in the two-stream): (a + 2 b_back) κ(ω_s), ω_s = 2 b_back / (a + 2 b_back); 0 when
// a = 0 (nothing is absorbed: the diffuse light does not decay), 0 for an empty medium.
double asymptoticDiffuseK(double a, double b_back);

// The diffuse field's attenuation over the depths a frame sees (docs/journal/underwater_regions_2_*.md):
// the mean log-slope -ln(E(D)/E(0))/D over [0, D] of a field of two modes, the fast one and the asymptotic
// e^{-K∞ y}, that holds the share w of E(0) and whose slope at the surface is the two-stream's k:
//   E(y) = (1 - w) e^{-k_f y} + w e^{-K∞ y},   (1 - w) k_f + w K∞ = k
//   k(D) = K∞ - ln(w + (1 - w) e^{-(k - K∞) D/(1 - w)}) / D
// k at D = 0 (and at w = 0), falling monotonically to K∞ as D grows; w >= 1 gives K∞. Taken as k when
// k <= K∞ or D <= 0. Continuous in D, w, k and K∞; finite for all finite inputs.
double depthMeanDiffuseK(double k_two_stream, double k_inf, double depth, double asymptotic_share);

// The asymptotic mode's share w of the diffuse field (depthMeanDiffuseK), fitted to the path tracer on
// the training grid (see the .cpp); 0 turns the depth dependence off.
double diffuseAsymptoticShare(double g);

// The scale s(g) of the flux term's asymmetry, g_f = s(g) g' (UwiBand::g_flux): a table fitted to the
// path tracer on the training grid (see the .cpp); 1 is the first-order phase expansion.
double diffuseFluxScale(double g);

// Where the scene's depth enters the discrete-ordinates model's k: the depth D over which the diffuse field's
// mean slope is taken (the camera's depth, within [0, H] over a bottom; set per frame, so the band
// table follows a moving camera) and the asymptotic share w.
struct DiffuseDepth {
  double depth = 0;
  double asymptotic_share = 0;
  double flux_scale = 1;  // s(g) of the flux term (diffuseFluxScale); 1: the first-order expansion
};
// The camera's depth -cam_pos[1], clamped to [0, bottom_depth] when there is a bottom (> 0).
double diffuseViewDepth(const UwParams& params);

// The discrete-ordinates model's delta-M medium (Wiscombe 1977; as deltaMScale in underwater/lamps_setup.h): the
// forward peak f = g^power counts as unscattered, b' = b (1 - f), c' = a + b', g' = (g - f)/(1 - f) (at the
// two-stream's power 2, g / (1 + g), without its 0/0 at g = 1); g < 0 is left unscaled. Both diffuse
// solvers' bands start from it: the two-stream at power 2, the discrete ordinates at their own order.
struct DeltaMMedium {
  double b_dm = 0, c_dm = 0, g_dm = 0;
};
DeltaMMedium ordinatesDeltaM(double a, double b, double g, int power = 2);
// A band block with the medium's c', b', g' and the flux term's g_f = flux_scale g' set, the rest 0.
UwiBand uwiBandOfMedium(const DeltaMMedium& medium, double flux_scale);
// The source table of the first-order phase (the two-stream's):
// J = b' [E_0 + 3 g_f (ν (E_d - E_u) + √(1 - ν²) cos Δφ F_h)]/(4π) per exponential from the band's o*, d*,
// u*, h* and g_flux.
void setFirstOrderSource(UwiBand& band);
// The tilted plane's irradiance table (UwiBand.tilt) of hemispheres of uniform radiance, E_d (1 + n_y)/2 +
// E_u (1 - n_y)/2 per exponential from the band's d*, u* (the two-stream's; azimuth modes 1, 2 zero).
void setHemisphereTilt(UwiBand& band);

// One band's coefficients. mu_w: the refracted sun's cosine (any value in (0, 1] when the sun is off:
// e_beam0 = e_sun0 = 0 then); bottom_depth <= 0: no bottom; g the water's HG asymmetry; mean: the
// streams' mean cosines (the first form: the fitted table at g).
UwiBand makeUwiBand(const UwBand& band, double g, double mu_w, double bottom_depth, double ior);
// peak: the forward peak of g and f = g² (forward_peak.h), the same for every band; null: computed here.
UwiBand makeUwiBand(const UwBand& band, double g, double mu_w, double bottom_depth, double ior,
                    DiffuseMeanCosines mean, TwoStreamClosure closure = twoStreamClosure(),
                    DiffuseDepth depth = {}, const ForwardPeak* peak = nullptr);

// All bands of a set-up (params.g, params.bottom_depth, params.ior, params.sun_dir_water[1]; the
// depth of diffuseViewDepth(params)) with the asymptotic share w (negative: diffuseAsymptoticShare(g)) and
// the flux term's scale (negative: diffuseFluxScale(g)).
std::vector<UwiBand> makeUwiBands(const UwParams& params, const std::vector<UwBand>& bands, DiffuseMeanCosines mean,
                                  TwoStreamClosure closure = twoStreamClosure(), double asymptotic_share = -1,
                                  double flux_scale = -1);

}  // namespace seasim
